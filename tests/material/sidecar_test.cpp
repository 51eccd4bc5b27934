// Sidecars: roles a glTF material or a Megascans asset JSON states for the set's files, and how
// discover_set uses them over the names.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>

#include "discovery_helpers.hpp"
#include "material/discovery.hpp"

namespace mf {
namespace {

using namespace discovery_test;
using NC = NormalConvention;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;

// "file role [gl|dx] [A=opacity] [unused:...] rule" per map.
std::vector<std::string> describe(const SidecarRoles& s) {
    std::vector<std::string> out;
    for (const auto& m : s.maps) {
        std::string e = m.file + " " + std::string(role_name(m.match.role));
        if (m.match.normal != NC::unknown) e.append(" ").append(convention_name(m.match.normal));
        if (m.match.opacity_in_alpha) e += " A=opacity";
        for (const Role r : m.match.unused) e.append(" unused:").append(role_name(r));
        e += " " + m.match.rule;
        out.push_back(e);
    }
    return out;
}

// The Khronos sample model's material (glTF-Sample-Models, DamagedHelmet.gltf), its mesh data
// left out.
const std::string kDamagedHelmet = R"({
  "asset": {"generator": "Khronos glTF Blender I/O", "version": "2.0"},
  "images": [{"uri": "Default_albedo.jpg"}, {"uri": "Default_metalRoughness.jpg"},
             {"uri": "Default_emissive.jpg"}, {"uri": "Default_AO.jpg"}, {"uri": "Default_normal.jpg"}],
  "samplers": [{}],
  "textures": [{"sampler": 0, "source": 0}, {"sampler": 0, "source": 1}, {"sampler": 0, "source": 2},
               {"sampler": 0, "source": 3}, {"sampler": 0, "source": 4}],
  "materials": [{
    "name": "Material_MR",
    "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicRoughnessTexture": {"index": 1}},
    "emissiveFactor": [1.0, 1.0, 1.0],
    "emissiveTexture": {"index": 2},
    "occlusionTexture": {"index": 3},
    "normalTexture": {"index": 4}
  }]
})";

TEST(SidecarRoles, GltfDamagedHelmet) {
    const auto s = sidecar_roles("DamagedHelmet.gltf", kDamagedHelmet);
    EXPECT_EQ(s.kind, SidecarKind::gltf);
    EXPECT_EQ(s.error, "");
    EXPECT_EQ(s.source, "DamagedHelmet.gltf");
    EXPECT_THAT(describe(s),
                ElementsAre("Default_albedo.jpg albedo gltf:materials[0].pbrMetallicRoughness.baseColorTexture",
                            "Default_normal.jpg normal gl gltf:materials[0].normalTexture",
                            "Default_metalRoughness.jpg metallic_roughness "
                            "gltf:materials[0].pbrMetallicRoughness.metallicRoughnessTexture",
                            "Default_AO.jpg occlusion gltf:materials[0].occlusionTexture",
                            "Default_emissive.jpg emissive gltf:materials[0].emissiveTexture"));
    for (const auto& m : s.maps) {
        EXPECT_EQ(m.match.family, "gltf");
        EXPECT_EQ(m.match.sidecar, "DamagedHelmet.gltf");
    }
}

