// Manifests of every shipped preset preview to the same image; the adapter maps channels to
// roles as the spec says.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <thread>

#include "core/files.hpp"
#include "core/json.hpp"
#include "manifest/spool.hpp"
#include "oiio_oracle.hpp"
#include "preview/preview.hpp"
#include "test_dirs.hpp"
#include "test_env.hpp"
#include "vulkan_fixture.hpp"

namespace mf::preview {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

fs::path temp_dir(const std::string& name) { return mf::testdirs::fresh("matforge-preview-test-", name); }

using mf::testenv::oiio_write_png8;

// The typed manifest of `j`, every material loaded as the preview loads it.
manifest::Manifest parse(const json& j) {
    std::string error;
    auto m = manifest::manifest_from_json(j, error);
    EXPECT_TRUE(m) << error;
    return m.value_or(manifest::Manifest{});
}

render::Material load(const manifest::Material& mm, const fs::path& dir, std::vector<std::string>& notes) {
    std::string error;
    auto m = load_material(mm, dir, MaterialOptions{}, notes, error);
    EXPECT_TRUE(m) << error;
    return m.value_or(render::Material{});
}

// ---- the documented manifest example, verbatim but for sizes

TEST(Manifest, SpecExampleMapsChannelsToRoles) {
    const fs::path dir = temp_dir("spec");
    oiio_write_png8(dir / "Bricks059/Bricks059_orm.png", 2, 2, 3, std::vector<uint8_t>(12, 100));
    const json j = json::parse(R"json({
      "manifest_version": 1,
      "generator": "matforge 0.1.0",
      "preset": "gltf",
      "materials": [
        {
          "name": "Bricks059",
          "source": "in/Bricks059_1K-PNG",
          "convention": "ambientcg",
          "inputs": {
            "albedo":    { "file": "Bricks059_1K-PNG_Color.png", "width": 1024, "height": 1024,
                           "channels": 3, "bit_depth": 8, "color_space": "sRGB" },
            "normal":    { "file": "Bricks059_1K-PNG_NormalGL.png", "normal_convention": "gl" },
            "roughness": { "file": "Bricks059_1K-PNG_Roughness.png" }
          },
          "constants": { "metalness": 0.0 },
          "outputs": [
            { "file": "Bricks059/Bricks059_orm.png", "color_space": "linear",
              "channels": { "R": "occlusion", "G": "roughness", "B": "metalness" },
              "width": 1024, "height": 1024, "bit_depth": 8, "sha256": "..." }
          ],
          "findings": [
            { "code": "MISSING_MAP", "severity": "info", "role": "metalness",
              "message": "no metalness map; generated constant 0 (dielectric)" }
          ]
        }
      ],
      "failures": [
        { "source": "in/Broken", "code": "UNREADABLE_FILE", "message": "..." }
      ]
    })json");
    const manifest::Manifest m = parse(j);
    ASSERT_EQ(m.materials.size(), 1u);
    ASSERT_EQ(m.failures.size(), 1u);
    EXPECT_EQ(m.failures[0].code, "UNREADABLE_FILE");
    std::vector<std::string> notes;
    const render::Material mat = load(m.materials[0], dir, notes);
    EXPECT_EQ(mat.name, "Bricks059");
    ASSERT_EQ(mat.textures.size(), 1u);
    EXPECT_FALSE(mat.textures[0].srgb);
    EXPECT_EQ(mat.occlusion.texture, 0);
    EXPECT_EQ(mat.occlusion.channel, render::Channel::R);
    EXPECT_EQ(mat.roughness.channel, render::Channel::G);
    EXPECT_EQ(mat.metalness.channel, render::Channel::B);
    EXPECT_EQ(mat.albedo.texture, -1);
    EXPECT_EQ(mat.normal.texture, -1);
}

