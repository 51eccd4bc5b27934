// `matforge ingest` on the synthetic sets of tools/gen_samples, generated at test time: the
// cases the real samples do not have (a set shipped as .zip, a DirectX-only ambientCG set, a
// gloss map and two albedo resolutions, a Megascans ORT, a glTF metallicRoughness map, an
// unnamed DirectX normal, EXR and 16-bit inputs in a nested folder).
#include <map>
#include <set>

#include "cli_util.hpp"
#include "synthetic_sets.hpp"

using namespace mft;

namespace {

// The named synthetic sets, generated once per process into their own folder.
fs::path synthetic(const std::vector<std::string>& sets) {
    static std::map<std::vector<std::string>, fs::path> cache;
    auto it = cache.find(sets);
    if (it != cache.end()) return it->second;
    std::string key;
    for (const auto& s : sets) key += "-" + s;
    const fs::path dir = fs::temp_directory_path() / ("matforge-cli-synthetic-" + std::to_string(::getpid()) + key);
    fs::remove_all(dir);
    EXPECT_TRUE(mf::testbin::generate_synthetic(dir, sets));
    return cache[sets] = dir;
}

// One ingest of those sets per preset.
const nlohmann::json& ingested(const std::vector<std::string>& sets, const std::string& preset) {
    static std::map<std::pair<std::vector<std::string>, std::string>, nlohmann::json> cache;
    auto it = cache.find({sets, preset});
    if (it != cache.end()) return it->second;
    const fs::path out = synthetic(sets).string() + "-out-" + preset;
    fs::remove_all(out);
    const auto r = run("ingest " + q(synthetic(sets)) + " -o " + q(out) + " --preset " + preset + " --fail-on error");
    EXPECT_EQ(r.code, 0) << r.output;
    auto m = read_json(out / "manifest.json");
    m["__out"] = out.string();
    return cache[{sets, preset}] = m;
}

// Removes this process's generated sets and outputs when the program ends.
struct CleanupSynthetic : ::testing::Environment {
    void TearDown() override {
        const std::string mine = "matforge-cli-synthetic-" + std::to_string(::getpid());
        std::error_code ec;
        for (const auto& e : fs::directory_iterator(fs::temp_directory_path(), ec))
            if (e.path().filename().string().rfind(mine, 0) == 0) fs::remove_all(e.path(), ec);
    }
};
[[maybe_unused]] auto* const kCleanupSynthetic = ::testing::AddGlobalTestEnvironment(new CleanupSynthetic);

const std::vector<std::string> kTiles{"Tiles101"};

}  // namespace

class SyntheticEveryPreset : public ::testing::TestWithParam<std::string> {};

TEST_P(SyntheticEveryPreset, IngestsAllSetsWithValidHashes) {
    // All nine synthetic sets (zip, EXR, 16-bit, gloss, ORT, metallicRoughness...) through the preset.
    const auto& m = ingested({}, GetParam());
    std::set<std::string> names;
    for (const auto& mat : m["materials"]) names.insert(mat["name"]);
    EXPECT_EQ(names, (std::set<std::string>{"Bricks076", "MarbleTiles0017", "MetalPlates013", "ScifiPanel", "Tiles101",
                                            "WalnutInlay", "ivy_leaves", "rocky_ground_02", "wood_planks_worn"}));
    expect_outputs_as_recorded(m);
}

INSTANTIATE_TEST_SUITE_P(Presets, SyntheticEveryPreset,
                         ::testing::Values("gltf", "unreal", "unity-hdrp", "unity-urp", "godot", "separate"),
                         [](const auto& param_info) {
                             std::string s = param_info.param;
                             std::replace(s.begin(), s.end(), '-', '_');
                             return s;
                         });

TEST(SyntheticSets, ZipSetWithDxNormalIsFlippedToGl) {
    const auto& m = ingested(kTiles, "gltf");
    const auto* mat = material(m, "Tiles101");
    ASSERT_TRUE(mat);
    EXPECT_NE((*mat)["source"].get<std::string>().find("Tiles101_1K-PNG.zip"), std::string::npos);
    EXPECT_TRUE(has_finding(*mat, "NORMAL_CONVENTION_CONVERTED", "normal"));
    const auto* n = output_with(*mat, "RGB", "normal");
    ASSERT_TRUE(n);
    EXPECT_EQ((*n)["normal_convention"], "gl");
    // Compare with the DX input (extracted by a second ingest with the DX-preferring preset).
    const auto* u = material(ingested(kTiles, "unreal"), "Tiles101");
    ASSERT_TRUE(u);
    const auto gl = output_pixels(m, *n);
    const auto dx = output_pixels(ingested(kTiles, "unreal"), *output_with(*u, "RGB", "normal"));
    expect_green_mirrored(gl, dx);
}

