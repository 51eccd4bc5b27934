// Bad inputs give coded errors naming the file; the other sets complete.
#include "cli_util.hpp"
#include "test_elf.hpp"

using namespace mft;

namespace {
mf::Image gradient(int w, int h, int c) {
    mf::Image img(w, h, c);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int k = 0; k < c; ++k) img.at(x, y, k) = static_cast<float>((x * 7 + y * 3 + k * 50) % 256) / 255.f;
    return img;
}
}  // namespace

TEST(IngestErrors, CorruptFilesAreReportedAndOtherSetsComplete) {
    const fs::path in = temp_dir("in"), out = temp_dir("out");
    // A good set.
    write_png(in / "Good" / "Good_Color.png", gradient(16, 16, 3));
    write_png(in / "Good" / "Good_Roughness.png", gradient(16, 16, 1));
    // A set with a text file named .png, an empty file and a truncated PNG, plus one good map.
    write_png(in / "Mixed" / "Mixed_Color.png", gradient(16, 16, 3));
    write_text(in / "Mixed" / "Mixed_Roughness.png", "this is not a png\n");
    write_text(in / "Mixed" / "Mixed_Metalness.png", "");
    std::vector<unsigned char> png;
    std::string err;
    ASSERT_TRUE(mf::encode_image(gradient(16, 16, 3), {mf::FileFormat::png, 8}, png, err));
    write_text(in / "Mixed" / "Mixed_NormalGL.png",
               std::string(png.begin(), png.begin() + static_cast<long>(png.size() / 2)));
    // A set where nothing is readable.
    write_text(in / "Dead" / "Dead_Color.png", "GIF89a garbage");

    const auto r = run("ingest " + q(in) + " -o " + q(out));
    EXPECT_EQ(r.code, 1) << r.output;
    const auto m = read_json(out / "manifest.json");
    const auto* good = material(m, "Good");
    ASSERT_TRUE(good);
    EXPECT_EQ((*good)["status"], "ok");
    const auto* mixed = material(m, "Mixed");
    ASSERT_TRUE(mixed);
    EXPECT_EQ((*mixed)["status"], "partial");
    int unreadable = 0;
    for (const auto& f : (*mixed)["findings"]) {
        if (f["code"] != "UNREADABLE_FILE") continue;
        ++unreadable;
        EXPECT_EQ(f["severity"], "error");
        EXPECT_NE(f["message"].get<std::string>().find(f["file"].get<std::string>()), std::string::npos)
            << "the message names the file: " << f["message"];
    }
    EXPECT_EQ(unreadable, 3);
    EXPECT_TRUE(fs::exists(out / "Mixed" / "Mixed_basecolor.png"));
    ASSERT_EQ(m["failures"].size(), 1u);
    EXPECT_EQ(m["failures"][0]["code"], "UNREADABLE_FILE");
    EXPECT_NE(m["failures"][0]["message"].get<std::string>().find("Dead_Color.png"), std::string::npos);
    // No temporary files left anywhere.
    for (auto& e : fs::recursive_directory_iterator(out))
        EXPECT_EQ(e.path().filename().string().find(mf::kTempMarker), std::string::npos) << e.path();
}

TEST(IngestErrors, SourcesAreNeverModified) {
    const fs::path in = temp_dir("in"), out = temp_dir("out");
    fs::copy(samples() / "flat_two_sets", in / "flat_two_sets");
    std::map<std::string, std::string> before;
    for (auto& e : fs::recursive_directory_iterator(in)) {
        std::vector<unsigned char> b;
        std::string err;
        if (e.is_regular_file() && mf::read_file(e.path(), b, err)) before[e.path().string()] = mf::sha256_hex(b);
    }
    ASSERT_EQ(run("ingest " + q(in) + " -o " + q(out)).code, 0);
    std::map<std::string, std::string> after;
    for (auto& e : fs::recursive_directory_iterator(in)) {
        std::vector<unsigned char> b;
        std::string err;
        if (e.is_regular_file() && mf::read_file(e.path(), b, err)) after[e.path().string()] = mf::sha256_hex(b);
    }
    EXPECT_EQ(before, after);
}

TEST(IngestErrors, OutputInsideInputIsNotIngested) {
    const fs::path in = temp_dir("in");
    fs::copy(samples() / "Metal_Damaged_001_SD", in / "Metal_Damaged_001_SD");
    for (int i = 0; i < 2; ++i) {
        const auto r = run("ingest " + q(in) + " -o " + q(in / "out"));
        ASSERT_EQ(r.code, 0) << r.output;
    }
    const auto m = read_json(in / "out" / "manifest.json");
    EXPECT_EQ(m["materials"].size(), 1u) << "the outputs of the first run are not a new set";
}