// A manifest's material as ingest writes one (an output, a constant, a finding; `i` varies it).
manifest::Material sample_material(int i) {
    manifest::Material mat;
    mat.name = "Set" + std::to_string(i);
    mat.source = "in/set " + std::to_string(i) + (i == 1 ? std::string("\xff\xfe") : std::string());
    mat.convention = "ambientcg";
    manifest::Output o;
    o.file = mat.name + "/" + mat.name + "_basecolor.png";
    o.srgb = true;
    o.width = o.height = 1024;
    o.bit_depth = 8;
    o.format = "png";
    o.sha256 = std::string(64, 'a');
    mat.outputs.push_back(o);
    mat.constants.push_back({Role::metalness, {0.f}});
    mat.findings.push_back({"CONSTANT_MAP", Severity::info, "metalness", "", "line one \"quoted\"", {{"k", 1.5}}});
    if (i == 2) mat.emissive_strength = 4.5f;
    if (i % 2 == 0) mat.material_files.push_back({mat.name + "/" + mat.name + ".gltf", "gltf", std::string(64, 'd')});
    return mat;
}

// manifest_text (one material at a time) writes the bytes of the whole-tree dump it replaces,
// for no material, one, several, non-UTF-8 bytes in a name, failures, a library and a shard.
TEST(Manifest, TextMadeOneMaterialAtATimeIsTheWholeDump) {
    manifest::Manifest m;
    m.generator = "matforge 0.1.0";
    m.preset = "gltf";
    EXPECT_EQ(manifest::manifest_text(m), json_text(manifest::to_json(m)));
    for (int i = 0; i < 3; ++i) {
        m.materials.push_back(sample_material(i));
        EXPECT_EQ(manifest::manifest_text(m), json_text(manifest::to_json(m))) << i + 1 << " material(s)";
    }
    m.failures.push_back({"in/broken", "UNREADABLE_FILE", "truncated"});
    m.library.push_back({"library.gltf", "gltf", std::string(64, 'b')});
    m.shard = manifest::Manifest::Shard{1, 3, std::string(64, 'c'), std::string(64, 'e'), 3};
    EXPECT_EQ(manifest::manifest_text(m), json_text(manifest::to_json(m)));
}

