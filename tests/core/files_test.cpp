#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>

#include <unistd.h>

#include "core/files.hpp"
#include "core/json.hpp"
#include "core_util.hpp"

namespace fs = std::filesystem;

namespace {
using coretest::fresh_dir;
std::vector<unsigned char> bytes_of(std::string_view s) { return {s.begin(), s.end()}; }
}  // namespace

TEST(Sha256, KnownVectors) {
    // FIPS 180-2 test vectors.
    EXPECT_EQ(mf::sha256_hex({}), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
    const auto abc = bytes_of("abc");
    EXPECT_EQ(mf::sha256_hex(abc), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST(AtomicWrite, WritesCreatesFoldersAndLeavesNoTemp) {
    const fs::path d = fresh_dir("atomic");
    const auto data = bytes_of("hello");
    std::string err;
    ASSERT_TRUE(mf::write_file_atomic(d / "a/b/out.bin", data, err)) << err;
    std::vector<unsigned char> back;
    ASSERT_TRUE(mf::read_file(d / "a/b/out.bin", back, err));
    EXPECT_EQ(back, data);
    for (auto& e : fs::directory_iterator(d / "a/b")) EXPECT_EQ(e.path().filename(), "out.bin");
    fs::remove_all(d);
}

TEST(AtomicWrite, SameBytesLeaveFileUntouched) {
    const fs::path d = fresh_dir("same");
    std::string err;
    ASSERT_TRUE(mf::write_file_atomic(d / "f", bytes_of("x"), err));
    const auto t0 = fs::last_write_time(d / "f");
    fs::last_write_time(d / "f", t0 - std::chrono::hours(1));
    ASSERT_TRUE(mf::write_file_atomic(d / "f", bytes_of("x"), err));
    EXPECT_EQ(fs::last_write_time(d / "f"), t0 - std::chrono::hours(1));
    ASSERT_TRUE(mf::write_file_atomic(d / "f", bytes_of("y"), err));
    EXPECT_NE(fs::last_write_time(d / "f"), t0 - std::chrono::hours(1));
    fs::remove_all(d);
}

TEST(AtomicWrite, UnwritableDestinationGivesErrorNamingIt) {
    // A regular file where the output folder should be: works as root too (unlike chmod).
    const fs::path d = fresh_dir("blocked");
    std::ofstream(d / "folder") << "a file, not a folder";
    std::string err;
    EXPECT_FALSE(mf::write_file_atomic(d / "folder/out.png", bytes_of("x"), err));
    EXPECT_NE(err.find("folder"), std::string::npos) << err;
    fs::remove_all(d);
}

TEST(AtomicWrite, StaleTempsAreRemoved) {
    const fs::path d = fresh_dir("stale");
    // 99999999 is above Linux's largest pid_max (2^22), so no process owns that temp; pid 1 would
    // be alive on a CI machine (init) and not in every container.
    const fs::path dead = d / (std::string(".x.png") + mf::kTempMarker + "99999999-2");
    const fs::path live = d / (std::string(".y.png") + mf::kTempMarker + std::to_string(::getpid()) + "-3");
    std::ofstream(dead) << "partial";
    std::ofstream(live) << "being written";
    std::ofstream(d / "keep.png") << "k";
    EXPECT_EQ(mf::remove_stale_temps(d), 1);
    EXPECT_FALSE(fs::exists(dead));
    EXPECT_TRUE(fs::exists(live));
    EXPECT_TRUE(fs::exists(d / "keep.png"));
    fs::remove_all(d);
}

// A farm's nodes share one output folder: a pid names a live writer only on its own host.
TEST(AtomicWrite, TemporariesOfOtherHostsAreKeptUnlessTheFolderIsTheCallers) {
    const fs::path d = fresh_dir("hosts");
    const std::string ours = mf::temp_name("a.png");
    const auto owner = mf::temp_owner(ours);
    ASSERT_TRUE(owner) << ours;
    EXPECT_EQ(owner->host, mf::this_host());
    EXPECT_EQ(owner->pid, ::getpid());
    // Another node's writer: its pid (here, this process's own, alive) says nothing on this host.
    const std::string other = std::string(".b.png") + mf::kTempMarker + "render-node-07-" + std::to_string(::getpid()) +
                              "-4";
    const auto o = mf::temp_owner(other);
    ASSERT_TRUE(o);
    EXPECT_EQ(o->host, "render-node-07");
    const fs::path dead_here = d / (std::string(".c.png") + mf::kTempMarker + mf::this_host() +
                                    "-99999999-1");  // above pid_max
    for (const auto& n : {ours, other}) std::ofstream(d / n) << "partial";
    std::ofstream(dead_here) << "partial";
    EXPECT_EQ(mf::remove_stale_temps(d), 1);  // only this host's dead writer's
    EXPECT_FALSE(fs::exists(dead_here));
    EXPECT_TRUE(fs::exists(d / other));
    EXPECT_EQ(mf::remove_stale_temps(d, /*other_hosts=*/true), 1);  // a lost node's, in a folder that is ours
    EXPECT_FALSE(fs::exists(d / other));
    EXPECT_TRUE(fs::exists(d / ours));  // this host's live writer's: never
    EXPECT_FALSE(mf::temp_owner(std::string(".x.png") + mf::kTempMarker + "-12-1"));
    fs::remove_all(d);
}

// Kubernetes indexed-job pods share long name prefixes (issue 45): every pod is its own host,
// and so is a second boot or another pid namespace of one host; one host is one identity.
TEST(AtomicWrite, HostIdentityTellsApartNamesThatShareLongPrefixes) {
    const std::string prefix = "matforge-library-ingest-indexed-job-shard-runner-";
    const std::string boot = "6f1c2a52-0d8e-4c1e-9d8b-1c2d3e4f5a6b", ns = "pid:[4026531836]";
    std::set<std::string> ids;
    for (int i = 0; i < 200; ++i) ids.insert(mf::host_identity(prefix + std::to_string(i) + "-x7k2q", boot, ns));
    EXPECT_EQ(ids.size(), 200u);
    const std::string one = mf::host_identity(prefix + "0-x7k2q", boot, ns);
    EXPECT_EQ(one, mf::host_identity(prefix + "0-x7k2q", boot, ns));
    EXPECT_NE(one, mf::host_identity(prefix + "0-x7k2q", "another-boot", ns));
    EXPECT_NE(one, mf::host_identity(prefix + "0-x7k2q", boot, "pid:[4026532999]"));
    EXPECT_LE(one.size(), 16u + 1u + 16u);
    // Temporaries name it, and a name of ours reads it back.
    const auto owner = mf::temp_owner(mf::temp_name("a.png"));
    ASSERT_TRUE(owner);
    EXPECT_EQ(owner->host, mf::this_host());
    EXPECT_NE(mf::this_host().find('~'), std::string::npos);
}

// What no document of ours may hold is refused while parsing, naming the file and the problem.
// An atomic write in two halves (stage_file_under, then StagedFile's sync and rename): nothing at
// the destination until the rename, a temporary that never outlives an abandoned write, the
// identical-bytes case with nothing staged, and a refusal before anything is written.
TEST(StagedWrite, NothingInPlaceUntilRenamedAndNoTemporaryLeft) {
    const fs::path d = fresh_dir("staged");
    auto names = [&d] {
        std::vector<std::string> n;
        for (auto& e : fs::recursive_directory_iterator(d))
            if (e.is_regular_file()) n.push_back(fs::relative(e.path(), d).generic_string());
        std::sort(n.begin(), n.end());
        return n;
    };
    const auto data = bytes_of("staged bytes");
    std::string err;
    std::optional<mf::StagedFile> s;
    ASSERT_TRUE(mf::stage_file_under(d, "a/out.bin", data, s, err)) << err;
    ASSERT_TRUE(s);
    EXPECT_FALSE(fs::exists(d / "a/out.bin"));
    ASSERT_EQ(names().size(), 1u);
    EXPECT_NE(names()[0].find(mf::kTempMarker), std::string::npos);
    EXPECT_FALSE(s->destination_exists());
    ASSERT_TRUE(s->sync(err)) << err;
    ASSERT_TRUE(s->rename(err)) << err;
    s.reset();
    EXPECT_EQ(names(), std::vector<std::string>{"a/out.bin"});
    std::vector<unsigned char> back;
    ASSERT_TRUE(mf::read_file(d / "a/out.bin", back, err));
    EXPECT_EQ(back, data);

    // The same bytes: nothing staged, nothing touched.
    ASSERT_TRUE(mf::stage_file_under(d, "a/out.bin", data, s, err)) << err;
    EXPECT_FALSE(s);
    // Other bytes, abandoned before the rename: the destination keeps its bytes, no temporary.
    ASSERT_TRUE(mf::stage_file_under(d, "a/out.bin", bytes_of("other"), s, err)) << err;
    ASSERT_TRUE(s);
    EXPECT_TRUE(s->destination_exists());
    s.reset();
    EXPECT_EQ(names(), std::vector<std::string>{"a/out.bin"});
    ASSERT_TRUE(mf::read_file(d / "a/out.bin", back, err));
    EXPECT_EQ(back, data);
    // A refusal: nothing written.
    EXPECT_FALSE(mf::stage_file_under(d, "b/x.bin", data, s, err, [](bool) { return std::string("not ours"); }));
    EXPECT_EQ(err, "b/x.bin: not ours");
    EXPECT_FALSE(s);
    EXPECT_EQ(names(), std::vector<std::string>{"a/out.bin"});
    fs::remove_all(d);
}

TEST(ParseJson, RefusesDuplicateMembersAndNulCharacters) {
    std::string error;
    EXPECT_TRUE(mf::parse_json(R"({"a": {"x": 1}, "b": {"x": 2}})", "ok.json", error)) << error;
    EXPECT_FALSE(mf::parse_json(R"({"material": {"roughness": 0.2, "roughness": 0.9}})", "scene.json", error));
    EXPECT_EQ(error, "scene.json: the member \"roughness\" is given twice in one object");
    EXPECT_FALSE(mf::parse_json(R"({"albedo": "maps/a\u0000../../etc/passwd"})", "scene.json", error));
    EXPECT_EQ(error, "scene.json: the string \"maps/a\\u0000…\" holds a NUL character");
    EXPECT_FALSE(mf::parse_json(R"({"a\u0000b": 1})", "k.json", error));
    EXPECT_NE(error.find("holds a NUL character"), std::string::npos) << error;
}
