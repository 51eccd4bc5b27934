// Block codecs from Debian's libraries: stb_dxt (libstb-dev) and libsquish for BC1-BC5, astcenc
// for ASTC LDR; BC7 is matforge's own (bc7.hpp), as no Debian package encodes it.
//
// Which BC encoder for which effort was decided by measurement (docs/texture/results.md,
// bench/texture/run.sh; 1K albedo and packed ORM photographs of the corpus, one thread):
// libsquish's cluster fit takes 1.4-3.0 s a map on real photographs (0.2 s on smooth noise)
// for 0.5-0.7 dB over stb_dxt's two-refinement mode, which takes 0.03 s; NVIDIA Texture Tools
// 2.0.8 (libnvtt, in process) takes 0.03 s at its fastest setting for stb's error (within
// 0.1 dB either way) and 0.5-1.1 s at its default for 1.5-4 dB more error, and it carries its
// own copy of squish whose symbols collide with libsquish's in one process. So BC1 colour (and
// BC3's colour half) is stb_dxt at `fast` (one refinement) and `normal` (two), squish's cluster
// fit at `thorough` (its iterative fit gains under 0.01 dB for 1.1-1.5x the time). BC4, BC5 and
// BC3's alpha stay with squish at every effort: its fit tries both of the format's interpolation
// modes (0.05-0.3 s a 1K map, 2.6-16 dB above nvcompress's BC4), where stb_dxt's tries one.
//
// libsquish over libnvtt 2.0.8 for the rest: squish compresses one 4x4 block at a time with no
// global state (so levels and blocks can be spread over threads, and the mip chain is ours,
// filtered in linear light). nvtt 2.0.8 wants to build the mip chain itself, writes only the
// DX9 DDS header (no DX10 header, so no sRGB formats) and exposes no decoder.
//
// The BC blocks are decoded here, not by squish: squish 1.15 expands 5/6-bit endpoints by bit
// replication ((r << 3) | (r >> 2): 231 for r = 28, where the D3D and Khronos specs' r / 31 is
// 230.3) and truncates the interpolants ((2 c0 + c1) / 3), so its decoded-back error is not
// what a GPU or another reader shows (OpenImageIO 2.4 reads our DDS files up to 2 dB away from
// squish's figure). decode_color / decode_alpha follow the specs: endpoints rounded to the
// nearest 8-bit code, interpolants rounded, in the integer form of bcdec (which OpenImageIO 2.4
// uses, so the recorded error is the one that reader sees, to the sample).
#include <astcenc.h>
#include <squish.h>
#include <stb_dxt.h>
#include <zstd.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <memory>

#include "base/parallel.hpp"
#include "texture/bc7.hpp"
#include "texture/texture.hpp"