// The spool (materials in a temporary file, the manifest written from it) gives the bytes of
// manifest_text for materials added in any order from several threads, reads them back in name
// order, and names a material added twice with the parts of both.
TEST(Manifest, SpooledMaterialsWriteTheSameBytes) {
    const fs::path dir = temp_dir("spool");
    manifest::Manifest m;
    m.generator = "matforge 0.1.0";
    m.preset = "gltf";
    m.failures.push_back({"in/broken", "UNREADABLE_FILE", "truncated"});
    for (int i = 0; i < 40; ++i) m.materials.push_back(sample_material(i));
    std::sort(m.materials.begin(), m.materials.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
    std::string error;
    auto spool = manifest::MaterialSpool::open(dir, error);
    ASSERT_TRUE(spool) << error;
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
        threads.emplace_back([&, t] {
            std::string e;
            for (int i = 39 - t; i >= 0; i -= 4) EXPECT_TRUE(spool->add(sample_material(i), e, t)) << e;
        });
    for (auto& th : threads) th.join();
    EXPECT_FALSE(spool->sort());
    std::string text;
    manifest::Manifest head = m;
    head.materials.clear();
    ASSERT_TRUE(spool->write_manifest(
        head, [&](std::string_view p) { return text.append(p), true; }, error))
        << error;
    EXPECT_EQ(text, manifest::manifest_text(m));
    std::vector<std::string> names;
    ASSERT_TRUE(spool->for_each([&](manifest::Material&& mat) { return names.push_back(mat.name), true; }, error));
    ASSERT_EQ(names.size(), 40u);
    for (size_t i = 0; i < names.size(); ++i) EXPECT_EQ(names[i], m.materials[i].name);
    EXPECT_EQ(spool->entries()[0].gltf, "Set0/Set0.gltf");
    EXPECT_EQ(spool->entries()[1].gltf, "");  // Set1: no .gltf

    ASSERT_TRUE(spool->add(sample_material(7), error, 9));
    const auto dup = spool->sort();
    ASSERT_TRUE(dup);
    EXPECT_EQ(dup->name, "Set7");
    EXPECT_EQ(dup->second_part, 9);
    fs::remove_all(dir);
}

// A material of sample_material(i) whose files are in `dir`, with their real sha256 (merge
// checks every file a part lists).
manifest::Material material_on_disk(const fs::path& dir, int i) {
    manifest::Material m = sample_material(i);
    auto put = [&](const std::string& rel, std::string& sha) {
        const std::string bytes = "the bytes of " + rel;
        fs::create_directories((dir / rel).parent_path());
        std::ofstream(dir / rel, std::ios::binary) << bytes;
        sha = sha256_hex(std::span(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size()));
    };
    for (auto& o : m.outputs) put(o.file, o.sha256);
    for (auto& f : m.material_files) put(f.file, f.sha256);
    return m;
}

// merge_shards reads the shards' manifests one material at a time: the merged manifest is the
// bytes of the unsharded one; a material in two shards, a shard missing, a part of another plan,
// a part lacking a material and a file that is not what the part says are refused by name.
TEST(Manifest, MergeOfSpooledShardsIsTheWholeRun) {
    const fs::path dir = temp_dir("merge");
    manifest::Manifest whole;
    whole.generator = "matforge 0.1.0";
    whole.preset = "gltf";
    for (int i = 0; i < 9; ++i) whole.materials.push_back(material_on_disk(dir, i));
    const std::string plan(64, 'e');
    auto write_part = [&](const fs::path& file, const manifest::Manifest& part) {
        std::ofstream(file) << manifest::manifest_text(part);
        return file.string();
    };
    std::vector<std::string> paths;
    for (int s = 0; s < 3; ++s) {
        manifest::Manifest part = whole;
        part.materials.clear();
        for (int i = s; i < 9; i += 3) part.materials.push_back(whole.materials[static_cast<size_t>(i)]);
        part.failures.push_back({"in/bad" + std::to_string(s % 2), "UNREADABLE_FILE", "truncated"});
        part.shard = manifest::Manifest::Shard{s, 3, std::string(64, 'c'), plan, 3};
        paths.push_back(write_part(dir / ("manifest.shard-" + std::to_string(s) + "-of-3.json"), part));
    }
    whole.failures = {{"in/bad0", "UNREADABLE_FILE", "truncated"}, {"in/bad1", "UNREADABLE_FILE", "truncated"}};
    std::string error;
    auto spool = manifest::MaterialSpool::open(dir, error);
    ASSERT_TRUE(spool) << error;
    const auto head = manifest::merge_shards(paths, dir, *spool, error);
    ASSERT_TRUE(head) << error;
    std::string text;
    ASSERT_TRUE(spool->write_manifest(
        *head, [&](std::string_view p) { return text.append(p), true; }, error));
    EXPECT_EQ(text, manifest::manifest_text(whole));

    auto refused = [&](std::vector<std::string> parts, const std::string& says) {
        std::string e;
        auto sp = manifest::MaterialSpool::open(dir, e);
        EXPECT_FALSE(manifest::merge_shards(parts, dir, *sp, e)) << says;
        EXPECT_NE(e.find(says), std::string::npos) << e;
        return e;
    };
    manifest::Manifest extra = whole;
    extra.materials = {whole.materials[4]};  // Set4 is shard 1's
    extra.failures.clear();
    extra.shard = manifest::Manifest::Shard{0, 3, std::string(64, 'c'), plan, 1};
    EXPECT_EQ(refused({write_part(dir / "extra.json", extra), paths[1], paths[2]}, "is in both"),
              "material \"Set4\" is in both " + (dir / "extra.json").string() + " and " + paths[1]);
    refused({paths[0], paths[2]}, "shard(s) 1 of 3 missing");
    // A shard of another plan (the library changed between the shards' runs).
    manifest::Manifest other = whole;
    other.materials = {whole.materials[1], whole.materials[4], whole.materials[7]};
    other.failures.clear();
    other.shard = manifest::Manifest::Shard{1, 3, std::string(64, 'c'), std::string(64, 'f'), 3};
    refused({paths[0], write_part(dir / "other.json", other), paths[2]}, "changed between the shards' runs");
    // A part that lost a material (given 3 sets, lists 2 and no failure).
    manifest::Manifest short_part = other;
    short_part.materials.pop_back();
    short_part.shard->plan = plan;
    refused({paths[0], write_part(dir / "short.json", short_part), paths[2]},
            "holds 2 materials and 0 failures for the 3 sets");
    // A file whose bytes changed, and a file outside the folder.
    std::ofstream(dir / "Set4/Set4_basecolor.png", std::ios::binary) << "edited";
    refused({paths[0], paths[1], paths[2]}, "material \"Set4\": Set4/Set4_basecolor.png: its bytes do not hash");
    manifest::Manifest outside = other;
    outside.shard->plan = plan;
    outside.materials[0].outputs[0].file = "../elsewhere.png";
    refused({paths[0], write_part(dir / "outside.json", outside), paths[2]}, "is not a path inside the output folder");
    fs::remove_all(dir);
}

TEST(Manifest, SmoothnessConstantsUnusedAndConventions) {
    const fs::path dir = temp_dir("layouts");
    oiio_write_png8(dir / "m/base.png", 2, 2, 4, std::vector<uint8_t>(16, 200));
    oiio_write_png8(dir / "m/n.png", 2, 2, 3, std::vector<uint8_t>(12, 128));
    oiio_write_png8(dir / "m/mask.png", 2, 2, 4, std::vector<uint8_t>(16, 50));
    oiio_write_png8(dir / "m/h.png", 2, 2, 1, std::vector<uint8_t>(4, 50));
    const json j = json::parse(R"({"manifest_version": 1, "materials": [{"name": "m", "outputs": [
        {"file": "m/base.png", "color_space": "sRGB", "channels": {"RGB": "albedo", "A": "opacity"}},
        {"file": "m/n.png", "color_space": "linear", "channels": {"RGB": "normal"}, "normal_convention": "dx"},
        {"file": "m/mask.png", "color_space": "linear", "channels": {"R": "metalness", "G": "occlusion", "B": 1.0, "A": "smoothness"}},
        {"file": "m/h.png", "color_space": "linear", "channels": {"R": "height"}}
      ], "constants": {"roughness": 0.7}}]})");
    std::vector<std::string> notes;
    const render::Material mat = load(parse(j).materials.at(0), dir, notes);
    ASSERT_EQ(mat.textures.size(), 3u);  // the height map is not read: the preview does not use it
    EXPECT_TRUE(mat.textures[0].srgb);
    EXPECT_EQ(mat.textures[0].channels, 4u);
    EXPECT_EQ(mat.opacity.texture, 0);
    EXPECT_EQ(mat.opacity.channel, render::Channel::A);
    EXPECT_TRUE(mat.normal.green_down);
    EXPECT_EQ(mat.roughness.texture, 2);
    EXPECT_EQ(mat.roughness.channel, render::Channel::A);
    EXPECT_TRUE(mat.roughness.invert);
    EXPECT_EQ(notes.size(), 1u);  // height
}