TEST(SidecarRoles, DiscoverSetTakesTheGltfRolesAndStopsReportingIt) {
    const std::vector<std::string> files{"DamagedHelmet.gltf",   "Default_AO.jpg",     "Default_albedo.jpg",
                                         "Default_emissive.jpg", "Default_normal.jpg", "Default_metalRoughness.jpg"};
    const auto by_name = discover_set(files, nullptr, ChoicePolicy{});
    EXPECT_EQ(find_choice(by_name, Role::normal)->chosen.match.normal, NC::unknown);
    EXPECT_THAT(keys(by_name), ElementsAre("UNRECOGNIZED_FILE  DamagedHelmet.gltf"));

    const auto d = discover_set(files, nullptr, ChoicePolicy{}, {sidecar_roles("DamagedHelmet.gltf", kDamagedHelmet)});
    EXPECT_EQ(d.convention, "gltf");
    EXPECT_THAT(roles_of(d), ElementsAre("albedo", "normal", "occlusion", "emissive", "metallic_roughness"));
    EXPECT_THAT(keys(d), IsEmpty());
    const auto& n = find_choice(d, Role::normal)->chosen;
    EXPECT_EQ(n.file, "Default_normal.jpg");
    EXPECT_EQ(n.match.normal, NC::gl);  // the name is silent; glTF's normalTexture is +Y
    EXPECT_EQ(n.match.sidecar, "DamagedHelmet.gltf");
    EXPECT_EQ(n.match.rule, "gltf:materials[0].normalTexture");
    EXPECT_EQ(find_choice(d, Role::albedo)->chosen.match.rule,
              "gltf:materials[0].pbrMetallicRoughness.baseColorTexture");
    EXPECT_FALSE(find_choice(d, Role::albedo)->chosen.match.opacity_in_alpha);  // alphaMode OPAQUE (default)
}

// Names that say nothing (an exporter's image0.png …): only the glTF gives roles. Also URI
// spellings: percent-encoding, "./", "..", an extension's source; data: and http URIs skipped.
const std::string kNameless = R"({
  "asset": {"version": "2.0"},
  "images": [{"uri": "textures/tex_0.png"}, {"uri": "textures/tex%201.png"}, {"uri": "./textures/tex_2.png"},
             {"uri": "textures/../textures/tex_3.png"}, {"uri": "data:image/png;base64,iVBORw0KGgo="},
             {"uri": "https://example.com/remote.png"}, {"bufferView": 3, "mimeType": "image/png"}],
  "textures": [{"source": 0}, {"source": 1}, {"extensions": {"KHR_texture_basisu": {"source": 2}}},
               {"source": 3}, {"source": 4}, {"source": 5}, {"source": 6}],
  "materials": [
    {"name": "leaf", "alphaMode": "MASK",
     "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicRoughnessTexture": {"index": 1},
                              "metallicFactor": 0},
     "occlusionTexture": {"index": 1}, "normalTexture": {"index": 2, "scale": 1.0},
     "emissiveTexture": {"index": 3}},
    {"name": "remote", "pbrMetallicRoughness": {"baseColorTexture": {"index": 4}},
     "emissiveTexture": {"index": 5}, "emissiveFactor": [1, 1, 1], "normalTexture": {"index": 6}},
    {"name": "again", "pbrMetallicRoughness": {"baseColorTexture": {"index": 3}}}
  ]
})";

TEST(SidecarRoles, GltfNamelessTexturesUrisAndFactors) {
    const auto s = sidecar_roles("scene.gltf", kNameless);
    EXPECT_EQ(s.kind, SidecarKind::gltf);
    EXPECT_THAT(
        describe(s),
        ElementsAre("textures/tex_0.png albedo A=opacity gltf:materials[0].pbrMetallicRoughness.baseColorTexture",
                    "textures/tex_2.png normal gl gltf:materials[0].normalTexture",
                    "textures/tex 1.png orm unused:metalness "
                    "gltf:materials[0].pbrMetallicRoughness.metallicRoughnessTexture+occlusionTexture",
                    // emissiveFactor defaults to 0: the texture adds nothing. Material 2's
                    // use of the same image as base color comes second: the first role wins.
                    "textures/tex_3.png emissive unused:emissive gltf:materials[0].emissiveTexture"));

    const std::vector<std::string> files{"scene.gltf", "textures/tex 1.png", "textures/tex_0.png", "textures/tex_2.png",
                                         "textures/tex_3.png"};
    const auto by_name = discover_set(files, nullptr, ChoicePolicy{});
    EXPECT_TRUE(by_name.choices.empty());
    EXPECT_EQ(unrecognized_reason(by_name, "textures/tex_0.png"), "no role tag in the name");
    const auto d = discover_set(files, nullptr, ChoicePolicy{}, {s});
    EXPECT_THAT(roles_of(d), ElementsAre("albedo", "normal", "emissive", "orm"));
    EXPECT_TRUE(find_choice(d, Role::albedo)->chosen.match.opacity_in_alpha);
    EXPECT_THAT(find_choice(d, Role::orm)->chosen.match.unused, ElementsAre(Role::metalness));
    EXPECT_THAT(keys(d), IsEmpty());
}

