// Manifest reader (preview): any bytes as a manifest.json. Malformed input must be a
// UsageError, never another exception or a crash.
#include <cstddef>
#include <cstdint>

#include "preview/preview.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const auto j = nlohmann::json::parse(data, data + size, nullptr, false);
    if (j.is_discarded()) return 0;
    try {
        (void)mf::preview::parse_manifest(j, "/nonexistent-fuzz-dir");
    } catch (const mf::preview::UsageError&) {
    }
    return 0;
}
