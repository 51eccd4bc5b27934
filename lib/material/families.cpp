// The naming rules of every family. Sources: each vendor's downloads as they are named (ambientCG
// "<Id>_<res>-<FMT>_<Tag>", Poly Haven "<name>_<tag>_<res>", Textures.com/Poliigon legacy
// "<Name>_<TAG>_<res>" and current "Poliigon_<Name>_<Tag>", Megascans "<id>_<res>_<Tag>" and its
// Unreal export "T_<id>_<res>_<TAG>", Substance Painter's export presets, glTF sample models,
// Unreal's own "T_<Name>_<Suffix>").
#include "material/families.hpp"

namespace mf::naming {
namespace {

using enum Role;
constexpr auto kU = NormalConvention::unknown;
constexpr auto kGL = NormalConvention::gl;
constexpr auto kDX = NormalConvention::dx;

constexpr Rule kAmbientCG[] = {
    {"color", albedo, kU, Case::capital, false, "_Color"},
    {"normal gl", normal, kGL, Case::capital, true, "_NormalGL"},
    {"normal dx", normal, kDX, Case::capital, true, "_NormalDX"},
    {"normal", normal, kU, Case::capital, false, "_Normal"},  // older sets
    {"roughness", roughness, kU, Case::capital, false, "_Roughness"},
    {"metalness", metalness, kU, Case::capital, false, "_Metalness"},
    {"ambient occlusion", occlusion, kU, Case::capital, true, "_AmbientOcclusion"},
    {"displacement", height, kU, Case::capital, false, "_Displacement"},
    {"opacity", opacity, kU, Case::capital, false, "_Opacity"},
    {"emission", emissive, kU, Case::capital, false, "_Emission"},
};

constexpr Rule kPolyHaven[] = {
    {"diff", albedo, kU, Case::lower, false, "_diff_"},
    {"col", albedo, kU, Case::lower, false, "_col_"},
    {"nor gl", normal, kGL, Case::lower, false, "_nor_gl_"},
    {"nor dx", normal, kDX, Case::lower, false, "_nor_dx_"},
    {"nor", normal, kU, Case::lower, false, "_nor_"},
    {"rough", roughness, kU, Case::lower, false, "_rough_"},
    {"arm", orm, kU, Case::lower, false, "_arm_"},
    {"ao", occlusion, kU, Case::lower, false, "_ao_"},
    {"disp", height, kU, Case::lower, false, "_disp_"},
    {"bump", height, kU, Case::lower, false, "_bump_"},
    {"metal", metalness, kU, Case::lower, false, "_metal_"},
    {"spec", specular, kU, Case::lower, false, "_spec_"},
    // Plants and cut-outs: recorded for their role even where no preset packs it.
    {"translucent", translucency, kU, Case::lower, false, "_translucent_", Need::res_after},
    {"alpha", opacity, kU, Case::lower, false, "_alpha_", Need::res_after},
};

// Textures.com / Poliigon: the legacy upper-case tags first, so that "METALNESS" reads as the
// legacy rule rather than the current "Metalness".
constexpr Rule kTexturesCom[] = {
    {"col", albedo, kU, Case::upper, false, "_COL"},
    {"nrm", normal, kU, Case::upper, false, "_NRM"},
    {"nrm16", normal, kU, Case::upper, false, "_NRM16"},
    {"gloss", gloss, kU, Case::upper, false, "_GLOSS"},
    {"refl", specular, kU, Case::upper, false, "_REFL"},
    {"disp", height, kU, Case::upper, false, "_DISP"},
    {"disp16", height, kU, Case::upper, false, "_DISP16"},
    {"bump", height, kU, Case::upper, false, "_BUMP"},
    {"bump16", height, kU, Case::upper, false, "_BUMP16"},
    {"ao", occlusion, kU, Case::upper, false, "_AO"},
    {"metalness", metalness, kU, Case::upper, false, "_METALNESS"},
    {"base color", albedo, kU, Case::capital, true, "_BaseColor"},
    {"normal gl", normal, kGL, Case::capital, true, "_NormalGL"},
    {"normal dx", normal, kDX, Case::capital, true, "_NormalDX"},
    {"normal", normal, kU, Case::capital, false, "_Normal"},
    {"roughness", roughness, kU, Case::capital, false, "_Roughness"},
    {"metallic", metalness, kU, Case::capital, false, "_Metallic"},
    {"metalness", metalness, kU, Case::capital, false, "_Metalness"},
    {"ambient occlusion", occlusion, kU, Case::capital, true, "_AmbientOcclusion"},
    {"displacement", height, kU, Case::capital, false, "_Displacement"},
    {"height", height, kU, Case::capital, false, "_Height"},
};

constexpr Rule kMegascans[] = {
    {"albedo", albedo, kU, Case::capital, false, "_Albedo"},
    {"roughness", roughness, kU, Case::capital, false, "_Roughness"},
    {"gloss", gloss, kU, Case::capital, false, "_Gloss"},
    {"specular", specular, kU, Case::capital, false, "_Specular"},
    {"normal", normal, kU, Case::capital, false, "_Normal"},
    {"cavity", cavity, kU, Case::capital, false, "_Cavity"},
    {"bump", height, kU, Case::capital, false, "_Bump"},
    {"displacement", height, kU, Case::capital, false, "_Displacement"},
    {"ao", occlusion, kU, Case::capital, false, "_AO"},
    {"opacity", opacity, kU, Case::capital, false, "_Opacity"},
    {"translucency", translucency, kU, Case::capital, false, "_Translucency"},
    {"ort", Role::ort, kU, Case::any, false, "_ORT"},  // only Megascans packs ORT
    // Megascans assets named the Unreal way outside Fab ("T_<name>_A/_N/_R/_O/_T/_D"): A is the
    // albedo and D the displacement there, the reverse of Epic's style guide (unreal below:
    // D base color, A opacity). The letters A and D are decided by the pixels as well
    // (discover_set: a colour image is never an opacity mask); O and T are Megascans' own.
    {"o", opacity, kU, Case::upper, false, "_O", Need::unreal_suffix},
    {"t", translucency, kU, Case::upper, false, "_T", Need::unreal_suffix},
    // Fab's current names ("Bracken_Fern_okdr22_4K_BaseColor").
    {"base color", albedo, kU, Case::capital, true, "_BaseColor"},
    // The Unreal export ("T_tbdpec3r_4K_B-O"): B base color, B-O base color with opacity in A,
    // N normal, ORM / ORT packed. Billboard maps ("T_<id>_4K_Billboard_B-O") are clutter.
    {"b o", albedo, kU, Case::upper, false, "_B-O", Need::unreal_texture, true},
    {"b", albedo, kU, Case::upper, false, "_B", Need::unreal_texture},
    {"n", normal, kU, Case::upper, false, "_N", Need::unreal_texture},
    {"orm", orm, kU, Case::upper, false, "_ORM", Need::unreal_texture},
};

// Unreal's texture naming ("T_<Name>_<Suffix>": Epic's and the community style guides, game
// and Marketplace folders): D or BC base color, N or NM normal, R roughness, M metallic (the
// style guides' "mask and/or metallic": a mask map is not grayscale, which NOT_GRAYSCALE says),
// ORM/ARM packed, E emissive, AO occlusion, H height, A opacity, S specular. B is left out: it
// is base color in Megascans' Unreal export (with a resolution before it, above) and bump in
// the style guides. Only with the T prefix and at the end of the name (Need::unreal_suffix).
constexpr Rule kUnreal[] = {
    {"d", albedo, kU, Case::upper, false, "_D", Need::unreal_suffix},
    {"bc", albedo, kU, Case::upper, false, "_BC", Need::unreal_suffix},
    {"n", normal, kU, Case::upper, false, "_N", Need::unreal_suffix},
    {"nm", normal, kU, Case::upper, false, "_NM", Need::unreal_suffix},
    {"r", roughness, kU, Case::upper, false, "_R", Need::unreal_suffix},
    {"m", metalness, kU, Case::upper, false, "_M", Need::unreal_suffix},
    {"orm", orm, kU, Case::upper, false, "_ORM", Need::unreal_suffix},
    {"arm", orm, kU, Case::upper, false, "_ARM", Need::unreal_suffix},
    {"e", emissive, kU, Case::upper, false, "_E", Need::unreal_suffix},
    {"ao", occlusion, kU, Case::upper, false, "_AO", Need::unreal_suffix},
    {"h", height, kU, Case::upper, false, "_H", Need::unreal_suffix},
    {"a", opacity, kU, Case::upper, false, "_A", Need::unreal_suffix},
    {"s", specular, kU, Case::upper, false, "_S", Need::unreal_suffix},
};

// Unity's shaders and the Substance/Unity export templates ("<Name>_MetallicSmoothness",
// "_AlbedoTransparency", "_MaskMap"): Standard/URP metallic, specular and HDRP Lit. The plain
// tags a Unity export writes beside them are listed too, so that such a set votes "unity"
// (its normal maps are +Y: Unity's convention).
constexpr Rule kUnity[] = {
    {"albedo transparency", albedo, kU, Case::any, true, "_AlbedoTransparency", Need::none, true},
    {"metallic smoothness", metallic_smoothness, kU, Case::any, true, "_MetallicSmoothness"},
    {"metallic gloss map", metallic_smoothness, kU, Case::any, true, "_MetallicGlossMap"},
    {"metallic gloss", metallic_smoothness, kU, Case::any, true, "_MetallicGloss"},
    {"specular smoothness", specular_smoothness, kU, Case::any, true, "_SpecularSmoothness"},
    {"spec gloss map", specular_smoothness, kU, Case::any, true, "_SpecGlossMap"},
    {"mask map", mask_map, kU, Case::any, true, "_MaskMap"},
    {"albedo", albedo, kU, Case::capital, false, "_Albedo"},
    {"normal", normal, kU, Case::capital, false, "_Normal"},
    {"occlusion", occlusion, kU, Case::capital, false, "_Occlusion"},
    {"emission", emissive, kU, Case::capital, false, "_Emission"},
    {"height", height, kU, Case::capital, false, "_Height"},
};

constexpr Rule kSubstance[] = {
    {"base color", albedo, kU, Case::capital, false, "_BaseColor"},
    {"normal opengl", normal, kGL, Case::capital, false, "_Normal_OpenGL"},
    {"normal directx", normal, kDX, Case::capital, false, "_Normal_DirectX"},
    {"normal", normal, kU, Case::capital, false, "_Normal"},
    {"height", height, kU, Case::capital, false, "_Height"},
    {"emissive", emissive, kU, Case::capital, false, "_Emissive"},
    {"metallic", metalness, kU, Case::capital, false, "_Metallic"},
    {"roughness", roughness, kU, Case::capital, false, "_Roughness"},
    {"occlusion roughness metallic", orm, kU, Case::capital, true, "_OcclusionRoughnessMetallic"},
    {"mixed ao", occlusion, kU, Case::capital, false, "_Mixed_AO"},
    {"opacity", opacity, kU, Case::capital, false, "_Opacity"},
};

constexpr Rule kGltf[] = {
    {"base color", albedo, kU, Case::lower_initial, true, "baseColor"},
    {"metallic roughness", metallic_roughness, kU, Case::lower_initial, true, "metallicRoughness"},
    {"metal roughness", metallic_roughness, kU, Case::lower_initial, true, "metalRoughness"},
    {"occlusion roughness metallic", orm, kU, Case::lower_initial, true, "occlusionRoughnessMetallic"},
    {"occlusion", occlusion, kU, Case::lower_initial, false, "occlusion"},
    {"emissive", emissive, kU, Case::lower_initial, false, "emissive"},
    {"normal", normal, kU, Case::lower_initial, false, "normal"},
};

// Any case, any separators. Deliberately no "metal roughness" with separators: a roughness map
// of "Rusty_Metal" is named "Rusty_Metal_Roughness".
constexpr Rule kGeneric[] = {
    {"diffuse", albedo, kU, Case::any, false, "diffuse"},
    {"diff", albedo, kU, Case::any, false, "diff"},
    {"albedo", albedo, kU, Case::any, false, "albedo"},
    {"base color", albedo, kU, Case::any, false, "base_color"},
    {"base colour", albedo, kU, Case::any, false, "base_colour"},
    {"basecolor", albedo, kU, Case::any, false, "basecolor"},
    {"base", albedo, kU, Case::any, false, "base"},
    {"col", albedo, kU, Case::any, false, "col"},
    {"color", albedo, kU, Case::any, false, "color"},
    {"colour", albedo, kU, Case::any, false, "colour"},
    {"normal gl", normal, kGL, Case::any, false, "normal_gl"},
    {"normal opengl", normal, kGL, Case::any, false, "normal_opengl"},
    {"normal ogl", normal, kGL, Case::any, false, "normal_ogl"},  // FreePBR's "-normal-ogl"
    {"normal dx", normal, kDX, Case::any, false, "normal_dx"},
    {"normal directx", normal, kDX, Case::any, false, "normal_directx"},
    {"normalgl", normal, kGL, Case::any, false, "normalgl"},
    {"normaldx", normal, kDX, Case::any, false, "normaldx"},
    {"nrm gl", normal, kGL, Case::any, false, "nrm_gl"},
    {"nrm dx", normal, kDX, Case::any, false, "nrm_dx"},
    {"nor gl", normal, kGL, Case::any, false, "nor_gl"},
    {"nor dx", normal, kDX, Case::any, false, "nor_dx"},
    {"normal", normal, kU, Case::any, false, "normal"},
    {"norm", normal, kU, Case::any, false, "norm"},
    {"nrm", normal, kU, Case::any, false, "nrm"},
    {"nor", normal, kU, Case::any, false, "nor"},
    {"roughness", roughness, kU, Case::any, false, "roughness"},
    {"rough", roughness, kU, Case::any, false, "rough"},
    {"rgh", roughness, kU, Case::any, false, "rgh"},
    {"gloss", gloss, kU, Case::any, false, "gloss"},
    {"glossiness", gloss, kU, Case::any, false, "glossiness"},
    {"smoothness", gloss, kU, Case::any, false, "smoothness"},
    {"metalness", metalness, kU, Case::any, false, "metalness"},
    {"metallic", metalness, kU, Case::any, false, "metallic"},
    {"metal", metalness, kU, Case::any, false, "metal"},
    {"ao", occlusion, kU, Case::any, false, "ao"},
    {"occ", occlusion, kU, Case::any, false, "occ"},  // 3dtextures.me's older "_OCC"
    {"occlusion", occlusion, kU, Case::any, false, "occlusion"},
    {"ambient occlusion", occlusion, kU, Case::any, false, "ambient_occlusion"},
    {"ambientocclusion", occlusion, kU, Case::any, false, "ambientocclusion"},
    {"height", height, kU, Case::any, false, "height"},
    {"heightmap", height, kU, Case::any, false, "heightmap"},
    // Names written as one word with "map" (three.js's material slots, normalMap, aoMap,
    // lower-cased by hand: "normalmap.jpg", "aomap.jpg" beside "basecolor.jpg" and "heightmap.png")
    // and the plural "normals" (Unity projects' "<Name>_normals").
    {"normalmap", normal, kU, Case::any, false, "normalmap"},
    {"normals", normal, kU, Case::any, false, "normals"},
    {"roughnessmap", roughness, kU, Case::any, false, "roughnessmap"},
    {"glossmap", gloss, kU, Case::any, false, "glossmap"},
    {"metallicmap", metalness, kU, Case::any, false, "metallicmap"},
    {"metalnessmap", metalness, kU, Case::any, false, "metalnessmap"},
    {"aomap", occlusion, kU, Case::any, false, "aomap"},
    {"occlusionmap", occlusion, kU, Case::any, false, "occlusionmap"},
    {"displacementmap", height, kU, Case::any, false, "displacementmap"},
    {"bumpmap", height, kU, Case::any, false, "bumpmap"},
    {"emissivemap", emissive, kU, Case::any, false, "emissivemap"},
    {"opacitymap", opacity, kU, Case::any, false, "opacitymap"},
    {"alphamap", opacity, kU, Case::any, false, "alphamap"},
    {"specularmap", specular, kU, Case::any, false, "specularmap"},
    {"disp", height, kU, Case::any, false, "disp"},
    {"displacement", height, kU, Case::any, false, "displacement"},
    {"bump", height, kU, Case::any, false, "bump"},
    // Godot 3's parallax maps ("rock_depth.jpg"): depth, white = deep, which the projects' Godot 4
    // materials read with heightmap_flip_texture. Read as height; plan.cpp inverts it unless its
    // slopes show it is height after all (the normal map's evidence, normal_convention.hpp).
    {"depth", height, kU, Case::any, false, "depth"},
    {"emissive", emissive, kU, Case::any, false, "emissive"},
    {"emission", emissive, kU, Case::any, false, "emission"},
    {"opacity", opacity, kU, Case::any, false, "opacity"},
    {"alpha", opacity, kU, Case::any, false, "alpha"},
    // "mask" alone is clutter (a mask with no PBR role); these two are opacity.
    {"opacity mask", opacity, kU, Case::any, false, "opacity_mask"},
    {"alpha mask", opacity, kU, Case::any, false, "alpha_mask"},
    {"specular", specular, kU, Case::any, false, "specular"},
    {"spec", specular, kU, Case::any, false, "spec"},
    {"orm", orm, kU, Case::any, false, "orm"},
    {"arm", orm, kU, Case::any, false, "arm"},
    {"occlusion roughness metallic", orm, kU, Case::any, true, "occlusion_roughness_metallic"},
    {"metallic roughness", metallic_roughness, kU, Case::any, true, "metallic_roughness"},
    {"metal roughness", metallic_roughness, kU, Case::any, true, "metal_roughness"},
    {"metallicroughness", metallic_roughness, kU, Case::any, false, "metallicroughness"},
    {"translucency", translucency, kU, Case::any, false, "translucency"},
    {"translucent", translucency, kU, Case::any, false, "translucent"},
    {"cavity", cavity, kU, Case::any, false, "cavity"},
    // Packed maps whose name states the order of their channels (Substance's engine templates,
    // game pipelines): letters only as the name's last word, words joined or apart.
    {"mra", mra, kU, Case::any, false, "_MRA", Need::at_end},
    {"mrao", mra, kU, Case::any, false, "_MRAO", Need::at_end},
    {"rma", rma, kU, Case::any, false, "_RMA", Need::at_end},
    {"rmao", rma, kU, Case::any, false, "_RMAO", Need::at_end},
    {"aorm", orm, kU, Case::any, false, "_AORM", Need::at_end},
    {"metallic roughness ao", mra, kU, Case::any, false, "metallic_roughness_ao"},
    {"metallic roughness occlusion", mra, kU, Case::any, false, "metallic_roughness_occlusion"},
    {"metalness roughness ao", mra, kU, Case::any, false, "metalness_roughness_ao"},
    {"roughness metallic ao", rma, kU, Case::any, false, "roughness_metallic_ao"},
    {"roughness metallic occlusion", rma, kU, Case::any, false, "roughness_metallic_occlusion"},
    {"roughness metallic", rm, kU, Case::any, true, "RoughnessMetallic"},
    {"ao roughness metallic", orm, kU, Case::any, false, "ao_roughness_metallic"},
    {"ambient occlusion roughness metallic", orm, kU, Case::any, true, "AmbientOcclusionRoughnessMetallic"},
    // A normal map's space named: a tangent-space map is the normal map; an object-space one
    // (baked for one mesh, "_nm" beside "_nm_tangent") never is (discover_set).
    {"nm tangent", normal, kU, Case::any, false, "_nm_tangent", Need::none, false, NormalSpace::tangent},
    {"normal tangent", normal, kU, Case::any, false, "_normal_tangent", Need::none, false, NormalSpace::tangent},
    {"tangent normal", normal, kU, Case::any, false, "_tangent_normal", Need::none, false, NormalSpace::tangent},
    {"tangent space normal", normal, kU, Case::any, false, "_tangent_space_normal", Need::none, false,
     NormalSpace::tangent},
    {"normal ts", normal, kU, Case::any, false, "_normal_ts", Need::none, false, NormalSpace::tangent},
    {"nm ts", normal, kU, Case::any, false, "_nm_ts", Need::none, false, NormalSpace::tangent},
    {"nm object", normal, kU, Case::any, false, "_nm_object", Need::none, false, NormalSpace::object},
    {"normal object", normal, kU, Case::any, false, "_normal_object", Need::none, false, NormalSpace::object},
    {"object normal", normal, kU, Case::any, false, "_object_normal", Need::none, false, NormalSpace::object},
    {"object space normal", normal, kU, Case::any, false, "_object_space_normal", Need::none, false,
     NormalSpace::object},
    {"normal os", normal, kU, Case::any, false, "_normal_os", Need::none, false, NormalSpace::object},
    {"nm os", normal, kU, Case::any, false, "_nm_os", Need::none, false, NormalSpace::object},
    {"world normal", normal, kU, Case::any, false, "_world_normal", Need::none, false, NormalSpace::object},
    {"normal world", normal, kU, Case::any, false, "_normal_world", Need::none, false, NormalSpace::object},
    // Game pipelines' two-letter tags, only as the name's last word ("Crate_BC", "Crate_NM_2K").
    {"bc", albedo, kU, Case::any, false, "_BC", Need::at_end},
    {"nm", normal, kU, Case::any, false, "_NM", Need::at_end},
    {"no", normal, kU, Case::upper, false, "_NO", Need::at_end},  // lower case "no" is a word
    {"ro", roughness, kU, Case::any, false, "_RO", Need::at_end},
    {"mt", metalness, kU, Case::any, false, "_MT", Need::at_end},
    {"em", emissive, kU, Case::any, false, "_EM", Need::at_end},
    {"op", opacity, kU, Case::any, false, "_OP", Need::at_end},
    // Emissive maps named for what glows ("Lamp_Glow", "LampIllum"; "LampLights" glued only).
    {"glow", emissive, kU, Case::any, false, "glow", Need::at_end},
    {"illum", emissive, kU, Case::any, false, "illum", Need::at_end},
    {"illumination", emissive, kU, Case::any, false, "illumination", Need::at_end},
    {"selfillum", emissive, kU, Case::any, false, "selfillum", Need::at_end},
    {"self illum", emissive, kU, Case::any, false, "self_illum", Need::at_end},
    {"lights", emissive, kU, Case::any, false, "Lights (glued)", Need::glued_at_end},
};

}  // namespace

const std::array<Family, 9> kFamilies{{
    {"ambientcg", kAmbientCG, [](const Layout& l) { return l.res_format_pair; }},
    {"polyhaven", kPolyHaven, [](const Layout& l) { return l.res_after; }},
    {"texturescom", kTexturesCom, [](const Layout& l) { return l.res_after || l.poliigon_prefix; }},
    {"megascans", kMegascans, [](const Layout& l) { return l.res_before; }},
    {"substance", kSubstance, [](const Layout& l) { return l.no_resolution; }},
    {"gltf", kGltf, [](const Layout& l) { return l.no_resolution; }},
    {"unity", kUnity, [](const Layout& l) { return l.no_resolution && !l.unreal_prefix; }},
    {"unreal", kUnreal, [](const Layout& l) { return l.unreal_prefix; }},
    {"generic", kGeneric, [](const Layout&) { return false; }},
}};

}  // namespace mf::naming
