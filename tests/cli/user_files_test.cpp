// Nothing of the user's is ever lost, round three (issue 24): the newer commands — the cache,
// merge (tests/cli/shard_test.cpp), validate's and plan's files, report — never delete, replace
// or write through what matforge did not write, and a usage error says what to do and creates
// nothing. Each test fails on the code before its fix.
#include <unistd.h>

#include <atomic>
#include <thread>

#include "cli_util.hpp"
#include "store/cache.hpp"

using namespace mft;

namespace {

// A copy of two sample sets: `dir`/lib/<set>/...
fs::path library(const fs::path& dir) {
    fs::create_directories(dir / "lib");
    for (const char* s : {"Metal_Damaged_001_SD", "Net004A_1K-JPG"})
        fs::copy(samples() / s, dir / "lib" / s, fs::copy_options::recursive);
    return dir / "lib";
}

using mf::testfiles::files_under;

}  // namespace

// `cache prune` / `cache stats` on a folder that is not a matforge cache: refused, nothing in it
// removed or created. In a real cache, prune removes only files named as the cache names them.
TEST(UserFiles, CacheCommandsTouchOnlyACache) {
    const fs::path work = temp_dir("notacache");
    const fs::path mine = work / "mine";
    write_text(mine / "ac/notes/t.txt", "my notes");
    write_text(mine / "cas/ab/readme", "mine too");
    const auto before = files_under(mine);
    for (const char* cmd : {"cache prune --max-size 0 --grace 0 --cache ", "cache stats --cache "}) {
        const auto r = run(cmd + q(mine));
        EXPECT_EQ(r.code, 2) << cmd << r.output;
        EXPECT_NE(r.output.find("not a matforge cache"), std::string::npos) << r.output;
        EXPECT_EQ(files_under(mine), before) << cmd;
        EXPECT_FALSE(fs::exists(mine / "version")) << cmd;
        EXPECT_FALSE(fs::exists(mine / "stat")) << cmd;
    }
    // ingest refuses it as a cache too (exit 2, nothing written anywhere).
    const fs::path lib = library(work);
    auto r = run("ingest " + q(lib) + " -o " + q(work / "out") + " --cache " + q(mine));
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_EQ(files_under(mine), before);
    EXPECT_FALSE(fs::exists(work / "out"));
    // A real cache holding a file of the user's: prune to nothing keeps it.
    const fs::path cache = work / "cache";
    ASSERT_EQ(run("ingest " + q(lib) + " -o " + q(work / "out") + " -q --cache " + q(cache)).code, 0);
    write_text(cache / "ac/notes.txt", "mine");
    write_text(cache / "cas/ab/not-a-digest", "mine");
    r = run("cache prune --cache " + q(cache) + " --max-size 0 --grace 0");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("removed 2 records"), std::string::npos) << r.output;
    EXPECT_EQ(bytes_of(cache / "ac/notes.txt"), "mine");
    EXPECT_EQ(bytes_of(cache / "cas/ab/not-a-digest"), "mine");
}

// Shards of one run making the same new cache at once (scripts/cluster-demo.sh's array job): none
// may see another's half-made cache as a user's folder. The marker is written before anything
// else, and a folder holding only a marker being written is a cache being made. Failed in CI
// before: one shard made `cas` first, the other refused "it holds cas and no cache marker".
TEST(UserFiles, ShardsMakeOneNewCacheTogether) {
    const fs::path work = temp_dir("cacherace");
    for (int round = 0; round < 20; ++round) {
        const fs::path dir = work / ("c" + std::to_string(round));
        std::vector<std::string> errors(6);
        std::vector<std::thread> threads;
        std::atomic<int> ready{0};
        for (size_t t = 0; t < errors.size(); ++t)
            threads.emplace_back([&, t] {
                ++ready;
                while (ready < static_cast<int>(errors.size())) std::this_thread::yield();
                std::string error;
                if (!mf::Cache::create(dir, error)) errors[t] = error.empty() ? "no error said" : error;
            });
        for (auto& th : threads) th.join();
        for (const auto& e : errors) EXPECT_EQ(e, "") << "round " << round;
        std::string error;
        EXPECT_TRUE(mf::Cache::open(dir, error)) << error;
    }
    // Only a marker being written (our temporary's exact name): usable. A name like it that is
    // not one of ours, or anything beside it: a user's folder, refused.
    const fs::path making = work / "making";
    write_text(making / ".version.matforge-tmp-4242-0", "matforge ca");
    EXPECT_EQ(mf::Cache::unusable(making), "");
    const fs::path other = work / "other";
    write_text(other / ".version.matforge-tmp-notes", "mine");
    EXPECT_NE(mf::Cache::unusable(other).find("not a matforge cache"), std::string::npos);
    write_text(making / "cas", "mine");
    EXPECT_NE(mf::Cache::unusable(making).find("not a matforge cache"), std::string::npos);
}

