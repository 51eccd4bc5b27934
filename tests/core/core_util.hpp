// Helpers of the core tests.
#pragma once
#include <filesystem>
#include <string>

#include "test_dirs.hpp"

namespace coretest {

// An empty folder of this process, named after the test's `name`.
inline std::filesystem::path fresh_dir(const std::string& name) { return mf::testdirs::fresh("matforge-test-", name); }

}  // namespace coretest
