// Hardening, round two: what an adversarial tester broke (issue #16), one or more cases per
// class, each run through the binary (README "Hostile inputs" lists class and outcome). Inputs
// are generated here, small or sparse: every case takes seconds.
#include <OpenImageIO/deepdata.h>
#include <OpenImageIO/imagebufalgo.h>

#include <sys/stat.h>

#include <map>
#include <set>

#include "hostile_fixture.hpp"
#include "pack/pack.hpp"
#include "sets/sets.hpp"
#include "store/output_dir.hpp"

using namespace mfh;

namespace {

std::string text_of(const fs::path& p) {
    const Bytes b = read_bytes(p);
    return {b.begin(), b.end()};
}

// Every output the manifest lists exists with the sha256 it states, and is listed once.
void expect_manifest_true(const fs::path& out, const nlohmann::json& m) {
    std::set<std::string> seen;
    for (const auto& mat : m["materials"])
        for (const auto& o : mat["outputs"]) {
            const std::string file = o["file"];
            EXPECT_TRUE(seen.insert(file).second) << file << " is listed twice";
            ASSERT_TRUE(fs::is_regular_file(out / file)) << file;
            EXPECT_EQ(mf::sha256_hex(read_bytes(out / file)), o["sha256"])
                << file << ": the manifest's sha256 is not the file's";
        }
}

// Regular files under `out` that the manifest does not list (manifest.json itself aside).
std::vector<std::string> unlisted(const fs::path& out, const nlohmann::json& m) {
    std::set<std::string> listed{"manifest.json"};
    for (const auto& mat : m["materials"]) {
        for (const auto& o : mat["outputs"]) listed.insert(o["file"].get<std::string>());
        if (mat.contains("material_files"))
            for (const auto& o : mat["material_files"]) listed.insert(o["file"].get<std::string>());
    }
    if (m.contains("library"))
        for (const auto& o : m["library"]) listed.insert(o["file"].get<std::string>());
    std::vector<std::string> extra;
    for (const auto& [rel, sha] : tree_hashes(out))
        if (!listed.count(rel)) extra.push_back(rel);
    return extra;
}

std::string deep_json(const std::string& before, int depth, const std::string& after) {
    return before + std::string(static_cast<size_t>(depth), '[') + std::string(static_cast<size_t>(depth), ']') + after;
}

// CRC-32 by table (hostile_util's bitwise one would take seconds on 150 MB).
uint32_t fast_crc32(const unsigned char* p, size_t n) {
    static const std::array<uint32_t, 256> table = [] {
        std::array<uint32_t, 256> t{};
        for (uint32_t i = 0; i < 256; ++i) {
            uint32_t c = i;
            for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
            t[i] = c;
        }
        return t;
    }();
    uint32_t crc = ~0u;
    for (size_t i = 0; i < n; ++i) crc = table[(crc ^ p[i]) & 0xffu] ^ (crc >> 8);
    return ~crc;
}

// `good_png` with one more chunk of `type` holding `bytes` bytes, right after its header.
Bytes png_with_chunks(const Bytes& good_png, const std::string& type, size_t bytes) {
    // good_png = signature + IHDR (8 + 25 bytes), then the rest: insert the chunk after IHDR.
    Bytes out(good_png.begin(), good_png.begin() + 33);
    Bytes data(bytes, 'x');
    const char key[] = "Comment";
    std::copy(key, key + 8, data.begin());  // keyword + NUL
    put32be(out, static_cast<uint32_t>(data.size()));
    const size_t type_at = out.size();
    out.insert(out.end(), type.begin(), type.end());
    out.insert(out.end(), data.begin(), data.end());
    put32be(out, fast_crc32(out.data() + type_at, out.size() - type_at));
    out.insert(out.end(), good_png.begin() + 33, good_png.end());
    return out;
}

// The preview's manifest folder: a good set ingested into `dir`.
void ingest_good(const fs::path& in, const fs::path& dir) {
    const Proc p = spawn({bin(), "ingest", in.string(), "-o", dir.string(), "--quiet", "--fail-on", "never"});
    ASSERT_EQ(p.code, 0) << p.output;
}

}  // namespace

// ===== 1. images past the device's limit

// A 4x100000 basecolor: ingest warns (engines import at most 16384 a side); the preview does not
// crash on lavapipe (maxImageDimension2D 16384) but renders it downsampled, with a note.
TEST_F(Hostile, OutputPastTheDeviceLimit) {
    write_bytes(in / "Tall" / "Tall_Color.png", encode(gradient(4, 100000, 3)));
    const Proc p = ingest({"--fail-on", "never"});
    ASSERT_EQ(p.code, 0) << p.output;
    expect_good_done();
    const auto* f = expect_finding("Tall", "OUTPUT_TOO_LARGE", "", "Tall/Tall_basecolor.png is 4x100000");
    if (f) {
        EXPECT_EQ((*f)["severity"], "warning");
    }
    const fs::path prev = temp_dir("preview");
    const Proc v = spawn({bin(), "preview", (out / "manifest.json").string(), "-o", prev.string(), "--device", "cpu",
                          "--size", "64"},
                         120);
    EXPECT_EQ(v.signal, 0) << "preview crashed\n" << v.output;
    EXPECT_EQ(v.code, 0) << v.output;
    EXPECT_NE(v.output.find("Tall: note: texture of 4x100000 pixels is larger than this device's limit of 16384"),
              std::string::npos)
        << v.output;
    EXPECT_TRUE(fs::is_regular_file(prev / "Tall.png"));
    EXPECT_TRUE(fs::is_regular_file(prev / "Good.png"));
}

TEST_F(Hostile, EnvironmentPastTheDeviceLimit) {
    const fs::path dir = temp_dir("env");
    write_bytes(dir / "wide.exr", encode(gradient(16400, 4, 3), "exr", 32));
    write_text(dir / "scene.json", R"({"material": {"albedo": [0.5, 0.5, 0.5]}})");
    const Proc v = spawn({bin(), "preview", "--scene", (dir / "scene.json").string(), "--env",
                          (dir / "wide.exr").string(), "-o", (dir / "prev").string(), "--device", "cpu", "--size",
                          "32"},
                         120);
    EXPECT_EQ(v.signal, 0) << "preview crashed\n" << v.output;
    EXPECT_EQ(v.code, 0) << v.output;
    EXPECT_NE(v.output.find("the environment image of 16400x4 pixels is larger than this device's limit of 16384"),
              std::string::npos)
        << v.output;
    EXPECT_TRUE(fs::is_regular_file(dir / "prev" / "scene.png"));
}

// A frame larger than the device can hold (--size 16384: 4 GiB for the fp32 render target alone,
// past lavapipe's 2 GiB maxMemoryAllocationSize) is an error naming the frame, what it needs and
// what the device allows, before anything is allocated: never a bare VK_ERROR_OUT_OF_DEVICE_MEMORY.
TEST_F(Hostile, PreviewSizePastTheDeviceMemory) {
    const fs::path dir = temp_dir("size");
    write_text(dir / "scene.json", R"({"material": {"albedo": [0.5, 0.5, 0.5]}})");
    const Proc v = spawn({bin(), "preview", "--scene", (dir / "scene.json").string(), "-o", (dir / "prev").string(),
                          "--device", "cpu", "--size", "16384"},
                         120);
    EXPECT_EQ(v.signal, 0) << "preview crashed\n" << v.output;
    EXPECT_EQ(v.code, 1) << v.output;
    EXPECT_NE(
        v.output.find("matforge preview: the 16384x16384 frame: a 16384x16384 image needs 4096 MB of device memory"),
        std::string::npos)
        << v.output;
    EXPECT_NE(v.output.find("use a smaller --size"), std::string::npos) << v.output;
    EXPECT_EQ(v.output.find("VK_ERROR"), std::string::npos) << v.output;
    EXPECT_FALSE(fs::exists(dir / "prev" / "scene.png"));
}

// ===== 2. deeply nested JSON: every reader refuses it, naming the file (exit 2)