// The cache is a folder of its own: not the output folder, inside it or around it, not an input.
TEST(UserFiles, CacheIsNeverMixedWithOutputsOrInputs) {
    const fs::path work = temp_dir("cacheplace");
    const fs::path lib = library(work);
    const auto lib_before = files_under(lib);
    for (const auto& [cache, says] :
         std::vector<std::pair<fs::path, std::string>>{{work / "out", "is the output folder"},
                                                       {work / "out/cache", "is inside the output folder"},
                                                       {work, "holds the output folder"},
                                                       {lib, "holds the output folder"},
                                                       {lib / "Net004A_1K-JPG", "is the input"}}) {
        const fs::path out = cache == lib ? lib / "out" : work / "out";
        const auto r = run("ingest " + q(lib / "Net004A_1K-JPG") + " -o " + q(out) + " --cache " + q(cache));
        EXPECT_EQ(r.code, 2) << cache << r.output;
        EXPECT_NE(r.output.find(says), std::string::npos) << cache << r.output;
        EXPECT_FALSE(fs::exists(out / "manifest.json")) << cache;
    }
    const auto r = run("ingest " + q(lib) + " -o " + q(work / "out") + " --cache " + q(lib / "Net004A_1K-JPG/c"));
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("is inside the input"), std::string::npos) << r.output;
    EXPECT_EQ(files_under(lib), lib_before);
}

// validate's report and plan's work list never replace an input they read, nor land among a
// set's maps (the next run would read them as the set's files).
TEST(UserFiles, ReportAndPlanFilesNeverReplaceAnInput) {
    const fs::path work = temp_dir("reportfile");
    const fs::path lib = library(work);
    const auto before = files_under(lib);
    const fs::path map = lib / "Net004A_1K-JPG/Net004A_1K-JPG_Color.jpg";
    for (const std::string& cmd :
         {"validate " + q(lib) + " --report json --report-file " + q(map),
          "validate " + q(lib) + " --report json --report-file " + q(lib / "Net004A_1K-JPG/report.json"),
          "plan " + q(lib) + " -o " + q(map), "plan " + q(lib) + " -o " + q(lib / "Metal_Damaged_001_SD/plan.json"),
          "validate " + q(lib / "Net004A_1K-JPG") + " --report-file " + q(lib / "Net004A_1K-JPG")}) {
        const auto r = run(cmd);
        EXPECT_EQ(r.code, 2) << cmd << "\n" << r.output;
        EXPECT_NE(r.output.find("never writes over what it reads"), std::string::npos) << r.output;
        EXPECT_EQ(files_under(lib), before) << cmd;
    }
    // Beside the library is fine.
    EXPECT_EQ(run("validate " + q(lib) + " --report json --report-file " + q(work / "report.json")).code, 0);
    EXPECT_EQ(run("plan " + q(lib) + " -o " + q(lib / "plan.json")).code, 0);
}

