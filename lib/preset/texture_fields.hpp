// The preset fields of GPU textures and material files: mip chains, block formats per output,
// encoder effort, error bounds, KTX2 supercompression, and the glTF material file. Every
// combination that cannot be written (BC5 for a 3-channel color, ASTC in a DDS, an sRGB BC4,
// mips in a PNG) is refused here, naming the field, before any set is read.
#pragma once
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <string_view>

#include "preset/preset.hpp"

namespace mf {

// What a block format stores. The codecs and containers that use it live in lib/texture.
struct BlockFormatInfo {
    std::string_view name;  // as presets spell it: "bc1", "astc-6x6", ...
    int block_width, block_height, block_bytes;
    int channels;   // channels it carries (bc1: RGB, bc3: RGBA, bc4: R, bc5: RG)
    bool has_srgb;  // an sRGB variant exists (the sampler decodes before filtering)
    bool in_dds;    // DXGI has it (DirectX reads it from a DDS)
    bool hdr;       // ASTC HDR profile: float samples only
};
// nullopt-like: nullptr for an unknown name.
const BlockFormatInfo* block_format_info(std::string_view name);
// Every name presets may use, for messages ("bc1, bc3, ...").
std::string block_format_names();

// The block format an output is encoded with when it is written with `written_channels`
// channels: block_format_alpha for 4 when the preset gives one, else block_format (nullptr for
// an output of a format without blocks).
const BlockFormatInfo* block_format_for(const OutputSpec& o, int written_channels);

// Whether output `o` is a normal map: its RGB holds the normal role.
bool is_rgb_normal(const OutputSpec& o);

// Reads the fields above from preset document `j` into `p` (whose outputs are already parsed, in
// the document's order) and checks them against the format and the channel layouts. False +
// `error` naming the field.
bool parse_texture_fields(const nlohmann::json& j, Preset& p, std::string& error);

}  // namespace mf