TEST_F(Hostile, DeepJsonPreset) {
    const fs::path preset = temp_dir("preset") / "deep.json";
    // A valid preset with one unknown member 100,000 levels deep: `presets show` used to print it
    // with a recursive dump (a stack overflow).
    std::string gltf = text_of(mf::testenv::source_dir() / "presets" / "gltf.json");
    gltf.erase(gltf.find_last_of('}'));
    write_text(preset, deep_json(gltf + ", \"x_deep\": ", 100000, "}"));
    for (const auto& argv :
         std::vector<std::vector<std::string>>{{bin(), "presets", "show", preset.string()},
                                               {bin(), "ingest", in.string(), "-o", out.string(), "--preset",
                                                preset.string()},
                                               {bin(), "validate", in.string(), "--preset", preset.string()}}) {
        const Proc p = spawn(argv, 60);
        EXPECT_EQ(p.signal, 0) << argv[1] << " crashed";
        EXPECT_EQ(p.code, 2) << argv[1] << "\n" << p.output;
        EXPECT_NE(p.output.find(preset.string() + ": JSON nested deeper than 256 levels"), std::string::npos)
            << p.output;
    }
    EXPECT_FALSE(fs::exists(out / "manifest.json"));
}

TEST_F(Hostile, DeepJsonRules) {
    const fs::path rules = temp_dir("rules") / "rules.json";
    write_text(rules, deep_json("{\"$comment\": ", 100000, "}"));
    for (const std::string cmd : {"ingest", "validate"}) {
        std::vector<std::string> argv{bin(), cmd, in.string(), "--rules", rules.string()};
        if (cmd == "ingest") argv.insert(argv.end(), {"-o", out.string()});
        const Proc p = spawn(argv, 60);
        EXPECT_EQ(p.code, 2) << cmd << "\n" << p.output;
        EXPECT_NE(p.output.find(rules.string() + ": JSON nested deeper than 256 levels"), std::string::npos)
            << p.output;
    }
}

TEST_F(Hostile, DeepJsonSceneAndManifest) {
    const fs::path dir = temp_dir("deep");
    write_text(dir / "scene.json", deep_json("{\"material\": ", 100000, "}"));
    write_text(dir / "manifest.json", deep_json("{\"manifest_version\": 1, \"materials\": ", 100000, "}"));
    const Proc s = spawn({bin(), "preview", "--scene", (dir / "scene.json").string(), "-o", (dir / "p").string()}, 60);
    EXPECT_EQ(s.code, 2) << s.output;
    EXPECT_NE(s.output.find("scene.json: JSON nested deeper than 256 levels"), std::string::npos) << s.output;
    const Proc m = spawn({bin(), "preview", (dir / "manifest.json").string(), "-o", (dir / "p").string()}, 60);
    EXPECT_EQ(m.code, 2) << m.output;
    EXPECT_NE(m.output.find("manifest.json: JSON nested deeper than 256 levels"), std::string::npos) << m.output;
}

// ===== 3. mixed aspect ratios: the set takes one map's shape, never N×N from N×1 and 1×N

TEST_F(Hostile, AspectConflictIsRefusedNotExploded) {
    constexpr int n = 65535;  // N×N would be 4.3 Gpixels (51 GB of planes); the files are a few hundred bytes
    write_bytes(in / "Odd" / "Odd_Color.png", encode(gradient(n, 1, 3)));
    write_bytes(in / "Odd" / "Odd_Roughness.png", encode(gradient(1, n, 1)));
    const auto t0 = std::chrono::steady_clock::now();
    const Proc p = spawn({bin(), "ingest", in.string(), "-o", out.string(), "--quiet"}, 60);
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ASSERT_FALSE(p.hung) << "ingest of an N×1 and a 1×N map ran past 60 s";
    EXPECT_EQ(p.code, 1) << p.output;  // ASPECT_MISMATCH is an error
    EXPECT_LT(secs, 30.0);
    EXPECT_LT(p.maxrss_kb, kBombRssLimitKb);
    manifest = read_json(out / "manifest.json");
    expect_good_done();
    const auto* f = expect_finding("Odd", "ASPECT_MISMATCH", "Odd_Roughness.png", "is 1x65535");
    if (f) {
        EXPECT_NE((*f)["message"].get<std::string>().find("65535x1 (Odd_Color.png)"), std::string::npos) << f->dump();
        EXPECT_EQ((*f)["severity"], "error");
    }
    const auto* o = mat("Odd");
    ASSERT_TRUE(o);
    EXPECT_FALSE((*o)["inputs"].contains("roughness")) << "the map of the other shape is not used";
    EXPECT_EQ((*o)["constants"]["roughness"], 0.5) << "its role takes the preset's constant";
    // Nothing says the albedo is resampled to the refused map's 1xN: it is not.
    for (const auto& g : (*o)["findings"]) EXPECT_NE(g["code"], "RESOLUTION_MISMATCH") << g.dump();
    // The albedo's output keeps its N×1; the ORM holds constants only: the preset's constant_size.
    ASSERT_EQ((*o)["outputs"].size(), 2u) << o->dump(1);
    const auto& base = (*o)["outputs"][0];
    EXPECT_EQ(base["file"], "Odd/Odd_basecolor.png");
    EXPECT_EQ(base["width"], n) << base.dump();
    EXPECT_EQ(base["height"], 1) << base.dump();
    const auto& orm = (*o)["outputs"][1];
    EXPECT_EQ(orm["file"], "Odd/Odd_orm.png");
    EXPECT_EQ(orm["width"], 2) << orm.dump();
    EXPECT_EQ(orm["height"], 2) << orm.dump();
    const mf::Image b = read_pixels(out / "Odd" / "Odd_basecolor.png");
    EXPECT_EQ(b.width, n);
    EXPECT_EQ(b.height, 1);
}

// Within 2x, maps share a shape: a 64x32 roughness is stretched to the 64x64 albedo, unreported.
TEST_F(Hostile, AspectWithinTwoIsResampled) {
    write_bytes(in / "Odd" / "Odd_Color.png", encode(gradient(64, 64, 3)));
    write_bytes(in / "Odd" / "Odd_Roughness.png", encode(gradient(64, 32, 1)));
    const auto* o = odd_ok_run("Odd_Roughness.png");
    ASSERT_TRUE(o);
    for (const auto& f : (*o)["findings"]) EXPECT_NE(f["code"], "ASPECT_MISMATCH") << f.dump();
    const mf::Image orm = read_pixels(out / "Odd" / "Odd_orm.png");
    EXPECT_EQ(orm.width, 64);
    EXPECT_EQ(orm.height, 64);
}

// Resampling is separable where OpenImageIO's 2-D form is slow (2x1024 -> 1024² took a minute),
// and is the same filter: it agrees with OpenImageIO's Lanczos-3 where both apply.
TEST(Resample, SeparableIsFastAndAgreesWithOpenImageIO) {
    const mf::Image narrow = gradient(2, 1024, 3);
    const auto t0 = std::chrono::steady_clock::now();
    const mf::Image wide = mf::resample(narrow, 1024, 1024);
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 5.0);
    ASSERT_EQ(wide.width, 1024);
    ASSERT_EQ(wide.height, 1024);
    // Against OpenImageIO on a size it handles quickly, axes scaled differently.
    const mf::Image src = gradient(37, 23, 2);
    const mf::Image ours = mf::resample(src, 50, 40);
    OIIO::ImageBuf in_buf(OIIO::ImageSpec(37, 23, 2, OIIO::TypeDesc::FLOAT), const_cast<float*>(src.pixels.data()));
    mf::Image ref(50, 40, 2);
    OIIO::ImageBuf ref_buf(OIIO::ImageSpec(50, 40, 2, OIIO::TypeDesc::FLOAT), ref.pixels.data());
    ASSERT_TRUE(OIIO::ImageBufAlgo::resize(ref_buf, in_buf, "lanczos3", 0.f, OIIO::ROI::All(), 1));
    double worst = 0;
    for (size_t i = 0; i < ref.pixels.size(); ++i)
        worst = std::max(worst, double(std::fabs(ours.pixels[i] - ref.pixels[i])));
    EXPECT_LT(worst, 2e-5);
    // Both axes scaled alike (within 4x): OpenImageIO's own result, bit for bit (earlier outputs).
    const mf::Image same = mf::resample(src, 74, 46);
    mf::Image ref2(74, 46, 2);
    OIIO::ImageBuf ref2_buf(OIIO::ImageSpec(74, 46, 2, OIIO::TypeDesc::FLOAT), ref2.pixels.data());
    ASSERT_TRUE(OIIO::ImageBufAlgo::resize(ref2_buf, in_buf, "lanczos3", 0.f, OIIO::ROI::All(), 1));
    EXPECT_EQ(same.pixels, ref2.pixels);
}

