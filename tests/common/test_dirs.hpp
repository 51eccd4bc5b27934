// The folders tests make under the system's temporary folder, and when they go. A test program
// whose tests all passed removes every folder it registered when it ends; one with a failure keeps
// them and names them, to be looked at. Without this each suite run left its folders behind
// (13 GB after four runs), which fills the disk of a CI machine that keeps its files between runs.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <string>
#include <vector>

#include <unistd.h>

namespace mf::testdirs {
namespace fs = std::filesystem;

inline std::mutex& mutex() {
    static std::mutex m;
    return m;
}
// Every folder registered in this process (removed at the end when all passed).
inline std::vector<fs::path>& made() {
    static std::vector<fs::path> dirs;
    return dirs;
}
// Those registered since the current test began (run_binary.hpp's schema spool reads them).
inline std::vector<fs::path>& of_current_test() {
    static std::vector<fs::path> dirs;
    return dirs;
}

inline void own(const fs::path& d) {
    std::lock_guard lock(mutex());
    of_current_test().push_back(d);
    if (std::find(made().begin(), made().end(), d) == made().end()) made().push_back(d);
}

// temp_directory_path()/"<prefix><name>-<pid>", emptied, created and registered.
inline fs::path fresh(const std::string& prefix, const std::string& name) {
    fs::path d = fs::temp_directory_path() / (prefix + name + "-" + std::to_string(::getpid()));
    std::error_code ec;
    fs::remove_all(d, ec);  // a test's unreadable leftovers do not stop the next run
    fs::create_directories(d);
    own(d);
    return d;
}

// fresh(prefix, "<suite>-<test>-<name>") for the running test; a parameterized suite's '/'
// ("Presets/EveryPreset") becomes '_': the folder sits straight under the temporary folder.
inline fs::path fresh_for_test(const std::string& prefix, const std::string& name) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string test = std::string(info->test_suite_name()) + "-" + info->name() + "-" + name;
    std::replace(test.begin(), test.end(), '/', '_');
    return fresh(prefix, test);
}

class Cleanup : public ::testing::EmptyTestEventListener {
    void OnTestProgramEnd(const ::testing::UnitTest& unit) override {
        std::vector<fs::path> dirs;
        {
            std::lock_guard lock(mutex());
            dirs.swap(made());
        }
        const fs::path tmp = fs::temp_directory_path();
        for (const auto& d : dirs) {
            // Only a folder straight under the temporary folder, never through a link.
            std::error_code ec;
            if (d.parent_path() != tmp || fs::is_symlink(d, ec)) continue;
            if (unit.Passed()) fs::remove_all(d, ec);
            else if (fs::exists(d, ec)) std::fprintf(stderr, "test folder kept for a look: %s\n", d.c_str());
        }
    }
};
inline const bool kCleanupInstalled = [] {
    ::testing::UnitTest::GetInstance()->listeners().Append(new Cleanup);
    return true;
}();

}  // namespace mf::testdirs
