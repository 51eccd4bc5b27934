// `matforge ingest` on the bundled sample_materials/, as the README runs it. The samples are
// real CC0 sets as vendors ship them (sample_materials/SOURCES.md); the expected roles,
// conventions and values are their measured ground truth.
#include <cmath>
#include <set>

#include "cli_util.hpp"

using namespace mft;

namespace {

// Every material of sample_materials/, in the manifest's (name) order: the flat folder holds two.
const std::vector<std::string> kMaterials{"Crystal_003", "Metal_Damaged_001", "Net004A", "brown_planks_09"};

// One ingest per preset, shared by the tests of this file (each run takes a few seconds).
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
            fs::remove_all(fs::temp_directory_path() /
                           ("matforge-cli-samples-" + std::string(p) + "-" + std::to_string(::getpid())));
    }
};
[[maybe_unused]] auto* const kCleanupOutputs = ::testing::AddGlobalTestEnvironment(new CleanupOutputs);

mf::Image input_pixels(const std::string& rel) { return read_pixels(samples() / rel); }

const nlohmann::json& mat_of(const nlohmann::json& m, const std::string& name) {
    const auto* mat = material(m, name);
    if (!mat) ADD_FAILURE() << name << " is not in the manifest";
    static const nlohmann::json empty = nlohmann::json::object();
    return mat ? *mat : empty;
}

// Files named by the material's findings of `code`.
std::set<std::string> files_of(const nlohmann::json& mat, const std::string& code) {
    std::set<std::string> files;
    for (const auto& f : mat["findings"])
        if (f["code"] == code) files.insert(f.value("file", ""));
    return files;
}

// Mean code of channel c.
double mean_code(const mf::Image& img, int c) {
    double sum = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) sum += code8(img.at(x, y, c));
    return sum / (static_cast<double>(img.width) * img.height);
}

// Pearson correlation of channel c of a and b (same size).
double correlation(const mf::Image& a, const mf::Image& b, int c) {
    double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
    const double n = static_cast<double>(a.width) * a.height;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            const double u = a.at(x, y, c), v = b.at(x, y, c);
            sa += u, sb += v, saa += u * u, sbb += v * v, sab += u * v;
        }
    return (sab - sa * sb / n) / std::sqrt((saa - sa * sa / n) * (sbb - sb * sb / n));
}

}  // namespace