// ===== 4. a FIFO or a device named in a manifest: never opened, the preview goes on

TEST_F(Hostile, PreviewManifestNamingFifoOrDevice) {
    ingest_good(in, out);
    nlohmann::json m = read_json(out / "manifest.json");
    ASSERT_EQ(::mkfifo((out / "fifo.png").c_str(), 0644), 0);
    fs::create_symlink("/dev/zero", out / "zero.png");
    nlohmann::json fifo = m["materials"][0], zero = m["materials"][0];
    fifo["name"] = "Fifo";
    fifo["outputs"][0]["file"] = "fifo.png";
    zero["name"] = "Zero";
    zero["outputs"][0]["file"] = "zero.png";
    m["materials"].push_back(fifo);
    m["materials"].push_back(zero);
    write_text(out / "hand.json", m.dump(1));
    const fs::path prev = temp_dir("preview");
    const Proc v = spawn({bin(), "preview", (out / "hand.json").string(), "-o", prev.string(), "--device", "cpu",
                          "--size", "32"},
                         60);
    ASSERT_FALSE(v.hung) << "the preview opened the FIFO\n" << v.output;
    EXPECT_EQ(v.code, 1) << v.output;
    EXPECT_NE(v.output.find("fifo.png: not a regular file (a FIFO)"), std::string::npos) << v.output;
    EXPECT_NE(v.output.find("zero.png: not a regular file (a device or special file)"), std::string::npos) << v.output;
    EXPECT_TRUE(fs::is_regular_file(prev / "Good.png")) << "the other materials are still rendered";
}

// ===== 5. generated names never collide (case-insensitively), whichever path renamed them

