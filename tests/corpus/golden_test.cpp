// Golden digests: every file ingest writes for every shipped preset, from sample_materials/ and the
// real corpus, has the SHA-256 recorded in tests/data/golden/outputs.sha256. A change of any
// output byte (a texture, a material file, a manifest) fails here, naming the files; a change that
// is meant updates the record in the same commit:
//
//     MATFORGE_UPDATE_GOLDEN=1 ctest --test-dir build -R Golden      (or scripts/golden.sh)
//
// The outputs do not depend on the current folder or --jobs (checked when this test was written:
// two runs, 1351 files, identical); the manifests name their sources relative to themselves, so
// the inputs are reached through links beside the output folder: the record holds in any clone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include "core/files.hpp"
#include "run_binary.hpp"
#include "test_dirs.hpp"
#include "test_env.hpp"
#include "test_files.hpp"

namespace {
namespace fs = std::filesystem;

fs::path record() { return mf::testenv::source_dir() / "tests/data/golden/outputs.sha256"; }

// "<sha256>  <path>" lines (sha256sum's format, so `sha256sum -c` checks a folder by hand).
std::map<std::string, std::string> read_record(const fs::path& file) {
    std::map<std::string, std::string> digests;
    std::ifstream in(file);
    for (std::string line; std::getline(in, line);)
        if (line.size() > 66) digests[line.substr(66)] = line.substr(0, 64);
    return digests;
}

std::map<std::string, std::string> digests_of(const fs::path& root) {
    std::map<std::string, std::string> digests;
    for (const auto& e : fs::recursive_directory_iterator(root))
        if (e.is_regular_file())
            digests[fs::relative(e.path(), root).generic_string()] =
                mf::sha256_hex(mf::testfiles::file_bytes(e.path()));
    return digests;
}

TEST(Golden, EveryPresetWritesTheRecordedBytes) {
    const auto presets_run = mf::testbin::spawn({mf::testenv::bin(), "presets"}, 60);
    ASSERT_EQ(presets_run.code, 0) << presets_run.output;
    std::string presets;
    std::istringstream lines(presets_run.output);
    for (std::string line; std::getline(lines, line);)
        if (const size_t tab = line.find('\t'); tab != std::string::npos)
            presets += (presets.empty() ? "" : ",") + line.substr(0, tab);
    ASSERT_NE(presets.find("gltf"), std::string::npos) << presets_run.output;

    // The inputs through links beside the output folder: a manifest names its sources relative to
    // itself, so the same relative paths in every clone, wherever it lies.
    const fs::path work = mf::testdirs::fresh_for_test("matforge-golden-", "work");
    fs::create_directories(work / "in");
    fs::create_directory_symlink(mf::testenv::source_dir() / "sample_materials", work / "in" / "samples");
    fs::create_directory_symlink(mf::testenv::corpus_dir() / "real", work / "in" / "corpus");
    const fs::path out = work / "out";
    const auto run = mf::testbin::spawn({mf::testenv::bin(), "ingest", (work / "in" / "samples").string(),
                                         (work / "in" / "corpus").string(), "-o", out.string(), "--preset", presets,
                                         "--no-cache", "--fail-on", "never", "--quiet"},
                                        1200);
    ASSERT_EQ(run.code, 0) << run.output;
    const auto now = digests_of(out);
    ASSERT_GT(now.size(), 1000u);  // 9 presets x 23 sets' textures, material files and manifests

    if (const char* update = std::getenv("MATFORGE_UPDATE_GOLDEN"); update && std::string(update) == "1") {
        std::ofstream f(record(), std::ios::binary | std::ios::trunc);
        for (const auto& [path, digest] : now) f << digest << "  " << path << "\n";
        ASSERT_TRUE(f.flush()) << record();
        std::cout << "golden: " << now.size() << " digests written to " << record() << "\n";
        return;
    }
    const auto want = read_record(record());
    ASSERT_FALSE(want.empty()) << "no record at " << record() << " (MATFORGE_UPDATE_GOLDEN=1 writes it)";
    std::vector<std::string> changed, added, removed;
    for (const auto& [path, digest] : now) {
        const auto it = want.find(path);
        if (it == want.end()) added.push_back(path);
        else if (it->second != digest) changed.push_back(path);
    }
    for (const auto& [path, digest] : want)
        if (!now.count(path)) removed.push_back(path);
    auto list = [](const std::vector<std::string>& paths) {
        std::string s;
        for (size_t i = 0; i < paths.size() && i < 25; ++i) s += "\n  " + paths[i];
        if (paths.size() > 25) s += "\n  ... and " + std::to_string(paths.size() - 25) + " more";
        return s;
    };
    EXPECT_TRUE(changed.empty() && added.empty() && removed.empty())
        << changed.size() << " changed, " << added.size() << " new, " << removed.size() << " gone of " << want.size()
        << " recorded outputs (if meant: MATFORGE_UPDATE_GOLDEN=1 ctest -R Golden, in the same commit)"
        << "\nchanged:" << list(changed) << "\nnew:" << list(added) << "\ngone:" << list(removed);
}

}  // namespace
