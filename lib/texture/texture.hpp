// GPU textures: mip chains, block compression (BC1/BC3/BC4/BC5 through libsquish, ASTC through
// ARM's astcenc), the DDS and KTX2 containers, and the decoded-back error of every level.
//
// Conventions of this module (decided once here):
//  - a level is 8-bit codes (Image8), channels as the output writes them, values in the output's
//    encoding (sRGB-encoded color where the output is sRGB, normals as n * 0.5 + 0.5): the file
//    stores 8-bit samples, so the chain starts from the codes a PNG of the output would hold;
//  - filtering happens in linear light for sRGB color (decode, filter, encode), on unit vectors
//    for normals (renormalized at every level), on the values for data, and keeps the alpha-test
//    coverage of level 0 for alpha-tested opacity;
//  - a chain runs down to 1x1 (each level floor(previous / 2), at least 1);
//  - codecs come from Debian's libraries (libsquish, libastcenc); the containers are ours;
//  - errors are returned (false + text), never thrown.
#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "color/color.hpp"
#include "findings/findings.hpp"
#include "image/image.hpp"
#include "manifest/manifest.hpp"
#include "pack/pack.hpp"
#include "preset/preset.hpp"
#include "preset/texture_fields.hpp"

namespace mf::texture {

// ---------------------------------------------------------------------------------------------
// Mip chains

// How one channel of an output is filtered.
enum class ChannelKind : uint8_t {
    srgb_color,    // decoded to linear light, filtered, encoded again
    data,          // filtered as stored (linear color, scalar maps, constants)
    normal,        // three consecutive channels: a unit vector, renormalized after filtering
    alpha_tested,  // opacity of a cutout: filtered, then scaled so level 0's coverage stays
};

// The kinds of an output's written channels: sRGB color for albedo/emissive of an sRGB output,
// normal for an RGB normal, alpha_tested for an opacity channel when `cutout`, data otherwise.
std::vector<ChannelKind> channel_kinds(const std::vector<ChannelSpec>& written, bool srgb, bool cutout);

struct MipOptions {
    // box: the mean of the 2x2 (or 3-wide at odd sizes) footprint. kaiser: a Kaiser-windowed
    // sinc (half-width 3 destination texels, alpha 4, NVIDIA Texture Tools' default), sharper and
    // less aliased; both wrap at the edges (materials tile).
    MipFilter filter = MipFilter::kaiser;
    float alpha_cutoff = 0.5f;  // the alpha test whose coverage alpha_tested channels keep
    // Toksvig (2005): the roughness channel `roughness_channel` (stored as 1 - r when
    // `smoothness`) of each level is widened by the spread of the level's normals, from the
    // unnormalized filtered `normals` (unit vectors at the level-0 size, 3 channels: the normal
    // map as written, normals_from_codes).
    int roughness_channel = -1;
    bool smoothness = false;
    const Image* normals = nullptr;
};

int mip_count(int width, int height);
// Unit vectors (3 floats) from a normal map's 8-bit RGB codes (n * 0.5 + 0.5), renormalized as a
// shader does after sampling: what Toksvig's spread is measured on, the normals an engine sees.
Image normals_from_codes(const Image8& codes);
// Level 0 (as given) and every smaller level down to 1x1.
std::vector<Image8> make_mips(const Image8& level0, const std::vector<ChannelKind>& kinds, const MipOptions& options);

// Colour into the texels a renderer never shows — alpha channel `alpha_channel` below
// `shown_from` (a cut-out's alpha test: first_kept_code; 1 for a blend: alpha 0) — from the nearest shown texels,
// so that filtering (mips, an engine's bilinear lookups) and block compression never mix their
// colour (often black) into what is shown: the dark fringe at every edge of every mip. Grows
// ring by ring over the 8 neighbours, wrapping as the mips do; each texel of a ring takes the
// mean of its neighbours filled before it, in each channel's filtering domain (sRGB colour in
// linear light). Every channel but alpha is filled; alpha is left as it is, so what the alpha
// test shows is unchanged. Returns the texels filled (0: none shown, or every texel shown).
size_t dilate_under_alpha(Image8& img, const std::vector<ChannelKind>& kinds, int alpha_channel, uint8_t shown_from);

// Resamples a level to w x h in the filtering domain of its channels (Kaiser, wrapping).
Image8 resize(const Image8& level, const std::vector<ChannelKind>& kinds, int w, int h);

// The first code (0..255) an alpha test at `cutoff` keeps: code / 255 >= cutoff; 256 keeps none.
// The one comparison behind alpha_coverage, the mips' coverage scaling and dilate_under_alpha's
// shown texels.
int first_kept_code(float cutoff);

// Share of texels whose `channel` is at least `cutoff` (the alpha test's coverage).
double alpha_coverage(const Image8& img, int channel, float cutoff);

// How a material's opacity is used: opaque (every texel 1), cutout (at least 95 % of the texels
// within 0.1 of 0 or 1: foliage, fences, decals; alpha-tested), or blend (translucent).
enum class AlphaUse { opaque, cutout, blend };
AlphaUse classify_opacity(const Image& opacity);

// ---------------------------------------------------------------------------------------------
// Block codecs

struct CodecOptions {
    const BlockFormatInfo* format = nullptr;
    bool srgb = false;  // sRGB variant (color weighting in the sRGB-encoded values)
    Effort effort = Effort::normal;
    bool normal_xy = false;  // BC5 of a normal: X, Y stored, Z dropped
    bool mask = false;       // channels are independent data (ASTC's mask-map error metric)
    int threads = 1;         // encode_level's threads (block rows / astcenc's own threads): same blocks
};

// A level of codes (1 to 4 channels) to blocks. 1-channel levels go to BC1/ASTC as grey.
bool encode_level(const Image8& level, const CodecOptions& opt, std::vector<uint8_t>& blocks, std::string& error);
// Blocks back to RGBA codes as a GPU returns them before sRGB decoding (BC4: R; BC5: R, G).
bool decode_level(std::span<const uint8_t> blocks, int width, int height, const CodecOptions& opt, Image8& rgba,
                  std::string& error);
size_t level_bytes(const BlockFormatInfo& f, int width, int height);

// ---------------------------------------------------------------------------------------------
// Containers

struct Level {
    int width = 0, height = 0;
    std::vector<uint8_t> data;  // blocks, row by row
};
struct GpuTexture {
    const BlockFormatInfo* format = nullptr;
    bool srgb = false;
    bool alpha = false;         // straight alpha present (bc3 with opacity)
    std::vector<Level> levels;  // largest first
};

// DXGI_FORMAT_BC1_UNORM_SRGB, ...; VK_FORMAT_BC1_RGB_SRGB_BLOCK, ...
// The versions of the encoders behind these outputs (libsquish, astcenc, zstd; Debian's package
// versions where a library reports none), for the ingest cache's action key: an upgraded
// encoder may write other blocks, so it must miss the cache.
std::string encoder_versions();

std::string dxgi_format_name(const GpuTexture& t);
std::string vk_format_name(const GpuTexture& t);
uint32_t dxgi_format(const GpuTexture& t);
uint32_t vk_format(const GpuTexture& t);

// DDS with the DX10 header (DirectXTK's DDSTextureLoader reads it: DXGI format, full chain).
std::vector<uint8_t> write_dds(const GpuTexture& t);
bool read_dds(std::span<const uint8_t> bytes, GpuTexture& t, std::string& error);

struct Ktx2Options {
    bool zstd = false;
    int zstd_level = kDefaultZstdLevel;
    std::string writer;  // KTXwriter value
};
// KTX 2.0: header, level index, data format descriptor (BT.709 primaries; sRGB transfer for
// sRGB formats, linear otherwise), KTXwriter, levels smallest first; zstd per level.
bool write_ktx2(const GpuTexture& t, const Ktx2Options& opt, std::vector<uint8_t>& out, std::string& error);
bool read_ktx2(std::span<const uint8_t> bytes, GpuTexture& t, std::string& error);

// A DDS or KTX2 file's container, told apart by its magic bytes (not its name): read_dds or
// read_ktx2. `is_gpu_texture_name`: the extensions matforge writes them under (.dds, .ktx2).
bool read_gpu_texture(std::span<const uint8_t> bytes, GpuTexture& t, std::string& error);
bool is_gpu_texture_name(const std::filesystem::path& file);

// Level 0 of `t` decoded with the codec that wrote it, as a GPU samples it before sRGB decoding:
// the first `channels` (1..4) of the decoded RGBA codes; `rebuild_z`: the third channel is the Z a
// shader rebuilds from a BC5 normal's X and Y (sqrt(1 - x² - y²)). What `matforge report` shows of
// a block-compressed output and what the preview uploads where the device cannot sample it.
bool decode_top_level(const GpuTexture& t, int channels, bool rebuild_z, Image8& codes, std::string& error);

// ---------------------------------------------------------------------------------------------
// Errors of a decoded level against its source

// PSNR in dB over the first `channels` channels of `ref` and of `decoded` (RGBA), peak 255;
// 100 when they are identical.
double psnr(const Image8& ref, const Image8& decoded, int channels);
struct AngleError {
    double mean_deg = 0, max_deg = 0;
};
// Angles between the normals of `ref` (RGB codes) and of `decoded` (RGBA; with `xy_only` Z is
// rebuilt from X and Y as an engine does for BC5).
AngleError normal_angle_error(const Image8& ref, const Image8& decoded, bool xy_only);
// The Z of a unit normal stored as X, Y only (BC5), as a shader rebuilds it: sqrt(1 - x² - y²),
// 0 where x² + y² exceeds 1.
double z_from_xy(double x, double y);

// ---------------------------------------------------------------------------------------------
// An output of a block-container preset, from the planes to the file's bytes

struct EncodedOutput {
    std::vector<uint8_t> bytes;  // the .dds / .ktx2 file
    int width = 0, height = 0;   // level 0
    std::string block_format, gpu_format, supercompression;
    bool normal_xy = false;
    std::vector<manifest::LevelError> levels;
    std::optional<int64_t> dilated_texels;  // dilate_under_alpha's count, where the output has alpha
    std::vector<Finding> findings;          // RESIZED (top level brought to a multiple of 4), errors over the bound
};

struct EncodeContext {
    const Preset* preset = nullptr;
    const ColorContext* color = nullptr;
    std::string writer;  // KTXwriter: "matforge <version>"
    int jobs = 1;        // threads for the block encoder
};

// Packs output `o` from `planes` at `size`, makes its mip chain (preset mips), encodes every
// level in the output's block format, decodes each back and records its error, and writes the
// container. Level 0 over the output's bound (min_psnr_db, max_mean_angle_deg) is a finding
// (lower levels are recorded, not bounded: encode.cpp says why).
bool encode_output(const OutputSpec& o, const Planes& planes, Size size, const EncodeContext& ctx, EncodedOutput& out,
                   std::string& error);

}  // namespace mf::texture
