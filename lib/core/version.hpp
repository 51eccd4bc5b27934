// The one version string: the CMake project version (CMakeLists.txt), compiled in. Manifests
// and reports say "matforge <version>" as their generator; `--version` prints the same.
// And what names the build itself (build_id.cpp): two builds of one version may write other
// bytes (a developer's tree, a patched package), so the ingest cache's records name the build.
#pragma once
#include <optional>
#include <string>
#include <string_view>

#ifndef MATFORGE_VERSION
#error "MATFORGE_VERSION is defined by lib/CMakeLists.txt for matforge_core and its users"
#endif

namespace mf {
inline constexpr std::string_view kVersion = MATFORGE_VERSION;
inline constexpr std::string_view kGenerator = "matforge " MATFORGE_VERSION;

// The GNU build-id (NT_GNU_BUILD_ID, lowercase hex as `readelf -n` prints it) of the loaded ELF
// object holding `address`, read from the process's own program headers (no file is opened);
// "" when that object carries none, or no loaded object holds `address`.
std::string loaded_build_id(const void* address);

// What names the code of the loaded object holding `address`: "build-id <hex>", else (an object
// linked without one) "sha256 <hex>" of its file. nullopt + `error` when neither can be had.
std::optional<std::string> code_identity_of(const void* address, std::string& error);

// code_identity_of the object holding matforge's library code in this process: the matforge
// executable, or the Python extension that links the library. Computed once per process.
std::optional<std::string> code_identity(std::string& error);
}  // namespace mf