TEST(Manifest, ConstantsAreRangeCheckedAndApplied) {
    const json j = json::parse(R"({"manifest_version": 1, "materials": [{"name": "m", "outputs": [],
      "constants": {"metalness": 0.25, "emissive": [2, 3, 4], "roughness": 0.5}}]})");
    std::vector<std::string> notes;
    const render::Material mat = load(parse(j).materials.at(0), ".", notes);
    EXPECT_EQ(mat.metalness.value, 0.25f);
    EXPECT_EQ(mat.roughness.value, 0.5f);
    EXPECT_EQ(mat.emissive.value[2], 4.f);
    // 1e300 would overflow a float (undefined behaviour when narrowed): refused, naming the
    // material and the constant, never turned into inf or silently dropped.
    for (const char* bad : {R"({"roughness": 1e300})", R"({"albedo": [0.5, 1e300, 0.5]})", R"({"albedo": [0.5, 0.5]})",
                            R"({"shininess": 0.5})"}) {
        json m = json::parse(R"({"manifest_version": 1, "materials": [{"name": "m", "outputs": []}]})");
        m["materials"][0]["constants"] = json::parse(bad);
        std::string error;
        EXPECT_FALSE(manifest::manifest_from_json(m, error)) << bad;
        EXPECT_NE(error.find("material m: constant"), std::string::npos) << error;
    }
}

