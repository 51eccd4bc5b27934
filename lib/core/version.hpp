// The one version string: the CMake project version (CMakeLists.txt), compiled in. Manifests
// and reports say "matforge <version>" as their generator; `--version` prints the same.
#pragma once
#include <string_view>

#ifndef MATFORGE_VERSION
#error "MATFORGE_VERSION is defined by lib/CMakeLists.txt for matforge_core and its users"
#endif

namespace mf {
inline constexpr std::string_view kVersion = MATFORGE_VERSION;
inline constexpr std::string_view kGenerator = "matforge " MATFORGE_VERSION;
}  // namespace mf