class EveryPreset : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryPreset, IngestsAllSetsWithValidHashes) {
    const auto& m = ingested(GetParam());
    EXPECT_EQ(m["manifest_version"], 1);
    EXPECT_EQ(m["preset"], GetParam());
    std::vector<std::string> names;
    for (const auto& mat : m["materials"]) names.push_back(mat["name"]);
    EXPECT_EQ(names, kMaterials);
    expect_outputs_as_recorded(m);
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

TEST(IngestSamples, FlatFolderSplitsIntoItsTwoSets) {
    // flat_two_sets/ holds Poly Haven's brown_planks_09 and 3dtextures.me's Crystal_003.
    const auto& m = ingested("gltf");
    for (const std::string name : {"Crystal_003", "brown_planks_09"}) {
        const auto& mat = mat_of(m, name);
        const std::string source = mat["source"];
        EXPECT_EQ(fs::path(source).filename(), "flat_two_sets") << source;
        ASSERT_FALSE(mat["inputs"].empty());
        for (const auto& [role, in] : mat["inputs"].items())
            EXPECT_EQ(in["file"].get<std::string>().rfind(name + "_", 0), 0u)
                << name << " " << role << ": " << in["file"];
        for (const auto& f : mat["findings"]) {
            if (f.contains("file")) {
                EXPECT_EQ(f["file"].get<std::string>().rfind(name + "_", 0), 0u) << name << ": " << f;
            }
        }
    }
    EXPECT_EQ(mat_of(m, "Crystal_003")["convention"], "generic");
    EXPECT_EQ(mat_of(m, "brown_planks_09")["convention"], "polyhaven");
    // The all-black file with no role is skipped, and it is the only file skipped.
    EXPECT_EQ(files_of(mat_of(m, "Crystal_003"), "UNRECOGNIZED_FILE"), std::set<std::string>{"Crystal_003_BLACK.jpg"});
    EXPECT_TRUE(files_of(mat_of(m, "brown_planks_09"), "UNRECOGNIZED_FILE").empty());
}

TEST(IngestSamples, AmbientCgGlAndDxChoosesPresetConvention) {
    const auto& m = ingested("gltf");
    const auto& mat = mat_of(m, "Net004A");
    EXPECT_EQ(mat["convention"], "ambientcg");
    EXPECT_EQ(mat["inputs"]["normal"]["file"], "Net004A_1K-JPG_NormalGL.jpg");
    EXPECT_EQ(mat["inputs"]["normal"]["normal_convention"], "gl");
    EXPECT_EQ(mat["inputs"]["normal"]["normal_convention_source"], "name");
    EXPECT_TRUE(has_finding(mat, "AMBIGUOUS_MAP", "normal"));
    EXPECT_FALSE(has_finding(mat, "NORMAL_CONVENTION_CONVERTED"));
    // Its USD file is skipped, nothing else; the vendor's preview is the set's preview input (never
    // read as a map); its MaterialX document is read as evidence: the normal map it names through a
    // normalmap node is the GL one.
    EXPECT_EQ(files_of(mat, "UNRECOGNIZED_FILE"), (std::set<std::string>{"Net004A_1K-JPG.usdc"}));
    EXPECT_EQ(mat["inputs"]["preview"]["file"], "Net004A.png");
    EXPECT_EQ(mat["inputs"]["normal"]["rule"], "ambientcg:_NormalGL + mtlx:standard_surface.normal");
    // Unreal wants DirectX: the DX file is chosen, nothing to convert.
    const auto& u = mat_of(ingested("unreal"), "Net004A");
    EXPECT_EQ(u["inputs"]["normal"]["file"], "Net004A_1K-JPG_NormalDX.jpg");
    EXPECT_EQ(u["inputs"]["normal"]["normal_convention"], "dx");
    EXPECT_FALSE(has_finding(u, "NORMAL_CONVENTION_CONVERTED"));
    const auto* n = output_with(u, "RGB", "normal");
    ASSERT_TRUE(n);
    EXPECT_EQ((*n)["normal_convention"], "dx");
}

TEST(IngestSamples, AmbientCgDxAloneIsFlippedToGl) {
    // Net004A without its GL file: the DX map is converted for glTF. The vendor's own GL map
    // is the ground truth for the flip.
    const fs::path work = temp_dir("dx");
    fs::create_directories(work / "in/Net004A_1K-JPG");
    for (const auto& e : fs::directory_iterator(samples() / "Net004A_1K-JPG"))
        if (e.path().filename() != "Net004A_1K-JPG_NormalGL.jpg")
            fs::copy(e.path(), work / "in/Net004A_1K-JPG" / e.path().filename());
    for (const char* preset : {"gltf", "unreal"}) {
        const auto r = run("ingest " + q(work / "in") + " -o " + q(work / preset) + " --preset " + preset);
        ASSERT_EQ(r.code, 0) << r.output;
    }
    const auto gm = read_json(work / "gltf/manifest.json"), um = read_json(work / "unreal/manifest.json");
    const auto& g = gm["materials"][0];
    EXPECT_EQ(g["inputs"]["normal"]["file"], "Net004A_1K-JPG_NormalDX.jpg");
    EXPECT_TRUE(has_finding(g, "NORMAL_CONVENTION_CONVERTED", "normal"));
    EXPECT_FALSE(has_finding(um["materials"][0], "NORMAL_CONVENTION_CONVERTED"));
    const auto* gn = output_with(g, "RGB", "normal");
    const auto* un = output_with(um["materials"][0], "RGB", "normal");
    ASSERT_TRUE(gn && un);
    EXPECT_EQ((*gn)["normal_convention"], "gl");
    const auto gl = read_pixels(work / "gltf" / (*gn)["file"].get<std::string>());
    const auto dx = read_pixels(work / "unreal" / (*un)["file"].get<std::string>());
    expect_green_mirrored(gl, dx);
    // Against the vendor's GL map: the flipped green follows it, the unflipped one mirrors it.
    const auto vendor_gl = input_pixels("Net004A_1K-JPG/Net004A_1K-JPG_NormalGL.jpg");
    ASSERT_EQ(vendor_gl.pixels.size(), gl.pixels.size());
    EXPECT_GT(correlation(gl, vendor_gl, 1), 0.95);
    EXPECT_LT(correlation(dx, vendor_gl, 1), -0.95);
    EXPECT_GT(correlation(gl, vendor_gl, 0), 0.95) << "red is the same in both conventions";
}

TEST(IngestSamples, MissingMetalnessBakedAsZeroAndAlbedoBitExact) {
    // Crystal_003: roughness and occlusion maps, no metalness map.
    const auto& m = ingested("gltf");
    const auto& mat = mat_of(m, "Crystal_003");
    EXPECT_EQ(mat["constants"]["metalness"], 0.0);
    EXPECT_TRUE(has_finding(mat, "MISSING_MAP", "metalness"));
    const auto* orm = output_with(mat, "B", "metalness");
    ASSERT_TRUE(orm);
    const auto img = output_pixels(m, *orm);
    ASSERT_EQ(img.width, 1024);
    for (int y = 0; y < img.height; y += 7)
        for (int x = 0; x < img.width; x += 5) ASSERT_EQ(code8(img.at(x, y, 2)), 0);
    // Roughness copied into G exactly; occlusion into R (3dtextures.me stores grey as R = G = B).
    const auto rough = input_pixels("flat_two_sets/Crystal_003_ROUGH.jpg");
    const auto ao = input_pixels("flat_two_sets/Crystal_003_OCC.jpg");
    for (int y = 0; y < img.height; y += 3)
        for (int x = 0; x < img.width; x += 3) {
            ASSERT_EQ(code8(img.at(x, y, 1)), code8(rough.at(x, y, 0)));
            ASSERT_EQ(code8(img.at(x, y, 0)), code8(ao.at(x, y, 0)));
        }
    // sRGB albedo in, sRGB out at the same size: bit-exact.
    const auto* bc = output_with(mat, "RGB", "albedo");
    ASSERT_TRUE(bc);
    EXPECT_EQ((*bc)["color_space"], "sRGB");
    const auto out = output_pixels(m, *bc);
    const auto in = input_pixels("flat_two_sets/Crystal_003_COLOR.jpg");
    ASSERT_EQ(out.pixels.size(), in.pixels.size());
    for (size_t i = 0; i < in.pixels.size(); ++i) ASSERT_EQ(code8(out.pixels[i]), code8(in.pixels[i])) << i;
}

TEST(IngestSamples, OpacityMapBecomesBaseColorAlpha) {
    // Net004A: a real cut-out (22.3 % of the pixels above 127), no occlusion or metalness map.
    const auto& m = ingested("gltf");
    const auto& mat = mat_of(m, "Net004A");
    const auto* bc = output_with(mat, "RGB", "albedo");
    ASSERT_TRUE(bc);
    EXPECT_EQ((*bc)["channels"]["A"], "opacity");
    const auto out = output_pixels(m, *bc);
    ASSERT_EQ(out.channels, 4);
    const auto opacity = input_pixels("Net004A_1K-JPG/Net004A_1K-JPG_Opacity.jpg");
    const auto color = input_pixels("Net004A_1K-JPG/Net004A_1K-JPG_Color.jpg");
    ASSERT_EQ(out.width, opacity.width);
    ASSERT_EQ(out.height, opacity.height);
    long opaque = 0;
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x) {
            ASSERT_EQ(code8(out.at(x, y, 3)), code8(opacity.at(x, y, 0))) << x << "," << y;
            // Unassociated alpha: the color under a transparent pixel is kept as it was.
            for (int c = 0; c < 3; ++c) ASSERT_EQ(code8(out.at(x, y, c)), code8(color.at(x, y, c))) << x << "," << y;
            opaque += code8(out.at(x, y, 3)) > 127;
        }
    EXPECT_NEAR(static_cast<double>(opaque) / (1024.0 * 1024.0), 0.223, 0.005);
    // Occlusion missing: the constant 1 fills R of the ORM map.
    EXPECT_EQ(mat["constants"]["occlusion"], 1.0);
    EXPECT_TRUE(has_finding(mat, "MISSING_MAP", "occlusion"));
    EXPECT_TRUE(has_finding(mat, "MISSING_MAP", "metalness"));
    const auto orm = output_pixels(m, *output_with(mat, "R", "occlusion"));
    for (int y = 0; y < orm.height; y += 5)
        for (int x = 0; x < orm.width; x += 3) {
            ASSERT_EQ(code8(orm.at(x, y, 0)), 255);
            ASSERT_EQ(code8(orm.at(x, y, 2)), 0);
        }
}