TEST(Manifest, TexturesOutsideTheManifestFolderAreRefusedUnlessAllowed) {
    const fs::path dir = temp_dir("outside");
    oiio_write_png8(dir / "elsewhere/a.png", 2, 2, 3, std::vector<uint8_t>(12, 100));
    fs::create_directories(dir / "sub");  // the manifest's folder
    const json j = json::parse(R"({"manifest_version": 1, "materials": [{"name": "m", "outputs": [
        {"file": "../elsewhere/a.png", "color_space": "sRGB", "channels": {"RGB": "albedo"}}]}]})");
    const manifest::Manifest m = parse(j);
    std::vector<std::string> notes;
    std::string error;
    EXPECT_FALSE(load_material(m.materials.at(0), dir / "sub", MaterialOptions{}, notes, error));
    EXPECT_NE(error.find("outside the manifest's folder"), std::string::npos) << error;
    const auto allowed = load_material(m.materials.at(0), dir / "sub", MaterialOptions{true, {}}, notes, error);
    ASSERT_TRUE(allowed) << error;
    EXPECT_EQ(allowed->textures.size(), 1u);
}

TEST(Manifest, AnUnknownChannelRoleIsAnErrorNotAGreyDefault) {
    for (const char* channels : {R"({"RGB": "albedoo"})", R"({"Q": "roughness"})", R"({"R": true})"}) {
        json m =
            json::parse(R"({"manifest_version": 1, "materials": [{"name": "m", "outputs": [{"file": "a.png"}]}]})");
        m["materials"][0]["outputs"][0]["channels"] = json::parse(channels);
        std::string error;
        EXPECT_FALSE(manifest::manifest_from_json(m, error)) << channels;
        EXPECT_NE(error.find("material m: outputs[0]: channel"), std::string::npos) << error;
    }
}

TEST(Manifest, BadManifestsAreErrorsNamingTheMember) {
    std::string error;
    EXPECT_FALSE(manifest::manifest_from_json(json::parse(R"({"materials": []})"), error));
    EXPECT_FALSE(manifest::manifest_from_json(json::parse(R"({"manifest_version": 1})"), error));
    EXPECT_FALSE(manifest::manifest_from_json(json::parse(R"({"manifest_version": 2, "materials": []})"), error));
    EXPECT_NE(error.find("newer"), std::string::npos) << error;
    EXPECT_FALSE(manifest::read_manifest("/nonexistent/manifest.json", error));
    EXPECT_NE(error.find("/nonexistent/manifest.json"), std::string::npos) << error;
    // Wrong types anywhere are errors too, never a JSON type_error (found by the fuzzer: a
    // string among the materials).
    for (
        const char* bad : {
            R"({"manifest_version": 1, "materials": ["x/x.png", {"name": "x"}]})",
            R"({"manifest_version": "1", "materials": []})",
            R"({"manifest_version": 1e100, "materials": []})",
            R"({"manifest_version": 1, "materials": [{"name": 7}]})",
            R"({"manifest_version": 1, "materials": [{"name": "x", "outputs": [3]}]})",
            R"({"manifest_version": 1, "materials": [{"name": "x", "outputs": [{"file": ["a"]}]}]})",
            R"({"manifest_version": 1, "materials": [{"name": "x", "outputs": [{"file": "a.png", "color_space": 1}]}]})",
            R"({"manifest_version": 1, "materials": [{"name": "x", "outputs": [{"file": "a.png", "normal_convention": {}}]}]})",
            R"({"manifest_version": 1, "materials": [{"name": "x", "status": "fine"}]})",
            R"({"manifest_version": 1, "materials": [], "thresholds": []})",
            R"({"manifest_version": 1, "materials": [], "thresholds": {"ALBEDO_TOO_DARK": 30}})",
            R"({"manifest_version": 1, "materials": [], "thresholds": {"ALBEDO_TOO_DARK": {"min_srgb": "30"}}})",
            R"({"manifest_version": 1, "materials": [{"name": "x", "outputs": [{"file": "a.png", "normal_converted_from": "up"}]}]})",
            R"({"manifest_version": 1, "materials": [{"name": "x", "findings": [{"code": "X", "severity": "fatal"}]}]})",
        }) {
        error.clear();
        EXPECT_FALSE(manifest::manifest_from_json(json::parse(bad), error)) << "accepted: " << bad;
        EXPECT_FALSE(error.empty()) << bad;
    }
    // The same members with the right types parse.
    const auto ok = manifest::manifest_from_json(json::parse(R"({"manifest_version": 1, "materials": [{"name": "x",
        "outputs": [{"file": "a.png", "color_space": "sRGB", "normal_convention": "gl"}]}]})"),
                                                 error);
    ASSERT_TRUE(ok) << error;
    EXPECT_TRUE(ok->materials.at(0).outputs.at(0).srgb);
    EXPECT_EQ(ok->materials[0].outputs[0].normal_convention, NormalConvention::gl);
}

