// Discovery tables: realistic file names of each family → roles, conventions, choices, findings.
#include "material/discovery.hpp"
#include <nlohmann/json.hpp>
#include "material/routing.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>

namespace mf {
namespace {

using NC = NormalConvention;
using ::testing::ElementsAre;
using ::testing::ElementsAreArray;
using ::testing::HasSubstr;

// ---------------------------------------------------------------------------------------------
// File types

TEST(IsImageFile, Table) {
    const std::vector<std::pair<std::string, bool>> table{
        {"a.png", true},
        {"a.jpg", true},
        {"a.jpeg", true},
        {"a.tga", true},
        {"a.tif", true},
        {"a.tiff", true},
        {"a.exr", true},
        {"a.hdr", true},
        {"a.webp", true},
        {"a.bmp", true},
        {"a.dds", true},
        {"a.psd", true},
        {"WOOD_COL_2K.JPG", true},
        {"sub/dir/x_Color.Png", true},
        {"Bricks059_1K-PNG.usdc", false},
        {"Bricks059_1K-PNG.mtlx", false},
        {"readme.txt", false},
        {"Bricks059.json", false},
        {"scene.blend", false},
        {".DS_Store", false},
        {"Thumbs.db", false},
        {"noext", false},
        {"png", false},
        {"textures.png/readme", false},
        {"a.png.bak", false},
    };
    for (const auto& [file, expected] : table) EXPECT_EQ(is_image_file(file), expected) << file;
}

TEST(IsClutter, Table) {
    const std::vector<std::pair<std::string, bool>> table{
        {"Bricks059_PREVIEW.jpg", true},
        {"rock_sfjmafua_Preview.png", true},
        {"WoodFine0012_Preview1.png", true},
        {"WoodFine0012_Sphere.png", true},
        {"WoodFine0012_Cube.png", true},
        {"Concrete_thumbnail.jpg", true},
        {"thumb.jpg", true},
        {"Fabric_Swatch.jpg", true},
        {"Mat_mask_id.png", true},
        {"Mat_IdMap.png", true},
        {"Mat_idmap.png", true},
        {"Chair_render.png", true},
        // Clutter words that are also ordinary words count only where the role tag would be.
        {"Sphere_Tiles_1K-PNG_Color.png", false},
        {"Render_Plaster_2K_Albedo.jpg", false},
        {"Bricks059_1K-PNG_Color.png", false},
        {"Iconic_Marble_2K_Albedo.jpg", false},
        {"Fabric_Swatch_Icon.png", true},
        {"Bricks059.png", false},  // ambientCG's preview has no tag: unclassified, not clutter
        {"metal_plate_diff_2k.jpg", false},
    };
    for (const auto& [file, expected] : table) EXPECT_EQ(is_clutter(file), expected) << file;
}

// ---------------------------------------------------------------------------------------------
// classify_name

struct Row {
    std::string file;
    Role role;
    std::string family;  // "" = not checked (the family is genuinely ambiguous for this name)
    std::string rule;    // "" = not checked
    NC normal = NC::unknown;
};

void check_rows(const std::vector<Row>& rows) {
    for (const auto& r : rows) {
        SCOPED_TRACE(r.file);
        const auto m = classify_name(r.file);
        ASSERT_TRUE(m.has_value());
        EXPECT_EQ(role_name(m->role), role_name(r.role));
        EXPECT_EQ(convention_name(m->normal), convention_name(r.normal));
        if (!r.family.empty()) {
            EXPECT_EQ(m->family, r.family);
        }
        if (!r.rule.empty()) {
            EXPECT_EQ(m->rule, r.rule);
        }
    }
}

TEST(ClassifyName, AmbientCG) {
    check_rows({
        {"Bricks059_1K-PNG_Color.png", Role::albedo, "ambientcg", "ambientcg:_Color"},
        {"Bricks059_1K-PNG_NormalGL.png", Role::normal, "ambientcg", "ambientcg:_NormalGL", NC::gl},
        {"Bricks059_2K-JPG_NormalDX.jpg", Role::normal, "ambientcg", "ambientcg:_NormalDX", NC::dx},
        {"Bricks059_1K-PNG_Roughness.png", Role::roughness, "ambientcg", "ambientcg:_Roughness"},
        {"Metal032_4K-JPG_Metalness.jpg", Role::metalness, "ambientcg", "ambientcg:_Metalness"},
        {"Bricks059_1K-PNG_AmbientOcclusion.png", Role::occlusion, "ambientcg", "ambientcg:_AmbientOcclusion"},
        {"Bricks059_8K-PNG_Displacement.png", Role::height, "ambientcg", "ambientcg:_Displacement"},
        {"Leaves001_1K-PNG_Opacity.png", Role::opacity, "ambientcg", "ambientcg:_Opacity"},
        {"Lamp001_2K-PNG_Emission.png", Role::emissive, "ambientcg", "ambientcg:_Emission"},
        {"Bricks059_1K-PNG_Normal.png", Role::normal, "ambientcg", "ambientcg:_Normal"},
        // Older ambientCG names: the bare normal says nothing about green.
        {"Bricks059_2K_Normal.jpg", Role::normal, "", ""},
        {"Bricks059_2K_Color.jpg", Role::albedo, "ambientcg", ""},
    });
}

TEST(ClassifyName, PolyHaven) {
    check_rows({
        {"brick_wall_001_diff_1k.jpg", Role::albedo, "polyhaven", "polyhaven:_diff_"},
        {"brick_wall_001_nor_gl_1k.exr", Role::normal, "polyhaven", "polyhaven:_nor_gl_", NC::gl},
        {"brick_wall_001_nor_dx_1k.exr", Role::normal, "polyhaven", "polyhaven:_nor_dx_", NC::dx},
        {"brick_wall_001_rough_1k.exr", Role::roughness, "polyhaven", "polyhaven:_rough_"},
        {"aerial_rocks_02_arm_4k.png", Role::orm, "polyhaven", "polyhaven:_arm_"},
        {"aerial_rocks_02_ao_4k.png", Role::occlusion, "polyhaven", "polyhaven:_ao_"},
        {"aerial_rocks_02_disp_4k.png", Role::height, "polyhaven", "polyhaven:_disp_"},
        {"metal_plate_metal_2k.jpg", Role::metalness, "polyhaven", "polyhaven:_metal_"},
        {"painted_plaster_wall_col_8k.jpg", Role::albedo, "polyhaven", "polyhaven:_col_"},
    });
}

TEST(ClassifyName, TexturesComAndPoliigon) {
    check_rows({
        {"Concrete0012_COL_2K.jpg", Role::albedo, "texturescom", "texturescom:_COL"},
        {"Concrete0012_COL_VAR1_2K.jpg", Role::albedo, "texturescom", "texturescom:_COL"},
        {"Concrete0012_COL_VAR2_2K.jpg", Role::albedo, "texturescom", "texturescom:_COL"},
        {"WoodFine0012_GLOSS_3K.jpg", Role::gloss, "texturescom", "texturescom:_GLOSS"},
        {"WoodFine0012_REFL_3K.jpg", Role::specular, "texturescom", "texturescom:_REFL"},
        {"WoodFine0012_NRM_3K.jpg", Role::normal, "texturescom", "texturescom:_NRM"},
        {"WoodFine0012_NRM16_3K.tif", Role::normal, "texturescom", "texturescom:_NRM16"},
        {"WoodFine0012_DISP_3K.jpg", Role::height, "texturescom", "texturescom:_DISP"},
        {"WoodFine0012_DISP16_3K.tif", Role::height, "texturescom", "texturescom:_DISP16"},
        {"WoodFine0012_AO_3K.jpg", Role::occlusion, "texturescom", "texturescom:_AO"},
        {"MetalPlate0012_METALNESS_2K.jpg", Role::metalness, "texturescom", "texturescom:_METALNESS"},
        {"Poliigon_BrickWallReclaimed_8320_BaseColor.jpg", Role::albedo, "texturescom", "texturescom:_BaseColor"},
        {"Poliigon_BrickWallReclaimed_8320_Roughness.jpg", Role::roughness, "texturescom", ""},
        {"Poliigon_BrickWallReclaimed_8320_Metallic.jpg", Role::metalness, "texturescom", ""},
        {"Poliigon_BrickWallReclaimed_8320_NormalGL.png", Role::normal, "texturescom", "texturescom:_NormalGL", NC::gl},
        {"Poliigon_BrickWallReclaimed_8320_Displacement.tiff", Role::height, "texturescom", ""},
        {"Poliigon_BrickWallReclaimed_8320_AmbientOcclusion.jpg", Role::occlusion, "texturescom", ""},
    });
}

TEST(ClassifyName, Megascans) {
    check_rows({
        {"rock_sfjmafua_2K_Albedo.jpg", Role::albedo, "megascans", "megascans:_Albedo"},
        {"rock_sfjmafua_2K_ORT.png", Role::ort, "megascans", "megascans:_ORT"},
        {"rock_sfjmafua_2K_Roughness.jpg", Role::roughness, "megascans", "megascans:_Roughness"},
        {"rock_sfjmafua_2K_Gloss.jpg", Role::gloss, "megascans", "megascans:_Gloss"},
        {"rock_sfjmafua_2K_Specular.jpg", Role::specular, "megascans", "megascans:_Specular"},
        {"rock_sfjmafua_2K_Normal.jpg", Role::normal, "megascans", "megascans:_Normal"},
        {"rock_sfjmafua_2K_Cavity.jpg", Role::cavity, "megascans", "megascans:_Cavity"},
        {"rock_sfjmafua_2K_Bump.jpg", Role::height, "megascans", "megascans:_Bump"},
        {"rock_sfjmafua_4K_Displacement.exr", Role::height, "megascans", "megascans:_Displacement"},
        {"rock_sfjmafua_2K_AO.jpg", Role::occlusion, "megascans", "megascans:_AO"},
        {"plant_tbdpec3r_2K_Opacity.jpg", Role::opacity, "megascans", "megascans:_Opacity"},
        {"plant_tbdpec3r_2K_Translucency.jpg", Role::translucency, "megascans", "megascans:_Translucency"},
    });
}

TEST(ClassifyName, Substance) {
    check_rows({
        {"Chair_BaseColor.png", Role::albedo, "substance", "substance:_BaseColor"},
        {"Chair_Normal.png", Role::normal, "substance", "substance:_Normal"},
        {"Chair_Normal_OpenGL.png", Role::normal, "substance", "substance:_Normal_OpenGL", NC::gl},
        {"Chair_Normal_DirectX.png", Role::normal, "substance", "substance:_Normal_DirectX", NC::dx},
        {"Chair_Height.png", Role::height, "substance", "substance:_Height"},
        {"Chair_Emissive.png", Role::emissive, "substance", "substance:_Emissive"},
        {"Chair_Metallic.png", Role::metalness, "substance", "substance:_Metallic"},
        {"Chair_Roughness.png", Role::roughness, "substance", "substance:_Roughness"},
        {"Chair_OcclusionRoughnessMetallic.png", Role::orm, "substance", "substance:_OcclusionRoughnessMetallic"},
        {"Chair_Mixed_AO.png", Role::occlusion, "substance", "substance:_Mixed_AO"},
    });
}

TEST(ClassifyName, Gltf) {
    check_rows({
        {"DamagedHelmet_baseColor.png", Role::albedo, "gltf", "gltf:baseColor"},
        {"DamagedHelmet_metalRoughness.png", Role::metallic_roughness, "gltf", "gltf:metalRoughness"},
        {"Material_metallicRoughness.png", Role::metallic_roughness, "gltf", "gltf:metallicRoughness"},
        {"DamagedHelmet_occlusion.png", Role::occlusion, "gltf", "gltf:occlusion"},
        {"DamagedHelmet_emissive.png", Role::emissive, "gltf", "gltf:emissive"},
        {"DamagedHelmet_normal.png", Role::normal, "gltf", "gltf:normal"},
    });
}

TEST(ClassifyName, Generic) {
    check_rows({
        {"wood_albedo.png", Role::albedo, "generic", "generic:albedo"},
        {"Wood_Diffuse.tga", Role::albedo, "generic", "generic:diffuse"},
        {"albedo.png", Role::albedo, "generic", "generic:albedo"},
        {"stone_basecolor.png", Role::albedo, "generic", "generic:basecolor"},
        {"stone_rgh.png", Role::roughness, "generic", "generic:rgh"},
        {"stone_smoothness.png", Role::gloss, "generic", "generic:smoothness"},
        {"stone_glossiness.png", Role::gloss, "generic", "generic:glossiness"},
        {"stone_metallic.png", Role::metalness, "generic", "generic:metallic"},
        {"stone_nrm.png", Role::normal, "generic", "generic:nrm"},
        {"stone_normal_gl.png", Role::normal, "generic", "generic:normal_gl", NC::gl},
        {"STONE_NORMAL_DX.PNG", Role::normal, "generic", "generic:normal_dx", NC::dx},
        {"Crate_Normal_GL.png", Role::normal, "generic", "generic:normal_gl", NC::gl},
        {"crate_normal_opengl.png", Role::normal, "generic", "", NC::gl},
        // FreePBR names the convention in the file name: evidence, not only the pixels.
        {"bamboo-wood-semigloss-normal-ogl.png", Role::normal, "generic", "generic:normal_ogl", NC::gl},
        {"bamboo-wood-semigloss-normal-dx.png", Role::normal, "generic", "generic:normal_dx", NC::dx},
        {"stone_height.png", Role::height, "generic", "generic:height"},
        {"stone_emission.png", Role::emissive, "generic", "generic:emission"},
        {"leaf_alpha.png", Role::opacity, "generic", "generic:alpha"},
        {"stone_ORM.png", Role::orm, "generic", "generic:orm"},
        {"Crate_NormalMap.png", Role::normal, "", ""},
    });
}

// Game pipelines: Unreal's "T_<Name>_<Suffix>", two-letter tags, emissive words glued on, a
// variant letter after a capitalised tag.
TEST(ClassifyName, GameAndHandNamed) {
    check_rows({
        {"T_Crate_D.png", Role::albedo, "unreal", "unreal:_D"},
        {"T_Crate_BC.tga", Role::albedo, "unreal", "unreal:_BC"},
        {"T_Crate_N.png", Role::normal, "unreal", "unreal:_N"},
        {"T_Crate_R.png", Role::roughness, "unreal", "unreal:_R"},
        {"T_Crate_M.png", Role::metalness, "unreal", "unreal:_M"},
        {"T_Crate_ORM_2K.png", Role::orm, "unreal", "unreal:_ORM"},
        {"T_Crate_E.png", Role::emissive, "unreal", "unreal:_E"},
        {"T_Crate_AO.png", Role::occlusion, "unreal", "unreal:_AO"},
        {"T_Crate_H.png", Role::height, "unreal", "unreal:_H"},
        {"T_Sand_BC_01.png", Role::albedo, "unreal", "unreal:_BC"},  // a variant number after the tag
        // Megascans' own Unreal export keeps its family (a resolution before the tag).
        {"T_tbdpec3r_4K_N.png", Role::normal, "megascans", "megascans:_N"},
        {"Crate_BC.png", Role::albedo, "generic", "generic:_BC"},
        {"crate_nm_2k.png", Role::normal, "generic", "generic:_NM"},
        {"Crate_NO.png", Role::normal, "generic", "generic:_NO"},
        {"Crate_RO.png", Role::roughness, "generic", "generic:_RO"},
        {"Crate_MT.png", Role::metalness, "generic", "generic:_MT"},
        {"Crate_EM.png", Role::emissive, "generic", "generic:_EM"},
        {"Crate_OP.png", Role::opacity, "generic", "generic:_OP"},
        {"LampLights.png", Role::emissive, "generic", "generic:Lights (glued)"},
        {"LampGlow.png", Role::emissive, "generic", "generic:glow"},
        {"Lamp_Illum.png", Role::emissive, "generic", "generic:illum"},
        {"Rock_DISPa.jpg", Role::height, "texturescom", "texturescom:_DISP"},
        {"Rock_NRMb_2K.jpg", Role::normal, "texturescom", "texturescom:_NRM"},
    });
    // Where a short tag would be a word, it is none: not at the end, without the T prefix, a
    // lone letter, "Lights" apart from the name, lower-case "no".
    for (const std::string file : {"Crate_D.png", "Crate_M.png", "T_Crate_D_Old.png", "Crate_BC_Old.png",
                                   "Street_Lights.png", "crate_no.png", "Rock_DISPab.jpg"})
        EXPECT_FALSE(classify_name(file)) << file;
    EXPECT_EQ(classify_name("Ro_Crate_Diffuse.png")->role, Role::albedo) << "the tag nearest the end";
}

// Material names that contain role words: the tag nearest the end decides.
TEST(ClassifyName, NameTraps) {
    check_rows({
        {"metal_plate_diff_2k.jpg", Role::albedo, "polyhaven", "polyhaven:_diff_"},
        {"metal_plate_diff_1k.png", Role::albedo, "polyhaven", ""},
        {"rough_plaster_brick_rough_1k.jpg", Role::roughness, "polyhaven", ""},
        {"Rusty_Metal_Roughness.png", Role::roughness, "", ""},  // not metallicRoughness
        {"RustyMetal_Roughness.png", Role::roughness, "", ""},
        {"MetalPlates006_1K-PNG_Roughness.png", Role::roughness, "ambientcg", ""},
        {"Normal_Concrete_2K_Albedo.jpg", Role::albedo, "megascans", ""},
        {"Rough_Rock_2K_Normal.jpg", Role::normal, "", ""},
        {"Sphere_Tiles_1K-PNG_Color.png", Role::albedo, "ambientcg", ""},
        {"Gloss_Paint_Roughness.png", Role::roughness, "", ""},
        {"Diffuse_Marble_nor_gl_1k.png", Role::normal, "polyhaven", "", NC::gl},
        {"Alpha_Brick_COL_2K.jpg", Role::albedo, "texturescom", ""},
        {"Opacity_Glass_AO_2K.jpg", Role::occlusion, "texturescom", ""},
        // A packed name needs its camel-case word: separated words are separate tags.
        {"Chair_Occlusion_Roughness_Metallic.png", Role::metalness, "", ""},
    });
}

TEST(ClassifyName, NotClassified) {
    for (const std::string file : {
             "Bricks059.png",               // ambientCG preview: no role tag
             "Bricks059_1K-PNG.usdc",       // not an image
             "Bricks059_1K-PNG.mtlx",       // not an image
             "Bricks059_1K-PNG_Color.txt",  // a role tag, but not an image
             "Bricks059_PREVIEW.jpg",       // clutter
             "rock_sfjmafua_Preview.png",
             "WoodFine0012_Sphere.png",
             "Concrete_Normal_thumbnail.jpg",  // clutter wins over a role word
             "Mat_mask_id.png",
             "brick_wall_001_1k.jpg",
             "scene.blend",
         })
        EXPECT_FALSE(classify_name(file).has_value()) << file;
}

// ---------------------------------------------------------------------------------------------
// material_stem, resolution_hint

TEST(MaterialStem, Table) {
    const std::vector<std::pair<std::string, std::string>> table{
        {"Bricks059_1K-PNG_Color.png", "Bricks059"},
        {"Bricks059_2K-JPG_NormalDX.jpg", "Bricks059"},
        {"brick_wall_001_nor_gl_1k.exr", "brick_wall_001"},
        {"metal_plate_diff_2k.jpg", "metal_plate"},
        {"aerial_rocks_02_arm_4k.png", "aerial_rocks_02"},
        {"Concrete0012_COL_VAR1_2K.jpg", "Concrete0012"},
        {"rock_sfjmafua_2K_Albedo.jpg", "rock_sfjmafua"},
        {"DamagedHelmet_baseColor.png", "DamagedHelmet"},
        {"WoodFloorNormal.png", "WoodFloor"},
        {"Chair_Normal_OpenGL.png", "Chair"},
        {"Chair_OcclusionRoughnessMetallic.png", "Chair"},
        {"Poliigon_BrickWallReclaimed_8320_BaseColor.jpg", "Poliigon_BrickWallReclaimed_8320"},
        {"textures/Wood-Planks 2K_Diffuse.png", "Wood_Planks"},
        {"albedo.png", ""},
        {"NormalGL.png", ""},
        {"Bricks059.png", "Bricks059"},
        {"Bricks059_1K-PNG.usdc", "Bricks059"},
        {"rock_sfjmafua_Preview.png", "rock_sfjmafua"},
    };
    for (const auto& [file, stem] : table) EXPECT_EQ(material_stem(file), stem) << file;
}

TEST(ResolutionHint, Table) {
    const std::vector<std::pair<std::string, int>> table{
        {"Bricks059_1K-PNG_Color.png", 1024}, {"rock_sfjmafua_2K_Albedo.jpg", 2048},
        {"WoodFine0012_GLOSS_3K.jpg", 3072},  {"aerial_rocks_02_arm_4k.png", 4096},
        {"brick_diff_8k.jpg", 8192},          {"Cliff_16K_Albedo.exr", 16384},
        {"Wood_Color_1024.png", 1024},        {"Wood_Color_512.png", 512},
        {"Wood_Color_2048px.png", 2048},      {"Wood_Color_4096x4096.png", 4096},
        {"Bricks059_Color.png", 0},           {"brick_wall_001_diff.png", 0},  // catalogue numbers are not sizes
        {"Metal_600_Color.png", 0},           {"Tiles059_Color.png", 0},
        {"Chair_Normal_DirectX.png", 0},
    };
    for (const auto& [file, px] : table) EXPECT_EQ(resolution_hint(file), px) << file;
}

// ---------------------------------------------------------------------------------------------
// discover_set

using HeaderMap = std::map<std::string, HeaderInfo>;

std::function<std::optional<HeaderInfo>(const std::string&)> headers(HeaderMap m) {
    return [m = std::move(m)](const std::string& f) -> std::optional<HeaderInfo> {
        const auto it = m.find(f);
        if (it == m.end()) return std::nullopt;
        return it->second;
    };
}
const auto kNoHeaders = headers({});

ChoicePolicy policy(NC preferred = NC::gl, int max_size = 0) {
    ChoicePolicy p;
    p.preferred_normal = preferred;
    p.max_size = max_size;
    return p;
}

const RoleChoice* choice(const SetDiscovery& d, Role r) {
    for (const auto& c : d.choices)
        if (c.role == r) return &c;
    return nullptr;
}

std::string chosen(const SetDiscovery& d, Role r) {
    const auto* c = choice(d, r);
    return c ? c->chosen.file : std::string("<none>");
}

std::vector<std::string> choice_roles(const SetDiscovery& d) {
    std::vector<std::string> out;
    for (const auto& c : d.choices) out.emplace_back(role_name(c.role));
    return out;
}

// "role<-file[channel]" (or "~" for inverted) per routed role, in order: routing
// (material/routing) over the chosen files, a file's channels from its header, else its role's.
std::vector<Role> routed_roles() {
    std::vector<Role> roles;
    for (int i = 0; i < kOutputRoleCount; ++i) roles.push_back(static_cast<Role>(i));
    roles.push_back(Role::translucency);
    return roles;
}
std::vector<std::pair<Role, Route>> routes(const SetDiscovery& d) {
    auto channels = [&](Role r) {
        for (const auto& c : d.choices)
            if (c.role == r) return c.chosen.header.channels > 0 ? c.chosen.header.channels : traits(r).channels;
        return 0;
    };
    std::vector<std::pair<Role, Route>> out;
    for (const Role r : routed_roles())
        if (const auto route = route_of(r, channels)) out.emplace_back(r, *route);
    return out;
}
std::string chosen_file(const SetDiscovery& d, Role r) {
    for (const auto& c : d.choices)
        if (c.role == r) return c.chosen.file;
    return "";
}
std::vector<std::string> sources(const SetDiscovery& d) {
    std::vector<std::string> out;
    for (const auto& [role, s] : routes(d)) {
        std::string e = std::string(role_name(role)) + "<-" + (s.invert ? "~" : "") + chosen_file(d, s.from);
        // Appended piece by piece: GCC 12 at -O3 reports `"[" + std::string` as an overlapping
        // memcpy (a false -Wrestrict).
        if (s.channel >= 0) e.append("[").append(1, "RGB"[s.channel]).append("]");
        e.append("(").append(role_name(s.from)).append(")");
        out.push_back(e);
    }
    return out;
}

// "CODE role file" per finding, in order.
std::vector<std::string> finding_keys(const SetDiscovery& d) {
    std::vector<std::string> out;
    for (const auto& f : d.findings) out.push_back(f.code + " " + f.role + " " + f.file);
    return out;
}

const Finding* finding(const SetDiscovery& d, std::string_view code, std::string_view role) {
    for (const auto& f : d.findings)
        if (f.code == code && f.role == role) return &f;
    return nullptr;
}

void expect_all_info(const SetDiscovery& d) {
    for (const auto& f : d.findings) EXPECT_EQ(f.severity, Severity::info) << f.message;
}

TEST(DiscoverSet, AmbientCG) {
    const std::vector<std::string> files{
        "Bricks059_1K-PNG_Color.png",
        "Bricks059_1K-PNG_NormalGL.png",
        "Bricks059_1K-PNG_NormalDX.png",
        "Bricks059_1K-PNG_Roughness.png",
        "Bricks059_1K-PNG_AmbientOcclusion.png",
        "Bricks059_1K-PNG_Displacement.png",
        "Bricks059.png",
        "Bricks059_1K-PNG.usdc",
        "Bricks059_1K-PNG.mtlx",
    };
    const auto d = discover_set(files, kNoHeaders, policy(NC::gl));
    EXPECT_EQ(d.convention, "ambientcg");
    EXPECT_THAT(choice_roles(d), ElementsAre("albedo", "normal", "roughness", "occlusion", "height"));
    EXPECT_EQ(chosen(d, Role::normal), "Bricks059_1K-PNG_NormalGL.png");
    EXPECT_EQ(choice(d, Role::normal)->chosen.match.normal, NC::gl);
    ASSERT_EQ(choice(d, Role::normal)->rejected.size(), 1u);
    EXPECT_EQ(choice(d, Role::normal)->rejected[0].file, "Bricks059_1K-PNG_NormalDX.png");
    EXPECT_THAT(sources(d), ElementsAre("albedo<-Bricks059_1K-PNG_Color.png(albedo)",
                                        "normal<-Bricks059_1K-PNG_NormalGL.png(normal)",
                                        "roughness<-Bricks059_1K-PNG_Roughness.png(roughness)",
                                        "occlusion<-Bricks059_1K-PNG_AmbientOcclusion.png(occlusion)",
                                        "height<-Bricks059_1K-PNG_Displacement.png(height)"));
    // The untagged "<id>.png" beside "<id>_1K-PNG_*" maps is ambientCG's preview render: the
    // set's preview, no map and no unrecognized file.
    EXPECT_THAT(finding_keys(d),
                ElementsAre("AMBIGUOUS_MAP normal Bricks059_1K-PNG_NormalGL.png",
                            "UNRECOGNIZED_FILE  Bricks059_1K-PNG.mtlx", "UNRECOGNIZED_FILE  Bricks059_1K-PNG.usdc"));
    ASSERT_TRUE(d.preview.has_value());
    EXPECT_EQ(d.preview->file, "Bricks059.png");
    EXPECT_EQ(d.preview->match.role, Role::preview);
    EXPECT_EQ(d.preview->match.rule, "ambientcg:<id>.png (the vendor's preview)");
    expect_all_info(d);
    const auto* amb = finding(d, code::ambiguous_map, "normal");
    ASSERT_NE(amb, nullptr);
    EXPECT_THAT(amb->message, HasSubstr("Bricks059_1K-PNG_NormalDX.png"));
    EXPECT_THAT(amb->message, HasSubstr("preset"));
    EXPECT_EQ(mf::to_json(amb->figures).at("chosen"), "Bricks059_1K-PNG_NormalGL.png");
    EXPECT_EQ(mf::to_json(amb->figures).at("candidates"),
              nlohmann::json({"Bricks059_1K-PNG_NormalGL.png", "Bricks059_1K-PNG_NormalDX.png"}));
    EXPECT_THAT(d.findings[1].message, HasSubstr("not an image"));
}

TEST(DiscoverSet, AmbientCGOlderNamesStillAmbientCG) {
    // Pre-2021 names: only _Color is distinctive, the rest is shared with other families.
    const auto d = discover_set({"Bricks059_2K_Color.jpg", "Bricks059_2K_Normal.jpg", "Bricks059_2K_Roughness.jpg",
                                 "Bricks059_2K_Displacement.jpg"},
                                kNoHeaders, policy());
    EXPECT_EQ(d.convention, "ambientcg");
    EXPECT_EQ(choice(d, Role::normal)->chosen.match.normal, NC::unknown);
    EXPECT_TRUE(d.findings.empty());
}

TEST(DiscoverSet, PolyHavenPackedAndDedicated) {
    const std::vector<std::string> files{
        "brick_wall_001_diff_1k.jpg",  "brick_wall_001_nor_gl_1k.exr", "brick_wall_001_nor_dx_1k.exr",
        "brick_wall_001_rough_1k.exr", "brick_wall_001_arm_1k.exr",    "brick_wall_001_ao_1k.jpg",
        "brick_wall_001_disp_1k.png",
    };
    const auto d = discover_set(files, kNoHeaders, policy(NC::gl));
    EXPECT_EQ(d.convention, "polyhaven");
    EXPECT_THAT(choice_roles(d), ElementsAre("albedo", "normal", "roughness", "occlusion", "height", "orm"));
    EXPECT_THAT(sources(d), ElementsAre("albedo<-brick_wall_001_diff_1k.jpg(albedo)",
                                        "normal<-brick_wall_001_nor_gl_1k.exr(normal)",
                                        "roughness<-brick_wall_001_rough_1k.exr(roughness)",
                                        "metalness<-brick_wall_001_arm_1k.exr[B](orm)",
                                        "occlusion<-brick_wall_001_ao_1k.jpg(occlusion)",
                                        "height<-brick_wall_001_disp_1k.png(height)"));
    EXPECT_THAT(finding_keys(d), ElementsAre("AMBIGUOUS_MAP normal brick_wall_001_nor_gl_1k.exr",
                                             "AMBIGUOUS_MAP roughness brick_wall_001_rough_1k.exr",
                                             "AMBIGUOUS_MAP occlusion brick_wall_001_ao_1k.jpg"));
    const auto* r = finding(d, code::ambiguous_map, "roughness");
    ASSERT_NE(r, nullptr);
    EXPECT_THAT(r->message, HasSubstr("dedicated roughness map beats the packed orm"));
    EXPECT_EQ(mf::to_json(r->figures).at("candidates"),
              nlohmann::json({"brick_wall_001_rough_1k.exr", "brick_wall_001_arm_1k.exr"}));
    expect_all_info(d);

    // Preferring DX picks the other normal.
    const auto dx = discover_set(files, kNoHeaders, policy(NC::dx));
    EXPECT_EQ(chosen(dx, Role::normal), "brick_wall_001_nor_dx_1k.exr");
    EXPECT_EQ(mf::to_json(finding(dx, code::ambiguous_map, "normal")->figures).at("chosen"),
              "brick_wall_001_nor_dx_1k.exr");
}

TEST(DiscoverSet, PolyHavenArmOnlyFeedsThreeRoles) {
    const auto d = discover_set({"aerial_rocks_02_diff_4k.png", "aerial_rocks_02_nor_gl_4k.png",
                                 "aerial_rocks_02_arm_4k.png"},
                                kNoHeaders, policy());
    EXPECT_THAT(sources(d), ElementsAre("albedo<-aerial_rocks_02_diff_4k.png(albedo)",
                                        "normal<-aerial_rocks_02_nor_gl_4k.png(normal)",
                                        "roughness<-aerial_rocks_02_arm_4k.png[G](orm)",
                                        "metalness<-aerial_rocks_02_arm_4k.png[B](orm)",
                                        "occlusion<-aerial_rocks_02_arm_4k.png[R](orm)"));
    EXPECT_TRUE(d.findings.empty());
}

TEST(DiscoverSet, TexturesComLegacy) {
    const std::vector<std::string> files{
        "Concrete0012_COL_VAR2_2K.jpg", "Concrete0012_COL_VAR1_2K.jpg", "Concrete0012_NRM_2K.jpg",
        "Concrete0012_NRM16_2K.tif",    "Concrete0012_GLOSS_2K.jpg",    "Concrete0012_REFL_2K.jpg",
        "Concrete0012_DISP_2K.jpg",     "Concrete0012_DISP16_2K.tif",   "Concrete0012_AO_2K.jpg",
        "Concrete0012_Preview1.png",
    };
    const auto d = discover_set(files, kNoHeaders, policy());
    EXPECT_EQ(d.convention, "texturescom");
    EXPECT_THAT(choice_roles(d), ElementsAre("albedo", "normal", "occlusion", "height", "gloss", "specular"));
    EXPECT_EQ(chosen(d, Role::albedo), "Concrete0012_COL_VAR1_2K.jpg");
    EXPECT_EQ(chosen(d, Role::normal), "Concrete0012_NRM16_2K.tif");
    EXPECT_EQ(chosen(d, Role::height), "Concrete0012_DISP16_2K.tif");
    EXPECT_THAT(sources(d),
                ElementsAre("albedo<-Concrete0012_COL_VAR1_2K.jpg(albedo)", "normal<-Concrete0012_NRM16_2K.tif(normal)",
                            "roughness<-~Concrete0012_GLOSS_2K.jpg(gloss)",
                            "occlusion<-Concrete0012_AO_2K.jpg(occlusion)",
                            "height<-Concrete0012_DISP16_2K.tif(height)"));
    EXPECT_TRUE(routes(d)[2].second.invert);
    EXPECT_THAT(finding_keys(d), ElementsAre("AMBIGUOUS_MAP albedo Concrete0012_COL_VAR1_2K.jpg",
                                             "AMBIGUOUS_MAP normal Concrete0012_NRM16_2K.tif",
                                             "AMBIGUOUS_MAP height Concrete0012_DISP16_2K.tif"));
    EXPECT_THAT(finding(d, code::ambiguous_map, "albedo")->message, HasSubstr("by name"));
    EXPECT_THAT(finding(d, code::ambiguous_map, "normal")->message, HasSubstr("tif"));
    // The vendor's "_Preview1" render of the material it names: the set's preview.
    ASSERT_TRUE(d.preview.has_value());
    EXPECT_EQ(d.preview->file, "Concrete0012_Preview1.png");
    EXPECT_EQ(d.preview->match.rule, "generic:_Preview1 (a preview image)");
}

TEST(DiscoverSet, MegascansRoughnessBeatsGloss) {
    const std::vector<std::string> files{
        "rock_sfjmafua_2K_Albedo.jpg", "rock_sfjmafua_2K_Normal.jpg", "rock_sfjmafua_2K_Roughness.jpg",
        "rock_sfjmafua_2K_Gloss.jpg",  "rock_sfjmafua_2K_Cavity.jpg", "rock_sfjmafua_2K_Displacement.exr",
        "rock_sfjmafua_2K_Bump.jpg",   "rock_sfjmafua_2K_AO.jpg",     "rock_sfjmafua_2K_Specular.jpg",
        "rock_sfjmafua_Preview.png",   "rock_sfjmafua.json",
    };
    const auto d = discover_set(files, kNoHeaders, policy());
    EXPECT_EQ(d.convention, "megascans");
    EXPECT_THAT(choice_roles(d),
                ElementsAre("albedo", "normal", "roughness", "occlusion", "height", "gloss", "specular", "cavity"));
    EXPECT_EQ(choice(d, Role::normal)->chosen.match.normal, NC::unknown);
    EXPECT_THAT(sources(d), ElementsAre("albedo<-rock_sfjmafua_2K_Albedo.jpg(albedo)",
                                        "normal<-rock_sfjmafua_2K_Normal.jpg(normal)",
                                        "roughness<-rock_sfjmafua_2K_Roughness.jpg(roughness)",
                                        "occlusion<-rock_sfjmafua_2K_AO.jpg(occlusion)",
                                        "height<-rock_sfjmafua_2K_Displacement.exr(height)"));
    EXPECT_THAT(finding_keys(d), ElementsAre("AMBIGUOUS_MAP roughness rock_sfjmafua_2K_Roughness.jpg",
                                             "AMBIGUOUS_MAP height rock_sfjmafua_2K_Displacement.exr",
                                             "UNRECOGNIZED_FILE  rock_sfjmafua.json"));
    ASSERT_TRUE(d.preview.has_value());  // by its name here: no sidecar was read
    EXPECT_EQ(d.preview->file, "rock_sfjmafua_Preview.png");
    const auto* r = finding(d, code::ambiguous_map, "roughness");
    EXPECT_THAT(r->message, HasSubstr("roughness map beats a gloss map"));
    EXPECT_EQ(mf::to_json(r->figures).at("candidates"),
              nlohmann::json({"rock_sfjmafua_2K_Roughness.jpg", "rock_sfjmafua_2K_Gloss.jpg"}));
}

TEST(DiscoverSet, MegascansOrtBlueIsTranslucencyNeverMetalness) {
    const auto d = discover_set({"plant_tbdpec3r_2K_Albedo.jpg", "plant_tbdpec3r_2K_Normal.jpg",
                                 "plant_tbdpec3r_2K_ORT.png", "plant_tbdpec3r_2K_Opacity.jpg"},
                                kNoHeaders, policy());
    EXPECT_EQ(d.convention, "megascans");
    EXPECT_THAT(sources(d), ElementsAre("albedo<-plant_tbdpec3r_2K_Albedo.jpg(albedo)",
                                        "normal<-plant_tbdpec3r_2K_Normal.jpg(normal)",
                                        "roughness<-plant_tbdpec3r_2K_ORT.png[G](ort)",
                                        "occlusion<-plant_tbdpec3r_2K_ORT.png[R](ort)",
                                        "opacity<-plant_tbdpec3r_2K_Opacity.jpg(opacity)",
                                        "translucency<-plant_tbdpec3r_2K_ORT.png[B](ort)"));
    for (const auto& [role, s] : routes(d)) EXPECT_NE(role, Role::metalness);
    EXPECT_TRUE(d.findings.empty());
}

// Poliigon ships BUMP (detail for bump mapping) beside DISP (the height): the displacement is the
// height whatever the sizes (MRPH95/HicSum's FabricLeatherBuffaloRustic001 took BUMP_2K by name order).
TEST(DiscoverSet, DisplacementBeatsBumpForHeight) {
    const auto d = discover_set({"Leather_COL_2K.jpg", "Leather_BUMP_2K.jpg", "Leather_DISP_1K.jpg"}, kNoHeaders,
                                policy());
    EXPECT_THAT(sources(d), ElementsAre("albedo<-Leather_COL_2K.jpg(albedo)", "height<-Leather_DISP_1K.jpg(height)"));
    const auto* f = finding(d, code::ambiguous_map, "height");
    ASSERT_NE(f, nullptr);
    EXPECT_THAT(f->message, HasSubstr("a displacement map is the height; a bump map is detail for bump mapping"));
}

TEST(DiscoverSet, MegascansDedicatedBeatsOrt) {
    const auto d = discover_set({"plant_x_2K_ORT.png", "plant_x_2K_Roughness.jpg", "plant_x_2K_Translucency.jpg",
                                 "plant_x_2K_Gloss.jpg"},
                                kNoHeaders, policy());
    EXPECT_THAT(sources(d),
                ElementsAre("roughness<-plant_x_2K_Roughness.jpg(roughness)", "occlusion<-plant_x_2K_ORT.png[R](ort)",
                            "translucency<-plant_x_2K_Translucency.jpg(translucency)"));
    EXPECT_THAT(finding_keys(d), ElementsAre("AMBIGUOUS_MAP roughness plant_x_2K_Roughness.jpg",
                                             "AMBIGUOUS_MAP translucency plant_x_2K_Translucency.jpg"));
    EXPECT_EQ(mf::to_json(finding(d, code::ambiguous_map, "roughness")->figures).at("candidates"),
              nlohmann::json({"plant_x_2K_Roughness.jpg", "plant_x_2K_ORT.png", "plant_x_2K_Gloss.jpg"}));
}

TEST(DiscoverSet, PackedRoughnessBeatsGloss) {
    const auto d = discover_set({"plant_x_2K_ORT.png", "plant_x_2K_Gloss.jpg"}, kNoHeaders, policy());
    EXPECT_THAT(sources(d),
                ElementsAre("roughness<-plant_x_2K_ORT.png[G](ort)", "occlusion<-plant_x_2K_ORT.png[R](ort)",
                            "translucency<-plant_x_2K_ORT.png[B](ort)"));
    EXPECT_THAT(finding_keys(d), ElementsAre("AMBIGUOUS_MAP roughness plant_x_2K_ORT.png"));
}

TEST(DiscoverSet, SubstancePacked) {
    const auto d = discover_set({"Chair_BaseColor.png", "Chair_Normal_OpenGL.png",
                                 "Chair_OcclusionRoughnessMetallic.png", "Chair_Height.png", "Chair_Emissive.png",
                                 "Chair_Mixed_AO.png"},
                                kNoHeaders, policy(NC::dx));
    EXPECT_EQ(d.convention, "substance");
    EXPECT_EQ(choice(d, Role::normal)->chosen.match.normal, NC::gl);
    EXPECT_THAT(sources(d),
                ElementsAre("albedo<-Chair_BaseColor.png(albedo)", "normal<-Chair_Normal_OpenGL.png(normal)",
                            "roughness<-Chair_OcclusionRoughnessMetallic.png[G](orm)",
                            "metalness<-Chair_OcclusionRoughnessMetallic.png[B](orm)",
                            "occlusion<-Chair_Mixed_AO.png(occlusion)", "height<-Chair_Height.png(height)",
                            "emissive<-Chair_Emissive.png(emissive)"));
    EXPECT_THAT(finding_keys(d), ElementsAre("AMBIGUOUS_MAP occlusion Chair_Mixed_AO.png"));
}

TEST(DiscoverSet, SubstanceSeparateMapsBeatPoliigonOnLayout) {
    // Every name here is also a current Poliigon name; no resolution tag points to Substance.
    const auto d = discover_set({"Chair_BaseColor.png", "Chair_Normal.png", "Chair_Roughness.png", "Chair_Metallic.png",
                                 "Chair_Height.png"},
                                kNoHeaders, policy());
    EXPECT_EQ(d.convention, "substance");
    const auto p = discover_set({"Poliigon_BrickWall_7612_BaseColor_2K.jpg", "Poliigon_BrickWall_7612_Normal_2K.png",
                                 "Poliigon_BrickWall_7612_Roughness_2K.jpg", "Poliigon_BrickWall_7612_Metallic_2K.jpg"},
                                kNoHeaders, policy());
    EXPECT_EQ(p.convention, "texturescom");
}

TEST(DiscoverSet, Gltf) {
    const auto d = discover_set({"DamagedHelmet_baseColor.png", "DamagedHelmet_metalRoughness.png",
                                 "DamagedHelmet_normal.png", "DamagedHelmet_occlusion.png",
                                 "DamagedHelmet_emissive.png", "DamagedHelmet.gltf"},
                                kNoHeaders, policy());
    EXPECT_EQ(d.convention, "gltf");
    EXPECT_THAT(sources(d),
                ElementsAre("albedo<-DamagedHelmet_baseColor.png(albedo)", "normal<-DamagedHelmet_normal.png(normal)",
                            "roughness<-DamagedHelmet_metalRoughness.png[G](metallic_roughness)",
                            "metalness<-DamagedHelmet_metalRoughness.png[B](metallic_roughness)",
                            "occlusion<-DamagedHelmet_occlusion.png(occlusion)",
                            "emissive<-DamagedHelmet_emissive.png(emissive)"));
    // metallicRoughness's R is unused, so occlusion had a single candidate.
    EXPECT_THAT(finding_keys(d), ElementsAre("UNRECOGNIZED_FILE  DamagedHelmet.gltf"));
}

TEST(DiscoverSet, MixedNamesAreGeneric) {
    const auto d = discover_set({"wood_albedo.png", "wood_normal.png", "wood_rough.png"}, kNoHeaders, policy());
    EXPECT_EQ(d.convention, "generic");
    EXPECT_THAT(choice_roles(d), ElementsAre("albedo", "normal", "roughness"));
    // No map: a preview of nothing stays unrecognized; a readme is read for the provenance
    // (material/provenance.hpp), not reported here.
    const auto none = discover_set({"readme.txt", "preview.jpg"}, kNoHeaders, policy());
    EXPECT_EQ(none.convention, "generic");
    EXPECT_TRUE(none.choices.empty());
    EXPECT_TRUE(routes(none).empty());
    EXPECT_FALSE(none.preview.has_value());
    EXPECT_THAT(finding_keys(none), ElementsAre("UNRECOGNIZED_FILE  preview.jpg"));
}

// ---------------------------------------------------------------------------------------------
// Ranking among candidates of one role

struct ChoiceCase {
    std::string name;
    std::vector<std::string> files;
    HeaderMap header;
    ChoicePolicy policy;
    Role role;
    std::string expected;
    std::string why;  // a piece of the AMBIGUOUS_MAP message
};

TEST(DiscoverSet, ChoiceTable) {
    auto hdr = [](int size, int depth = 8) {
        HeaderInfo h;
        h.width = h.height = size;
        h.channels = 3;
        h.bit_depth = depth;
        return h;
    };
    const std::vector<ChoiceCase> table{
        {"two resolutions: the largest",
         {"Bricks059_1K-PNG_Color.png", "Bricks059_2K-PNG_Color.png"},
         {},
         policy(),
         Role::albedo,
         "Bricks059_2K-PNG_Color.png",
         "largest (2048 px vs 1024 px)"},
        {"two resolutions: the largest within the preset's limit",
         {"Bricks059_1K-PNG_Color.png", "Bricks059_2K-PNG_Color.png"},
         {},
         policy(NC::gl, 1024),
         Role::albedo,
         "Bricks059_1K-PNG_Color.png",
         "size limit of 1024"},
        {"all above the limit: the smallest",
         {"Cliff_4K_Albedo.jpg", "Cliff_8K_Albedo.jpg"},
         {},
         policy(NC::gl, 2048),
         Role::albedo,
         "Cliff_4K_Albedo.jpg",
         "smallest above the size limit"},
        {"header size beats the name and the format",
         {"Tiles_Albedo.png", "Tiles_Albedo.tga"},
         {{"Tiles_Albedo.png", hdr(1024)}, {"Tiles_Albedo.tga", hdr(2048)}},
         policy(),
         Role::albedo,
         "Tiles_Albedo.tga",
         "largest (2048 px"},
        {"header size beats a misleading name hint",
         {"Tiles_2K_Albedo.jpg", "Tiles_1K_Albedo.jpg"},
         {{"Tiles_2K_Albedo.jpg", hdr(512)}, {"Tiles_1K_Albedo.jpg", hdr(1024)}},
         policy(),
         Role::albedo,
         "Tiles_1K_Albedo.jpg",
         "largest"},
        {"JPEG and PNG of one size: lossless",
         {"Bricks059_1K-JPG_Color.jpg", "Bricks059_1K-PNG_Color.png"},
         {},
         policy(),
         Role::albedo,
         "Bricks059_1K-PNG_Color.png",
         "png"},
        {"EXR over PNG",
         {"brick_wall_001_rough_1k.png", "brick_wall_001_rough_1k.exr"},
         {},
         policy(),
         Role::roughness,
         "brick_wall_001_rough_1k.exr",
         "exr"},
        {"higher bit depth from the header",
         {"Rock_Height.png", "Rock_Height_b.png"},
         {{"Rock_Height.png", hdr(1024, 8)}, {"Rock_Height_b.png", hdr(1024, 16)}},
         policy(),
         Role::height,
         "Rock_Height_b.png",
         "bit depth (16 vs 8)"},
        {"higher bit depth from the name",
         {"Rock_Height_8bit.png", "Rock_Height_16bit.png"},
         {},
         policy(),
         Role::height,
         "Rock_Height_16bit.png",
         "bit depth"},
        {"GL and DX, preset gl",
         {"Bricks059_1K-PNG_NormalDX.png", "Bricks059_1K-PNG_NormalGL.png"},
         {},
         policy(NC::gl),
         Role::normal,
         "Bricks059_1K-PNG_NormalGL.png",
         "preset"},
        {"GL and DX, preset dx",
         {"Bricks059_1K-PNG_NormalDX.png", "Bricks059_1K-PNG_NormalGL.png"},
         {},
         policy(NC::dx),
         Role::normal,
         "Bricks059_1K-PNG_NormalDX.png",
         "preset"},
        {"convention beats size",
         {"Bricks059_1K-PNG_NormalGL.png", "Bricks059_4K-PNG_NormalDX.png"},
         {},
         policy(NC::gl),
         Role::normal,
         "Bricks059_1K-PNG_NormalGL.png",
         "preset"},
        {"a stated convention beats an unknown one",
         {"Bricks059_1K-PNG_Normal.png", "Bricks059_1K-PNG_NormalGL.png"},
         {},
         policy(NC::dx),
         Role::normal,
         "Bricks059_1K-PNG_NormalGL.png",
         "states a normal convention"},
        {"all equal: byte-wise name",
         {"Concrete0012_COL_VAR2_2K.jpg", "Concrete0012_COL_VAR1_2K.jpg"},
         {},
         policy(),
         Role::albedo,
         "Concrete0012_COL_VAR1_2K.jpg",
         "by name"},
    };
    for (const auto& c : table) {
        SCOPED_TRACE(c.name);
        const auto d = discover_set(c.files, headers(c.header), c.policy);
        EXPECT_EQ(chosen(d, c.role), c.expected);
        const auto* f = finding(d, code::ambiguous_map, role_name(c.role));
        ASSERT_NE(f, nullptr);
        EXPECT_EQ(f->severity, Severity::info);
        EXPECT_EQ(f->file, c.expected);
        EXPECT_EQ(mf::to_json(f->figures).at("chosen"), c.expected);
        EXPECT_EQ(mf::to_json(f->figures).at("candidates").size(), c.files.size());
        EXPECT_THAT(f->message, HasSubstr(c.why));
        for (const auto& file : c.files) EXPECT_THAT(f->message, HasSubstr(file));
        EXPECT_EQ(d.findings.size(), 1u);
        const auto* ch = choice(d, c.role);
        ASSERT_NE(ch, nullptr);
        EXPECT_EQ(ch->rejected.size(), c.files.size() - 1);
    }
}

TEST(DiscoverSet, RejectedAreBestFirstAndHeadersReachTheChoice) {
    HeaderInfo h;
    h.width = 2048;
    h.height = 1024;
    h.bit_depth = 16;
    const auto d = discover_set({"W_1K_Albedo.jpg", "W_4K_Albedo.jpg", "W_2K_Albedo.jpg", "W_2K_Albedo.png"},
                                headers({{"W_2K_Albedo.png", h}}), policy());
    const auto* c = choice(d, Role::albedo);
    ASSERT_NE(c, nullptr);
    EXPECT_EQ(c->chosen.file, "W_4K_Albedo.jpg");
    ASSERT_EQ(c->rejected.size(), 3u);
    EXPECT_EQ(c->rejected[0].file, "W_2K_Albedo.png");
    EXPECT_EQ(c->rejected[0].header.bit_depth, 16);
    EXPECT_EQ(c->rejected[1].file, "W_2K_Albedo.jpg");
    EXPECT_EQ(c->rejected[2].file, "W_1K_Albedo.jpg");
    EXPECT_EQ(c->chosen.match.family, "megascans");
}

TEST(DiscoverSet, DeterministicWhateverTheOrder) {
    std::vector<std::string> files{
        "brick_wall_001_diff_1k.jpg",
        "brick_wall_001_diff_2k.jpg",
        "brick_wall_001_nor_gl_1k.exr",
        "brick_wall_001_nor_dx_1k.exr",
        "brick_wall_001_rough_1k.exr",
        "brick_wall_001_arm_1k.exr",
        "brick_wall_001_ao_1k.jpg",
        "notes.txt",
        "preview.png",
    };
    const auto reference = discover_set(files, kNoHeaders, policy());
    std::mt19937 rng(7);
    for (int i = 0; i < 5; ++i) {
        std::shuffle(files.begin(), files.end(), rng);
        const auto d = discover_set(files, kNoHeaders, policy());
        EXPECT_EQ(d.convention, reference.convention);
        EXPECT_EQ(sources(d), sources(reference));
        ASSERT_EQ(d.findings.size(), reference.findings.size());
        for (size_t k = 0; k < d.findings.size(); ++k)
            EXPECT_EQ(to_json(d.findings[k]), to_json(reference.findings[k]));
    }
}

TEST(DiscoverSet, NullHeaderFunctionIsAllowed) {
    const auto d = discover_set({"Bricks059_1K-PNG_Color.png"}, nullptr, policy());
    EXPECT_EQ(chosen(d, Role::albedo), "Bricks059_1K-PNG_Color.png");
}

TEST(DiscoverSet, PathsInSubfolders) {
    const auto d = discover_set({"textures/Bricks059_1K-PNG_Color.png", "textures/Bricks059_1K-PNG_NormalGL.png",
                                 "Bricks059.png"},
                                kNoHeaders, policy());
    EXPECT_EQ(chosen(d, Role::albedo), "textures/Bricks059_1K-PNG_Color.png");
    EXPECT_EQ(chosen(d, Role::normal), "textures/Bricks059_1K-PNG_NormalGL.png");
    EXPECT_EQ(d.convention, "ambientcg");
}

// ---------------------------------------------------------------------------------------------
// group_files

std::vector<std::string> group_names(const std::vector<FileGroup>& groups) {
    std::vector<std::string> out;
    for (const auto& g : groups) out.push_back(g.name);
    return out;
}

TEST(GroupFiles, FlatFolderOfThreeAmbientCGMaterials) {
    const std::vector<std::string> files{
        "Metal032_1K-PNG_Metalness.png",
        "Bricks059_1K-PNG_Color.png",
        "Ground037_1K-PNG_Color.png",
        "Bricks059_1K-PNG_NormalGL.png",
        "Bricks059.png",
        "Ground037_1K-PNG_Roughness.png",
        "Metal032_1K-PNG_Color.png",
        "Bricks059_1K-PNG.usdc",
        "Ground037.png",
        "preview.jpg",
    };
    const auto g = group_files(files, "in");
    EXPECT_THAT(group_names(g), ElementsAre("Bricks059", "Ground037", "Metal032"));
    ASSERT_EQ(g.size(), 3u);
    // The stray preview joins the first group; files are in byte order.
    EXPECT_THAT(g[0].files, ElementsAre("Bricks059.png", "Bricks059_1K-PNG.usdc", "Bricks059_1K-PNG_Color.png",
                                        "Bricks059_1K-PNG_NormalGL.png", "preview.jpg"));
    EXPECT_THAT(g[1].files,
                ElementsAre("Ground037.png", "Ground037_1K-PNG_Color.png", "Ground037_1K-PNG_Roughness.png"));
    EXPECT_THAT(g[2].files, ElementsAre("Metal032_1K-PNG_Color.png", "Metal032_1K-PNG_Metalness.png"));
}

TEST(GroupFiles, PolyHavenTwoMaterialsWithSharedPrefix) {
    const auto g = group_files({"brick_wall_001_diff_1k.jpg", "brick_wall_001_nor_gl_1k.exr",
                                "brick_wall_002_diff_1k.jpg", "brick_wall_002_rough_1k.jpg", "brick_wall_002.blend",
                                "brick_wall_002_preview.png", "metal_plate_diff_1k.png", "metal_plate_metal_1k.png"},
                               "x");
    EXPECT_THAT(group_names(g), ElementsAre("brick_wall_001", "brick_wall_002", "metal_plate"));
    EXPECT_THAT(g[1].files, ElementsAre("brick_wall_002.blend", "brick_wall_002_diff_1k.jpg",
                                        "brick_wall_002_preview.png", "brick_wall_002_rough_1k.jpg"));
    EXPECT_THAT(g[2].files, ElementsAre("metal_plate_diff_1k.png", "metal_plate_metal_1k.png"));
}

TEST(GroupFiles, LongestPrefixWins) {
    const auto g = group_files({"Tiles01_Color.png", "Tiles012_Color.png", "Tiles012_Preview.jpg",
                                "Tiles01_Preview.jpg"},
                               "x");
    ASSERT_EQ(g.size(), 2u);
    EXPECT_THAT(g[0].files, ElementsAre("Tiles01_Color.png", "Tiles01_Preview.jpg"));
    EXPECT_THAT(g[1].files, ElementsAre("Tiles012_Color.png", "Tiles012_Preview.jpg"));
}

TEST(GroupFiles, RoleOnlyNamesUseTheFallbackName) {
    const auto g = group_files({"albedo.png", "normal.png", "roughness.png", "preview.jpg"}, "Wood");
    ASSERT_EQ(g.size(), 1u);
    EXPECT_EQ(g[0].name, "Wood");
    EXPECT_THAT(g[0].files, ElementsAre("albedo.png", "normal.png", "preview.jpg", "roughness.png"));
    EXPECT_TRUE(group_files({}, "Wood").empty());
}

TEST(GroupFiles, StemsCompareWithoutCaseAndKeepTheFirstSpelling) {
    const auto g = group_files({"Wood_Color.png", "wood_Normal.png", "WOOD_Roughness.png", "Wood-Planks_Color.png",
                                "Wood_Planks_Roughness.png"},
                               "x");
    ASSERT_EQ(g.size(), 2u);
    EXPECT_EQ(g[0].name, "Wood");
    EXPECT_EQ(g[0].files.size(), 3u);
    EXPECT_EQ(g[1].name, "Wood_Planks");
    EXPECT_THAT(g[1].files, ElementsAre("Wood-Planks_Color.png", "Wood_Planks_Roughness.png"));
}

TEST(GroupFiles, MegascansAndGltfMixed) {
    const auto g = group_files({"rock_sfjmafua_2K_Albedo.jpg", "rock_sfjmafua_2K_Normal.jpg",
                                "rock_sfjmafua_Preview.png", "rock_sfjmafua.json", "DamagedHelmet_baseColor.png",
                                "DamagedHelmet_normal.png", "DamagedHelmet.gltf"},
                               "x");
    EXPECT_THAT(group_names(g), ElementsAre("DamagedHelmet", "rock_sfjmafua"));
    EXPECT_EQ(g[0].files.size(), 3u);
    EXPECT_EQ(g[1].files.size(), 4u);
}

}  // namespace
}  // namespace mf
