// The ingest cache's records are a build's own (store/cache.hpp): two builds of one version may
// write other bytes, so a record computed by one is never restored by another. "Another build"
// here is the matforge binary with one byte of its build-id changed, and the binary with its
// build-id note removed (named by its file's SHA-256); binutils and sha256sum name each build
// independently of matforge.
#include <cstdio>
#include <map>
#include <set>

#include "cli_util.hpp"
#include "store/cache.hpp"
#include "test_elf.hpp"

namespace fs = std::filesystem;

namespace cache_build {

// "cache: R sets restored, C computed" of `matforge ingest IN -o OUT --cache CACHE` run by the
// binary `exe`; {-1, -1} when the run failed or printed none.
std::pair<int, int> ingest(const std::string& exe, const fs::path& in, const fs::path& out, const fs::path& cache) {
    const auto p = mf::testbin::spawn({exe, "ingest", in.string(), "-o", out.string(), "--cache", cache.string()});
    int restored = -1, computed = -1;
    const auto at = p.output.find("cache: ");
    if (p.code != 0 || at == std::string::npos ||
        std::sscanf(p.output.c_str() + at, "cache: %d sets restored, %d computed", &restored, &computed) != 2) {
        ADD_FAILURE() << exe << " ingest:\n" << p.output;
        return {-1, -1};
    }
    return {restored, computed};
}

std::string unhex(const std::string& h) {
    std::string raw;
    for (size_t i = 0; i + 1 < h.size(); i += 2) raw += static_cast<char>(std::stoi(h.substr(i, 2), nullptr, 16));
    return raw;
}

void write_executable(const fs::path& p, const std::string& bytes) {
    fs::create_directories(p.parent_path());
    {
        std::ofstream o(p, std::ios::binary);
        o << bytes;
    }
    fs::permissions(p, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec);
}

// The `code` of every action record in `cache`, with how many records name it.
std::map<std::string, int> record_codes(const fs::path& cache) {
    std::map<std::string, int> codes;
    for (const auto& e : fs::recursive_directory_iterator(cache / "ac"))
        if (e.is_regular_file()) ++codes[mft::read_json(e.path()).value("code", "(none)")];
    return codes;
}

}  // namespace cache_build