// ---- one surface, ingested by every shipped preset, previews the same

constexpr int kW = 32, kH = 16;

struct Source {
    std::vector<double> albedo, normal, roughness, metalness, occlusion;  // per texel
};

// Codes chosen so that every preset's layout stores the surface exactly (smoothness = 255 −
// roughness code, a DirectX green = 255 − the OpenGL code).
Source make_source() {
    Source s;
    const double pi = std::numbers::pi;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const double u = (x + 0.5) / kW, v = (y + 0.5) / kH;
            s.albedo.insert(s.albedo.end(), {0.3 + 0.5 * std::sin(pi * u) * v, 0.4, 0.2 + 0.3 * u});
            const double nx = 0.3 * std::sin(4 * pi * u), ny = 0.3 * std::cos(2 * pi * v);
            const double len = std::sqrt(nx * nx + ny * ny + 1);
            s.normal.insert(s.normal.end(), {nx / len, ny / len, 1 / len});
            s.roughness.push_back(0.2 + 0.6 * u * v);
            s.metalness.push_back(u > 0.5 ? 1.0 : 0.0);
            s.occlusion.push_back(0.6 + 0.4 * v);
        }
    return s;
}

uint8_t code(double v) { return static_cast<uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255)); }

// Writes the outputs `preset` asks for (the roles the source has) and a manifest listing them.
fs::path ingest_like(const fs::path& preset_file, const Source& src, const fs::path& dir) {
    std::ifstream in(preset_file);
    const json preset = json::parse(in);
    const std::string name = preset["name"];
    const bool dx = preset.value("normal_convention", "gl") == "dx";
    json outputs = json::array();
    for (const json& o : preset["outputs"]) {
        json channels = o["channels"];
        for (const json& drop : o.value("drop_if_missing", json::array())) channels.erase(drop.get<std::string>());
        bool useful = false;
        int nch = 0;
        for (const auto& [key, role] : channels.items()) {
            if (key == "RGB") nch = std::max(nch, 3);
            else nch = std::max(nch, int(std::string("RGBA").find(key)) + 1);
            if (role.is_string() && (role == "albedo" || role == "normal" || role == "roughness" ||
                                     role == "smoothness" || role == "metalness" || role == "occlusion"))
                useful = true;
        }
        if (!useful) continue;
        std::vector<uint8_t> px(size_t(kW) * kH * size_t(nch), 0);
        for (size_t p = 0; p < size_t(kW) * kH; ++p) {
            uint8_t* t = &px[p * size_t(nch)];
            for (const auto& [key, role] : channels.items()) {
                if (key == "RGB") {
                    for (int c = 0; c < 3; ++c) {
                        if (role == "albedo") {
                            const double l = src.albedo[3 * p + size_t(c)];
                            t[c] = code(l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1 / 2.4) - 0.055);
                        } else {
                            const uint8_t g = code(src.normal[3 * p + size_t(c)] * 0.5 + 0.5);
                            t[c] = (c == 1 && dx) ? uint8_t(255 - g) : g;
                        }
                    }
                    continue;
                }
                const size_t c = std::string("RGBA").find(key);
                if (role.is_number()) t[c] = code(role.get<double>());
                else if (role == "roughness") t[c] = code(src.roughness[p]);
                else if (role == "smoothness") t[c] = uint8_t(255 - code(src.roughness[p]));
                else if (role == "metalness") t[c] = code(src.metalness[p]);
                else if (role == "occlusion") t[c] = code(src.occlusion[p]);
            }
        }
        const std::string file = "Surface/Surface_" + o["suffix"].get<std::string>() + ".png";
        oiio_write_png8(dir / file, kW, kH, nch, px);
        json out = {{"file", file},         {"color_space", o["color_space"]},
                    {"channels", channels}, {"width", kW},
                    {"height", kH},         {"bit_depth", 8}};
        if (channels.contains("RGB") && channels["RGB"] == "normal") out["normal_convention"] = dx ? "dx" : "gl";
        outputs.push_back(out);
    }
    const json manifest = {{"manifest_version", 1},
                           {"generator", "test"},
                           {"preset", name},
                           {"materials", json::array({{{"name", "Surface"}, {"outputs", outputs}}})}};
    std::ofstream(dir / "manifest.json") << manifest.dump(2);
    return dir / "manifest.json";
}