TEST(SidecarRoles, GltfFactorsOfZero) {
    const auto s = sidecar_roles("m.gltf", R"({"images": [{"uri": "a.png"}, {"uri": "b.png"}, {"uri": "c.png"}],
      "textures": [{"source": 0}, {"source": 1}, {"source": 2}],
      "materials": [
        {"pbrMetallicRoughness": {"metallicRoughnessTexture": {"index": 0}, "roughnessFactor": 0.0, "metallicFactor": 0.0}},
        {"pbrMetallicRoughness": {"metallicRoughnessTexture": {"index": 1}, "metallicFactor": 0.5}},
        {"emissiveTexture": {"index": 2}, "emissiveFactor": [0, 0.2, 0]}]})");
    EXPECT_THAT(describe(s),
                ElementsAre("a.png metallic_roughness unused:roughness unused:metalness "
                            "gltf:materials[0].pbrMetallicRoughness.metallicRoughnessTexture",
                            "b.png metallic_roughness gltf:materials[1].pbrMetallicRoughness.metallicRoughnessTexture",
                            "c.png emissive gltf:materials[2].emissiveTexture"));
    // unused is in Role order whatever the factors' order.
    EXPECT_THAT(s.maps[0].match.unused, ElementsAre(Role::roughness, Role::metalness));
}

TEST(SidecarRoles, GltfInASubfolderResolvesAgainstItsFolder) {
    const auto s = sidecar_roles("standard/tbdpec3r_tier_1_nonUE.gltf", R"({
      "images": [{"uri": "../Textures/T_tbdpec3r_4K_B-O.png"}, {"uri": "../../outside.png"}, {"uri": "/abs.png"},
                 {"uri": "C:\\Textures\\a.png"}, {"uri": "N.png"}],
      "textures": [{"source": 0}, {"source": 1}, {"source": 2}, {"source": 3}, {"source": 4}],
      "materials": [{"alphaMode": "BLEND", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}},
                    {"pbrMetallicRoughness": {"baseColorTexture": {"index": 1}}},
                    {"pbrMetallicRoughness": {"baseColorTexture": {"index": 2}}},
                    {"pbrMetallicRoughness": {"baseColorTexture": {"index": 3}}},
                    {"normalTexture": {"index": 4}},
                    {"normalTexture": {"index": 99}}, {"normalTexture": {"index": -1}}, {"normalTexture": 3}, 7]})");
    EXPECT_THAT(describe(s), ElementsAre("Textures/T_tbdpec3r_4K_B-O.png albedo A=opacity "
                                         "gltf:materials[0].pbrMetallicRoughness.baseColorTexture",
                                         "standard/N.png normal gl gltf:materials[4].normalTexture"));
}

std::string glb(const std::string& json_text) {
    std::string chunk = json_text;
    while (chunk.size() % 4) chunk += ' ';
    auto u32 = [](uint32_t v) {
        std::string b(4, '\0');
        for (size_t k = 0; k < 4; ++k) b[k] = static_cast<char>((v >> (8 * k)) & 0xFF);
        return b;
    };
    const auto total = static_cast<uint32_t>(12 + 8 + chunk.size());
    return "glTF" + u32(2) + u32(total) + u32(static_cast<uint32_t>(chunk.size())) + "JSON" + chunk;
}

