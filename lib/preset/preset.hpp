// Presets: what a target engine wants (presets/*.json; fields documented in presets/README.md).
#pragma once
#include <array>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "base/vocabulary.hpp"
#include "findings/findings.hpp"
#include "material/channel.hpp"
#include "material/roles.hpp"

namespace mf {

struct BlockFormatInfo;  // preset/texture_fields.hpp

// What one channel (or the RGB triple) of an output holds, as the preset asks for it.
struct ChannelSpec : Channel {
    bool optional = false;  // dropped when its role has no map (key must be the last one)
};

struct OutputSpec {
    std::string suffix;
    bool srgb = false;                  // color channels sRGB-encoded
    int bit_depth = 8;                  // 8 | 16 (png, tif); 16 = half, 32 = float (exr)
    bool always = true;                 // false: written only when one of its roles has a map
    std::vector<ChannelSpec> channels;  // in file channel order (RGB counts as three)
    // Block-compressed containers (format dds | ktx2; lib/preset/texture_fields.cpp checks them).
    const BlockFormatInfo* block_format = nullptr;          // bc1, bc3, bc4, bc5, astc-6x6, ...
    const BlockFormatInfo* block_format_alpha = nullptr;    // used instead when the written output has 4 channels
    std::optional<Effort> effort;                           // per output; nullopt = the preset's
    std::optional<double> min_psnr_db, max_mean_angle_deg;  // error bounds of the decoded levels
    int channel_count() const;
    std::vector<Role> roles() const;  // the roles it reads (roughness for smoothness)
};

// zstd's level for KTX2 supercompression when a preset names none (and in the shipped presets).
// Measured (docs/performance.md, "The GPU presets against gltf"): level 19 runs at 2-4 MB/s on
// BC data and was half of a vulkan-ktx2 ingest; level 9 runs at 25-30 MB/s for 3.9 % more bytes
// on the corpus's photographs (7.7 % on generated sets); levels 10-16 gain under 0.5 %.
inline constexpr int kDefaultZstdLevel = 9;

struct Preset {
    std::string name, description, engine_convention;
    std::vector<std::string> sources;
    NormalConvention normal_convention = NormalConvention::gl;
    FileFormat format = FileFormat::png;
    int max_size = 0;  // 0 = no limit; larger maps are downsampled (a list's largest tier)
    // "max_size": [512, 1024, 2048]: resolution tiers, ascending (empty for a number). `ingest`
    // runs one preset per tier (with_max_size), each into <out>/<tier>; validate judges the largest.
    std::vector<int> tiers;
    int constant_size = 2;  // size of an output made only of constants
    std::string file_pattern = "{material}/{material}_{suffix}.{ext}";
    std::array<float, 3> default_albedo{0.5f, 0.5f, 0.5f};
    std::map<Role, float> defaults;             // scalar roles
    std::map<Role, Severity> missing_severity;  // roles whose absence is reported
    std::vector<OutputSpec> outputs;
    // Block-compressed containers and material files (lib/preset/texture_fields.cpp).
    bool mips = false;  // full mip chains (dds, ktx2)
    MipFilter mip_filter = MipFilter::kaiser;
    Effort effort = Effort::normal;
    Supercompression supercompression = Supercompression::none;  // ktx2 only
    int zstd_level = kDefaultZstdLevel;
    bool toksvig = false;       // roughness mips widened by the normal mips' spread
    float alpha_cutoff = 0.5f;  // alpha test of opacity (coverage kept per mip; glTF alphaCutoff)
    MaterialFileKind material_file = MaterialFileKind::none;  // the engine's material files (lib/engine)
    nlohmann::json validate = nlohmann::json::object();       // rule overrides for validate
    nlohmann::json source_json;                               // as loaded

    float default_value(Role r) const;
    std::string output_path(const std::string& material, const OutputSpec& o) const;
};

// Parses a preset document; false + `error` naming the field on any problem.
bool parse_preset(const nlohmann::json& j, Preset& p, std::string& error);

// `name_or_path`: a shipped preset's name (embedded in the binary) or a JSON file path.
std::optional<Preset> load_preset(const std::string& name_or_path, std::string& error);

// Resolution tiers (ingest --tiers 512,1024, a preset's "max_size": [512, 1024]): each a side in
// 1..kMaxTier pixels, no two equal. Returned ascending; nullopt + `error` saying which entry is
// wrong and why. parse_tiers reads the option's text ("512,1024,2048"); check_tiers judges the
// numbers, `what` naming the list in the error ("--tiers", "max_size").
inline constexpr int kMaxTier = 65536;
std::optional<std::vector<int>> parse_tiers(const std::string& list, std::string& error);
std::optional<std::vector<int>> check_tiers(const std::vector<long long>& tiers, const std::string& what,
                                            std::string& error);

// The preset of one tier: `p` with `max_size` = `tier` and no tiers, its source_json saying so
// (the action key is then that of a preset file of this max_size: ingest --tiers writes each tier
// what that file writes alone).
Preset with_max_size(const Preset& p, int tier);

// Names of the shipped presets, sorted.
std::vector<std::string> shipped_presets();
// The shipped presets a word people type for an engine, tool or format means ("unity":
// unity-urp and unity-hdrp; "ue5": unreal; "blender", "three": gltf; "astc", "mobile":
// vulkan-ktx2-astc), empty for any other: an unknown preset's error suggests by meaning.
std::vector<std::string> presets_meant_by(const std::string& word);
std::optional<std::string> shipped_preset_text(const std::string& name);

}  // namespace mf