TEST_F(Hostile, NamesFromFoldersAaA2AreUnique) {
    for (const std::string d : {"A", "a", "a_2"}) write_bytes(in / d / (d + "_Color.png"), encode(gradient(8, 8, 3)));
    const Proc p = ingest({"--fail-on", "never", "--jobs", "2"});
    ASSERT_EQ(p.code, 0) << p.output;
    std::set<std::string> lower;
    for (const auto& m : manifest["materials"]) {
        std::string n = m["name"];
        std::transform(n.begin(), n.end(), n.begin(),
                       [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
        EXPECT_TRUE(lower.insert(n).second) << "two materials named " << n << "\n" << manifest.dump(1);
    }
    EXPECT_EQ(manifest["materials"].size(), 4u);
    // The folder a_2 keeps its own name; the second "a" steps over it.
    for (const auto& m : manifest["materials"])
        if (m["source"].get<std::string>().ends_with("/a_2")) {
            EXPECT_EQ(m["name"], "a_2");
        }
    expect_manifest_true(out, manifest);
    EXPECT_TRUE(temp_files_under(out).empty());
}

TEST(UniqueNames, EveryRenamingPath) {
    const std::string l100(100, 'L');
    const std::vector<std::string> names = mf::unique_names({
        "A", "a", "a_2",                   // case, and a suffix another set holds
        "a b", "a_b",                      // characters made safe
        ".hidden", "hidden",               // leading dots
        "", "material",                    // empty -> "material"
        l100 + "x", l100 + "y",            // both cut at 96 bytes
        "manifest.json", "Manifest.JSON",  // the manifest's own name is never a material's
    });
    std::set<std::string> lower;
    for (const auto& n : names) {
        std::string k = n;
        std::transform(k.begin(), k.end(), k.begin(),
                       [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
        EXPECT_TRUE(lower.insert(k).second) << n;
        EXPECT_LE(n.size(), mf::kMaxNameBytes) << n;
        EXPECT_EQ(n.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789._-"),
                  std::string::npos)
            << n;
        EXPECT_NE(n.front(), '.') << n;
    }
    EXPECT_EQ(lower.count("manifest.json"), 0u);
    EXPECT_EQ(names[0], "A");
    EXPECT_EQ(names[1], "a_3");  // a_2 is the third set's own name
    EXPECT_EQ(names[2], "a_2");
    EXPECT_EQ(names[3], "a_b");
    EXPECT_EQ(names[4], "a_b_2");
    EXPECT_EQ(names[5], "hidden");
    EXPECT_EQ(names[6], "hidden_2");
    EXPECT_EQ(names[7], "material");
    EXPECT_EQ(names[8], "material_2");
    EXPECT_EQ(names[9], std::string(96, 'L'));
    EXPECT_EQ(names[10], std::string(94, 'L') + "_2");
}

// ===== 6. presets whose outputs collide: refused at load; no path written twice at run time

TEST_F(Hostile, PresetOutputsThatCollide) {
    const fs::path dir = temp_dir("presets");
    const std::string outputs = R"("outputs": [{"suffix": "c", "channels": {"RGB": "albedo"}}])";
    const std::vector<std::pair<std::string, std::string>> cases{
        {R"({"name": "flat", "file_pattern": "all_{suffix}.{ext}", )" + outputs + "}",
         "file_pattern must contain {material}"},
        {R"({"name": "twice", "outputs": [{"suffix": "c", "channels": {"RGB": "albedo"}}, {"suffix": "c", "channels": {"R": "roughness"}}]})",
         "suffix 'c' names the file of suffix 'c'"},
        {R"({"name": "case", "outputs": [{"suffix": "BC", "channels": {"RGB": "albedo"}}, {"suffix": "bc", "channels": {"R": "roughness"}}]})",
         "suffix 'bc' names the file of suffix 'BC'"},
    };
    for (const auto& [text, needle] : cases) {
        write_text(dir / "p.json", text);
        const Proc p = ingest({"--preset", (dir / "p.json").string()});
        EXPECT_EQ(p.code, 2) << text << "\n" << p.output;
        EXPECT_NE(p.output.find(needle), std::string::npos) << p.output;
        EXPECT_FALSE(fs::exists(out / "manifest.json"));
    }
}

// "{material}{suffix}" makes a+bc and ab+c one file: the first set in path order writes it, the
// other's output is refused naming both; the manifest lists the file once, with its true hash.
TEST_F(Hostile, OutputPathClaimedTwiceAtRunTime) {
    const fs::path preset = temp_dir("preset") / "p.json";
    write_text(preset, R"({"name": "glued", "file_pattern": "{material}{suffix}.{ext}", "outputs": [
        {"suffix": "bc", "color_space": "srgb", "channels": {"RGB": "albedo"}},
        {"suffix": "c", "channels": {"R": "roughness"}}]})");
    write_bytes(in / "a" / "a_Color.png", encode(gradient(8, 8, 3)));
    write_bytes(in / "ab" / "ab_Color.png", encode(gradient(8, 8, 3)));
    const Proc p = ingest({"--preset", preset.string()});
    EXPECT_EQ(p.code, 1) << p.output;
    expect_manifest_true(out, manifest);
    const auto* f = expect_finding("ab", "OUTPUT_WRITE_FAILED", "",
                                   "abc.png: the file is also an output of material 'a'");
    EXPECT_TRUE(f);
}

// ===== 7. two ingests into one folder: the second refuses, naming the first

TEST_F(Hostile, SecondIngestIntoOneFolderRefuses) {
    for (int s = 0; s < 4; ++s)
        write_bytes(in / ("Set" + std::to_string(s)) / ("Set" + std::to_string(s) + "_Color.png"),
                    encode(gradient(256, 256, 3)));
    fs::create_directories(out);
    // A temporary of a running writer (this test process) is never deleted by another run.
    const fs::path live = out / (".x.png" + std::string(mf::kTempMarker) + std::to_string(::getpid()) + "-7");
    write_text(live, "in flight");
    Background first({bin(), "ingest", in.string(), "-o", out.string(), "--quiet", "--jobs", "1"});
    // The lock file holds the writer's pid once its flock is taken (it is created just before):
    // stopped between the two, the first would hold nothing.
    ASSERT_TRUE(Background::until(
        [&] {
            std::error_code ec;
            return fs::file_size(out / ".manifest.json.lock", ec) > 0 && !ec;
        },
        60));
    first.signal(SIGSTOP);  // holds the lock while the second one tries
    const Proc second = spawn({bin(), "ingest", in.string(), "-o", out.string(), "--quiet"}, 60);
    first.signal(SIGCONT);
    const Proc p1 = first.wait();
    EXPECT_EQ(second.code, 1) << second.output;
    EXPECT_NE(second.output.find("another matforge (pid " + std::to_string(first.pid()) + ") is writing in " +
                                 out.string()),
              std::string::npos)
        << second.output;
    EXPECT_EQ(p1.code, 0) << p1.output;
    manifest = read_json(out / "manifest.json");
    expect_good_done();
    expect_manifest_true(out, manifest);
    EXPECT_EQ(manifest["materials"].size(), 5u);
    EXPECT_TRUE(fs::exists(live)) << "a live process's temporary was removed";
}

TEST(StaleTemps, OnlyOursAndOnlyOfDeadProcesses) {
    const fs::path d = temp_dir("temps");
    const pid_t dead = ::fork();
    if (dead == 0) ::_exit(0);
    ::waitpid(dead, nullptr, 0);
    const std::string m = mf::kTempMarker;
    const std::vector<std::string> keep{"holiday" + m + "notes.txt", "x.png" + m + "1-2", ".x.png" + m + "12",
                                        ".x.png" + m + std::to_string(::getpid()) + "-1", ".x.png" + m + "a-1"};
    const std::string gone = ".x.png" + m + std::to_string(dead) + "-3";
    for (const auto& k : keep) write_text(d / k, "k");
    write_text(d / gone, "partial");
    EXPECT_EQ(mf::remove_stale_temps(d), 1);
    for (const auto& k : keep) EXPECT_TRUE(fs::exists(d / k)) << k;
    EXPECT_FALSE(fs::exists(d / gone));
    EXPECT_EQ(mf::temp_owner(gone)->pid, dead);
    EXPECT_FALSE(mf::temp_owner(keep[0]));
}

// The committer (OutputFolder::Batch): files are written aside at once and put in place by the
// folder's thread; wait() sees every one in place, journaled, with no temporary left; a file that
// is not ours is refused at once (nothing queued); identical bytes queue nothing; a wait reports
// each failure once.
TEST(OutputBatch, FilesAreInPlaceAndJournaledWhenWaitReturns) {
    const fs::path d = temp_dir("batch");
    write_text(d / "Set/foreign.png", "a user's file");
    mf::OutputFolder::Options o;
    o.dir = d;
    std::string err;
    bool usage = false;
    auto folder = mf::OutputFolder::open(o, err, usage);
    ASSERT_TRUE(folder) << err;
    ASSERT_TRUE(folder->begin(err)) << err;
    auto bytes = [](const std::string& s) { return std::vector<unsigned char>(s.begin(), s.end()); };
    auto read_text = [](const fs::path& p) {
        const Bytes b = read_bytes(p);
        return std::string(b.begin(), b.end());
    };
    {
        mf::OutputFolder::Batch batch(*folder);
        std::vector<std::vector<unsigned char>> data;
        for (int i = 0; i < 20; ++i) data.push_back(bytes("file " + std::to_string(i)));
        for (int i = 0; i < 20; ++i)
            ASSERT_TRUE(batch.write("Set/sub" + std::to_string(i % 3) + "/f" + std::to_string(i) + ".png", data[i],
                                    err))
                << err;
        EXPECT_FALSE(batch.write("Set/foreign.png", data[0], err));
        EXPECT_NE(err.find("did not write"), std::string::npos) << err;
        EXPECT_TRUE(batch.wait().empty());
        for (int i = 0; i < 20; ++i)
            EXPECT_EQ(read_text(d / ("Set/sub" + std::to_string(i % 3)) / ("f" + std::to_string(i) + ".png")),
                      "file " + std::to_string(i));
        // The same bytes again: nothing to do, in place already.
        ASSERT_TRUE(batch.write("Set/sub0/f0.png", data[0], err)) << err;
        EXPECT_TRUE(batch.wait().empty());
    }
    EXPECT_EQ(read_text(d / "Set/foreign.png"), "a user's file");
    const std::string journal = read_text(d / folder->journal_name());
    for (int i = 0; i < 20; ++i)
        EXPECT_NE(journal.find("\"Set/sub" + std::to_string(i % 3) + "/f" + std::to_string(i) + ".png\""),
                  std::string::npos)
            << i;
    size_t temps = 0;
    for (const auto& e : fs::recursive_directory_iterator(d))
        temps += e.path().filename().string().find(mf::kTempMarker) != std::string::npos ? 1 : 0;
    EXPECT_EQ(temps, 0u);
    std::vector<std::string> notes;
    const std::string manifest = R"({"generator": "matforge test"})";
    const mf::ByteProducer produce = [&manifest](const mf::ByteSink& sink) { return sink(manifest); };
    ASSERT_TRUE(folder->finish(produce, {}, notes, err)) << err;
    EXPECT_FALSE(fs::exists(d / folder->journal_name()));
}

// ===== 8. files in the output folder that are not ours

TEST_F(Hostile, ForeignFilesInTheOutputFolder) {
    fs::create_directories(out / "Good");
    const std::string marker = std::string("holiday") + mf::kTempMarker + "photo.jpg";
    write_text(out / marker, "a user's file");
    write_text(out / "Good" / marker, "another");
    write_text(out / "Good" / "Good_basecolor.png", "my own texture, not matforge's");
    // An output that could not be written fails the run even with --fail-on never (exit 1).
    Proc p = ingest({"--fail-on", "never"});
    EXPECT_EQ(p.code, 1) << p.output;
    EXPECT_EQ(text_of(out / "Good" / "Good_basecolor.png"), "my own texture, not matforge's");
    const auto* g = mat("Good");
    ASSERT_TRUE(g);
    EXPECT_EQ((*g)["status"], "partial");
    // A partial material records no action key: plan --changed-since must schedule it again.
    EXPECT_FALSE(g->contains("key")) << g->dump(1);
    expect_finding("Good", "OUTPUT_WRITE_FAILED", "",
                   "Good/Good_basecolor.png: a file matforge did not write is in the way");
    EXPECT_TRUE(fs::exists(out / marker));
    EXPECT_TRUE(fs::exists(out / "Good" / marker));
    // --force replaces it; a second run without --force is fine: the file is ours now.
    p = ingest({"--force"});
    EXPECT_EQ(p.code, 0) << p.output;
    expect_good_done();
    p = ingest();
    EXPECT_EQ(p.code, 0) << p.output;
    EXPECT_TRUE(fs::exists(out / marker));
}

// A folder whose maps only a broken MaterialX document names (issue 45) leaves a trace in a
// library run: a failure naming the folder and the document, while the good set beside it is
// made. Cut short, an undefined entity in place of a file name, nesting past libxml2's limit;
// a defined internal entity is expanded and names its map.
TEST_F(Hostile, FolderNamedOnlyByABrokenSidecarLeavesATrace) {
    const std::map<std::string, std::string> docs{
        {"cut", "<?xml version=\"1.0\"?><materialx version=\"1.38\"><nodegraph name=\"g\">"},
        {"entity", "<?xml version=\"1.0\"?><!DOCTYPE materialx [<!ENTITY c \"img1.png\">]><materialx version=\"1.38\">"
                   "<image name=\"base\" type=\"color3\"><input name=\"file\" type=\"filename\" value=\"&c;\"/></image>"
                   "<standard_surface name=\"s\" type=\"surfaceshader\"><input name=\"base_color\" type=\"color3\" "
                   "nodename=\"base\"/></standard_surface></materialx>"},
        {"undefined", "<?xml version=\"1.0\"?><materialx version=\"1.38\"><image name=\"base\" type=\"color3\">"
                      "<input name=\"file\" type=\"filename\" value=\"&nowhere;\"/></image></materialx>"},
        {"deep", "<?xml version=\"1.0\"?><materialx>" +
                     [] {
                         std::string d;
                         for (int i = 0; i < 300; ++i) d += "<a>";
                         for (int i = 0; i < 300; ++i) d += "</a>";
                         return d;
                     }() +
                     "</materialx>"},
    };
    for (const auto& [name, doc] : docs) {
        write_bytes(in / name / "img1.png", encode(gradient(16, 16, 3)));
        write_bytes(in / name / "img2.png", encode(gradient(16, 16, 1)));
        write_text(in / name / (name + ".mtlx"), doc);
    }
    const Proc p = ingest({"--fail-on", "never"});
    EXPECT_EQ(p.code, 1) << p.output;
    expect_good_done();
    for (const std::string name : {"cut", "deep", "undefined"}) {
        SCOPED_TRACE(name);
        expect_failure(p, "UNRECOGNIZED_FILE", (in / name).string() + ": img1.png, img2.png name no map role");
        EXPECT_NE(p.output.find(name + ".mtlx"), std::string::npos) << p.output;
    }
    // An internal entity libxml2 expands names a file: that folder is a material.
    const auto* e = mat("entity");
    ASSERT_TRUE(e) << manifest.dump(1);
    EXPECT_EQ((*e)["inputs"]["albedo"]["file"], "img1.png");
}

// Another preset's outputs are not replaced without a word (issue 45): a second run with another
// preset into the folder is refused (exit 2), naming the first preset, and changes nothing; with
// --replace it runs.
TEST_F(Hostile, AnotherPresetsOutputsAreNotReplacedUnlessAsked) {
    Proc p = ingest({"--preset", "unity-urp"});
    ASSERT_EQ(p.code, 0) << p.output;
    const auto before = tree_hashes(out);
    p = ingest({"--preset", "gltf"});
    EXPECT_EQ(p.code, 2) << p.output;
    EXPECT_NE(p.output.find("holds the outputs of preset 'unity-urp'"), std::string::npos) << p.output;
    EXPECT_NE(p.output.find("--replace"), std::string::npos) << p.output;
    EXPECT_EQ(tree_hashes(out), before) << "nothing changed";
    p = spawn({bin(), "ingest", in.string(), "-o", out.string(), "--preset", "gltf", "--replace"}, 120);
    EXPECT_EQ(p.code, 0) << p.output;
    // Said in a few lines: three removals named, the rest counted.
    size_t removed_lines = 0;
    for (size_t at = 0; (at = p.output.find("note: removed ", at)) != std::string::npos; ++at) ++removed_lines;
    EXPECT_EQ(removed_lines, 4u) << p.output;
    EXPECT_NE(p.output.find("more files for the same reason"), std::string::npos) << p.output;
    manifest = read_json(out / "manifest.json");
    EXPECT_EQ(manifest["preset"], "gltf");
    expect_good_done();
    p = ingest({"--preset", "gltf"});  // the same preset again: no question
    EXPECT_EQ(p.code, 0) << p.output;
}

TEST_F(Hostile, ForeignManifestIsNotReplaced) {
    fs::create_directories(out);
    const std::string theirs = R"({"generator": "another tool 2.0", "assets": []})";
    write_text(out / "manifest.json", theirs);
    Proc p = ingest();
    EXPECT_EQ(p.code, 2) << p.output;
    EXPECT_NE(p.output.find((out / "manifest.json").string() +
                            " was not written by matforge (its generator is \"another tool 2.0\")"),
              std::string::npos)
        << p.output;
    EXPECT_EQ(text_of(out / "manifest.json"), theirs);
    EXPECT_FALSE(fs::exists(out / "Good"));
    p = ingest({"--force"});
    EXPECT_EQ(p.code, 0) << p.output;
    expect_good_done();
}

// ===== 9. the output folder is a set's folder; a link inside the output folder

TEST_F(Hostile, OutputFolderIsASetsFolder) {
    const auto before = tree_hashes(in);
    for (const fs::path& o : {in / "Good", in.parent_path() / (in.filename().string() + "-link")}) {
        if (o.filename() != "Good") fs::create_directory_symlink(in / "Good", o);
        const Proc p = spawn({bin(), "ingest", in.string(), "-o", o.string(), "--quiet"}, 60);
        EXPECT_EQ(p.code, 2) << o << "\n" << p.output;
        EXPECT_NE(p.output.find("is the folder of the material set 'Good'"), std::string::npos) << p.output;
        EXPECT_EQ(tree_hashes(in), before) << "nothing written among the sources";
        EXPECT_FALSE(fs::exists(fs::symlink_status(in / "Good" / ".manifest.json.lock")));
        if (o.filename() != "Good") fs::remove(o);
    }
}

TEST_F(Hostile, LinkInsideTheOutputFolderIsNeverFollowed) {
    const fs::path elsewhere = temp_dir("elsewhere");
    fs::create_directories(out);
    fs::create_directory_symlink(elsewhere, out / "Good");
    const Proc p = ingest();
    EXPECT_EQ(p.code, 1) << p.output;
    EXPECT_TRUE(fs::is_empty(elsewhere)) << "an output landed through the link";
    expect_finding("Good", "OUTPUT_WRITE_FAILED", "", "Good is a symbolic link; matforge never writes through links");
    EXPECT_TRUE(fs::is_symlink(out / "Good"));
}

// ===== 10. two spellings grouped as one material: said

TEST_F(Hostile, NamesMerged) {
    write_bytes(in / "Flat" / "Wood_Color.png", encode(gradient(8, 8, 3)));
    write_bytes(in / "Flat" / "WOOD_Roughness.png", encode(gradient(8, 8, 1)));
    write_bytes(in / "Tags" / "Metal_1K_Color.png", encode(gradient(8, 8, 3)));
    write_bytes(in / "Tags" / "Metal_2K_Roughness.png", encode(gradient(8, 8, 1)));
    const Proc p = ingest({"--fail-on", "never"});
    ASSERT_EQ(p.code, 0) << p.output;
    // One material, named by the first spelling in byte order (sorted file names: "WOOD" < "Wood",
    // lib/material/discovery.hpp group_files); the finding names both spellings and their files.
    const nlohmann::json* wood = mat("WOOD");
    ASSERT_TRUE(wood) << manifest.dump(1);
    EXPECT_FALSE(mat("Wood")) << "two spellings made one material, not two";
    EXPECT_EQ((*wood)["inputs"]["albedo"]["file"], "Wood_Color.png");
    EXPECT_EQ((*wood)["inputs"]["roughness"]["file"], "WOOD_Roughness.png");
    const auto* w = expect_finding("WOOD", "NAMES_MERGED", "WOOD_Roughness.png",
                                   "2 spellings of a material name were grouped as 'WOOD': WOOD (WOOD_Roughness.png), "
                                   "Wood (Wood_Color.png); they differ in letter case or separators");
    if (w) {
        EXPECT_EQ((*w)["severity"], "warning");
    }
    const nlohmann::json* metal = mat("Metal");
    ASSERT_TRUE(metal) << manifest.dump(1);
    bool info = false;
    for (const auto& f : (*metal)["findings"])
        info = info ||
               (f["code"] == "NAMES_MERGED" && f["severity"] == "info" &&
                f["message"].get<std::string>().find("they differ in resolution/format tags") != std::string::npos);
    EXPECT_TRUE(info) << metal->dump(1);
}

// ===== 11. SIGINT / SIGTERM: stop cleanly, say so, 130 / 143; the rerun completes the job

TEST_F(Hostile, InterruptedBySignal) {
    for (int s = 0; s < 6; ++s)
        write_bytes(in / ("Set" + std::to_string(s)) / ("Set" + std::to_string(s) + "_Color.png"),
                    encode(gradient(512, 512, 3)));
    const fs::path ref = temp_dir("ref");
    ASSERT_EQ(spawn({bin(), "ingest", in.string(), "-o", ref.string(), "--quiet", "--jobs", "1"}).code, 0);
    const auto ref_tree = tree_hashes(ref);
    for (const int sig : {SIGINT, SIGTERM}) {
        fs::remove_all(out);
        Background run({bin(), "ingest", in.string(), "-o", out.string(), "--quiet", "--jobs", "1"});
        ASSERT_TRUE(Background::until([&] { return any_output_under(out, "_basecolor.png"); }, 60));
        run.signal(sig);
        const Proc p = run.wait();
        EXPECT_EQ(p.signal, 0) << "died of the signal instead of stopping";
        EXPECT_EQ(p.code, sig == SIGINT ? 130 : 143) << p.output;
        EXPECT_NE(p.output.find(sig == SIGINT ? "interrupted (SIGINT)" : "interrupted (SIGTERM)"), std::string::npos)
            << p.output;
        EXPECT_TRUE(temp_files_under(out).empty());
        EXPECT_FALSE(fs::exists(out / "manifest.json")) << "no manifest for an unfinished run";
        ASSERT_EQ(spawn({bin(), "ingest", in.string(), "-o", out.string(), "--quiet"}).code, 0);
        EXPECT_EQ(tree_hashes(out), ref_tree) << "the rerun completes the job";
    }
}

// A rerun killed after it replaced outputs must not leave the old manifest describing them.
TEST_F(Hostile, KilledRerunLeavesNoStaleManifest) {
    for (int s = 0; s < 6; ++s)
        write_bytes(in / ("Set" + std::to_string(s)) / ("Set" + std::to_string(s) + "_Color.png"),
                    encode(gradient(512, 512, 3)));
    ASSERT_EQ(ingest({"--jobs", "1"}).code, 0);
    // Other sources: every output changes.
    for (int s = 0; s < 6; ++s)
        write_bytes(in / ("Set" + std::to_string(s)) / ("Set" + std::to_string(s) + "_Color.png"),
                    encode(gradient(512, 512, 3), "jpg"));
    write_bytes(in / "Good" / "Good_Color.png", encode(gradient(16, 16, 3), "jpg"));
    const std::string old_sha = mf::sha256_hex(read_bytes(out / "Good" / "Good_basecolor.png"));
    Background run({bin(), "ingest", in.string(), "-o", out.string(), "--quiet", "--jobs", "1"});
    ASSERT_TRUE(Background::until(
        [&] {
            std::error_code ec;
            return fs::exists(out / "Good" / "Good_basecolor.png", ec) &&
                   mf::sha256_hex(read_bytes(out / "Good" / "Good_basecolor.png")) != old_sha;
        },
        60));
    run.signal(SIGKILL);
    run.wait();
    if (fs::exists(out / "manifest.json")) expect_manifest_true(out, read_json(out / "manifest.json"));
    EXPECT_TRUE(fs::exists(out / ".manifest.json.journal")) << "the journal tells the next run which files are ours";
    const Proc again = ingest();
    EXPECT_EQ(again.code, 0) << again.output;
    expect_manifest_true(out, manifest);
    EXPECT_TRUE(unlisted(out, manifest).empty());
}

// ===== 12. outputs an earlier run wrote that this one does not: removed (or kept, said)

TEST_F(Hostile, StaleOutputsAreRemoved) {
    Bytes flat;  // a flat normal (128, 128, 255): a map of grey 128 is no normal map (NORMAL_INVALID, not written)
    for (int i = 0; i < 16 * 16; ++i) flat.insert(flat.end(), {128, 128, 255});
    write_bytes(in / "Good" / "Good_NormalGL.png", make_png(16, 16, 8, 2, flat));
    ASSERT_EQ(ingest({"--fail-on", "never"}).code, 0);
    ASSERT_TRUE(fs::exists(out / "Good" / "Good_normal.png"));
    fs::remove(in / "Good" / "Good_NormalGL.png");  // a source map deleted
    Proc p = spawn({bin(), "ingest", in.string(), "-o", out.string(), "--fail-on", "never"});
    ASSERT_EQ(p.code, 0) << p.output;
    manifest = read_json(out / "manifest.json");
    EXPECT_FALSE(fs::exists(out / "Good" / "Good_normal.png"));
    EXPECT_NE(p.output.find("note: removed Good/Good_normal.png"), std::string::npos) << p.output;
    EXPECT_TRUE(unlisted(out, manifest).empty()) << unlisted(out, manifest).front();
    // Another preset (asked for: --replace): the gltf outputs go, except one the user changed
    // since (kept, said so).
    write_text(out / "Good" / "Good_orm.png", "edited by hand");
    p = spawn({bin(), "ingest", in.string(), "-o", out.string(), "--preset", "unreal", "--fail-on", "never",
               "--replace"});
    ASSERT_EQ(p.code, 0) << p.output;
    manifest = read_json(out / "manifest.json");
    EXPECT_FALSE(fs::exists(out / "Good" / "Good_basecolor.png"));
    EXPECT_TRUE(fs::exists(out / "Good" / "T_Good_BC.png"));
    EXPECT_EQ(text_of(out / "Good" / "Good_orm.png"), "edited by hand");
    EXPECT_NE(p.output.find("note: kept Good/Good_orm.png"), std::string::npos) << p.output;
    const auto extra = unlisted(out, manifest);
    EXPECT_EQ(extra, std::vector<std::string>{"Good/Good_orm.png"});
}

// ===== 13. nothing found is not a pass

TEST_F(Hostile, NothingFoundFails) {
    const fs::path empty = temp_dir("empty");
    write_text(empty / "readme.txt", "no maps here");
    write_bytes(in / "Gifs" / "Gifs_Color.gif", Bytes{'G', 'I', 'F', '8', '9', 'a'});
    write_bytes(in / "Gifs" / "Gifs_Roughness.jp2", Bytes{0, 0, 0, 12});
    write_bytes(in / "Gifs" / "Gifs_Normal.ppm", Bytes{'P', '6'});
    for (const std::string cmd : {"ingest", "validate"}) {
        std::vector<std::string> argv{bin(), cmd, empty.string(), "--fail-on", "never"};
        if (cmd == "ingest") argv.insert(argv.end(), {"-o", (empty / "out").string()});
        Proc p = spawn(argv, 60);
        EXPECT_EQ(p.code, 1) << cmd << "\n" << p.output;
        EXPECT_NE(p.output.find(empty.string() + ": no material set found"), std::string::npos) << p.output;
        argv[2] = (in / "Gifs").string();
        p = spawn(argv, 60);
        EXPECT_EQ(p.code, 1) << cmd << "\n" << p.output;
        EXPECT_NE(
            p.output.find(
                "Gifs_Color.gif, Gifs_Normal.ppm, Gifs_Roughness.jp2 name material maps in a format matforge does not read"),
            std::string::npos)
            << p.output;
    }
    // Beside a good set, the unread folder is a failure naming it; the good set is done.
    const Proc p = ingest({"--fail-on", "never"});
    EXPECT_EQ(p.code, 1) << p.output;
    expect_good_done();
    expect_failure(p, "UNRECOGNIZED_FILE", "Gifs_Color.gif");
}

// ===== 14. rules can never silence a file that was not read; thresholds are range-checked

TEST_F(Hostile, RulesCannotSilenceUnreadableFiles) {
    write_bytes(in / "Hostile" / "Hostile_Color.png", encode(gradient(16, 16, 3)));
    write_text(in / "Hostile" / "Hostile_Roughness.png", "not a png");
    const fs::path rules = temp_dir("rules") / "r.json";
    for (const std::string text :
         {R"({"rules": {"UNREADABLE_FILE": "off"}})", R"({"rules": {"UNREADABLE_FILE": "info"}})",
          R"({"rules": {"UNREADABLE_FILE": {"enabled": false}}})", R"({"ignore": ["UNREADABLE_FILE"]})",
          R"({"severityOverrides": {"UNREADABLE_FILE": 2}})",
          R"({"suppress": [{"material": "*", "code": "UNREADABLE_FILE"}]})",
          R"({"rules": {"OUTPUT_WRITE_FAILED": "off"}})"}) {
        write_text(rules, text);
        const Proc p = ingest({"--rules", rules.string()});
        EXPECT_EQ(p.code, 2) << text << "\n" << p.output;
        EXPECT_NE(p.output.find("cannot be switched off, lowered or suppressed"), std::string::npos) << text << "\n"
                                                                                                     << p.output;
    }
    // A suppression of every code of every material leaves it; --fail-on never still fails.
    write_text(rules,
               R"({"suppress": [{"material": "*", "code": "*"}, {"material": "Nomatch*", "code": "CONSTANT_MAP"}]})");
    const Proc p = ingest({"--rules", rules.string(), "--fail-on", "never"});
    EXPECT_EQ(p.code, 1) << p.output;
    expect_finding("Hostile", "UNREADABLE_FILE", "Hostile_Roughness.png");
    EXPECT_NE(p.output.find(R"(suppression {"material": "Nomatch*", "code": "CONSTANT_MAP"} matches no material)"),
              std::string::npos)
        << p.output;
}

TEST_F(Hostile, RuleThresholdsAreRangeChecked) {
    const fs::path rules = temp_dir("rules") / "r.json";
    for (const auto& [text, needle] : std::vector<std::pair<std::string, std::string>>{
             {R"({"rules": {"ALBEDO_TOO_DARK": {"min_srgb": 300}}})",
              "\"ALBEDO_TOO_DARK\".min_srgb must be a number within 0.0..255.0"},
             {R"({"rules": {"ALBEDO_TOO_BRIGHT": {"max_share": 1.5}}})",
              "\"ALBEDO_TOO_BRIGHT\".max_share must be a number within 0.0..1.0"},
             {R"({"rules": {"NOT_GRAYSCALE": {"tolerance": -0.1}}})",
              "\"NOT_GRAYSCALE\".tolerance must be a number within"},
             {R"({"rules": {"ALBEDO_TOO_DARK": {"min_srgb": 250}, "ALBEDO_TOO_BRIGHT": {"max_srgb": 200}}})",
              "ALBEDO_TOO_DARK.min_srgb (250.0) is above ALBEDO_TOO_BRIGHT.max_srgb (200.0)"}}) {
        write_text(rules, text);
        const Proc p = spawn({bin(), "validate", in.string(), "--rules", rules.string()}, 60);
        EXPECT_EQ(p.code, 2) << text << "\n" << p.output;
        EXPECT_NE(p.output.find(needle), std::string::npos) << p.output;
    }
}

// ===== 15. preview: file stems, confinement, scene ranges, channel roles

TEST_F(Hostile, PreviewManifestHostileValues) {
    ingest_good(in, out);
    const nlohmann::json good = read_json(out / "manifest.json");
    const fs::path prev = temp_dir("preview");
    auto preview = [&](const nlohmann::json& m, std::vector<std::string> extra = {}) {
        write_text(out / "hand.json", m.dump(1));
        std::vector<std::string> argv{bin(), "preview",     (out / "hand.json").string(),
                                      "-o",  prev.string(), "--device",
                                      "cpu", "--size",      "16"};
        argv.insert(argv.end(), extra.begin(), extra.end());
        return spawn(argv, 60);
    };
    // Names meeting on one file stem: distinct files.
    nlohmann::json m = good;
    nlohmann::json other = m["materials"][0];
    other["name"] = "GOOD";
    m["materials"].push_back(other);
    Proc p = preview(m);
    EXPECT_EQ(p.code, 0) << p.output;
    EXPECT_TRUE(fs::is_regular_file(prev / "Good.png"));
    EXPECT_TRUE(fs::is_regular_file(prev / "GOOD_2.png"));
    // A path leaving the manifest's folder: refused unless --allow-outside.
    m = good;
    const fs::path outside = temp_dir("outside");
    fs::copy_file(out / "Good" / "Good_basecolor.png", outside / "b.png");
    m["materials"][0]["outputs"][0]["file"] = (fs::path("..") / outside.filename() / "b.png").string();
    fs::rename(outside, out.parent_path() / outside.filename());
    p = preview(m);
    EXPECT_EQ(p.code, 1) << p.output;
    EXPECT_NE(p.output.find("outside"), std::string::npos) << p.output;
    p = preview(m, {"--allow-outside"});
    EXPECT_EQ(p.code, 0) << p.output;
    fs::remove_all(out.parent_path() / outside.filename());
    // An unknown channel role is an error naming it, not a grey default.
    m = good;
    m["materials"][0]["outputs"][0]["channels"] = {{"RGB", "albedo_typo"}};
    p = preview(m);
    EXPECT_EQ(p.code, 2) << p.output;
    EXPECT_NE(p.output.find("albedo_typo"), std::string::npos) << p.output;
    // Scene values out of range; a camera at its target or looking along its up.
    for (const auto& [scene, needle] : std::vector<std::pair<std::string, std::string>>{
             {R"({"camera": {"yfov_deg": 500}})", "camera.yfov_deg: must be in (0, 180)"},
             {R"({"image": {"width": 0}})", "image.width"},
             {R"({"lights": [{"type": "point", "position": [0, 0, 2], "intensity": -1}]})", "intensity"},
             {R"({"camera": {"position": [1, 2, 3], "target": [1, 2, 3]}})",
              "camera: position and target are the same point"},
             {R"({"camera": {"position": [0, 5, 0], "target": [0, 0, 0], "up": [0, 1, 0]}})",
              "camera.up: is parallel to the direction from position to target"}}) {
        write_text(prev / "scene.json", scene);
        p = preview(good, {"--scene", (prev / "scene.json").string()});
        EXPECT_EQ(p.code, 2) << scene << "\n" << p.output;
        EXPECT_NE(p.output.find(needle), std::string::npos) << scene << "\n" << p.output;
    }
}

// ===== 16. silent choices become findings

TEST_F(Hostile, OverlappingInputsAreReadOnce) {
    const Proc p = spawn({bin(), "ingest", in.string(), (in / "Good").string(), "-o", out.string(), "--quiet",
                          "--fail-on", "never"});
    ASSERT_EQ(p.code, 0) << p.output;
    manifest = read_json(out / "manifest.json");
    ASSERT_EQ(manifest["materials"].size(), 1u) << manifest.dump(1);
    expect_good_done();
    const auto* f = expect_finding("Good", "DUPLICATE_INPUT", "",
                                   "also reached through the input " + (in / "Good").string());
    EXPECT_TRUE(f);
}

TEST_F(Hostile, DuplicateZipEntryName) {
    const fs::path z = in / "Dup.zip";
    // Two entries, then the second renamed to the first's name in both headers (libzip refuses to
    // write one name twice; archivers are not so careful).
    write_zip(z,
              {{"Dup_Color.png", encode(gradient(8, 8, 3))},
               {"Dup_Roughness.png", encode(gradient(8, 8, 1))},
               {"Dup_Roughnesz.png", encode(gradient(4, 4, 1))}},
              true);
    Bytes b = read_bytes(z);
    int patched = 0;
    const std::string from = "Dup_Roughnesz.png", to = "Dup_Roughness.png";
    for (size_t i = 0; i + from.size() < b.size(); ++i)
        if (std::memcmp(&b[i], from.data(), from.size()) == 0) {
            std::memcpy(&b[i], to.data(), to.size());
            ++patched;
        }
    ASSERT_EQ(patched, 2);
    write_bytes(z, b);
    const Proc p = ingest({"--fail-on", "never"});
    EXPECT_EQ(p.code, 0) << p.output;
    const auto* f = expect_finding("Dup", "DUPLICATE_ENTRY", "Dup_Roughness.png",
                                   "2 entries are named 'Dup_Roughness.png'; the first is used");
    if (f) {
        EXPECT_EQ((*f)["severity"], "warning");
    }
    EXPECT_EQ((*mat("Dup"))["inputs"]["roughness"]["width"], 8) << "the first entry";
}

TEST_F(Hostile, MultipartExrAndOrientation) {
    // Two EXR parts: the first is used, and said so.
    const fs::path exr = in / "Odd" / "Odd_Roughness.exr";
    fs::create_directories(exr.parent_path());
    {
        auto o = OIIO::ImageOutput::create(exr.string());
        ASSERT_TRUE(o && o->supports("multiimage"));
        OIIO::ImageSpec specs[2] = {OIIO::ImageSpec(8, 8, 1, OIIO::TypeDesc::HALF),
                                    OIIO::ImageSpec(4, 4, 1, OIIO::TypeDesc::HALF)};
        specs[0].attribute("oiio:subimagename", "rough");
        specs[1].attribute("oiio:subimagename", "other");
        // The parts of one OpenEXR file share a display window (OpenEXR refuses conflicting
        // ones): the second part's 4x4 data window lies inside the first's 8x8.
        specs[1].full_width = specs[1].full_height = 8;
        ASSERT_TRUE(o->open(exr.string(), 2, specs)) << o->geterror();
        std::vector<float> px(64, 0.5f);
        ASSERT_TRUE(o->write_image(OIIO::TypeDesc::FLOAT, px.data()));
        ASSERT_TRUE(o->open(exr.string(), specs[1], OIIO::ImageOutput::AppendSubimage));
        ASSERT_TRUE(o->write_image(OIIO::TypeDesc::FLOAT, px.data()));
        o->close();
    }
    // A TIFF tagged "rotated 90° clockwise": used as stored, and said so.
    const fs::path tif = in / "Odd" / "Odd_Color.tif";
    {
        auto o = OIIO::ImageOutput::create(tif.string());
        OIIO::ImageSpec spec(8, 8, 3, OIIO::TypeDesc::UINT8);
        spec.attribute("Orientation", 6);
        ASSERT_TRUE(o->open(tif.string(), spec));
        std::vector<float> px(192, 0.4f);
        ASSERT_TRUE(o->write_image(OIIO::TypeDesc::FLOAT, px.data()));
        o->close();
    }
    const auto* o = odd_ok_run("Odd_Roughness.exr");
    ASSERT_TRUE(o);
    expect_finding("Odd", "MULTIPART_IMAGE", "Odd_Roughness.exr", "holds 2 parts; the first ('rough') is used");
    expect_finding("Odd", "ORIENTATION_IGNORED", "Odd_Color.tif",
                   "orientation is 6 (rotated 90° clockwise), which is not applied");
    EXPECT_EQ((*o)["inputs"]["roughness"]["width"], 8);
}

// ===== 17. messages in the user's terms

TEST_F(Hostile, SymlinkZipEntry) {
    const fs::path z = in / "Linked.zip";
    write_zip(z,
              {{"Linked_Color.png", encode(gradient(8, 8, 3))}, {"Linked_Roughness.png", Bytes{'/', 'e', 't', 'c'}}});
    int err = 0;
    zip_t* a = zip_open(z.c_str(), 0, &err);
    ASSERT_TRUE(a);
    const zip_int64_t idx = zip_name_locate(a, "Linked_Roughness.png", 0);
    ASSERT_GE(idx, 0);
    ASSERT_EQ(zip_file_set_external_attributes(a, static_cast<zip_uint64_t>(idx), 0, ZIP_OPSYS_UNIX,
                                               (S_IFLNK | 0777u) << 16),
              0);
    ASSERT_EQ(zip_close(a), 0);
    const Proc p = ingest();
    EXPECT_EQ(p.code, 1) << p.output;
    expect_finding("Linked", "UNREADABLE_FILE", "Linked_Roughness.png", "a symbolic link stored in the archive");
}

TEST_F(Hostile, BrokenSymlinkAsOutputFolder) {
    fs::create_directory_symlink(out.string() + "-missing", out);
    const Proc p = ingest();
    EXPECT_EQ(p.code, 1) << p.output;
    EXPECT_NE(p.output.find(out.string() + ": a symbolic link to " + out.string() + "-missing, which does not exist"),
              std::string::npos)
        << p.output;
    fs::remove(out);
}

TEST_F(Hostile, OutputNameTooLong) {
    const fs::path preset = temp_dir("preset") / "p.json";
    write_text(preset, R"({"name": "long", "outputs": [{"suffix": ")" + std::string(250, 's') +
                           R"(", "channels": {"RGB": "albedo"}}]})");
    const Proc p = ingest({"--preset", preset.string()});
    EXPECT_EQ(p.code, 1) << p.output;
    const auto* g = mat("Good");
    ASSERT_TRUE(g);
    bool said = false;
    for (const auto& f : (*g)["findings"])
        said = said ||
               (f["code"] == "OUTPUT_WRITE_FAILED" &&
                f["message"].get<std::string>().find("longer than the file system allows (255 bytes per name)") !=
                    std::string::npos);
    EXPECT_TRUE(said) << g->dump(1);
}

