// `ingest --preset a,b,...`: one pass over the sets writes each preset into <out>/<its name>, each
// folder byte for byte what a run of that preset alone writes into the same folder (its own
// manifest, library and material files), computed or restored from the cache, whole or sharded.
// A set's outputs of every preset are one list of tasks (base/parallel.hpp SpareTasks), an output
// equal to another preset's encoded once (process/share.hpp claims), on a second thread while a
// core is idle, a worker waiting for the memory budget counting as idle (base/budget.hpp).
#include <atomic>
#include <chrono>
#include <map>
#include <thread>

#include "base/budget.hpp"
#include "base/parallel.hpp"
#include "cli_util.hpp"
#include "process/share.hpp"

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

namespace multi_preset_test {

// One roughness plane of 4x4 codes, all `code`.
std::shared_ptr<const mf::Planes> roughness_planes(uint8_t code) {
    auto planes = std::make_shared<mf::Planes>();
    mf::RolePlane plane;
    plane.codes = mf::Image8(4, 4, 1, code);
    planes->emplace(mf::Role::roughness, std::move(plane));
    return planes;
}

// An 8-bit PNG of that plane's one channel, its spec as pack_spec would make it.
mf::SetShare::Source roughness_output(std::shared_ptr<const mf::Planes> planes) {
    mf::PackSpec spec;
    spec.size = {4, 4};
    spec.roles = {mf::Role::roughness};
    return {spec, nullptr, std::move(planes)};
}

// Waits (at most 10 s: a hung thread fails the test instead of the suite) until `done` holds.
template <class F>
bool within_10s(F&& done) {
    for (int i = 0; i < 10000 && !done(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    return done();
}

}  // namespace multi_preset_test

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

TEST(MultiPreset, OutputsEqualAcrossPresetsAreEncodedOnceEvenWhileTheFirstEncodes) {
    using multi_preset_test::roughness_output;
    using multi_preset_test::roughness_planes;
    mf::SetShare share(2);
    // The first preset's claim leads; the second preset's, of other planes with equal pixels,
    // follows; other pixels lead again.
    const auto first = share.claim(roughness_output(roughness_planes(7)));
    const auto second = share.claim(roughness_output(roughness_planes(7)));
    const auto other = share.claim(roughness_output(roughness_planes(8)));
    EXPECT_TRUE(first->leads());
    EXPECT_FALSE(second->leads());
    EXPECT_TRUE(other->leads());

    // The follower asks while the leader is still encoding (on another thread): it waits, and
    // gets the leader's bytes and SHA-256 without encoding.
    std::atomic<int> encodes{0};
    std::atomic<bool> follower_asking{false};
    std::vector<unsigned char> led, followed;
    std::string led_sha, followed_sha;
    std::thread leader([&] {
        EXPECT_TRUE(share.encode(
            *first,
            [&] {
                ++encodes;
                multi_preset_test::within_10s([&] { return follower_asking.load(); });
                std::this_thread::sleep_for(std::chrono::milliseconds(20));  // the follower waits meanwhile
                led = {1, 2, 3};
                return true;
            },
            led, led_sha));
        share.settle(*first);
    });
    follower_asking = true;
    EXPECT_TRUE(share.encode(
        *second,
        [&] {
            ++encodes;
            followed = {9};
            return true;
        },
        followed, followed_sha));
    share.settle(*second);
    leader.join();
    EXPECT_EQ(encodes, 1);
    EXPECT_EQ(followed, (std::vector<unsigned char>{1, 2, 3}));
    EXPECT_EQ(followed_sha, mf::sha256_hex(led));
    EXPECT_EQ(led_sha, followed_sha);

    // A later claim (a third preset's) follows the kept encoding.
    const auto third = share.claim(roughness_output(roughness_planes(7)));
    EXPECT_FALSE(third->leads());
    std::vector<unsigned char> bytes;
    std::string sha;
    EXPECT_TRUE(share.encode(
        *third, [] { return false; }, bytes, sha));
    EXPECT_EQ(bytes, (std::vector<unsigned char>{1, 2, 3}));

    // A leader that encodes nothing (refused, interrupted) lets its follower encode its own.
    const auto late = share.claim(roughness_output(roughness_planes(8)));
    EXPECT_FALSE(late->leads());
    share.settle(*other);
    EXPECT_TRUE(share.encode(
        *late,
        [&] {
            ++encodes;
            bytes = {4};
            return true;
        },
        bytes, sha));
    EXPECT_EQ(encodes, 2);
    EXPECT_EQ(bytes, (std::vector<unsigned char>{4}));
    EXPECT_EQ(sha, mf::sha256_hex(bytes));
}

TEST(MultiPreset, SetTasksRunLargestFirstAndOnTheSpareCore) {
    // No core spare: the owner runs every task, the largest first, equal costs in posting order.
    std::vector<int> order;
    std::vector<std::thread::id> ran_on;
    {
        mf::SpareTasks tasks([] { return false; });
        for (const auto& [cost, id] : std::vector<std::pair<uint64_t, int>>{{3, 0}, {10, 1}, {0, 2}, {10, 3}, {5, 4}})
            tasks.post(cost, [&order, &ran_on, id = id] {
                order.push_back(id);
                ran_on.push_back(std::this_thread::get_id());
            });
        tasks.run();
        EXPECT_EQ(order, (std::vector<int>{1, 3, 4, 0, 2}));
        tasks.post(1, [&order] { order.push_back(5); });  // posted after a run: the next runs it
        tasks.run();
        EXPECT_EQ(order.back(), 5);
    }
    for (const auto& id : ran_on) EXPECT_EQ(id, std::this_thread::get_id());

    // A core spare: a second thread takes tasks. Each of two tasks waits for the other to have
    // started: both see it only when they run at once.
    std::atomic<int> started{0};
    std::atomic<int> saw_both{0};
    {
        mf::SpareTasks tasks([] { return true; });
        for (int i = 0; i < 2; ++i)
            tasks.post(1, [&] {
                ++started;
                if (multi_preset_test::within_10s([&] { return started.load() == 2; })) ++saw_both;
            });
        tasks.run();
    }
    EXPECT_EQ(saw_both, 2);
}

TEST(MultiPreset, AWorkerWaitingForTheMemoryBudgetCountsAsIdle) {
    mf::MemoryBudget budget(100);
    budget.acquire(80);
    EXPECT_EQ(budget.waiting(), 0);
    std::thread second([&] {
        budget.acquire(50);  // over the budget with 80 held: waits
        budget.release(50);
    });
    EXPECT_TRUE(multi_preset_test::within_10s([&] { return budget.waiting() == 1; }));
    budget.release(80);
    second.join();
    EXPECT_EQ(budget.waiting(), 0);
}

TEST(MultiPreset, OneSetOfFourPresetsOnTwoThreadsOrOneIsEachPresetsOwnRun) {
    // One set alone: a core is spare from the start, so its outputs of every preset are written on
    // two threads, two presets at a time (the third and fourth after the first two); --jobs 1
    // writes them on one. Each folder is what its preset alone writes.
    const fs::path work = temp_dir("one-set");
    const fs::path set = corpus_set("ambientcg_OfficeCeiling005_1K-JPG");
    const std::vector<std::string> presets{"gltf", "unity-hdrp", "unreal", "godot"};
    std::map<std::string, std::map<std::string, std::string>> alone;
    for (const auto& p : presets) {
        const auto r = run("ingest " + q(set) + " -o " + q(work / "alone" / p) + " -q --no-cache --preset " + p);
        ASSERT_EQ(r.code, 0) << r.output;
        alone[p] = files_under(work / "alone" / p);
        EXPECT_GE(alone[p].size(), 5u) << p << ": outputs, material file, manifest";
    }
    for (const std::string jobs : {"2", "1"}) {
        const fs::path out = work / ("jobs" + jobs);
        const auto r = run("ingest " + q(set) + " -o " + q(out) +
                           " -q --no-cache --preset gltf,unity-hdrp,unreal,godot --jobs " + jobs);
        ASSERT_EQ(r.code, 0) << r.output;
        for (const auto& p : presets) expect_same_tree(files_under(out / p), alone[p], p + " --jobs " + jobs);
    }
}