class PresetInvariance : public test::VulkanTest {};

TEST_F(PresetInvariance, EveryShippedPresetPreviewsTheSameImage) {
    const Source src = make_source();
    render::Scene scene;
    scene.width = scene.height = 96;
    render::Light point;
    point.type = render::LightType::point;
    point.position = {2.5f, -0.5f, 1.5f};
    point.color = {0.3f, 0.5f, 1.0f};
    point.intensity = 10.f;
    scene.lights.push_back(point);
    render::Renderer renderer(context(), scene);

    std::vector<std::pair<std::string, render::Frame>> frames;
    std::vector<fs::path> presets;
    for (const auto& entry : fs::directory_iterator(mf::testenv::source_dir() / "presets"))
        if (entry.path().extension() == ".json") presets.push_back(entry.path());
    std::sort(presets.begin(), presets.end());
    for (const fs::path& file : presets) {
        const std::string preset = file.stem().string();
        const fs::path manifest = ingest_like(file, src, temp_dir("preset_" + preset));
        std::vector<std::string> notes;
        std::string error;
        const auto man = manifest::read_manifest(manifest.string(), error);
        ASSERT_TRUE(man) << error;
        const render::Material m = load(man->materials.at(0), manifest.parent_path(), notes);
        const render::GpuMaterial gm = renderer.upload(m);
        EXPECT_NE(gm.variant().find("albedo:tex normal:"), std::string::npos) << preset << ": " << gm.variant();
        frames.emplace_back(preset, renderer.render(gm));
    }
    ASSERT_GE(frames.size(), 6u);  // gltf, unreal, unity-hdrp, unity-urp, godot, separate
    for (size_t i = 1; i < frames.size(); ++i) {
        int max_code = 0;
        for (size_t k = 0; k < frames[0].second.rgba8.size(); ++k)
            max_code = std::max(max_code, std::abs(int(frames[i].second.rgba8[k]) - int(frames[0].second.rgba8[k])));
        EXPECT_LE(max_code, 1) << frames[i].first << " vs " << frames[0].first;
        std::printf("  %-12s vs %-12s max |Δcode| %d\n", frames[i].first.c_str(), frames[0].first.c_str(), max_code);
    }
}

}  // namespace
}  // namespace mf::preview