TEST_F(Hostile, DeepExrIsNamed) {
    const fs::path exr = in / "Hostile" / "Hostile_Roughness.exr";
    fs::create_directories(exr.parent_path());
    {
        auto o = OIIO::ImageOutput::create(exr.string());
        ASSERT_TRUE(o && o->supports("deepdata"));
        OIIO::ImageSpec spec(4, 4, 1, OIIO::TypeDesc::FLOAT);
        spec.channelnames = {"Z"};
        spec.deep = true;
        ASSERT_TRUE(o->open(exr.string(), spec)) << o->geterror();
        OIIO::DeepData deep(spec);
        for (int p = 0; p < 16; ++p) deep.set_samples(p, 1 + p % 2);
        ASSERT_TRUE(o->write_deep_image(deep)) << o->geterror();
        o->close();
    }
    write_bytes(in / "Hostile" / "Hostile_Color.png", encode(gradient(16, 16, 3)));
    const Proc p = ingest();
    expect_bad_map_result(p, "Hostile_Roughness.exr", "a deep openexr image (a varying number of samples per pixel)");
}

// ===== 18. archives are opened once: zip costs what folders cost

// Counted, not timed: the quadratic cost came from opening and parsing the archive once per map,
// so the test counts the archive's open(2) calls under strace (a count is the same on a loaded
// machine and under the sanitizers). bench/ has the zip-vs-folder timings at 1k/10k/100k entries.
TEST_F(Hostile, ZipOfManyEntriesIsOpenedOnce) {
    constexpr int kSets = 1500;  // 3000 map entries
    std::vector<ZipEntry> entries;
    const Bytes c = make_png(1, 1, 8, 2, {100, 120, 140}), r = make_png(1, 1, 8, 0, {90});
    for (int s = 0; s < kSets; ++s) {
        const std::string n = std::string("S").append(std::to_string(s));  // GCC 12 -O3: false -Wrestrict on "S" + …
        entries.push_back({n + "/" + n + "_Color.png", c});
        entries.push_back({n + "/" + n + "_Roughness.png", r});
    }
    const fs::path zips = temp_dir("zip");
    write_zip(zips / "many.zip", entries, true);
    const fs::path trace = zips / "open.trace";
    const Proc p = spawn({"strace", "-f", "-qq", "-e", "trace=open,openat,openat2", "-o", trace.string(), bin(),
                          "validate", (zips / "many.zip").string(), "--report", "json", "--report-file",
                          (zips / "r.json").string(), "--fail-on", "never"},
                         300);
    ASSERT_EQ(p.code, 0) << p.output;
    std::ifstream f(trace);
    ASSERT_TRUE(f) << "strace wrote no trace";
    int opens = 0, lines = 0;
    for (std::string line; std::getline(f, line); ++lines)
        if (line.find("many.zip\"") != std::string::npos && line.find("= -1") == std::string::npos) ++opens;
    EXPECT_GT(lines, 10) << "the trace holds the binary's opens";
    EXPECT_GE(opens, 1);
    EXPECT_LE(opens, 2) << "the archive was opened " << opens << " times for " << 2 * kSets << " maps";
    EXPECT_EQ(read_json(zips / "r.json")["materials"].size(), static_cast<size_t>(kSets));
}