TEST(IngestErrors, UsageErrorsExitTwo) {
    const fs::path out = temp_dir("out");
    auto r = run("ingest " + q(samples()) + " -o " + q(out) + " --preset no-such-engine");
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.output.find("no-such-engine"), std::string::npos) << r.output;
    EXPECT_EQ(run("ingest " + q(samples())).code, 2) << "missing -o";
    EXPECT_EQ(run("ingest " + q(samples()) + " -o " + q(out) + " --jobs -3").code, 2);
    EXPECT_EQ(run("frobnicate").code, 2);
    EXPECT_EQ(run("--help").code, 0);
    r = run("ingest --help");
    EXPECT_EQ(r.code, 0);
    EXPECT_NE(r.output.find("--preset"), std::string::npos);
    const fs::path bad_ocio = out / "broken.ocio";
    write_text(bad_ocio, "not: [a config");
    r = run_env("OCIO=" + q(bad_ocio), "ingest " + q(samples()) + " -o " + q(out));
    EXPECT_EQ(r.code, 2) << "unreadable OpenColorIO config: " << r.output;
    EXPECT_NE(r.output.find("matforge ingest: "), std::string::npos) << r.output;
}

// --version: the version on the first line (scripts and bench/*/run.sh read it), the build's
// build-id as binutils reads it from the file, then every library that reads inputs or decides
// output bytes, with a version number, as loaded.
TEST(IngestErrors, VersionNamesTheLibraries) {
    const auto r = run("--version");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(r.output.substr(0, r.output.find('\n')), "matforge " MATFORGE_VERSION) << r.output;
    const std::string id = mf::testelf::readelf_build_id(mf::testenv::bin());
    ASSERT_EQ(id.size(), 40u) << "a sha1 build-id";
    EXPECT_NE(r.output.find("\n  build build-id " + id + "\n"), std::string::npos) << r.output;
    for (const char* lib : {"OpenImageIO 2.", "png:libpng", "OpenColorIO 2.", "squish ", "astcenc ", "zstd 1.",
                            "libzip 1.", "OpenSSL 3.", "Vulkan headers 1.3.", "CLI11 2."})
        EXPECT_NE(r.output.find(lib), std::string::npos) << lib << " in:\n" << r.output;
    EXPECT_EQ(r.output.find("unknown"), std::string::npos) << "a package version CMake did not find:\n" << r.output;
}

TEST(IngestErrors, MissingInputIsAFailureNotACrash) {
    const fs::path out = temp_dir("out");
    const auto r = run("ingest /nonexistent/folder " + q(samples() / "Metal_Damaged_001_SD") + " -o " + q(out));
    EXPECT_EQ(r.code, 1);
    const auto m = read_json(out / "manifest.json");
    EXPECT_EQ(m["materials"].size(), 1u);
    ASSERT_EQ(m["failures"].size(), 1u);
    EXPECT_EQ(m["failures"][0]["code"], "INPUT_NOT_FOUND");
}

TEST(IngestErrors, UserPresetFile) {
    const fs::path out = temp_dir("out");
    write_text(out / "mine.json",
               R"({"name": "mine", "normal_convention": "dx", "file_pattern": "{material}_{suffix}.{ext}",
      "outputs": [{"suffix": "rm", "channels": {"R": "roughness", "G": "metalness"}}]})");
    const fs::path set = samples() / "Metal_Damaged_001_SD";
    const auto r = run("ingest " + q(set) + " -o " + q(out / "o") + " --preset " + q(out / "mine.json"));
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_TRUE(fs::exists(out / "o" / "Metal_Damaged_001_rm.png"));
    const auto img = read_pixels(out / "o" / "Metal_Damaged_001_rm.png");
    EXPECT_EQ(img.channels, 2);
    // The user's layout, channel by channel: R roughness, G metalness (the set's own maps).
    const auto rough = read_pixels(set / "Metal_Damaged_001_roughness.jpg");
    const auto metal = read_pixels(set / "Metal_Damaged_001_metallic.jpg");
    ASSERT_EQ(img.width, rough.width);
    for (int y = 0; y < img.height; y += 5)
        for (int x = 0; x < img.width; x += 5) {
            ASSERT_EQ(code8(img.at(x, y, 0)), code8(rough.at(x, y, 0)));
            ASSERT_EQ(code8(img.at(x, y, 1)), code8(metal.at(x, y, 0)));
        }
}