TEST(SidecarRoles, BinaryGltf) {
    const auto bytes = glb(kDamagedHelmet);
    const auto s = sidecar_roles("DamagedHelmet.glb", bytes);
    EXPECT_EQ(s.kind, SidecarKind::gltf);
    EXPECT_EQ(s.maps.size(), 5u);
    EXPECT_EQ(describe(s), describe(sidecar_roles("DamagedHelmet.gltf", kDamagedHelmet)));
    const auto cut = sidecar_roles("DamagedHelmet.glb", bytes.substr(0, 200));
    EXPECT_EQ(cut.kind, SidecarKind::none);
    EXPECT_THAT(cut.error, HasSubstr("truncated"));
    EXPECT_THAT(sidecar_roles("x.glb", "GLTF....").error, HasSubstr("not a binary glTF"));
}

// A Megascans surface's asset file (the fields a Bridge download carries; values shortened).
const std::string kMegascansSurface = R"({
  "id": "sfjmafua", "name": "Mossy Rock",
  "semanticTags": {"asset_type": "surface"},
  "maps": [
    {"mimeType": "image/jpeg", "resolution": "2048x2048", "type": "albedo", "colorSpace": "sRGB",
     "bitDepth": 8, "name": "Albedo", "uri": "rock_sfjmafua_2K_Albedo.jpg"},
    {"mimeType": "image/jpeg", "resolution": "2048x2048", "type": "normal", "name": "Normal",
     "uri": "rock_sfjmafua_2K_Normal.jpg"},
    {"mimeType": "image/jpeg", "resolution": "2048x2048", "type": "bump", "name": "Bump",
     "uri": "rock_sfjmafua_2K_Bump.jpg"},
    {"mimeType": "image/jpeg", "resolution": "2048x2048", "type": "AO", "name": "AO",
     "uri": "rock_sfjmafua_2K_AO.jpg"},
    {"mimeType": "image/jpeg", "resolution": "2048x2048", "type": "fuzz", "name": "Fuzz",
     "uri": "rock_sfjmafua_2K_Fuzz.jpg"},
    {"mimeType": "image/x-exr", "resolution": "4096x4096", "type": "displacement", "name": "Displacement",
     "uri": "rock_sfjmafua_4K_Displacement.exr"},
    {"type": "roughness", "name": "rock_sfjmafua_2K_Roughness.jpg"},
    {"type": "gloss", "name": "Gloss"}
  ],
  "previews": {"images": [{"resolution": "360x360", "uri": "rock_sfjmafua_Preview.png"}]}
})";

TEST(SidecarRoles, MegascansMaps) {
    const auto s = sidecar_roles("rock_sfjmafua.json", kMegascansSurface);
    EXPECT_EQ(s.kind, SidecarKind::megascans);
    EXPECT_THAT(describe(s), ElementsAre("rock_sfjmafua_2K_Albedo.jpg albedo megascans:maps[].type=albedo",
                                         "rock_sfjmafua_2K_Normal.jpg normal megascans:maps[].type=normal",
                                         "rock_sfjmafua_2K_Bump.jpg height megascans:maps[].type=bump",
                                         "rock_sfjmafua_2K_AO.jpg occlusion megascans:maps[].type=AO",
                                         "rock_sfjmafua_4K_Displacement.exr height megascans:maps[].type=displacement",
                                         "rock_sfjmafua_2K_Roughness.jpg roughness megascans:maps[].type=roughness"));
    EXPECT_EQ(s.maps[0].match.family, "megascans");

    // In the set: the JSON is read (not reported), the map the JSON lists without a file is
    // the name's business, the fuzz map has no role either way, the preview the JSON lists is
    // the set's preview. The asset's facts are kept for its provenance.
    const auto d = discover_set({"rock_sfjmafua.json", "rock_sfjmafua_2K_Albedo.jpg", "rock_sfjmafua_2K_Normal.jpg",
                                 "rock_sfjmafua_2K_Bump.jpg", "rock_sfjmafua_2K_AO.jpg", "rock_sfjmafua_2K_Fuzz.jpg",
                                 "rock_sfjmafua_2K_Gloss.jpg", "rock_sfjmafua_Preview.png"},
                                nullptr, ChoicePolicy{}, {s});
    EXPECT_EQ(d.convention, "megascans");
    EXPECT_THAT(roles_of(d), ElementsAre("albedo", "normal", "occlusion", "height", "gloss"));
    EXPECT_EQ(find_choice(d, Role::albedo)->chosen.match.sidecar, "rock_sfjmafua.json");
    EXPECT_EQ(find_choice(d, Role::gloss)->chosen.match.sidecar, "");  // by name
    EXPECT_THAT(keys(d), ElementsAre("UNRECOGNIZED_FILE  rock_sfjmafua_2K_Fuzz.jpg"));
    ASSERT_TRUE(d.preview.has_value());
    EXPECT_EQ(d.preview->file, "rock_sfjmafua_Preview.png");
    EXPECT_EQ(d.preview->match.rule, "megascans:previews.images[].uri");
    EXPECT_EQ(s.facts.asset_id, "sfjmafua");
    EXPECT_EQ(s.facts.title, "Mossy Rock");
    EXPECT_THAT(s.facts.previews, ElementsAre("rock_sfjmafua_Preview.png"));
    EXPECT_EQ(s.facts.licence, "");  // Bridge's JSON names no licence
}

