// Preset parser: any bytes as a preset file. A refusal must say why; an accepted preset must
// give output paths that stay inside the output folder.
#include <cstddef>
#include <cstdint>
#include <filesystem>

#include "preset/preset.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const auto j = nlohmann::json::parse(data, data + size, nullptr, false);
    if (j.is_discarded()) return 0;
    mf::Preset p;
    std::string error;
    if (!mf::parse_preset(j, p, error)) {
        if (error.empty()) __builtin_trap();
        return 0;
    }
    for (const auto& o : p.outputs) {
        if (o.channel_count() < 1 || o.channel_count() > 4) __builtin_trap();
        (void)o.roles();
        const std::filesystem::path rel = std::filesystem::path(p.output_path("Material_1", o)).lexically_normal();
        if (rel.is_absolute() || (!rel.empty() && *rel.begin() == "..")) __builtin_trap();
    }
    return 0;
}