// ===== 19. metadata we do not use is not kept

TEST_F(Hostile, PngWithHugeTextChunk) {
    const Bytes png = png_with_chunks(encode(gradient(16, 16, 1)), "tEXt", size_t{150} << 20);
    write_bytes(in / "Odd" / "Odd_Roughness.png", png);
    write_bytes(in / "Odd" / "Odd_Color.png", encode(gradient(16, 16, 3)));
    const Proc p = ingest({"--fail-on", "never"});
    EXPECT_EQ(p.code, 0) << p.output;
    expect_good_done();
    EXPECT_LT(p.maxrss_kb, 400 * 1024) << "a 150 MB text chunk was kept (peak " << p.maxrss_kb / 1024 << " MB)";
    EXPECT_EQ((*mat("Odd"))["inputs"]["roughness"]["width"], 16);
}

// report stopped by a signal ends as ingest does: exit 130/143, no temporary left, no index.html
// naming pictures of materials never done; a rerun writes the whole report.
TEST_F(Hostile, ReportInterruptedBySignal) {
    for (int s = 0; s < 8; ++s)
        write_bytes(in / ("Set" + std::to_string(s)) / ("Set" + std::to_string(s) + "_Color.png"),
                    encode(gradient(1024, 1024, 3)));
    ASSERT_EQ(spawn({bin(), "ingest", in.string(), "-o", out.string(), "--quiet"}).code, 0);
    const fs::path report = temp_dir("report");
    for (const int sig : {SIGINT, SIGTERM}) {
        fs::remove_all(report);
        Background run({bin(), "report", (out / "manifest.json").string(), "-o", report.string(), "--jobs", "1"});
        ASSERT_TRUE(Background::until([&] { return any_output_under(report, ".png"); }, 60));
        run.signal(sig);
        const Proc p = run.wait();
        EXPECT_EQ(p.signal, 0) << "died of the signal instead of stopping";
        EXPECT_EQ(p.code, sig == SIGINT ? 130 : 143) << p.output;
        EXPECT_NE(p.output.find("matforge report: interrupted"), std::string::npos) << p.output;
        EXPECT_TRUE(temp_files_under(report).empty());
        EXPECT_FALSE(fs::exists(report / "index.html"));
    }
    ASSERT_EQ(spawn({bin(), "report", (out / "manifest.json").string(), "-o", report.string(), "--quiet"}).code, 0);
    EXPECT_TRUE(fs::exists(report / "index.html"));
}
