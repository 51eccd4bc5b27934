// The ingest cache (lib/store/cache.hpp) through the binary: an unchanged set is restored with
// the same bytes as a run without the cache, a changed file recomputes its set only, a corrupt
// blob or an unusable cache never fails a run, and `matforge cache` reports and prunes it.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <thread>

#include "cli_util.hpp"

using namespace mft;
using nlohmann::json;

namespace {

// Two real sets (3dtextures.me metal, ambientCG net) copied to `dir`.
fs::path two_sets(const fs::path& dir) {
    for (const char* s : {"Metal_Damaged_001_SD", "Net004A_1K-JPG"}) {
        fs::create_directories(dir / "in" / s);
        fs::copy(samples() / s, dir / "in" / s, fs::copy_options::recursive);
    }
    return dir / "in";
}

// "cache: R sets restored, C computed" from ingest's summary; {-1, -1} when absent.
std::pair<int, int> cache_line(const std::string& output) {
    // (No std::regex: GCC 12's <regex> trips -Wmaybe-uninitialized in the sanitizer build.)
    int restored = -1, computed = -1;
    for (size_t at = output.find("cache: "); at != std::string::npos; at = output.find("cache: ", at + 1))
        if (std::sscanf(output.c_str() + at, "cache: %d sets restored, %d computed", &restored, &computed) == 2)
            return {restored, computed};
    return {-1, -1};
}

// Every output file and material file of `manifest` (under its folder) with its bytes.
std::map<std::string, std::string> files_of(const fs::path& out) {
    std::map<std::string, std::string> f;
    const json m = read_json(out / "manifest.json");
    for (const auto& mat : m["materials"]) {
        for (const auto& o : mat["outputs"]) f[o["file"]] = bytes_of(out / o["file"].get<std::string>());
        for (const auto& o : mat["material_files"]) f[o["file"]] = bytes_of(out / o["file"].get<std::string>());
    }
    return f;
}

// ingest IN -o OUT with this test's own cache (ctest sets $MATFORGE_CACHE to the suite's shared
// cache, whose records other tests' runs of the same samples would hit).
RunResult ingest(const fs::path& in, const fs::path& out, const fs::path& cache, const std::string& extra = "") {
    return run("ingest " + q(in) + " -o " + q(out) + " --cache " + q(cache) + extra);
}

}  // namespace

TEST(Cache, WarmRunRestoresTheSameBytesAsARunWithoutIt) {
    const fs::path work = temp_dir("warm");
    const fs::path in = two_sets(work);
    ASSERT_EQ(run("ingest " + q(in) + " -o " + q(work / "plain") + " --no-cache").code, 0);
    EXPECT_FALSE(fs::exists(work / "plain/.matforge-cache")) << "--no-cache writes no cache";

    const fs::path cache = work / "cache";
    auto r = ingest(in, work / "out", cache);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(cache_line(r.output), std::make_pair(0, 2)) << r.output;
    EXPECT_TRUE(fs::is_directory(cache / "cas"));
    EXPECT_FALSE(fs::exists(work / "out/.matforge-cache")) << "the output folder holds what the manifest lists";
    r = ingest(in, work / "out", cache);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(cache_line(r.output), std::make_pair(2, 0)) << r.output;
    // Sibling folders: the same relative sources, so the same manifest bytes.
    EXPECT_EQ(bytes_of(work / "out/manifest.json"), bytes_of(work / "plain/manifest.json"));
    EXPECT_EQ(files_of(work / "out"), files_of(work / "plain"));

    // An output deleted by hand is restored from its blob; the set is not recomputed.
    fs::remove(work / "out/Net004A/Net004A_normal.png");
    r = ingest(in, work / "out", cache);
    EXPECT_EQ(cache_line(r.output), std::make_pair(2, 0)) << r.output;
    EXPECT_EQ(files_of(work / "out"), files_of(work / "plain"));

    // A new output folder restores from a shared cache ($MATFORGE_CACHE): a CI job or a node.
    r = run_env("MATFORGE_CACHE=" + q(cache), "ingest " + q(in) + " -o " + q(work / "other"));
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(cache_line(r.output), std::make_pair(2, 0)) << r.output;
    EXPECT_EQ(bytes_of(work / "other/manifest.json"), bytes_of(work / "plain/manifest.json"));
    // Without --cache and $MATFORGE_CACHE: the user's cache folder (XDG), never beside or inside
    // the output folder or the input tree; ~/.cache/matforge when $XDG_CACHE_HOME is unset.
    r = run_env("MATFORGE_CACHE= XDG_CACHE_HOME=" + q(work / "xdg"), "ingest " + q(in) + " -o " + q(work / "mine/"));
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_TRUE(fs::is_directory(work / "xdg/matforge/ac")) << r.output;
    EXPECT_EQ(cache_line(r.output), std::make_pair(0, 2)) << r.output;
    EXPECT_FALSE(fs::exists(work / ".mine.matforge-cache"));
    for (const auto& e : fs::directory_iterator(work / "mine"))
        EXPECT_NE(e.path().filename().string().front(), '.') << e.path();
    r = run_env("MATFORGE_CACHE= XDG_CACHE_HOME= HOME=" + q(work / "home"),
                "ingest " + q(in) + " -o " + q(work / "mine2"));
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_TRUE(fs::is_directory(work / "home/.cache/matforge/ac")) << r.output;
    r = run_env("MATFORGE_CACHE= XDG_CACHE_HOME=" + q(work / "xdg"), "cache stats");
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("2 records"), std::string::npos) << r.output;
    // Its blobs are hard links to the outputs: no second copy on disk.
    EXPECT_EQ(fs::hard_link_count(work / "mine/Net004A/Net004A_basecolor.png"), 2u);
}