TEST(SyntheticSets, NormalConventionOverrideReachesThePixels) {
    // --normal-convention dx on the glTF preset: written as DX, and its pixels are the GL
    // output's with green mirrored.
    const fs::path out = temp_dir("dx");
    const auto r = run("ingest " + q(synthetic(kTiles) / "Tiles101_1K-PNG.zip") + " -o " + q(out) +
                       " --preset gltf --normal-convention dx");
    ASSERT_EQ(r.code, 0) << r.output;
    const auto m = read_json(out / "manifest.json");
    EXPECT_EQ(m["normal_convention"], "dx");
    const auto& mat = m["materials"][0];
    const auto* n = output_with(mat, "RGB", "normal");
    ASSERT_TRUE(n);
    EXPECT_EQ((*n)["normal_convention"], "dx");
    EXPECT_FALSE(has_finding(mat, "NORMAL_CONVENTION_CONVERTED")) << "DX in, DX out";
    const auto dx = read_pixels(out / (*n)["file"].get<std::string>());
    const auto& gl_manifest = ingested(kTiles, "gltf");
    const auto gl =
        read_pixels(out_of(gl_manifest) /
                    output_with(*material(gl_manifest, "Tiles101"), "RGB", "normal")->at("file").get<std::string>());
    ASSERT_EQ(dx.pixels.size(), gl.pixels.size());
    for (int y = 0; y < dx.height; y += 3)
        for (int x = 0; x < dx.width; x += 3) ASSERT_NEAR(code8(dx.at(x, y, 1)), 255 - code8(gl.at(x, y, 1)), 1);
}

TEST(SyntheticSets, GlossInvertedAndLargestAlbedoChosen) {
    const auto& m = ingested({"MarbleTiles0017"}, "gltf");
    const auto* mat = material(m, "MarbleTiles0017");
    ASSERT_TRUE(mat);
    EXPECT_EQ((*mat)["convention"], "texturescom");
    EXPECT_TRUE(has_finding(*mat, "GLOSS_INVERTED", "roughness"));
    EXPECT_TRUE(has_finding(*mat, "AMBIGUOUS_MAP", "albedo"));
    EXPECT_EQ((*mat)["inputs"]["albedo"]["file"], "MarbleTiles0017_COL_2K.jpg");
    EXPECT_TRUE(has_finding(*mat, "RESOLUTION_MISMATCH"));
    const auto* orm = output_with(*mat, "G", "roughness");
    ASSERT_TRUE(orm);
    EXPECT_EQ((*orm)["width"], 256) << "all maps brought to the largest size";
}

TEST(SyntheticSets, ResolutionMismatchNamesEachResampledMap) {
    // MarbleTiles0017's albedo is 2K (256 px here), its other maps 1K (128 px): the set is the
    // albedo's size, so the 1K maps the preset uses are resampled, and each gets the warning; the
    // albedo, at the set's size, none (the rules once put it on the albedo, the odd one out).
    const auto r = run("validate " + q(synthetic({"MarbleTiles0017"}) / "MarbleTiles0017") + " --report sarif");
    ASSERT_EQ(r.code, 0) << r.output;
    const auto j = nlohmann::json::parse(r.output);
    std::set<std::string> on;
    for (const auto& res : j["runs"][0]["results"]) {
        if (res["ruleId"] != "RESOLUTION_MISMATCH") continue;
        const std::string uri = res["locations"][0]["physicalLocation"]["artifactLocation"]["uri"];
        on.insert(uri.substr(uri.rfind('/') + 1));
        EXPECT_EQ(res["level"], "warning");
        EXPECT_NE(res["message"]["text"].get<std::string>().find("but the set is 256x256 (MarbleTiles0017_COL_2K.jpg)"),
                  std::string::npos)
            << res.dump();
    }
    EXPECT_EQ(on, (std::set<std::string>{"MarbleTiles0017_AO_1K.jpg", "MarbleTiles0017_DISP_1K.jpg",
                                         "MarbleTiles0017_GLOSS_1K.jpg", "MarbleTiles0017_NRM_1K.jpg"}));
    EXPECT_EQ(run("validate " + q(synthetic({"MarbleTiles0017"})) + " --fail-on warning").code, 1);
}