TEST(SidecarRoles, MegascansComponents) {
    const auto s = sidecar_roles("Textures/scrap.json", R"({"id": "39bfc763", "components": [
      {"type": "albedo", "name": "Albedo", "colorSpace": "sRGB", "uris": [{"physicalSize": "40x40", "resolutions": [
        {"resolution": "2048x2048", "formats": [{"mimeType": "image/jpeg", "bitDepth": 8, "uri": "Scrap_2K_Albedo.jpg"},
                                                {"mimeType": "image/x-exr", "bitDepth": 32, "uri": "Scrap_2K_Albedo.exr"}]}]}]},
      {"type": "translucency", "uris": [{"resolutions": [{"formats": [{"uri": "Scrap_2K_Translucency.jpg"}]}]}]},
      {"type": "thickness", "uris": [{"resolutions": [{"formats": [{"uri": "Scrap_2K_Thickness.jpg"}]}]}]},
      {"type": "metalness", "uris": "broken"}]})");
    EXPECT_EQ(s.kind, SidecarKind::megascans);
    EXPECT_THAT(describe(s), ElementsAre("Textures/Scrap_2K_Albedo.jpg albedo megascans:components[].type=albedo",
                                         "Textures/Scrap_2K_Albedo.exr albedo megascans:components[].type=albedo",
                                         "Textures/Scrap_2K_Translucency.jpg translucency "
                                         "megascans:components[].type=translucency"));
}

TEST(SidecarRoles, PrecedenceAndMatchingByBaseName) {
    // The glTF calls the map a base color, the Megascans JSON a roughness map: the JSON wins
    // whatever order they come in; a JSON naming the file without its folder still matches it.
    const auto gltf = sidecar_roles("plant.gltf", R"({"images": [{"uri": "Textures/leaf_2K_X.png"}],
      "textures": [{"source": 0}], "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]})");
    const auto json = sidecar_roles("plant.json", R"({"maps": [{"type": "roughness", "uri": "leaf_2K_X.png"}]})");
    const std::vector<std::string> files{"Textures/leaf_2K_X.png", "plant.gltf", "plant.json"};
    for (const auto& order : {std::vector{gltf, json}, std::vector{json, gltf}}) {
        const auto d = discover_set(files, nullptr, ChoicePolicy{}, order);
        EXPECT_THAT(roles_of(d), ElementsAre("roughness"));
        EXPECT_EQ(find_choice(d, Role::roughness)->chosen.match.sidecar, "plant.json");
        EXPECT_EQ(find_choice(d, Role::roughness)->chosen.file, "Textures/leaf_2K_X.png");
        EXPECT_THAT(keys(d), IsEmpty());
    }
    // Two files share that base name: the folderless name matches neither.
    const auto two = discover_set({"a/leaf_2K_X.png", "b/leaf_2K_X.png", "plant.json"}, nullptr, ChoicePolicy{},
                                  {json});
    EXPECT_TRUE(two.choices.empty());
    EXPECT_EQ(unrecognized_reason(two, "plant.json"), "sidecar naming no map of this set");
}