// What a run loads, from the dynamic loader's own log (glibc's LD_DEBUG=files names every file
// it opens, also the module matforge opens with dlopen). The sanitizer build's matforge links
// OpenImageIO at start (tools/matforge/CMakeLists.txt says why): there, only the module counts.
bool loads_image_library(const std::string& output) {
#ifdef MATFORGE_SANITIZE_BUILD
    constexpr bool kLinkedAtStart = true;
#else
    constexpr bool kLinkedAtStart = false;
#endif
    return output.find("matforge_oiio.so") != std::string::npos ||
           (!kLinkedAtStart && output.find("libOpenImageIO") != std::string::npos);
}

// OpenImageIO and its 261 libraries took 0.3 s of every start (docs/performance.md, "A run
// with nothing to do"): a run that decodes nothing must not load them, nor one that decodes
// only everyday JPEGs and PNGs.
TEST(Cache, ARunWithNothingToDecodeLoadsNoImageLibrary) {
    const fs::path work = temp_dir("lazy");
    const fs::path in = two_sets(work);
    const std::string env = "LD_DEBUG=files MATFORGE_CACHE=" + q(work / "cache");
    auto r = run_env(env, "ingest " + q(in) + " -o " + q(work / "out"));
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(cache_line(r.output), std::make_pair(0, 2)) << r.output;
    // Their JPEG and PNG maps are decoded without OpenImageIO (lib/image/direct.hpp); the log
    // shows the module where it is loaded (LD_LIBRARY_PATH below).
    EXPECT_FALSE(loads_image_library(r.output)) << r.output;
    const std::string manifest = bytes_of(work / "out/manifest.json");
    // Up to date, into the same folder and into a new one from the same cache.
    for (const char* out : {"out", "other"}) {
        r = run_env(env, "ingest " + q(in) + " -o " + q(work / out));
        ASSERT_EQ(r.code, 0) << r.output;
        EXPECT_EQ(cache_line(r.output), std::make_pair(2, 0)) << r.output;
        EXPECT_FALSE(loads_image_library(r.output)) << out << ":\n" << r.output;
        EXPECT_EQ(bytes_of(work / out / "manifest.json"), manifest);
    }
    r = run_env("LD_DEBUG=files", "--help");
    EXPECT_FALSE(loads_image_library(r.output)) << r.output;
    // The cache key names the same OpenImageIO whether the build's library path is trusted or
    // the module is loaded and asked (LD_LIBRARY_PATH set): a farm's nodes share records.
    r = run_env(env + " LD_LIBRARY_PATH=" + q(work / "nothing-here"), "ingest " + q(in) + " -o " + q(work / "ld"));
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(cache_line(r.output), std::make_pair(2, 0)) << r.output;
    EXPECT_TRUE(loads_image_library(r.output)) << r.output;
}