namespace mf::texture {
namespace {

bool is_astc(const BlockFormatInfo& f) { return f.name.substr(0, 4) == "astc"; }

// BC7 is matforge's own encoder (bc7.hpp): Debian packages none.
bc7::Options bc7_options(const CodecOptions& opt, const Image8& level) {
    bc7::Options o;
    o.level = opt.effort == Effort::fast ? 0 : opt.effort == Effort::normal ? 1 : 2;
    o.alpha_data = level.channels == 4;
    return o;
}

// The colour encoder of BC1 and BC3 at an effort (see the top of this file).
bool stb_colour(const BlockFormatInfo& f, Effort effort) {
    return (f.name == "bc1" || f.name == "bc3") && effort != Effort::thorough;
}

int squish_flags(const BlockFormatInfo& f, Effort effort) {
    const int flags = f.name == "bc1"   ? squish::kDxt1
                      : f.name == "bc3" ? squish::kDxt5
                      : f.name == "bc4" ? squish::kBc4
                                        : squish::kBc5;
    // Where stb_dxt writes the colour, squish's cheapest colour fit fills what it overwrites.
    return flags | (stb_colour(f, effort) ? squish::kColourRangeFit : squish::kColourClusterFit);
}

// The 16 texels of block (bx, by) as RGBA codes; texels past the edge repeat the last row or
// column (they are masked out of the fit, the values only fill the array).
void gather_block(const Image8& img, int bx, int by, bool normal_xy, std::array<uint8_t, 64>& rgba, int& mask) {
    mask = 0;
    const auto c = static_cast<size_t>(img.channels);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            const int px = bx * 4 + x, py = by * 4 + y;
            if (px < img.width && py < img.height) mask |= 1 << (y * 4 + x);
            const uint8_t* s = &img.pixels[img.index(std::min(px, img.width - 1), std::min(py, img.height - 1))];
            uint8_t* d = &rgba[static_cast<size_t>(y * 4 + x) * 4];
            if (c == 1) {
                d[0] = d[1] = d[2] = s[0];
                d[3] = 255;
            } else if (c == 2 || normal_xy) {
                d[0] = s[0], d[1] = s[1], d[2] = 0, d[3] = 255;
            } else {
                d[0] = s[0], d[1] = s[1], d[2] = s[2];
                d[3] = c == 4 ? s[3] : 255;
            }
        }
}

// stb_dxt tests a block for one colour on whole RGBA texels: alpha (BC3 encodes it apart) must
// not split one colour into several.
void rgba_opaque(std::array<uint8_t, 64>& rgba) {
    for (size_t t = 0; t < 16; ++t) rgba[t * 4 + 3] = 255;
}

struct AstcContext {
    astcenc_context* ctx = nullptr;
    ~AstcContext() {
        if (ctx) astcenc_context_free(ctx);
    }
    AstcContext() = default;
    AstcContext(const AstcContext&) = delete;
    AstcContext& operator=(const AstcContext&) = delete;
};

bool astc_context(const CodecOptions& opt, bool decompress_only, int threads, AstcContext& out, std::string& error) {
    const float quality = opt.effort == Effort::fast     ? ASTCENC_PRE_FAST
                          : opt.effort == Effort::normal ? ASTCENC_PRE_MEDIUM
                                                         : ASTCENC_PRE_THOROUGH;
    unsigned flags = decompress_only ? ASTCENC_FLG_DECOMPRESS_ONLY : 0u;
    if (opt.mask) flags |= ASTCENC_FLG_MAP_MASK;
    astcenc_config config{};
    auto status = astcenc_config_init(opt.srgb ? ASTCENC_PRF_LDR_SRGB : ASTCENC_PRF_LDR,
                                      static_cast<unsigned>(opt.format->block_width),
                                      static_cast<unsigned>(opt.format->block_height), 1, quality, flags, &config);
    if (status == ASTCENC_SUCCESS) status = astcenc_context_alloc(&config, static_cast<unsigned>(threads), &out.ctx);
    if (status != ASTCENC_SUCCESS) {
        error = std::string("astcenc: ") + astcenc_get_error_string(status);
        return false;
    }
    return true;
}

// A BC1 colour block (8 bytes) to 16 RGBA texels. `four_colors`: BC3's colour half, which has
// no 3-colour + transparent mode.
void decode_color(const uint8_t* in, bool four_colors, std::array<uint8_t, 64>& out) {
    const auto c0 = static_cast<unsigned>(in[0] | in[1] << 8), c1 = static_cast<unsigned>(in[2] | in[3] << 8);
    std::array<std::array<unsigned, 4>, 4> color{};
    auto expand = [](unsigned c, std::array<unsigned, 4>& rgba) {
        rgba[0] = (((c >> 11) & 31u) * 527u + 23u) >> 6;  // round(r * 255 / 31)
        rgba[1] = (((c >> 5) & 63u) * 259u + 33u) >> 6;   // round(g * 255 / 63)
        rgba[2] = ((c & 31u) * 527u + 23u) >> 6;
        rgba[3] = 255;
    };
    expand(c0, color[0]);
    expand(c1, color[1]);
    const bool four = four_colors || c0 > c1;
    for (size_t k = 0; k < 3; ++k) {
        if (four) {
            color[2][k] = (2 * color[0][k] + color[1][k] + 1) / 3;
            color[3][k] = (color[0][k] + 2 * color[1][k] + 1) / 3;
        } else {
            color[2][k] = (color[0][k] + color[1][k] + 1) / 2;
            color[3][k] = 0;
        }
    }
    color[2][3] = 255;
    color[3][3] = four ? 255 : 0;
    const auto indices = static_cast<uint32_t>(in[4]) | static_cast<uint32_t>(in[5]) << 8 |
                         static_cast<uint32_t>(in[6]) << 16 | static_cast<uint32_t>(in[7]) << 24;
    for (size_t t = 0; t < 16; ++t) {
        const auto& c = color[(indices >> (2 * t)) & 3u];
        for (size_t k = 0; k < 4; ++k) out[t * 4 + k] = static_cast<uint8_t>(c[k]);
    }
}

// A BC3 alpha / BC4 channel block (8 bytes) to 16 values.
void decode_alpha(const uint8_t* in, std::array<uint8_t, 16>& out) {
    std::array<unsigned, 8> v{in[0], in[1]};
    if (v[0] > v[1]) {
        for (unsigned i = 1; i < 7; ++i) v[i + 1] = ((7 - i) * v[0] + i * v[1] + 1) / 7;
    } else {
        for (unsigned i = 1; i < 5; ++i) v[i + 1] = ((5 - i) * v[0] + i * v[1] + 1) / 5;
        v[6] = 0;
        v[7] = 255;
    }
    uint64_t indices = 0;
    for (size_t i = 0; i < 6; ++i) indices |= static_cast<uint64_t>(in[2 + i]) << (8 * i);
    for (size_t t = 0; t < 16; ++t) out[t] = static_cast<uint8_t>(v[(indices >> (3 * t)) & 7u]);
}

Image8 to_rgba(const Image8& img) {
    if (img.channels == 4) return img;
    Image8 out(img.width, img.height, 4);
    const size_t n = static_cast<size_t>(img.width) * static_cast<size_t>(img.height);
    const auto c = static_cast<size_t>(img.channels);
    for (size_t p = 0; p < n; ++p) {
        const uint8_t* s = &img.pixels[p * c];
        uint8_t* d = &out.pixels[p * 4];
        d[0] = s[0];
        d[1] = c >= 2 ? s[1] : s[0];
        d[2] = c >= 3 ? s[2] : c == 1 ? s[0] : 0;
        d[3] = 255;
    }
    return out;
}

}  // namespace

