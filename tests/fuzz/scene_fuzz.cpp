// Scene file parser (preview --scene): any bytes as a scene file. Malformed input must be a
// UsageError (exit 2 for the user), never another exception or a crash.
#include <cstddef>
#include <cstdint>

#include "preview/preview.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const auto j = nlohmann::json::parse(data, data + size, nullptr, false);
    if (j.is_discarded()) return 0;
    try {
        (void)mf::preview::parse_scene(j, "/nonexistent-fuzz-dir", "fuzz.json");
    } catch (const mf::preview::UsageError&) {
    }
    return 0;
}