TEST(CacheBuild, RecordsOfAnotherBuildAreNeverRestored) {
    using cache_build::ingest;
    const fs::path work = mft::temp_dir("builds");
    const fs::path in = work / "in" / "Net004A_1K-JPG";
    fs::create_directories(in);
    fs::copy(mft::samples() / "Net004A_1K-JPG", in, fs::copy_options::recursive);
    const fs::path cache = work / "cache";
    const std::string bin = mf::testenv::bin();
    const std::string id = mf::testelf::readelf_build_id(bin);
    ASSERT_EQ(id.size(), 40u) << mf::testelf::output_of("readelf -n " + mf::testelf::shell_word(bin));
    ASSERT_EQ(mft::run("ingest " + mft::q(in) + " -o " + mft::q(work / "plain") + " --no-cache").code, 0);
    const std::string manifest = mft::bytes_of(work / "plain/manifest.json");

    // This build: computed once, then restored.
    EXPECT_EQ(ingest(bin, in, work / "a", cache), std::make_pair(0, 1));
    EXPECT_EQ(ingest(bin, in, work / "a", cache), std::make_pair(1, 0));

    // Another build of the same version (one byte of its build-id changed): it computes the set,
    // writing the same manifest (the build is not in the action key), then restores its own.
    std::string bytes = mft::bytes_of(bin);
    const std::string note = std::string("GNU\0", 4) + cache_build::unhex(id);
    const auto at = bytes.find(note);
    ASSERT_NE(at, std::string::npos);
    ASSERT_EQ(bytes.find(note, at + 1), std::string::npos) << "one build-id note";
    bytes[at + 4] = static_cast<char>(bytes[at + 4] ^ 0x5a);
    const fs::path other = work / "other-build/matforge";
    cache_build::write_executable(other, bytes);
    char first[3];
    std::snprintf(first, sizeof first, "%02x", std::stoi(id.substr(0, 2), nullptr, 16) ^ 0x5a);
    const std::string other_id = first + id.substr(2);
    ASSERT_EQ(mf::testelf::readelf_build_id(other.string()), other_id);
    EXPECT_EQ(ingest(other.string(), in, work / "b", cache), std::make_pair(0, 1));
    EXPECT_EQ(mft::bytes_of(work / "b/manifest.json"), manifest);
    EXPECT_EQ(ingest(other.string(), in, work / "b", cache), std::make_pair(1, 0));

    // A build without a build-id: named by its file's SHA-256, never by nothing (which every
    // such build would share).
    const fs::path bare = work / "no-build-id/matforge";
    fs::create_directories(bare.parent_path());
    const std::string objcopy = "objcopy --remove-section=.note.gnu.build-id " + mf::testelf::shell_word(bin) + " " +
                                mf::testelf::shell_word(bare);
    ASSERT_EQ(mf::testelf::output_of(objcopy), "");
    ASSERT_EQ(mf::testelf::readelf_build_id(bare.string()), "");
    EXPECT_EQ(ingest(bare.string(), in, work / "c", cache), std::make_pair(0, 1));
    EXPECT_EQ(mft::bytes_of(work / "c/manifest.json"), manifest);
    EXPECT_EQ(ingest(bare.string(), in, work / "c", cache), std::make_pair(1, 0));
    // The first build's record is still there.
    EXPECT_EQ(ingest(bin, in, work / "a", cache), std::make_pair(1, 0));

    // One record per build, each naming its build as binutils and sha256sum do.
    const std::string sum = mf::testelf::output_of("sha256sum " + mf::testelf::shell_word(bare));
    ASSERT_GE(sum.size(), 64u) << sum;
    const std::map<std::string, int> want{{"build-id " + id, 1},
                                          {"build-id " + other_id, 1},
                                          {"sha256 " + sum.substr(0, 64), 1}};
    EXPECT_EQ(cache_build::record_codes(cache), want);

    // In-process: a cache for the first build's id finds its record of the set's action key, and
    // one for an id no build has finds nothing.
    const nlohmann::json m = mft::read_json(work / "plain/manifest.json");
    const std::string key = m["materials"][0]["key"], name = m["materials"][0]["name"];
    int writes = 0;
    const mf::Cache::Write count = [&](const std::string&, std::span<const unsigned char>, std::string&) {
        ++writes;
        return true;
    };
    std::string error;
    std::vector<std::string> corrupt;
    const auto mine = mf::Cache::create(cache, error, "build-id " + id);
    ASSERT_TRUE(mine) << error;
    const auto hit = mine->restore(key, name, work / "a", count, corrupt);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->entry.outputs.size(), m["materials"][0]["outputs"].size());
    EXPECT_EQ(writes, 0) << "a's outputs already hold the recorded bytes";
    const auto none = mf::Cache::create(cache, error, "build-id " + std::string(40, '0'));
    ASSERT_TRUE(none) << error;
    EXPECT_FALSE(none->restore(key, name, work / "a", count, corrupt));
    EXPECT_TRUE(corrupt.empty()) << corrupt.front();

    // `matforge cache` sizes and prunes every build's records.
    auto r = mft::run("cache stats --cache " + mft::q(cache));
    EXPECT_NE(r.output.find(": 3 records"), std::string::npos) << r.output;
    r = mft::run("cache prune --cache " + mft::q(cache) + " --max-size 0 --grace 0");
    EXPECT_NE(r.output.find("removed 3 records"), std::string::npos) << r.output;
    r = mft::run("cache stats --cache " + mft::q(cache));
    EXPECT_NE(r.output.find(": 0 records, 0 blobs"), std::string::npos) << r.output;
}
