// `matforge ingest` on the bundled sample_materials/, as the README runs it.
#include "cli_util.hpp"

using namespace mft;

namespace {

// One ingest per preset, shared by the tests of this file (each run takes ~1 s).
const nlohmann::json& ingested(const std::string& preset) {
    static std::map<std::string, nlohmann::json> cache;
    auto it = cache.find(preset);
    if (it != cache.end()) return it->second;
    // Per process: ctest runs each test in its own process, several at once.
    const fs::path out = fs::temp_directory_path() /
                         ("matforge-cli-samples-" + preset + "-" + std::to_string(::getpid()));
    fs::remove_all(out);
    const auto r = run("ingest " + q(samples()) + " -o " + q(out) + " --preset " + preset + " --fail-on error");
    EXPECT_EQ(r.code, 0) << r.output;
    auto m = read_json(out / "manifest.json");
    m["__out"] = out.string();
    return cache[preset] = m;
}

// Removes the shared per-process outputs when the program ends.
struct CleanupOutputs : ::testing::Environment {
    void TearDown() override {
        for (const char* p : {"gltf", "unreal", "unity-hdrp", "unity-urp", "godot", "separate"})
            fs::remove_all(fs::temp_directory_path() / ("matforge-cli-samples-" + std::string(p) + "-" + std::to_string(::getpid())));
    }
};
[[maybe_unused]] auto* const kCleanup = ::testing::AddGlobalTestEnvironment(new CleanupOutputs);

fs::path out_of(const nlohmann::json& m) { return m["__out"].get<std::string>(); }

mf::Image input_pixels(const std::string& rel) { return read_pixels(samples() / rel); }

mf::Image output_pixels(const nlohmann::json& m, const nlohmann::json& o) {
    return read_pixels(out_of(m) / o["file"].get<std::string>());
}

}  // namespace

class EveryPreset : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryPreset, IngestsAllSetsWithValidHashes) {
    const auto& m = ingested(GetParam());
    EXPECT_EQ(m["manifest_version"], 1);
    EXPECT_EQ(m["preset"], GetParam());
    EXPECT_EQ(m["materials"].size(), 9u);
    EXPECT_TRUE(m["failures"].empty()) << m["failures"].dump(1);
    for (const auto& mat : m["materials"]) {
        EXPECT_EQ(mat["status"], "ok") << mat["name"];
        EXPECT_FALSE(mat["outputs"].empty());
        for (const auto& o : mat["outputs"]) {
            std::vector<unsigned char> bytes;
            std::string err;
            ASSERT_TRUE(mf::read_file(out_of(m) / o["file"].get<std::string>(), bytes, err)) << err;
            EXPECT_EQ(mf::sha256_hex(bytes), o["sha256"]) << o["file"];
            const auto img = output_pixels(m, o);
            EXPECT_EQ(img.width, o["width"]);
            EXPECT_EQ(img.height, o["height"]);
        }
    }
}

TEST_P(EveryPreset, SecondRunIsByteIdentical) {
    const auto& first = ingested(GetParam());
    const fs::path out2 = temp_dir(GetParam());
    const auto r = run("ingest " + q(samples()) + " -o " + q(out2) + " --preset " + GetParam() + " --jobs 1");
    ASSERT_EQ(r.code, 0) << r.output;
    auto second = read_json(out2 / "manifest.json");
    second["__out"] = first["__out"];
    // Same manifest apart from where it lies (source paths are relative to the manifest).
    for (auto& mat : second["materials"]) mat.erase("source"), mat.erase("archive");
    auto a = first;
    for (auto& mat : a["materials"]) mat.erase("source"), mat.erase("archive");
    EXPECT_EQ(a, second);
    // Identical output bytes: the manifest's hashes already cover them; check one file directly too.
    const auto& o = first["materials"][0]["outputs"][0];
    std::vector<unsigned char> x, y;
    std::string err;
    ASSERT_TRUE(mf::read_file(out_of(first) / o["file"].get<std::string>(), x, err));
    ASSERT_TRUE(mf::read_file(out2 / o["file"].get<std::string>(), y, err));
    EXPECT_EQ(x, y);
}

