// Scene file parser (preview --scene): any bytes as a scene file. Malformed input (deep nesting
// included) must be an error naming the key (exit 2 for the user), never an exception or a crash.
#include <cstddef>
#include <cstdint>

#include "core/json.hpp"
#include "preview/preview.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::string error;
    const auto j = mf::parse_json(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.json", error);
    if (!j) return 0;
    (void)mf::preview::parse_scene(*j, "/nonexistent-fuzz-dir", "fuzz.json", error);
    return 0;
}