TEST(IngestSamples, PackedArmUnpackedAndRepacked) {
    const auto& m = ingested("gltf");
    const auto& mat = mat_of(m, "brown_planks_09");
    EXPECT_EQ(mat["inputs"]["orm"]["file"], "brown_planks_09_arm_1k.jpg");
    EXPECT_TRUE(has_finding(mat, "PACKED_INPUT_UNPACKED", "orm"));
    EXPECT_FALSE(mat["constants"].contains("metalness"));
    EXPECT_FALSE(mat["constants"].contains("occlusion"));
    // ARM and glTF ORM share a layout: the packed output equals the input.
    const auto arm = input_pixels("flat_two_sets/brown_planks_09_arm_1k.jpg");
    const auto orm = output_pixels(m, *output_with(mat, "B", "metalness"));
    ASSERT_EQ(arm.pixels.size(), orm.pixels.size());
    for (size_t i = 0; i < arm.pixels.size(); ++i) ASSERT_EQ(code8(arm.pixels[i]), code8(orm.pixels[i])) << i;
    // Poly Haven's channel means (R occlusion, G roughness, B metalness: a dielectric).
    EXPECT_NEAR(mean_code(orm, 0), 159.14, 0.5);
    EXPECT_NEAR(mean_code(orm, 1), 222.59, 0.5);
    EXPECT_NEAR(mean_code(orm, 2), 0.91, 0.5);
}