// A prune that cannot remove (a cache it may not write) says so and fails, instead of counting
// what it did not remove.
TEST(UserFiles, PruneOfAReadOnlyCacheSaysWhatStayed) {
    const fs::path work = temp_dir("readonly");
    const fs::path lib = library(work);
    const fs::path cache = work / "cache";
    ASSERT_EQ(run("ingest " + q(lib) + " -o " + q(work / "out") + " -q --cache " + q(cache)).code, 0);
    const auto before = files_under(cache);
    const auto rx = fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read | fs::perms::group_exec |
                    fs::perms::others_read | fs::perms::others_exec;
    for (fs::path p = cache; p != p.root_path(); p = p.parent_path())
        fs::permissions(p, rx, fs::perm_options::add);  // nobody may look in (not write)
    for (const auto& e : fs::recursive_directory_iterator(cache))
        if (e.is_directory()) fs::permissions(e.path(), rx);
    fs::permissions(cache, rx);
    // Root may remove anything: the prune runs as nobody then.
    std::vector<std::string> argv;
    if (::geteuid() == 0) argv = {"setpriv", "--reuid=65534", "--regid=65534", "--clear-groups"};
    for (const char* a : {"cache", "prune", "--max-size", "0", "--grace", "0", "--cache"}) argv.emplace_back(a);
    argv.insert(argv.begin() + static_cast<long>(::geteuid() == 0 ? 4 : 0), mf::testenv::bin());
    argv.push_back(cache.string());
    const auto p = mf::testbin::spawn(argv);
    for (const auto& e : fs::recursive_directory_iterator(cache))
        if (e.is_directory()) fs::permissions(e.path(), fs::perms::owner_all, fs::perm_options::add);
    fs::permissions(cache, fs::perms::owner_all, fs::perm_options::add);
    EXPECT_EQ(p.code, 1) << p.output;
    EXPECT_NE(p.output.find("removed 0 records and 0 blobs"), std::string::npos) << p.output;
    EXPECT_NE(p.output.find("could not be removed"), std::string::npos) << p.output;
    EXPECT_EQ(files_under(cache), before);
}

// Usage errors say what is wrong in matforge's own words, with the nearest command, option or
// preset, and a run whose inputs cannot be read creates nothing.
TEST(UserFiles, UsageErrorsSuggestAndCreateNothing) {
    const fs::path work = temp_dir("usage");
    auto r = run("injest " + q(samples()) + " -o " + q(work / "a"));
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.output.find("matforge: 'injest' is not a command; did you mean 'ingest'?"), std::string::npos)
        << r.output;
    r = run("ingest " + q(samples()) + " -o " + q(work / "b") + " --presett unreal");
    EXPECT_EQ(r.code, 2);
    EXPECT_EQ(r.output.rfind("matforge ingest: ", 0), 0u) << r.output;
    EXPECT_NE(r.output.find("did you mean --preset?"), std::string::npos) << r.output;
    r = run("validate " + q(samples()) + " --preset Unrel");
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.output.find("did you mean 'unreal'?"), std::string::npos) << r.output;
    // Engine names people type are answered by meaning, not spelling (issue 45).
    for (const auto& [typed, meant] :
         std::vector<std::pair<std::string, std::string>>{{"unity", "'unity-urp' (Unity URP Lit"},
                                                          {"HDRP", "'unity-hdrp'"},
                                                          {"ue5", "'unreal' (Unreal Engine"},
                                                          {"blender", "'gltf'"},
                                                          {"three", "'gltf'"},
                                                          {"mobile", "'vulkan-ktx2-astc'"},
                                                          {"ktx2", "'vulkan-ktx2'"}}) {
        r = run("validate " + q(samples()) + " --preset " + typed);
        EXPECT_EQ(r.code, 2) << typed;
        EXPECT_NE(r.output.find("by that you may mean " + meant), std::string::npos) << typed << ": " << r.output;
    }
    EXPECT_EQ(run("validate " + q(samples()) + " --preset UNREAL --report json").code, 0) << "names in any case";
    // A typo'd input: nothing created (no output folder, manifest or cache).
    r = run_env("MATFORGE_CACHE=" + q(work / "cache"), "ingest " + q(work / "no-such") + " -o " + q(work / "out"));
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.output.find("no such folder or .zip file"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(work / "out"));
    EXPECT_FALSE(fs::exists(work / "cache"));
    // A map given instead of its folder: said so, naming the folder.
    const fs::path map = samples() / "Net004A_1K-JPG/Net004A_1K-JPG_Color.jpg";
    r = run("ingest " + q(map) + " -o " + q(work / "out"));
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.output.find("a file, not a folder or a .zip file; give the folder that holds the set"),
              std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(work / "out"));
}