TEST(SidecarRoles, BillboardsStayClutterWhateverTheSidecarSays) {
    const auto s = sidecar_roles("x.gltf",
                                 R"({"images": [{"uri": "T_x_4K_Billboard_B-O.png"}, {"uri": "T_x_4K_B-O.png"}],
      "textures": [{"source": 0}, {"source": 1}],
      "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}},
                    {"pbrMetallicRoughness": {"baseColorTexture": {"index": 1}}}]})");
    ASSERT_EQ(s.maps.size(), 2u);
    const auto d = discover_set({"T_x_4K_Billboard_B-O.png", "T_x_4K_B-O.png", "x.gltf"}, nullptr, ChoicePolicy{}, {s});
    EXPECT_THAT(candidates(d, Role::albedo), ElementsAre("T_x_4K_B-O.png"));
    EXPECT_THAT(unrecognized_reason(d, "T_x_4K_Billboard_B-O.png"), HasSubstr("billboard"));
    // The glTF's material is OPAQUE (the default), but the name agrees on the role and states
    // opacity in A ("_B-O"): that fact is kept. The rule is the sidecar's.
    const auto& m = find_choice(d, Role::albedo)->chosen.match;
    EXPECT_TRUE(m.opacity_in_alpha);
    EXPECT_EQ(m.rule, "gltf:materials[1].pbrMetallicRoughness.baseColorTexture");
}

TEST(SidecarRoles, UnreadableSidecarsAreReported) {
    const auto bad = sidecar_roles("notes.json", R"({"title": "my notes"})");
    EXPECT_EQ(bad.kind, SidecarKind::none);
    EXPECT_THAT(bad.error, HasSubstr("neither a glTF nor a Megascans asset file"));
    EXPECT_EQ(sidecar_roles("broken.gltf", "{\"images\": [").error, "not a JSON object");
    EXPECT_EQ(sidecar_roles("list.json", "[1, 2]").error, "not a JSON object");
    EXPECT_THAT(sidecar_roles("readme.txt", "{}").error, HasSubstr("not a .gltf, .glb, .json or .mtlx"));
    const auto empty = sidecar_roles("mesh.gltf", R"({"asset": {"version": "2.0"}, "meshes": []})");
    EXPECT_EQ(empty.kind, SidecarKind::gltf);
    EXPECT_EQ(empty.error, "");
    EXPECT_TRUE(empty.maps.empty());
    // A .json that is a glTF by content.
    EXPECT_EQ(sidecar_roles("model.json", kDamagedHelmet).kind, SidecarKind::gltf);

    const auto d = discover_set({"Wood_Color.png", "notes.json", "mesh.gltf"}, nullptr, ChoicePolicy{}, {bad, empty});
    EXPECT_THAT(unrecognized_reason(d, "notes.json"), HasSubstr("sidecar not read (neither a glTF"));
    EXPECT_EQ(unrecognized_reason(d, "mesh.gltf"), "sidecar naming no map of this set");
    for (const std::string f : {"a.gltf", "b.GLB", "c.json", "d.mtlx"}) EXPECT_TRUE(is_sidecar_name(f)) << f;
    for (const std::string f : {"b.usdc", "c.png", "json"}) EXPECT_FALSE(is_sidecar_name(f)) << f;
}