TEST(Cache, ChangedFileOrPresetRecomputesOnlyWhatItTouches) {
    const fs::path work = temp_dir("change");
    const fs::path in = two_sets(work);
    const fs::path cache = work / "cache";
    ASSERT_EQ(ingest(in, work / "out", cache).code, 0);
    // Other pixels in one map of the metal (a valid JPEG of the same size): its set only.
    fs::copy_file(in / "Metal_Damaged_001_SD/Metal_Damaged_001_ambientOcclusion.jpg",
                  in / "Metal_Damaged_001_SD/Metal_Damaged_001_roughness.jpg", fs::copy_options::overwrite_existing);
    auto r = ingest(in, work / "out", cache);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(cache_line(r.output), std::make_pair(1, 1)) << r.output;
    ASSERT_EQ(run("ingest " + q(in) + " -o " + q(work / "plain") + " --no-cache").code, 0);
    EXPECT_EQ(bytes_of(work / "out/manifest.json"), bytes_of(work / "plain/manifest.json"));
    EXPECT_EQ(files_of(work / "out"), files_of(work / "plain"));
    // A time stamp is not content: still restored.
    fs::last_write_time(in / "Net004A_1K-JPG/Net004A_1K-JPG_Color.jpg", fs::file_time_type::clock::now());
    r = ingest(in, work / "out", cache);
    EXPECT_EQ(cache_line(r.output), std::make_pair(2, 0)) << r.output;
    // Another preset or normal convention is another action: every set computed.
    r = ingest(in, work / "out", cache, " --normal-convention dx");
    EXPECT_EQ(cache_line(r.output), std::make_pair(0, 2)) << r.output;
}

