// Helpers of the core tests.
#pragma once
#include <filesystem>
#include <string>

#include <unistd.h>

namespace coretest {

// An empty folder of this process, named after the test's `name`.
inline std::filesystem::path fresh_dir(const std::string& name) {
    const std::filesystem::path d = std::filesystem::temp_directory_path() /
                                    ("matforge-test-" + name + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(d);
    std::filesystem::create_directories(d);
    return d;
}

}  // namespace coretest