// ambientCG's MaterialX document as it ships (Net004A_1K-JPG.mtlx of the corpus, trimmed of its
// layout attributes): every map the standard_surface and the displacement shader read, the
// normal map through a normalmap node (gl), the DX twin not named.
constexpr const char* kAmbientCgMtlx = R"(<?xml version="1.0"?>
<materialx version="1.38" fileprefix="./">
  <standard_surface type="surfaceshader" name="Net004A_1K_JPG_StandardSurface">
    <input type="float" name="specular" value="0" />
    <input type="color3" name="base_color" nodename="Net004A_1K_JPG_Color" />
    <input type="vector3" name="normal" nodename="normalmap" />
    <input type="vector3" name="coat_normal" nodename="normalmap" />
    <input type="float" name="specular_roughness" nodename="Net004A_1K_JPG_Roughness" />
    <input type="float" name="coat_roughness" nodename="Net004A_1K_JPG_Roughness" />
    <input type="color3" name="opacity" nodename="Net004A_1K_JPG_Opacity" />
  </standard_surface>
  <surfacematerial type="material" name="Net004A_1K_JPG">
    <input type="surfaceshader" name="surfaceshader" nodename="Net004A_1K_JPG_StandardSurface" />
    <input type="displacementshader" name="displacementshader" nodename="displacement" />
  </surfacematerial>
  <tiledimage type="color3" name="Net004A_1K_JPG_Color">
    <input type="filename" name="file" colorspace="srgb_texture" value="Net004A_1K-JPG_Color.jpg" />
  </tiledimage>
  <tiledimage type="float" name="Net004A_1K_JPG_Displacement">
    <input type="filename" name="file" value="Net004A_1K-JPG_Displacement.jpg" />
  </tiledimage>
  <displacement type="displacementshader" name="displacement">
    <input type="float" name="displacement" nodename="Net004A_1K_JPG_Displacement" />
  </displacement>
  <tiledimage type="vector3" name="Net004A_1K_JPG_NormalGL">
    <input type="filename" name="file" value="Net004A_1K-JPG_NormalGL.jpg" />
  </tiledimage>
  <normalmap type="vector3" name="normalmap">
    <input type="vector3" name="in" nodename="Net004A_1K_JPG_NormalGL" />
  </normalmap>
  <tiledimage type="float" name="Net004A_1K_JPG_Roughness">
    <input type="filename" name="file" value="Net004A_1K-JPG_Roughness.jpg" />
  </tiledimage>
  <tiledimage type="color3" name="Net004A_1K_JPG_Opacity">
    <input type="filename" name="file" value="Net004A_1K-JPG_Opacity.jpg" />
  </tiledimage>
</materialx>)";

TEST(SidecarRoles, MaterialXNamesEachMapsShaderInput) {
    const auto s = sidecar_roles("Net004A_1K-JPG.mtlx", kAmbientCgMtlx);
    EXPECT_EQ(s.kind, SidecarKind::materialx);
    EXPECT_EQ(s.error, "");
    std::vector<std::string> got = describe(s);
    std::sort(got.begin(), got.end());
    EXPECT_THAT(got, ElementsAre("Net004A_1K-JPG_Color.jpg albedo mtlx:standard_surface.base_color",
                                 "Net004A_1K-JPG_Displacement.jpg height mtlx:displacement.displacement",
                                 "Net004A_1K-JPG_NormalGL.jpg normal gl mtlx:standard_surface.normal",
                                 "Net004A_1K-JPG_Opacity.jpg opacity mtlx:standard_surface.opacity",
                                 "Net004A_1K-JPG_Roughness.jpg roughness mtlx:standard_surface.specular_roughness"));
    // In a set: the names agree, so they keep naming the material and its convention; the
    // rule cites both. The DX twin is still a candidate for a DirectX preset.
    const std::vector<std::string> files{"Net004A.png",
                                         "Net004A_1K-JPG.mtlx",
                                         "Net004A_1K-JPG_Color.jpg",
                                         "Net004A_1K-JPG_NormalDX.jpg",
                                         "Net004A_1K-JPG_NormalGL.jpg",
                                         "Net004A_1K-JPG_Roughness.jpg"};
    const auto d = discover_set(files, nullptr, ChoicePolicy{}, {s});
    EXPECT_EQ(d.convention, "ambientcg");
    EXPECT_EQ(chosen_file(d, Role::normal), "Net004A_1K-JPG_NormalGL.jpg");
    EXPECT_EQ(unrecognized_reason(d, "Net004A_1K-JPG.mtlx"), "");
    for (const auto& c : d.choices)
        if (c.role == Role::albedo) {
            EXPECT_EQ(c.chosen.match.rule, "ambientcg:_Color + mtlx:standard_surface.base_color");
        }
    ChoicePolicy dx;
    dx.preferred_normal = NC::dx;
    EXPECT_EQ(chosen_file(discover_set(files, nullptr, dx, {s}), Role::normal), "Net004A_1K-JPG_NormalDX.jpg");
}