TEST(SyntheticSets, PackedArmUnpackedAndRepacked) {
    const auto& m = ingested({"wood_planks_worn"}, "gltf");
    const auto* mat = material(m, "wood_planks_worn");
    ASSERT_TRUE(mat);
    EXPECT_TRUE(has_finding(*mat, "PACKED_INPUT_UNPACKED", "orm"));
    EXPECT_FALSE((*mat)["constants"].contains("metalness"));
    // ARM and glTF ORM share a layout: the packed output equals the input.
    const auto arm = read_pixels(synthetic({"wood_planks_worn"}) / "wood_planks_worn/wood_planks_worn_arm_1k.png");
    const auto orm = output_pixels(m, *output_with(*mat, "B", "metalness"));
    ASSERT_EQ(arm.pixels.size(), orm.pixels.size());
    for (size_t i = 0; i < arm.pixels.size(); ++i) ASSERT_EQ(code8(arm.pixels[i]), code8(orm.pixels[i]));
}

TEST(SyntheticSets, OrtBlueIsNeverMetalness) {
    const auto& m = ingested({"ivy_leaves"}, "gltf");
    const auto* mat = material(m, "ivy_leaves");
    ASSERT_TRUE(mat);
    EXPECT_EQ((*mat)["convention"], "megascans");
    EXPECT_EQ((*mat)["constants"]["metalness"], 0.0);
    const auto* bc = output_with(*mat, "RGB", "albedo");
    ASSERT_TRUE(bc);
    EXPECT_EQ((*bc)["channels"]["A"], "opacity") << "cut-out leaves keep their opacity in alpha";
    const auto orm = output_pixels(m, *output_with(*mat, "B", "metalness"));
    for (size_t i = 2; i < orm.pixels.size(); i += 3) ASSERT_EQ(orm.pixels[i], 0.f);
}

TEST(SyntheticSets, GltfMetallicRoughnessChannels) {
    const auto& m = ingested({"WalnutInlay"}, "unity-hdrp");
    const auto* mat = material(m, "WalnutInlay");
    ASSERT_TRUE(mat);
    const auto mr = read_pixels(synthetic({"WalnutInlay"}) / "WalnutInlay/WalnutInlay_metallicRoughness.png");
    const auto* mask = output_with(*mat, "A", "smoothness");
    ASSERT_TRUE(mask);
    const auto out = output_pixels(m, *mask);
    for (int y = 0; y < out.height; y += 4)
        for (int x = 0; x < out.width; x += 4) {
            ASSERT_EQ(code8(out.at(x, y, 0)), code8(mr.at(x, y, 2))) << "R metallic <- B";
            ASSERT_EQ(code8(out.at(x, y, 3)), 255 - code8(mr.at(x, y, 1))) << "A smoothness <- 1 - G";
        }
}

TEST(SyntheticSets, SeparatePresetTwoByTwoConstants) {
    // rocky_ground_02: maps nested under textures/, a 16-bit PNG height, no metalness.
    const auto& m = ingested({"rocky_ground_02"}, "separate");
    const auto* mat = material(m, "rocky_ground_02");
    ASSERT_TRUE(mat);
    const auto* metal = output_with(*mat, "R", "metalness");
    ASSERT_TRUE(metal);
    EXPECT_EQ((*metal)["width"], 2);
    EXPECT_EQ((*metal)["height"], 2);
    const auto* h = output_with(*mat, "R", "height");
    ASSERT_TRUE(h);
    EXPECT_EQ((*h)["bit_depth"], 16);
}

TEST(IngestContent, UnnamedDxNormalDecidedFromContent) {
    // ScifiPanel's "_Normal" says nothing about green; its pixels are DirectX.
    const fs::path out = temp_dir("out");
    const auto r = run("ingest " + q(synthetic({"ScifiPanel"}) / "ScifiPanel") + " -o " + q(out));
    ASSERT_EQ(r.code, 0) << r.output;
    const auto m = read_json(out / "manifest.json");
    const auto& n = m["materials"][0]["inputs"]["normal"];
    EXPECT_EQ(n["normal_convention"], "dx");
    EXPECT_EQ(n["normal_convention_source"], "content");
    EXPECT_GE(n["normal_convention_confidence"].get<double>(), 0.6);
    EXPECT_TRUE(has_finding(m["materials"][0], "NORMAL_CONVENTION_CONVERTED", "normal"));
}