size_t level_bytes(const BlockFormatInfo& f, int width, int height) {
    const auto bx = static_cast<size_t>((width + f.block_width - 1) / f.block_width);
    const auto by = static_cast<size_t>((height + f.block_height - 1) / f.block_height);
    return bx * by * static_cast<size_t>(f.block_bytes);
}

bool encode_level(const Image8& level, const CodecOptions& opt, std::vector<uint8_t>& blocks, std::string& error) {
    const BlockFormatInfo& f = *opt.format;
    blocks.assign(level_bytes(f, level.width, level.height), 0);
    if (is_astc(f)) {
        AstcContext ctx;
        const int threads = std::max(1, opt.threads);
        if (!astc_context(opt, false, threads, ctx, error)) return false;
        Image8 rgba = to_rgba(level);
        void* slice = rgba.pixels.data();
        astcenc_image image{static_cast<unsigned>(level.width), static_cast<unsigned>(level.height), 1, ASTCENC_TYPE_U8,
                            &slice};
        const astcenc_swizzle swz{ASTCENC_SWZ_R, ASTCENC_SWZ_G, ASTCENC_SWZ_B, ASTCENC_SWZ_A};
        // astcenc shares the image's blocks among the threads that call it with their index.
        std::vector<astcenc_error> status(static_cast<size_t>(threads), ASTCENC_SUCCESS);
        parallel_for(status.size(), threads, [&](size_t t) {
            status[t] = astcenc_compress_image(ctx.ctx, &image, &swz, blocks.data(), blocks.size(),
                                               static_cast<unsigned>(t));
        });
        for (const astcenc_error e : status)
            if (e != ASTCENC_SUCCESS) {
                error = std::string("astcenc: ") + astcenc_get_error_string(e);
                return false;
            }
        return true;
    }
    const int flags = squish_flags(f, opt.effort);
    const bool stb = stb_colour(f, opt.effort);
    const int stb_mode = opt.effort == Effort::fast ? STB_DXT_NORMAL : STB_DXT_HIGHQUAL;
    const bc7::Options bc7 = bc7_options(opt, level);
    const int bw = (level.width + 3) / 4, bh = (level.height + 3) / 4;
    // Rows of blocks are independent: any number of threads writes the same bytes.
    parallel_for(static_cast<size_t>(bh), std::max(1, opt.threads), [&](size_t row) {
        const int by = static_cast<int>(row);
        std::array<uint8_t, 64> rgba{};
        for (int bx = 0; bx < bw; ++bx) {
            int mask = 0;
            gather_block(level, bx, by, opt.normal_xy, rgba, mask);
            uint8_t* out = &blocks[(static_cast<size_t>(by) * static_cast<size_t>(bw) + static_cast<size_t>(bx)) *
                                   static_cast<size_t>(f.block_bytes)];
            if (f.name == "bc7") {
                bc7::encode_block(rgba.data(), bc7, out);
                continue;
            }
            if (stb && f.name == "bc1") {
                // Texels past the edge repeat the edge (gather_block): they cost the fit nothing.
                rgba_opaque(rgba);
                stb_compress_dxt_block(out, rgba.data(), 0, stb_mode);
                continue;
            }
            squish::CompressMasked(rgba.data(), mask, out, flags);
            if (stb) {  // BC3: squish's alpha half, stb_dxt's colour half (always 4-colour there)
                rgba_opaque(rgba);
                stb_compress_dxt_block(out + 8, rgba.data(), 0, stb_mode);
            }
        }
    });
    return true;
}