// File names reach the terminal with their control characters escaped: ESC/BEL in a map's name
// cannot clear the screen or retitle the terminal (validate's text report, stderr).
TEST(UserFiles, ControlCharactersNeverReachTheTerminal) {
    const fs::path work = temp_dir("escape");
    const fs::path set = work / "lib" / "Evil";
    fs::create_directories(set);
    fs::copy(samples() / "Net004A_1K-JPG/Net004A_1K-JPG_Color.jpg", set / "Evil_Color.jpg");
    fs::copy(samples() / "Net004A_1K-JPG/Net004A_1K-JPG_Roughness.jpg", set / "Evil_Roughness.jpg");
    write_text(set / "Evil_\x1b]0;owned\x07_Normal.png", "\x1b[2J not a png");
    auto r = run("validate " + q(work / "lib") + " --fail-on never");
    EXPECT_EQ(r.output.find('\x1b'), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find('\x07'), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("\\x1b]0;owned\\x07"), std::string::npos) << r.output;
    r = run("ingest " + q(work / "lib") + " -o " + q(work / "out") + " --fail-on never");
    EXPECT_EQ(r.output.find('\x1b'), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find('\x07'), std::string::npos) << r.output;
}

// An output folder of an earlier run (or a report) inside the library is never read as material
// sets: skipped with a note naming it, and the real sets keep their names (no "<name>_2").
TEST(UserFiles, EarlierOutputsInTheLibraryAreNotMaterials) {
    const fs::path work = temp_dir("outputs");
    const fs::path lib = library(work);
    ASSERT_EQ(run("ingest " + q(lib) + " -o " + q(lib / "out") + " -q").code, 0);
    ASSERT_EQ(run("report " + q(lib / "out/manifest.json") + " -o " + q(lib / "review") + " -q").code, 0);
    for (const std::string& cmd : {"validate " + q(lib) + " --report json --report-file " + q(work / "v.json"),
                                   "ingest " + q(lib) + " -o " + q(work / "elsewhere")}) {
        const auto r = run(cmd);
        EXPECT_EQ(r.code, 0) << cmd << "\n" << r.output;
        EXPECT_NE(r.output.find((lib / "out").string() +
                                ": skipped, an output folder of matforge (it holds its manifest.json)"),
                  std::string::npos)
            << r.output;
        EXPECT_NE(r.output.find((lib / "review").string() + ": skipped"), std::string::npos) << r.output;
    }
    const auto m = read_json(work / "elsewhere/manifest.json");
    ASSERT_EQ(m["materials"].size(), 2u) << m.dump(1);
    EXPECT_EQ(m["materials"][0]["name"], "Metal_Damaged_001");
    EXPECT_EQ(m["materials"][1]["name"], "Net004A");
    EXPECT_EQ(read_json(work / "v.json")["materials"].size(), 2u);
}

// A scene file naming a member twice, or a path holding a NUL (cut there by the system: another
// file would be rendered), is refused naming the file and the problem, before any device is used.
TEST(UserFiles, SceneFilesSayEachThingOnce) {
    const fs::path work = temp_dir("scene");
    write_text(work / "twice.json", R"({"material": {"albedo": [0.5, 0.5, 0.5], "roughness": 0.2, "roughness": 0.9}})");
    auto r = run("preview --scene " + q(work / "twice.json") + " -o " + q(work / "out"));
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("twice.json: the member \"roughness\" is given twice in one object"), std::string::npos)
        << r.output;
    write_text(work / "nul.json", R"({"material": {"albedo_map": "maps/a\u0000.png"}})");
    r = run("preview --scene " + q(work / "nul.json") + " -o " + q(work / "out"));
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("holds a NUL character"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(work / "out"));
}
