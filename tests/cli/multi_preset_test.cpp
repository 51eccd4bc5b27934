// `ingest --preset a,b,...`: one pass over the sets writes each preset into <out>/<its name>, each
// folder byte for byte what a run of that preset alone writes into the same folder (its own
// manifest, library and material files), computed or restored from the cache, whole or sharded.
#include <map>

#include "cli_util.hpp"

using namespace mft;

namespace {

// Every file under a folder (temporaries and locks included: a leftover would differ).
using mf::testfiles::files_under;

void expect_same_tree(const std::map<std::string, std::string>& got, const std::map<std::string, std::string>& want,
                      const std::string& what) {
    EXPECT_EQ(got.size(), want.size()) << what;
    for (const auto& [rel, bytes] : want) {
        const auto it = got.find(rel);
        if (it == got.end()) {
            ADD_FAILURE() << what << ": " << rel << " missing";
            continue;
        }
        EXPECT_TRUE(it->second == bytes) << what << ": " << rel << " differs";
    }
}

const std::vector<std::string> kPresets{"gltf", "unity-hdrp", "unreal"};

}  // namespace

TEST(MultiPreset, EachFolderIsByteIdenticalToItsOwnRun) {
    const fs::path work = temp_dir("multi");
    const fs::path out = work / "out";
    const std::string cache = " --cache " + q(work / "cache");
    auto r = run("ingest " + q(samples()) + " -o " + q(out) + " --preset gltf,unity-hdrp,unreal" + cache);
    ASSERT_EQ(r.code, 0) << r.output;
    for (const auto& p : kPresets)  // each preset's summary, named
        EXPECT_NE(r.output.find("matforge ingest [" + p + "]: 4 materials"), std::string::npos) << r.output;
    std::map<std::string, std::map<std::string, std::string>> together;
    for (const auto& p : kPresets) {
        together[p] = files_under(out / p);
        EXPECT_TRUE(together[p].count("manifest.json")) << p;
        EXPECT_EQ(read_json(out / p / "manifest.json")["preset"], p);
    }
    EXPECT_EQ(together["unity-hdrp"].count("Metal_Damaged_001/Metal_Damaged_001.mat"), 1u);
    // Each preset alone, computed, into the same folder (an earlier run of ours: replaced).
    for (const auto& p : kPresets) {
        r = run("ingest " + q(samples()) + " -o " + q(out / p) + " -q --no-cache --preset " + p);
        ASSERT_EQ(r.code, 0) << r.output;
        expect_same_tree(files_under(out / p), together[p], p + " alone vs together");
    }
    // Together again, every set restored from the cache into fresh folders: the same bytes.
    const fs::path again = work / "again";
    ASSERT_EQ(run("ingest " + q(samples()) + " -o " + q(again) + " -q --preset gltf,unity-hdrp,unreal" + cache).code,
              0);
    for (const auto& p : kPresets) expect_same_tree(files_under(again / p), together[p], p + " restored together");
    // Sharded: each folder's parts merge into that preset's one run.
    const fs::path sharded = work / "sharded";
    for (const char* s : {"0/2", "1/2"})
        ASSERT_EQ(run("ingest " + q(samples()) + " -o " + q(sharded) + " -q --no-cache --preset gltf,unreal --shard " +
                      s)
                      .code,
                  0);
    for (const std::string p : {"gltf", "unreal"}) {
        const fs::path d = sharded / p;
        r = run("merge " + q(d / "manifest.shard-0-of-2.json") + " " + q(d / "manifest.shard-1-of-2.json") + " -o " +
                q(d / "manifest.json"));
        ASSERT_EQ(r.code, 0) << r.output;
        EXPECT_EQ(bytes_of(d / "manifest.json"), together[p]["manifest.json"]) << p;
    }
}

TEST(MultiPreset, UnclearRequestsAreRefusedBeforeAnythingIsWritten) {
    const fs::path work = temp_dir("refused");
    auto refused = [&](const std::string& args, const std::string& says) {
        const auto r = run("ingest " + q(samples()) + " -o " + q(work / "out") + " " + args);
        EXPECT_EQ(r.code, 2) << r.output;
        EXPECT_NE(r.output.find(says), std::string::npos) << r.output;
        EXPECT_FALSE(fs::exists(work / "out")) << args;
    };
    refused("--preset gltf,gltf", "two presets of the run are named \"gltf\"");
    refused("--preset gltf,", "names an empty preset");
    refused("--preset gltf,no-such-preset", "no-such-preset");
    refused("--preset gltf,unreal --report json", "--report takes one preset's run");
}