bool decode_level(std::span<const uint8_t> blocks, int width, int height, const CodecOptions& opt, Image8& rgba,
                  std::string& error) {
    const BlockFormatInfo& f = *opt.format;
    if (blocks.size() < level_bytes(f, width, height)) {
        error = "level of " + std::to_string(width) + "x" + std::to_string(height) + " " + std::string(f.name) +
                " has " + std::to_string(blocks.size()) + " bytes, needs " +
                std::to_string(level_bytes(f, width, height));
        return false;
    }
    rgba = Image8(width, height, 4);
    if (is_astc(f)) {
        AstcContext ctx;
        if (!astc_context(opt, true, 1, ctx, error)) return false;
        void* slice = rgba.pixels.data();
        astcenc_image image{static_cast<unsigned>(width), static_cast<unsigned>(height), 1, ASTCENC_TYPE_U8, &slice};
        const astcenc_swizzle swz{ASTCENC_SWZ_R, ASTCENC_SWZ_G, ASTCENC_SWZ_B, ASTCENC_SWZ_A};
        const auto status = astcenc_decompress_image(ctx.ctx, blocks.data(), blocks.size(), &image, &swz, 0);
        if (status != ASTCENC_SUCCESS) {
            error = std::string("astcenc: ") + astcenc_get_error_string(status);
            return false;
        }
        return true;
    }
    const int bw = (width + 3) / 4, bh = (height + 3) / 4;
    std::array<uint8_t, 64> texels{};
    std::array<uint8_t, 16> values{};
    for (int by = 0; by < bh; ++by)
        for (int bx = 0; bx < bw; ++bx) {
            const uint8_t* in = &blocks[(static_cast<size_t>(by) * static_cast<size_t>(bw) + static_cast<size_t>(bx)) *
                                        static_cast<size_t>(f.block_bytes)];
            if (f.name == "bc7") {
                bc7::decode_block(in, texels.data());
            } else if (f.name == "bc4" || f.name == "bc5") {
                // One channel block per 8 bytes: R, then G for BC5.
                for (size_t half = 0; half < (f.name == "bc5" ? 2u : 1u); ++half) {
                    decode_alpha(in + 8 * half, values);
                    for (size_t t = 0; t < 16; ++t) texels[t * 4 + half] = values[t];
                }
            } else if (f.name == "bc3") {
                decode_color(in + 8, true, texels);
                decode_alpha(in, values);
                for (size_t t = 0; t < 16; ++t) texels[t * 4 + 3] = values[t];
            } else {
                decode_color(in, false, texels);
            }
            for (int y = 0; y < 4; ++y)
                for (int x = 0; x < 4; ++x) {
                    const int px = bx * 4 + x, py = by * 4 + y;
                    if (px >= width || py >= height) continue;
                    const uint8_t* s = &texels[static_cast<size_t>(y * 4 + x) * 4];
                    uint8_t* d = &rgba.pixels[rgba.index(px, py)];
                    std::memcpy(d, s, 4);
                    // A GPU returns (r, 0, 0, 1) for BC4 and (r, g, 0, 1) for BC5.
                    if (f.name == "bc4") d[1] = d[2] = 0, d[3] = 255;
                    if (f.name == "bc5") d[2] = 0, d[3] = 255;
                }
        }
    return true;
}

std::string encoder_versions() {
    // stb_dxt, libsquish and astcenc report no version at run time: the package versions CMake found.
    return std::string("stb_dxt ") + MATFORGE_STB_VERSION + ", squish " + MATFORGE_SQUISH_VERSION + ", astcenc " +
           MATFORGE_ASTCENC_VERSION + ", zstd " + ZSTD_versionString() + ", bc7 " +
           std::to_string(bc7::kEncoderVersion);
}

}  // namespace mf::texture
