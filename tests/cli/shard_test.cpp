// Sharded runs: `plan` (keys, shards), `ingest --shard I/N`, `merge` — the merged manifest of N
// shards is byte-identical to one unsharded run; merging parts of different runs is refused.
#include <map>

#include "cli_util.hpp"

using namespace mft;
using nlohmann::json;

namespace {

std::map<std::string, std::string> keys_of(const fs::path& plan) {
    std::map<std::string, std::string> k;
    const json p = read_json(plan);  // not `read_json(plan)["sets"]` in the for: the temporary would die first
    for (const auto& s : p["sets"]) k[s["name"]] = s["key"];
    return k;
}

}  // namespace

TEST(Shard, MergedShardsAreByteIdenticalToOneRun) {
    const fs::path work = temp_dir("merge");
    ASSERT_EQ(run("plan " + q(samples()) + " -o " + q(work / "plan.json") + " --shards 3").code, 0);
    const json plan = read_json(work / "plan.json");
    std::map<int, int> per_shard;
    for (const auto& s : plan["sets"]) ++per_shard[s["shard"].get<int>()];
    EXPECT_EQ(per_shard.size(), 3u) << plan.dump(2);
    for (int i = 0; i < 3; ++i) {
        const auto r = run("ingest " + q(samples()) + " -o " + q(work / "out") + " -q --shard " + std::to_string(i) + "/3");
        ASSERT_EQ(r.code, 0) << r.output;
        // Each shard processed exactly the sets the plan gave it.
        const json part = read_json(work / "out" / ("manifest.shard-" + std::to_string(i) + "-of-3.json"));
        EXPECT_EQ(static_cast<int>(part["materials"].size()), per_shard[i]);
        for (const auto& m : part["materials"])
            for (const auto& s : plan["sets"]) {
                if (s["name"] == m["name"]) {
                    EXPECT_EQ(s["shard"], i) << m["name"];
                }
            }
    }
    ASSERT_EQ(run("merge " + q(work / "out/manifest.shard-0-of-3.json") + " " + q(work / "out/manifest.shard-1-of-3.json") +
                  " " + q(work / "out/manifest.shard-2-of-3.json") + " -o " + q(work / "out/manifest.json"))
                  .code,
              0);
    ASSERT_EQ(run("ingest " + q(samples()) + " -o " + q(work / "single") + " -q --no-cache").code, 0);
    EXPECT_EQ(bytes_of(work / "out/manifest.json"), bytes_of(work / "single/manifest.json"));
    // The run's library.gltf, which no shard writes (each sees its part), comes from the merge.
    EXPECT_EQ(bytes_of(work / "out/library.gltf"), bytes_of(work / "single/library.gltf"));
    fs::remove(work / "out/manifest.json");
    fs::remove(work / "out/library.gltf");
    // A killed shard re-run completes its part: the same bytes again.
    fs::remove(work / "out/manifest.shard-1-of-3.json");
    ASSERT_EQ(run("ingest " + q(samples()) + " -o " + q(work / "out") + " -q --shard 1/3").code, 0);
    ASSERT_EQ(run("merge " + q(work / "out/manifest.shard-0-of-3.json") + " " + q(work / "out/manifest.shard-1-of-3.json") +
                  " " + q(work / "out/manifest.shard-2-of-3.json") + " -o " + q(work / "out/manifest.json"))
                  .code,
              0);
    EXPECT_EQ(bytes_of(work / "out/manifest.json"), bytes_of(work / "single/manifest.json"));
    EXPECT_EQ(bytes_of(work / "out/library.gltf"), bytes_of(work / "single/library.gltf"));
}

TEST(Shard, MergeRefusesPartsOfDifferentRuns) {
    const fs::path work = temp_dir("refuse");
    ASSERT_EQ(run("ingest " + q(samples() / "Metal_Damaged_001_SD") + " -o " + q(work / "a") + " -q").code, 0);
    ASSERT_EQ(run("ingest " + q(samples() / "Metal_Damaged_001_SD") + " -o " + q(work / "b") + " -q --preset unreal").code, 0);
    auto r = run("merge " + q(work / "a/manifest.json") + " " + q(work / "b/manifest.json") + " -o " + q(work / "m.json"));
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("preset \"gltf\" vs \"unreal\""), std::string::npos) << r.output;
    EXPECT_NE(r.output.find((work / "b/manifest.json").string()), std::string::npos) << r.output;
    // The same material in two parts is not one run either.
    r = run("merge " + q(work / "a/manifest.json") + " " + q(work / "a/manifest.json") + " -o " + q(work / "m.json"));
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("is in both"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(work / "m.json"));
    EXPECT_EQ(run("ingest " + q(samples()) + " -o " + q(work / "c") + " --shard 3/3").code, 2);
}

TEST(Shard, ActionKeysFollowContentAndConfigurationOnly) {
    const fs::path work = temp_dir("keys");
    fs::copy(samples(), work / "in", fs::copy_options::recursive);
    ASSERT_EQ(run("plan " + q(work / "in") + " -o " + q(work / "p1.json")).code, 0);
    const auto k1 = keys_of(work / "p1.json");
    // A time stamp is not content: the same keys.
    fs::last_write_time(work / "in/Metal_Damaged_001_SD/Metal_Damaged_001_basecolor.jpg", fs::file_time_type::clock::now());
    ASSERT_EQ(run("plan " + q(work / "in") + " -o " + q(work / "p2.json")).code, 0);
    EXPECT_EQ(keys_of(work / "p2.json"), k1);
    // One byte of one file: that set's key only.
    {
        std::fstream f(work / "in/Metal_Damaged_001_SD/Metal_Damaged_001_basecolor.jpg", std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(-1, std::ios::end);
        f.put('\x7f');
    }
    ASSERT_EQ(run("plan " + q(work / "in") + " -o " + q(work / "p3.json")).code, 0);
    const auto k3 = keys_of(work / "p3.json");
    ASSERT_EQ(k3.size(), k1.size());
    for (const auto& [name, key] : k1) EXPECT_EQ(key != k3.at(name), name == "Metal_Damaged_001") << name;
    // Another preset: every key.
    ASSERT_EQ(run("plan " + q(work / "in") + " -o " + q(work / "p4.json") + " --preset unreal").code, 0);
    const auto k4 = keys_of(work / "p4.json");
    for (const auto& [name, key] : k3) EXPECT_NE(key, k4.at(name)) << name;
}