INSTANTIATE_TEST_SUITE_P(Presets, EveryPreset,
                         ::testing::Values("gltf", "unreal", "unity-hdrp", "unity-urp", "godot", "separate"),
                         [](const auto& param_info) {
                             std::string s = param_info.param;
                             std::replace(s.begin(), s.end(), '-', '_');
                             return s;
                         });

TEST(IngestSamples, RerunIntoSameFolderIsStable) {
    const auto& m = ingested("gltf");
    const auto r = run("ingest " + q(samples()) + " -o " + q(out_of(m)) + " --preset gltf");
    ASSERT_EQ(r.code, 0) << r.output;
    auto again = read_json(out_of(m) / "manifest.json");
    again["__out"] = m["__out"];
    EXPECT_EQ(again, m);
}

TEST(IngestSamples, AmbientCgGlAndDxChoosesPresetConvention) {
    const auto& m = ingested("gltf");
    const auto* mat = material(m, "Bricks076");
    ASSERT_TRUE(mat);
    EXPECT_EQ((*mat)["convention"], "ambientcg");
    EXPECT_EQ((*mat)["inputs"]["normal"]["file"], "Bricks076_1K-PNG_NormalGL.png");
    EXPECT_EQ((*mat)["inputs"]["normal"]["normal_convention"], "gl");
    EXPECT_TRUE(has_finding(*mat, "AMBIGUOUS_MAP", "normal"));
    EXPECT_FALSE(has_finding(*mat, "NORMAL_CONVENTION_CONVERTED"));
    EXPECT_TRUE(has_finding(*mat, "UNRECOGNIZED_FILE"));
    // Unreal wants DirectX: the DX file is chosen, nothing to convert.
    const auto* u = material(ingested("unreal"), "Bricks076");
    ASSERT_TRUE(u);
    EXPECT_EQ((*u)["inputs"]["normal"]["file"], "Bricks076_1K-PNG_NormalDX.png");
    EXPECT_FALSE(has_finding(*u, "NORMAL_CONVENTION_CONVERTED"));
}

TEST(IngestSamples, MissingMetalnessBakedAsZeroAndAlbedoBitExact) {
    const auto& m = ingested("gltf");
    const auto* mat = material(m, "Bricks076");
    ASSERT_TRUE(mat);
    EXPECT_EQ((*mat)["constants"]["metalness"], 0.0);
    EXPECT_TRUE(has_finding(*mat, "MISSING_MAP", "metalness"));
    const auto* orm = output_with(*mat, "B", "metalness");
    ASSERT_TRUE(orm);
    const auto img = output_pixels(m, *orm);
    for (int y = 0; y < img.height; y += 7)
        for (int x = 0; x < img.width; x += 5) ASSERT_EQ(code8(img.at(x, y, 2)), 0);
    // Roughness copied into G exactly; occlusion into R.
    const auto rough = input_pixels("Bricks076_1K-PNG/Bricks076_1K-PNG_Roughness.png");
    const auto ao = input_pixels("Bricks076_1K-PNG/Bricks076_1K-PNG_AmbientOcclusion.png");
    for (int y = 0; y < img.height; y += 3)
        for (int x = 0; x < img.width; x += 3) {
            ASSERT_EQ(code8(img.at(x, y, 1)), code8(rough.at(x, y, 0)));
            ASSERT_EQ(code8(img.at(x, y, 0)), code8(ao.at(x, y, 0)));
        }
    // sRGB albedo in, sRGB out at the same size: bit-exact.
    const auto* bc = output_with(*mat, "RGB", "albedo");
    ASSERT_TRUE(bc);
    EXPECT_EQ((*bc)["color_space"], "sRGB");
    const auto out = output_pixels(m, *bc);
    const auto in = input_pixels("Bricks076_1K-PNG/Bricks076_1K-PNG_Color.png");
    ASSERT_EQ(out.pixels.size(), in.pixels.size());
    for (size_t i = 0; i < in.pixels.size(); ++i) ASSERT_EQ(code8(out.pixels[i]), code8(in.pixels[i])) << i;
}

