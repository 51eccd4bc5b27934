#include "sets.hpp"

#include <map>

namespace gen {

std::vector<SetDef> sample_sets() {
    // Name builders per family keep the table to what differs between sets.
    auto acg = [](const std::string& n, const std::string& tag, Map m, int size) {
        return FileDef{n + "_1K-PNG_" + tag + ".png", m, Enc::png8, size};
    };
    auto ph = [](const std::string& dir, const std::string& n, const std::string& tag, Map m, Enc e, int size) {
        static const std::map<Enc, std::string> ext{{Enc::png8, "png"},
                                                    {Enc::png16, "png"},
                                                    {Enc::jpg, "jpg"},
                                                    {Enc::exr_half, "exr"}};
        return FileDef{dir + n + "_" + tag + "_1k." + ext.at(e), m, e, size};
    };
    auto tcom = [](const std::string& n, const std::string& tag, Map m, const std::string& res, int size) {
        return FileDef{n + "_" + tag + "_" + res + ".jpg", m, Enc::jpg, size};
    };
    auto mega = [](const std::string& n, const std::string& tag, Map m) {
        return FileDef{n + "_2K_" + tag + ".jpg", m, Enc::jpg, 256};
    };
    auto sub = [](const std::string& n, const std::string& tag, Map m) {
        return FileDef{n + "_" + tag + ".png", m, Enc::png8, 256};
    };
    auto gltf = [](const std::string& n, const std::string& tag, Map m) {
        return FileDef{n + "_" + tag + ".png", m, Enc::png8, 256};
    };
    return {
        {"Bricks076_1K-PNG",
         "ambientcg",
         "Bricks076",
         &kBricks,
         "no metalness map (dielectric); both _NormalGL and _NormalDX present (name decides, "
         "content agrees); clutter: preview render `Bricks076.png` and a MaterialX sidecar",
         {acg("Bricks076", "Color", Map::albedo, 256),
          acg("Bricks076", "NormalGL", Map::normal_gl, 256),
          acg("Bricks076", "NormalDX", Map::normal_dx, 256),
          acg("Bricks076", "Roughness", Map::roughness, 256),
          acg("Bricks076", "AmbientOcclusion", Map::occlusion, 256),
          acg("Bricks076", "Displacement", Map::height, 256),
          {"Bricks076.png", Map::preview, Enc::png8, 64}},
         {{"Bricks076_1K-PNG.mtlx", Text::mtlx}}},
        {"Tiles101_1K-PNG.zip",
         "ambientcg",
         "Tiles101",
         &kTiles,
         "set shipped as a .zip (flat, as ambientCG ships it); DirectX normal only (_NormalDX); "
         "clutter inside the archive (preview, MaterialX); no metalness",
         {acg("Tiles101", "Color", Map::albedo, 128),
          acg("Tiles101", "NormalDX", Map::normal_dx, 128),
          acg("Tiles101", "Roughness", Map::roughness, 128),
          acg("Tiles101", "AmbientOcclusion", Map::occlusion, 128),
          acg("Tiles101", "Displacement", Map::height, 128),
          {"Tiles101.png", Map::preview, Enc::png8, 64}},
         {{"Tiles101_1K-PNG.mtlx", Text::mtlx}}},
        {"MetalPlates013_1K-PNG",
         "ambientcg",
         "MetalPlates013",
         &kMetalPlates,
         "metal set: binary _Metalness (bare iron where paint chipped, rivet heads; iron albedo "
         "from physicallybased.info, 185-193 sRGB); painted and rusty areas dielectric",
         {acg("MetalPlates013", "Color", Map::albedo, 256), acg("MetalPlates013", "NormalGL", Map::normal_gl, 256),
          acg("MetalPlates013", "Roughness", Map::roughness, 256),
          acg("MetalPlates013", "Metalness", Map::metalness, 256),
          acg("MetalPlates013", "AmbientOcclusion", Map::occlusion, 256),
          acg("MetalPlates013", "Displacement", Map::height, 256)},
         {{"MetalPlates013_1K-PNG.mtlx", Text::mtlx}}},
        {"rocky_ground_02",
         "polyhaven",
         "rocky_ground_02",
         &kRockyGround,
         "nested folder (maps under `textures/`); 16-bit PNG height; EXR (half) normal map; "
         "JPEG albedo; clutter: `thumbnail.jpg` at the set root; no metalness",
         {ph("textures/", "rocky_ground_02", "diff", Map::albedo, Enc::jpg, 256),
          ph("textures/", "rocky_ground_02", "nor_gl", Map::normal_gl, Enc::exr_half, 256),
          ph("textures/", "rocky_ground_02", "rough", Map::roughness, Enc::png8, 256),
          ph("textures/", "rocky_ground_02", "ao", Map::occlusion, Enc::png8, 256),
          ph("textures/", "rocky_ground_02", "disp", Map::height, Enc::png16, 256),
          {"thumbnail.jpg", Map::preview, Enc::jpg, 64}},
         {}},
        {"wood_planks_worn",
         "polyhaven",
         "wood_planks_worn",
         &kWoodPlanks,
         "packed ARM map (R=AO, G=roughness, B=metalness: iron nail heads are the only metal); "
         "both _nor_gl_ and _nor_dx_; half-float EXR displacement",
         {ph("", "wood_planks_worn", "diff", Map::albedo, Enc::png8, 128),
          ph("", "wood_planks_worn", "nor_gl", Map::normal_gl, Enc::png8, 128),
          ph("", "wood_planks_worn", "nor_dx", Map::normal_dx, Enc::png8, 128),
          ph("", "wood_planks_worn", "arm", Map::arm, Enc::png8, 128),
          ph("", "wood_planks_worn", "disp", Map::height, Enc::exr_half, 128)},
         {}},
        {"MarbleTiles0017",
         "texturescom",
         "MarbleTiles0017",
         &kMarbleTiles,
         "gloss map and no roughness (inverted into roughness); _REFL specular level; all JPEG; "
         "two resolutions of the albedo (_COL_1K 128 px, _COL_2K 256 px: ambiguity, and the 2K "
         "one mismatches the other maps); normal named only _NRM (content is OpenGL +Y)",
         {tcom("MarbleTiles0017", "COL", Map::albedo, "1K", 128),
          tcom("MarbleTiles0017", "COL", Map::albedo, "2K", 256),
          tcom("MarbleTiles0017", "NRM", Map::normal_gl, "1K", 128),
          tcom("MarbleTiles0017", "GLOSS", Map::gloss, "1K", 128),
          tcom("MarbleTiles0017", "REFL", Map::specular, "1K", 128),
          tcom("MarbleTiles0017", "DISP", Map::height, "1K", 128),
          tcom("MarbleTiles0017", "AO", Map::occlusion, "1K", 128)},
         {}},
        {"ivy_leaves",
         "megascans",
         "ivy_leaves",
         &kIvyLeaves,
         "opacity map (cut-out leaves); packed _ORT (R=AO, G=roughness, B=translucency, not "
         "metalness); all JPEG; normal named only _Normal (content is OpenGL +Y); clutter: "
         "`_Preview.png` and a Bridge-style JSON",
         {mega("ivy_leaves", "Albedo", Map::albedo),
          mega("ivy_leaves", "Normal", Map::normal_gl),
          mega("ivy_leaves", "Displacement", Map::height),
          mega("ivy_leaves", "ORT", Map::ort),
          mega("ivy_leaves", "Opacity", Map::opacity),
          {"ivy_leaves_Preview.png", Map::preview, Enc::png8, 64}},
         {{"ivy_leaves.json", Text::megascans_json}}},
        {"ScifiPanel",
         "substance",
         "ScifiPanel",
         &kScifiPanel,
         "Unreal-style export: packed _OcclusionRoughnessMetallic (bare aluminium bolts and paint "
         "chips are metal); _Emissive light strips; _Height; normal named only _Normal and its "
         "content is DirectX (-Y)",
         {sub("ScifiPanel", "BaseColor", Map::albedo), sub("ScifiPanel", "Normal", Map::normal_dx),
          sub("ScifiPanel", "Height", Map::height), sub("ScifiPanel", "OcclusionRoughnessMetallic", Map::arm),
          sub("ScifiPanel", "Emissive", Map::emissive)},
         {}},
        {"WalnutInlay",
         "gltf",
         "WalnutInlay",
         &kWalnutInlay,
         "glTF texture set: _metallicRoughness (G=roughness, B=metalness, R unused) with gold "
         "inlay (physicallybased.info gold); _emissive gems; separate _occlusion; _normal (OpenGL)",
         {gltf("WalnutInlay", "baseColor", Map::albedo), gltf("WalnutInlay", "metallicRoughness", Map::metal_rough),
          gltf("WalnutInlay", "normal", Map::normal_gl), gltf("WalnutInlay", "occlusion", Map::occlusion),
          gltf("WalnutInlay", "emissive", Map::emissive)},
         {}},
    };
}

}  // namespace gen