// Names that say nothing, a glTF PBR shader through a nodegraph with extract nodes (a packed
// metal/roughness map reached for two roles is left to its name), fileprefix, and documents
// that are not MaterialX or name paths outside the set.
TEST(SidecarRoles, MaterialXThroughNodegraphsAndPrefixes) {
    const auto s = sidecar_roles("mat/wall.mtlx", R"(<materialx version="1.39">
  <nodegraph name="NG" fileprefix="tex/">
    <image name="base" type="color3"><input name="file" type="filename" value="a.png" /></image>
    <image name="nrm" type="vector3"><input name="file" type="filename" value="b.png" /></image>
    <normalmap name="nm" type="vector3"><input name="in" type="vector3" nodename="nrm" /></normalmap>
    <image name="mr" type="vector3"><input name="file" type="filename" value="c.png" /></image>
    <extract name="m" type="float"><input name="in" type="vector3" nodename="mr" /><input name="index" type="integer" value="2" /></extract>
    <extract name="r" type="float"><input name="in" type="vector3" nodename="mr" /><input name="index" type="integer" value="1" /></extract>
    <image name="up" type="float"><input name="file" type="filename" value="../../../outside.png" /></image>
    <output name="base_out" type="color3" nodename="base" />
    <output name="n_out" type="vector3" nodename="nm" />
    <output name="m_out" type="float" nodename="m" />
    <output name="r_out" type="float" nodename="r" />
    <output name="o_out" type="float" nodename="up" />
  </nodegraph>
  <gltf_pbr name="pbr" type="surfaceshader">
    <input name="base_color" type="color3" nodegraph="NG" output="base_out" />
    <input name="normal" type="vector3" nodegraph="NG" output="n_out" />
    <input name="metallic" type="float" nodegraph="NG" output="m_out" />
    <input name="roughness" type="float" nodegraph="NG" output="r_out" />
    <input name="occlusion" type="float" nodegraph="NG" output="o_out" />
  </gltf_pbr>
</materialx>)");
    EXPECT_EQ(s.kind, SidecarKind::materialx);
    EXPECT_THAT(describe(s), ElementsAre("mat/tex/a.png albedo mtlx:gltf_pbr.base_color",
                                         "mat/tex/b.png normal gl mtlx:gltf_pbr.normal"));
    const auto d = discover_set({"mat/tex/a.png", "mat/tex/b.png", "mat/wall.mtlx"}, nullptr, ChoicePolicy{}, {s});
    EXPECT_EQ(chosen_file(d, Role::albedo), "mat/tex/a.png");
    EXPECT_EQ(chosen_file(d, Role::normal), "mat/tex/b.png");
    EXPECT_EQ(unrecognized_reason(d, "mat/wall.mtlx"), "");
    EXPECT_EQ(sidecar_roles("x.mtlx", "<materialx><oops").error, "not well-formed XML");
    EXPECT_EQ(sidecar_roles("x.mtlx", "<svg/>").error, "not a MaterialX document (no <materialx> root)");
    // No entity is substituted and nothing is fetched: the file value stays the literal text.
    const auto ent = sidecar_roles("x.mtlx", R"(<?xml version="1.0"?>
<!DOCTYPE materialx [<!ENTITY f SYSTEM "file:///etc/passwd">]>
<materialx><standard_surface name="s" type="surfaceshader"><input name="base_color" type="color3" nodename="i" /></standard_surface>
<image name="i" type="color3"><input name="file" type="filename" value="&f;" /></image></materialx>)");
    EXPECT_TRUE(ent.maps.empty() || ent.maps[0].file.find("root:") == std::string::npos);
}

}  // namespace
}  // namespace mf