TEST(IngestSamples, ZipSetWithDxNormalIsFlippedToGl) {
    const auto& m = ingested("gltf");
    const auto* mat = material(m, "Tiles101");
    ASSERT_TRUE(mat);
    EXPECT_NE((*mat)["source"].get<std::string>().find("Tiles101_1K-PNG.zip"), std::string::npos);
    EXPECT_TRUE(has_finding(*mat, "NORMAL_CONVENTION_CONVERTED", "normal"));
    const auto* n = output_with(*mat, "RGB", "normal");
    ASSERT_TRUE(n);
    EXPECT_EQ((*n)["normal_convention"], "gl");
    // Compare with the DX input (extracted by a second ingest with the DX-preferring preset).
    const auto* u = material(ingested("unreal"), "Tiles101");
    ASSERT_TRUE(u);
    const auto gl = output_pixels(m, *n);
    const auto dx = output_pixels(ingested("unreal"), *output_with(*u, "RGB", "normal"));
    int worst = 0;
    for (int y = 0; y < gl.height; ++y)
        for (int x = 0; x < gl.width; ++x) {
            worst = std::max(worst, std::abs(code8(gl.at(x, y, 1)) - (255 - code8(dx.at(x, y, 1)))));
            ASSERT_NEAR(code8(gl.at(x, y, 0)), code8(dx.at(x, y, 0)), 1);
        }
    EXPECT_LE(worst, 1) << "green flipped (255 - g, renormalization may move one code)";
}

TEST(IngestSamples, GlossInvertedAndLargestAlbedoChosen) {
    const auto& m = ingested("gltf");
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

TEST(IngestSamples, PackedArmUnpackedAndRepacked) {
    const auto& m = ingested("gltf");
    const auto* mat = material(m, "wood_planks_worn");
    ASSERT_TRUE(mat);
    EXPECT_TRUE(has_finding(*mat, "PACKED_INPUT_UNPACKED", "orm"));
    EXPECT_FALSE((*mat)["constants"].contains("metalness"));
    // ARM and glTF ORM share a layout: the packed output equals the input.
    const auto arm = input_pixels("wood_planks_worn/wood_planks_worn_arm_1k.png");
    const auto orm = output_pixels(m, *output_with(*mat, "B", "metalness"));
    ASSERT_EQ(arm.pixels.size(), orm.pixels.size());
    for (size_t i = 0; i < arm.pixels.size(); ++i) ASSERT_EQ(code8(arm.pixels[i]), code8(orm.pixels[i]));
}

TEST(IngestSamples, OrtBlueIsNeverMetalness) {
    const auto& m = ingested("gltf");
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

TEST(IngestSamples, GltfMetallicRoughnessChannels) {
    const auto& m = ingested("unity-hdrp");
    const auto* mat = material(m, "WalnutInlay");
    ASSERT_TRUE(mat);
    const auto mr = input_pixels("WalnutInlay/WalnutInlay_metallicRoughness.png");
    const auto* mask = output_with(*mat, "A", "smoothness");
    ASSERT_TRUE(mask);
    const auto out = output_pixels(m, *mask);
    for (int y = 0; y < out.height; y += 4)
        for (int x = 0; x < out.width; x += 4) {
            ASSERT_EQ(code8(out.at(x, y, 0)), code8(mr.at(x, y, 2))) << "R metallic <- B";
            ASSERT_EQ(code8(out.at(x, y, 3)), 255 - code8(mr.at(x, y, 1))) << "A smoothness <- 1 - G";
        }
}

TEST(IngestSamples, SeparatePresetTwoByTwoConstants) {
    const auto& m = ingested("separate");
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

TEST(IngestSamples, NormalConventionOverrideReachesThePixels) {
    // --normal-convention dx on the glTF preset: written as DX, and its pixels are the GL
    // output's with green mirrored.
    const fs::path out = temp_dir("dx");
    const auto r = run("ingest " + q(samples() / "Tiles101_1K-PNG.zip") + " -o " + q(out) +
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
    const auto& gl_manifest = ingested("gltf");
    const auto gl = read_pixels(out_of(gl_manifest) / output_with(*material(gl_manifest, "Tiles101"), "RGB", "normal")
                                                          ->at("file").get<std::string>());
    ASSERT_EQ(dx.pixels.size(), gl.pixels.size());
    for (int y = 0; y < dx.height; y += 3)
        for (int x = 0; x < dx.width; x += 3) ASSERT_NEAR(code8(dx.at(x, y, 1)), 255 - code8(gl.at(x, y, 1)), 1);
}