TEST(IngestSamples, JpegChosenOverItsSmallerWebpCopy) {
    // Each brown_planks_09 map comes as a 1024² JPEG and a 512² WebP: one AMBIGUOUS_MAP per
    // role, the larger chosen, and the outputs at its size.
    const auto& m = ingested("gltf");
    const auto& mat = mat_of(m, "brown_planks_09");
    for (const auto& [role, file] : std::map<std::string, std::string>{{"albedo", "brown_planks_09_diff_1k.jpg"},
                                                                       {"normal", "brown_planks_09_nor_gl_1k.jpg"},
                                                                       {"orm", "brown_planks_09_arm_1k.jpg"}}) {
        EXPECT_EQ(mat["inputs"][role]["file"], file) << role;
        EXPECT_EQ(mat["inputs"][role]["width"], 1024) << role;
        int ambiguous = 0;
        for (const auto& f : mat["findings"])
            if (f["code"] == "AMBIGUOUS_MAP" && f["role"] == role) {
                ++ambiguous;
                EXPECT_EQ(f["file"], file);
            }
        EXPECT_EQ(ambiguous, 1) << role;
    }
    EXPECT_EQ(mat["inputs"]["normal"]["normal_convention"], "gl");
    EXPECT_EQ(mat["inputs"]["normal"]["normal_convention_source"], "name");
    for (const auto& o : mat["outputs"]) EXPECT_EQ(o["width"], 1024) << o["file"];
}

TEST(IngestSamples, SeparateMapsIntoTheHdrpMaskMap) {
    // Metal_Damaged_001's own metallic, occlusion and roughness maps into HDRP's MaskMap:
    // R metallic, G occlusion, B detail mask 1, A smoothness = 1 - roughness.
    const auto& m = ingested("unity-hdrp");
    const auto& mat = mat_of(m, "Metal_Damaged_001");
    EXPECT_EQ(mat["inputs"]["metalness"]["file"], "Metal_Damaged_001_metallic.jpg");
    const auto metal = input_pixels("Metal_Damaged_001_SD/Metal_Damaged_001_metallic.jpg");
    const auto ao = input_pixels("Metal_Damaged_001_SD/Metal_Damaged_001_ambientOcclusion.jpg");
    const auto rough = input_pixels("Metal_Damaged_001_SD/Metal_Damaged_001_roughness.jpg");
    const auto* mask = output_with(mat, "A", "smoothness");
    ASSERT_TRUE(mask);
    const auto out = output_pixels(m, *mask);
    ASSERT_EQ(out.width, metal.width);
    for (int y = 0; y < out.height; y += 4)
        for (int x = 0; x < out.width; x += 4) {
            ASSERT_EQ(code8(out.at(x, y, 0)), code8(metal.at(x, y, 0))) << "R metallic";
            ASSERT_EQ(code8(out.at(x, y, 1)), code8(ao.at(x, y, 0))) << "G occlusion";
            ASSERT_EQ(code8(out.at(x, y, 2)), 255) << "B detail mask";
            ASSERT_EQ(code8(out.at(x, y, 3)), 255 - code8(rough.at(x, y, 0))) << "A smoothness <- 1 - roughness";
        }
    // A metal: metalness 175.8/255 on average (graded, not binary).
    EXPECT_NEAR(mean_code(out, 0), 175.78, 0.5);
}

TEST(IngestSamples, SeparatePresetTwoByTwoConstants) {
    const auto& m = ingested("separate");
    const auto& net = mat_of(m, "Net004A");  // no metalness map; an 8-bit JPEG height
    const auto* metal = output_with(net, "R", "metalness");
    ASSERT_TRUE(metal);
    EXPECT_EQ((*metal)["width"], 2);
    EXPECT_EQ((*metal)["height"], 2);
    const auto px = output_pixels(m, *metal);
    for (float v : px.pixels) EXPECT_EQ(v, 0.f);
    const auto* h = output_with(net, "R", "height");
    ASSERT_TRUE(h);
    EXPECT_EQ((*h)["bit_depth"], 16);
    EXPECT_TRUE(output_with(net, "R", "opacity"));
    // brown_planks_09 has no height map: no height output; its metalness is a real map.
    const auto& planks = mat_of(m, "brown_planks_09");
    EXPECT_FALSE(output_with(planks, "R", "height"));
    const auto* pm = output_with(planks, "R", "metalness");
    ASSERT_TRUE(pm);
    EXPECT_EQ((*pm)["width"], 1024);
}
