// Manifest reader: any bytes as a manifest.json. Malformed input (deep nesting included) must
// be an error naming the problem, never an exception or a crash; what parses writes back to
// JSON that parses to the same manifest.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "core/json.hpp"
#include "manifest/manifest.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::string error;
    const auto j = mf::parse_json(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.json", error);
    if (!j) return 0;
    const auto m = mf::manifest::manifest_from_json(*j, error);
    if (!m) return 0;
    const auto again = mf::manifest::manifest_from_json(mf::manifest::to_json(*m), error);
    if (!again || mf::manifest::to_json(*again) != mf::manifest::to_json(*m)) std::abort();  // round trip
    return 0;
}
