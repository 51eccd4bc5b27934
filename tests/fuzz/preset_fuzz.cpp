// Preset parser: any bytes as a preset file. A refusal must say why; an accepted preset must
// give output paths that stay inside the output folder.
#include <cstddef>
#include <cstdint>
#include <filesystem>

#include "core/json.hpp"
#include "preset/preset.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    // As load_preset reads a file: depth-limited (core/json.hpp).
    std::string error;
    const auto j = mf::parse_json(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.json", error);
    if (!j) return 0;
    mf::Preset p;
    if (!mf::parse_preset(*j, p, error)) {
        if (error.empty()) __builtin_trap();
        return 0;
    }
    (void)p.source_json.dump();  // `presets show` prints it: a deep document must not overflow the stack
    for (const auto& o : p.outputs) {
        if (o.channel_count() < 1 || o.channel_count() > 4) __builtin_trap();
        (void)o.roles();
        const std::filesystem::path rel = std::filesystem::path(p.output_path("Material_1", o)).lexically_normal();
        if (rel.is_absolute() || (!rel.empty() && *rel.begin() == "..")) __builtin_trap();
    }
    return 0;
}