TEST(Cache, CorruptBlobIsRecomputedAndSaid) {
    const fs::path work = temp_dir("corrupt");
    const fs::path in = two_sets(work);
    const fs::path cache = work / "shared-cache";
    ASSERT_EQ(run("ingest " + q(in) + " -o " + q(work / "a") + " --cache " + q(cache)).code, 0);
    ASSERT_EQ(run("ingest " + q(in) + " -o " + q(work / "plain") + " --no-cache").code, 0);
    // Truncate the blob of the net's base color (blobs are named by their SHA-256).
    const json m = read_json(work / "a/manifest.json");
    std::string sha;
    for (const auto& mat : m["materials"])
        if (mat["name"] == "Net004A") sha = mat["outputs"][0]["sha256"];
    ASSERT_EQ(sha.size(), 64u);
    const fs::path blob = cache / "cas" / sha.substr(0, 2) / sha;
    ASSERT_TRUE(fs::is_regular_file(blob));
    // The blob may be a hard link to a's output: replace it, leaving a's file as it is.
    fs::remove(blob);
    write_text(blob, "truncated");
    const auto r = run("ingest " + q(in) + " -o " + q(work / "b") + " --cache " + q(cache));
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(cache_line(r.output), std::make_pair(1, 1)) << r.output;
    EXPECT_NE(r.output.find("warning: cache:"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(sha), std::string::npos) << "names the blob:\n" << r.output;
    EXPECT_NE(r.output.find("computed again"), std::string::npos) << r.output;
    EXPECT_EQ(bytes_of(work / "b/manifest.json"), bytes_of(work / "plain/manifest.json"));
    EXPECT_EQ(files_of(work / "b"), files_of(work / "plain"));
    EXPECT_EQ(bytes_of(work / "a/Net004A/Net004A_basecolor.png"),
              bytes_of(work / "plain/Net004A/Net004A_basecolor.png"));
}

// The action records are checked like the blobs: one cut short, one altered (still valid JSON)
// and one of an older cache version are each reported, removed and their set computed again.
TEST(Cache, CorruptRecordIsRecomputedAndSaid) {
    const fs::path work = temp_dir("record");
    const fs::path in = two_sets(work);
    const fs::path cache = work / "cache";
    ASSERT_EQ(run("ingest " + q(in) + " -o " + q(work / "plain") + " --no-cache").code, 0);
    std::vector<fs::path> records;
    auto find_records = [&] {
        records.clear();
        for (const auto& e : fs::recursive_directory_iterator(cache / "ac"))
            if (e.is_regular_file()) records.push_back(e.path());
        std::sort(records.begin(), records.end());
    };
    const std::vector<std::function<void(const fs::path&)>> damage{
        [](const fs::path& rec) {  // cut short
            const std::string text = bytes_of(rec);
            std::ofstream(rec, std::ios::binary | std::ios::trunc) << text.substr(0, text.size() / 2);
        },
        [](const fs::path& rec) {  // altered: valid JSON whose entry no longer hashes to its digest
            json j = read_json(rec);
            j["entry"]["findings"] = json::array({{{"code", "TAMPERED"}, {"severity", "info"}, {"message", "x"}}});
            std::ofstream(rec, std::ios::binary | std::ios::trunc) << j.dump();
        }};
    for (size_t d = 0; d < damage.size(); ++d) {
        const fs::path out = work / ("out" + std::to_string(d));
        ASSERT_EQ(run("ingest " + q(in) + " -o " + q(out) + " --cache " + q(cache)).code, 0);
        find_records();
        ASSERT_EQ(records.size(), 2u);
        damage[d](records[0]);
        fs::remove_all(out);
        const auto r = run("ingest " + q(in) + " -o " + q(out) + " --cache " + q(cache));
        ASSERT_EQ(r.code, 0) << r.output;
        EXPECT_EQ(cache_line(r.output), std::make_pair(1, 1)) << "damage " << d << ":\n" << r.output;
        EXPECT_NE(r.output.find(records[0].filename().string()), std::string::npos) << "names the record:\n"
                                                                                    << r.output;
        EXPECT_NE(r.output.find("computed again"), std::string::npos) << r.output;
        EXPECT_EQ(r.output.find("TAMPERED"), std::string::npos) << r.output;
        EXPECT_EQ(bytes_of(out / "manifest.json"), bytes_of(work / "plain/manifest.json")) << "damage " << d;
    }
}

// A record an earlier matforge wrote (another cache_version): a plain miss, said nowhere (an
// upgrade is no fault of the cache: a warning per set would be noise in every CI log), and
// replaced by this version's record.
TEST(Cache, RecordOfAnEarlierVersionIsAQuietMiss) {
    const fs::path work = temp_dir("earlier");
    const fs::path in = two_sets(work);
    const fs::path cache = work / "cache";
    ASSERT_EQ(run("ingest " + q(in) + " -o " + q(work / "plain") + " --no-cache").code, 0);
    ASSERT_EQ(run("ingest " + q(in) + " -o " + q(work / "a") + " --cache " + q(cache)).code, 0);
    std::vector<fs::path> records;
    for (const auto& e : fs::recursive_directory_iterator(cache / "ac"))
        if (e.is_regular_file()) records.push_back(e.path());
    ASSERT_EQ(records.size(), 2u);
    for (const auto& rec : records) {  // version 1: no digest
        json j = read_json(rec);
        j["cache_version"] = 1;
        j.erase("entry_sha256");
        std::ofstream(rec, std::ios::binary | std::ios::trunc) << j.dump();
    }
    const auto r = run("ingest " + q(in) + " -o " + q(work / "b") + " --cache " + q(cache));
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(cache_line(r.output), std::make_pair(0, 2)) << r.output;
    EXPECT_EQ(r.output.find("warning: cache"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("computed again"), std::string::npos) << r.output;
    EXPECT_EQ(bytes_of(work / "b/manifest.json"), bytes_of(work / "plain/manifest.json"));
    for (const auto& rec : records) EXPECT_EQ(read_json(rec)["cache_version"], read_json(records[0])["cache_version"]);
    EXPECT_NE(read_json(records[0])["cache_version"], 1) << "replaced by this version's record";
}

TEST(Cache, UnusableCacheNeverFailsARun) {
    const fs::path work = temp_dir("unusable");
    const fs::path in = two_sets(work);
    // A cache whose layout cannot be made (its `cas` is a file): the run goes on without it.
    const fs::path broken = work / "broken";
    write_text(broken / "version", "matforge cache 1\n");
    write_text(broken / "cas", "x");
    const auto r = run("ingest " + q(in) + " -o " + q(work / "out") + " --cache " + q(broken));
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("running without the cache"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find((broken / "cas").string()), std::string::npos) << r.output;
    ASSERT_EQ(run("ingest " + q(in) + " -o " + q(work / "plain") + " --no-cache").code, 0);
    EXPECT_EQ(bytes_of(work / "out/manifest.json"), bytes_of(work / "plain/manifest.json"));
    // --cache and --no-cache together is a usage error.
    EXPECT_EQ(run("ingest " + q(in) + " -o " + q(work / "x") + " --cache " + q(work / "c") + " --no-cache").code, 2);
}

TEST(Cache, StatsAndPrune) {
    const fs::path work = temp_dir("prune");
    const fs::path in = two_sets(work);
    const fs::path cache = work / "cache";
    ASSERT_EQ(ingest(in, work / "out", cache).code, 0);
    auto r = run("cache stats --cache " + q(cache));
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("2 records"), std::string::npos) << r.output;
    // A prune whose limit holds everything keeps every record usable: the blobs of its outputs
    // and of its material files (.gltf, .bin) alike, so the next run restores both sets.
    r = run("cache prune --cache " + q(cache) + " --max-size 10G --grace 0");
    ASSERT_EQ(r.code, 0) << r.output;
    r = ingest(in, work / "again", cache);
    EXPECT_EQ(cache_line(r.output), std::make_pair(2, 0)) << r.output;
    // Pruned to nothing: every record and blob goes (a zero grace so the fresh blobs go too) and
    // the next run computes both sets again, with the same bytes.
    r = run("cache prune --cache " + q(cache) + " --max-size 0 --grace 0");
    ASSERT_EQ(r.code, 0) << r.output;
    r = run("cache stats --cache " + q(cache));
    EXPECT_NE(r.output.find("0 records, 0 blobs"), std::string::npos) << r.output;
    const std::string before = bytes_of(work / "out/manifest.json");
    r = ingest(in, work / "out", cache);
    EXPECT_EQ(cache_line(r.output), std::make_pair(0, 2)) << r.output;
    EXPECT_EQ(bytes_of(work / "out/manifest.json"), before);
}

// The cache remembers a file's digest by its settled identity (base/file_identity.hpp), the rule
// lib/image keeps header reads by: a file changed in the last two seconds is hashed and nothing is
// remembered of it (a rewrite of the same size within one tick of the kernel's clock would keep
// its times); once settled, its digest is remembered, and a change in place (the modification
// time put back) is still seen by its change time.
TEST(Cache, NothingIsRememberedOfAFileChangedInTheLastSeconds) {
    const fs::path work = temp_dir("settled");
    const fs::path in = two_sets(work);  // copied just now
    const fs::path cache = work / "cache";
    auto hints = [&] {
        size_t n = 0;
        std::error_code ec;
        for (fs::recursive_directory_iterator it(cache / "stat", ec), end; !ec && it != end; it.increment(ec))
            n += it->is_regular_file() ? 1 : 0;
        return n;
    };
    auto r = ingest(in, work / "out", cache);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(hints(), 0u) << "inputs and outputs were all written in the last seconds";
    std::this_thread::sleep_for(std::chrono::milliseconds(2100));
    r = ingest(in, work / "out", cache);
    EXPECT_EQ(cache_line(r.output), std::make_pair(2, 0)) << r.output;
    EXPECT_GT(hints(), 8u) << "every settled input and output is remembered";
    // Other pixels, the same size and modification time: only the change time tells it apart.
    const fs::path map = in / "Net004A_1K-JPG" / "Net004A_1K-JPG_Color.jpg";
    std::string bytes = bytes_of(map);
    const auto mtime = fs::last_write_time(map);
    bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 0x10);
    std::ofstream(map, std::ios::binary | std::ios::trunc) << bytes;
    fs::last_write_time(map, mtime);
    r = ingest(in, work / "out", cache, " --fail-on never");
    EXPECT_EQ(cache_line(r.output), std::make_pair(1, 1)) << r.output;
}
