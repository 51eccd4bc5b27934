// Material textures: 4-channel upload formats and mip chains averaged per role.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <type_traits>

#include "base/srgb.hpp"  // header-only, standard library only
#include "render/internal.hpp"

namespace mf::render::detail {

// The sRGB curves are mf::srgb_to_linear / mf::linear_to_srgb (exact IEC 61966-2-1, in double
// here). Negatives are mirrored (−f(−x)): for −0.04045 ≤ x < 0 that is the linear segment
// continued, x / 12.92. The encoder here only ever sees [0, 1] (clamped first); the decoder sees
// negatives only in a float texture tagged sRGB. NaN passes through, but none arrives: to_rgba()
// turns non-finite float texels into 0.

uint16_t float_to_half(float f) {
    uint32_t x;
    std::memcpy(&x, &f, 4);
    const uint32_t sign = (x >> 16) & 0x8000u;
    const int32_t exp = static_cast<int32_t>((x >> 23) & 0xff) - 127 + 15;
    uint32_t mant = x & 0x7fffffu;
    if (((x >> 23) & 0xff) == 0xff) return static_cast<uint16_t>(sign | 0x7c00u | (mant ? 0x200u : 0u));
    if (exp >= 31) return static_cast<uint16_t>(sign | 0x7c00u);  // overflow → infinity
    if (exp <= 0) {
        if (exp < -10) return static_cast<uint16_t>(sign);
        mant |= 0x800000u;
        const auto shift = static_cast<uint32_t>(14 - exp);
        uint32_t h = mant >> shift;
        const uint32_t rem = mant & ((1u << shift) - 1u), halfway = 1u << (shift - 1);
        if (rem > halfway || (rem == halfway && (h & 1u))) ++h;
        return static_cast<uint16_t>(sign | h);
    }
    uint32_t h = (static_cast<uint32_t>(exp) << 10) | (mant >> 13);
    const uint32_t rem = mant & 0x1fffu;
    if (rem > 0x1000u || (rem == 0x1000u && (h & 1u))) ++h;  // round to nearest even
    return static_cast<uint16_t>(sign | h);
}

namespace {

struct FloatLevel {
    uint32_t width = 0, height = 0;
    std::vector<float> rgba;
};

// Gray → (g, g, g, 1); gray+alpha → (g, g, g, a); RGB → (r, g, b, 1). Integer samples to [0,1].
FloatLevel to_rgba(const Texture& t) {
    FloatLevel out{t.width, t.height, std::vector<float>(size_t{t.width} * t.height * 4)};
    const size_t n = size_t{t.width} * t.height;
    auto sample = [&](size_t i) -> float {
        switch (t.type) {
            case TexelType::u8: return t.data[i] / 255.f;
            case TexelType::u16: {
                uint16_t v;
                std::memcpy(&v, t.data.data() + 2 * i, 2);
                return v / 65535.f;
            }
            case TexelType::f32: {
                float v;
                std::memcpy(&v, t.data.data() + 4 * i, 4);
                return std::isfinite(v) ? v : 0.f;  // NaN/Inf texels would poison every mip above
            }
        }
        return 0.f;
    };
    const uint32_t c = t.channels;
    for (size_t p = 0; p < n; ++p) {
        float* o = &out.rgba[4 * p];
        const size_t s = p * c;
        if (c <= 2) {
            o[0] = o[1] = o[2] = sample(s);
            o[3] = c == 2 ? sample(s + 1) : 1.f;
        } else {
            o[0] = sample(s);
            o[1] = sample(s + 1);
            o[2] = sample(s + 2);
            o[3] = c == 4 ? sample(s + 3) : 1.f;
        }
    }
    return out;
}

// Area weights of source texels under destination texel `i` when `src` texels shrink to
// `dst` (a box filter exact for odd sizes too).
struct Tap {
    uint32_t index;
    float weight;
};
std::vector<std::vector<Tap>> box_taps(uint32_t src, uint32_t dst) {
    std::vector<std::vector<Tap>> taps(dst);
    const double scale = static_cast<double>(src) / dst;
    for (uint32_t i = 0; i < dst; ++i) {
        const double a = i * scale, b = (i + 1) * scale;
        for (auto s = static_cast<uint32_t>(std::floor(a)); s < src && s < b; ++s) {
            const double w = (std::min<double>(s + 1, b) - std::max<double>(s, a)) / scale;
            if (w > 0) taps[i].push_back({s, static_cast<float>(w)});
        }
    }
    return taps;
}

FloatLevel downsample(const FloatLevel& src) {
    FloatLevel dst{std::max(1u, src.width / 2), std::max(1u, src.height / 2), {}};
    dst.rgba.assign(size_t{dst.width} * dst.height * 4, 0.f);
    const auto tx = box_taps(src.width, dst.width), ty = box_taps(src.height, dst.height);
    for (uint32_t y = 0; y < dst.height; ++y)
        for (uint32_t x = 0; x < dst.width; ++x) {
            float* o = &dst.rgba[(size_t{y} * dst.width + x) * 4];
            for (const Tap& ry : ty[y])
                for (const Tap& rx : tx[x]) {
                    const float* s = &src.rgba[(size_t{ry.index} * src.width + rx.index) * 4];
                    const float w = ry.weight * rx.weight;
                    for (int c = 0; c < 4; ++c) o[c] += w * s[c];
                }
        }
    return dst;
}

// Level 0 into the averaging domain: linear light for color, vectors in [−1,1] for normals.
// 8-bit sRGB decodes through a table of the 256 codes (a pow per texel costs ~40 ns).
void to_domain(FloatLevel& l, MipKind kind, bool srgb, bool eight_bit) {
    static const std::array<float, 256> decode = [] {
        std::array<float, 256> t{};
        for (int i = 0; i < 256; ++i) t[size_t(i)] = static_cast<float>(mf::srgb_to_linear(i / 255.0));
        return t;
    }();
    const size_t n = size_t{l.width} * l.height;
    for (size_t p = 0; p < n; ++p) {
        float* c = &l.rgba[4 * p];
        for (int i = 0; i < 3; ++i) {
            if (kind == MipKind::color && srgb)
                c[i] = eight_bit ? decode[static_cast<size_t>(std::lround(c[i] * 255.f))]
                                 : static_cast<float>(mf::srgb_to_linear(double{c[i]}));
            if (kind == MipKind::normal) c[i] = c[i] * 2.f - 1.f;
        }
    }
}

// A normal map's mips hold unit vectors: the average of unit vectors is shorter than 1 (the
// shorter, the more the normals disagree) and is renormalized.
void renormalize(FloatLevel& l) {
    const size_t n = size_t{l.width} * l.height;
    for (size_t p = 0; p < n; ++p) {
        float* c = &l.rgba[4 * p];
        const float len = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        if (len > 1e-6f) {
            for (int i = 0; i < 3; ++i) c[i] /= len;
        } else {
            c[0] = c[1] = 0.f;
            c[2] = 1.f;
        }
    }
}

// Back from the averaging domain to stored values (sRGB-encoded where the format decodes).
float from_domain(float v, int channel, MipKind kind, bool encode_srgb) {
    if (channel < 3) {
        if (kind == MipKind::normal) return v * 0.5f + 0.5f;
        if (kind == MipKind::color && encode_srgb)
            return static_cast<float>(mf::linear_to_srgb(double{std::clamp(v, 0.f, 1.f)}));
    }
    return v;
}

enum class Storage { U8, U16, F16, F32 };

void store(const FloatLevel& l, Storage s, MipKind kind, bool encode_srgb, TextureLevel& out) {
    out.width = l.width;
    out.height = l.height;
    const size_t n = size_t{l.width} * l.height * 4;
    const size_t bytes = s == Storage::U8 ? 1 : s == Storage::F32 ? 4 : 2;
    out.bytes.resize(n * bytes);
    for (size_t i = 0; i < n; ++i) {
        const float v = from_domain(l.rgba[i], static_cast<int>(i % 4), kind, encode_srgb);
        switch (s) {
            case Storage::U8: {
                // lround, not (x + 0.5) truncated: the float sum rounds 0.49999997 up to 1
                out.bytes[i] = static_cast<uint8_t>(std::lround(std::clamp(v, 0.f, 1.f) * 255.f));
                break;
            }
            case Storage::U16: {
                const auto q = static_cast<uint16_t>(std::lround(std::clamp(v, 0.f, 1.f) * 65535.f));
                std::memcpy(out.bytes.data() + 2 * i, &q, 2);
                break;
            }
            case Storage::F16: {
                const uint16_t h = float_to_half(v);
                std::memcpy(out.bytes.data() + 2 * i, &h, 2);
                break;
            }
            case Storage::F32: std::memcpy(out.bytes.data() + 4 * i, &v, 4); break;
        }
    }
}

}  // namespace

const BlockFormatDesc* block_format_desc(uint32_t vk_format) {
    static constexpr BlockFormatDesc kFormats[] = {
        {VK_FORMAT_BC1_RGB_UNORM_BLOCK, VK_FORMAT_BC1_RGB_SRGB_BLOCK, 4, 4, 8},
        {VK_FORMAT_BC1_RGBA_UNORM_BLOCK, VK_FORMAT_BC1_RGBA_SRGB_BLOCK, 4, 4, 8},
        {VK_FORMAT_BC3_UNORM_BLOCK, VK_FORMAT_BC3_SRGB_BLOCK, 4, 4, 16},
        {VK_FORMAT_BC4_UNORM_BLOCK, VK_FORMAT_UNDEFINED, 4, 4, 8},
        {VK_FORMAT_BC5_UNORM_BLOCK, VK_FORMAT_UNDEFINED, 4, 4, 16},
        {VK_FORMAT_BC7_UNORM_BLOCK, VK_FORMAT_BC7_SRGB_BLOCK, 4, 4, 16},
        {VK_FORMAT_ASTC_4x4_UNORM_BLOCK, VK_FORMAT_ASTC_4x4_SRGB_BLOCK, 4, 4, 16},
        {VK_FORMAT_ASTC_5x5_UNORM_BLOCK, VK_FORMAT_ASTC_5x5_SRGB_BLOCK, 5, 5, 16},
        {VK_FORMAT_ASTC_6x6_UNORM_BLOCK, VK_FORMAT_ASTC_6x6_SRGB_BLOCK, 6, 6, 16},
        {VK_FORMAT_ASTC_8x8_UNORM_BLOCK, VK_FORMAT_ASTC_8x8_SRGB_BLOCK, 8, 8, 16},
        {VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R8G8B8A8_SRGB, 1, 1, 4},  // kDecodedLevels
    };
    static_assert(kDecodedLevels == static_cast<uint32_t>(VK_FORMAT_R8G8B8A8_UNORM));
    for (const BlockFormatDesc& f : kFormats)
        if (static_cast<uint32_t>(f.unorm) == vk_format ||
            (f.srgb != VK_FORMAT_UNDEFINED && static_cast<uint32_t>(f.srgb) == vk_format))
            return &f;
    return nullptr;
}

namespace {

// A block-compressed texture goes up as written: its own mip chain, no averaging here.
PreparedTexture prepare_blocks(const Device& d, const Texture& t, MipKind kind) {
    const BlockFormatDesc* f = block_format_desc(t.block_format);
    if (!f) throw Error("texture block format " + std::to_string(t.block_format) + " is not one the preview reads");
    PreparedTexture out;
    out.format = t.srgb && kind == MipKind::color && f->srgb != VK_FORMAT_UNDEFINED ? f->srgb : f->unorm;
    if (!d.supports(out.format, kSampledTextureFeatures))
        throw Error("this device does not sample block format " + std::to_string(t.block_format) +
                    " (decode it on the CPU: render::samples says which it does)");
    if (t.width == 0 || t.height == 0 || t.block_levels.empty()) throw Error("block-compressed texture without levels");
    uint32_t w = t.width, h = t.height;
    for (size_t i = 0; i < t.block_levels.size(); ++i) {
        const size_t expected = size_t{(w + f->block_width - 1) / f->block_width} *
                                ((h + f->block_height - 1) / f->block_height) * f->block_bytes;
        if (t.block_levels[i].size() != expected)
            throw Error("block-compressed level " + std::to_string(i) + " (" + std::to_string(w) + "x" +
                        std::to_string(h) + ") holds " + std::to_string(t.block_levels[i].size()) + " bytes, not " +
                        std::to_string(expected));
        out.levels.push_back({w, h, t.block_levels[i]});
        if (w == 1 && h == 1) break;
        w = std::max(1u, w / 2);
        h = std::max(1u, h / 2);
    }
    fit_to_device(d, out, "texture");
    return out;
}

}  // namespace

namespace {

// Level 0 of an 8-bit texture in its upload format, without the float chain: each code's stored
// value (per channel: color channels and alpha differ) is computed once through the CPU path's
// own steps (to_domain, store) and the texels are looked up, so the bytes are the ones the CPU
// path stores for level 0. Missing channels are filled as to_rgba does (gray to RGB, alpha 1).
// T: the stored sample (uint8_t, uint16_t, or a float's bits as uint32_t).
template <class T>
void expand_codes(const Texture& t, const std::vector<uint8_t>& table_bytes, std::vector<uint8_t>& out) {
    std::vector<T> table(table_bytes.size() / sizeof(T));  // 256 texels × 4 channels
    std::memcpy(table.data(), table_bytes.data(), table_bytes.size());
    const size_t n = size_t{t.width} * t.height;
    out.resize(n * 4 * sizeof(T));
    uint8_t* o = out.data();
    const uint8_t* s = t.data.data();
    const uint32_t c = t.channels;
    if constexpr (std::is_same_v<T, uint8_t>) {
        // Every code stored as itself (8-bit colour kept sRGB, data not inverted): the texels are
        // the file's codes, alpha 255 where it has none, with no lookup per channel (the lookups
        // were 4 % of a lavapipe preview of 100 PNG materials). Same bytes as the loop below.
        bool identity = c >= 3;
        for (size_t i = 0; i < table.size() && identity; ++i) identity = size_t{table[i]} == i / 4;
        if (identity && c == 4) {
            std::memcpy(o, s, n * 4);
            return;
        }
        if (identity) {
            for (size_t p = 0; p < n; ++p, s += 3, o += 4) o[0] = s[0], o[1] = s[1], o[2] = s[2], o[3] = 255;
            return;
        }
    }
    for (size_t p = 0; p < n; ++p, s += c, o += 4 * sizeof(T)) {
        const size_t r = s[0], g = c <= 2 ? s[0] : s[1], b = c <= 2 ? s[0] : s[2];
        const size_t a = c == 2 ? s[1] : c == 4 ? s[3] : 255;  // no alpha: 1
        const T texel[4] = {table[4 * r + 0], table[4 * g + 1], table[4 * b + 2], table[4 * a + 3]};
        std::memcpy(o, texel, sizeof texel);
    }
}

}  // namespace

PreparedTexture prepare_texture(const Device& d, const Texture& t, MipKind kind, bool fast, uint32_t invert) {
    if (t.block_format != 0) return prepare_blocks(d, t, kind);
    const size_t bytes = t.type == TexelType::u8 ? 1 : t.type == TexelType::u16 ? 2 : 4;
    if (t.width == 0 || t.height == 0 || t.channels < 1 || t.channels > 4 ||
        t.data.size() != size_t{t.width} * t.height * t.channels * bytes)
        throw Error("texture data does not match its size, channels and type");

    constexpr VkFormatFeatureFlags kFilter = kSampledTextureFeatures;
    PreparedTexture out;
    Storage storage = Storage::F16;
    // 8-bit color keeps its sRGB encoding and lets the sampler decode it (before filtering, as
    // the _SRGB formats require). 16-bit and float have no sRGB formats: they are decoded here
    // and stored linear, as half floats (a relative precision of 2⁻¹¹ at every magnitude).
    bool encode_srgb = false;
    // ContextOptions::precise_cpu_textures: on lavapipe 8-bit texels go up as 16-bit linear
    // UNORM (data × 257 exactly; color decoded here with the exact curve), filtered in float. The
    // fast path (Scene::fast_textures) keeps 8-bit color as R8G8B8A8_SRGB, as on a GPU: a quarter
    // of the float's bytes to convert, upload, blit and sample, and within a code or two at preview
    // sizes (tests/render/fast_path_test.cpp); data keeps its promotion (8-bit filtering would move
    // a smooth highlight by up to 20 codes where a roughness mip is a code off).
    const bool srgb_color = t.srgb && kind == MipKind::color;
    const bool fast_u8 = fast && t.type == TexelType::u8 &&
                         std::max(t.width, t.height) <= std::max(1u, d.properties.limits.maxImageDimension2D);
    const bool color_as_read = fast_u8 && srgb_color && d.supports(VK_FORMAT_R8G8B8A8_SRGB, kFilter | kBlitMipFeatures);
    const bool promote = !color_as_read && d.precise_textures && d.supports(VK_FORMAT_R16G16B16A16_UNORM, kFilter);
    if (t.type == TexelType::u8 && !promote) {
        storage = Storage::U8;
        encode_srgb = srgb_color;
        out.format = encode_srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM;
    } else if (!srgb_color && (t.type == TexelType::u8 ||  // promoted: `promote` checked the format
                               (t.type == TexelType::u16 && d.supports(VK_FORMAT_R16G16B16A16_UNORM, kFilter)))) {
        storage = Storage::U16;
        out.format = VK_FORMAT_R16G16B16A16_UNORM;
    } else if ((t.type == TexelType::u8 || t.type == TexelType::f32) &&
               d.supports(VK_FORMAT_R32G32B32A32_SFLOAT, kFilter)) {
        // U8 here is promoted color, decoded: float keeps the darkest codes exact (16-bit UNORM
        // would round 1/255 of sRGB, 3.0e-4 linear, by half a per cent)
        storage = Storage::F32;
        out.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    } else {
        out.format = VK_FORMAT_R16G16B16A16_SFLOAT;  // filterable on every Vulkan device
    }

    // Scene::fast_textures: level 0 of an 8-bit texture in the format and bytes the float chain
    // below would store (8-bit, as on a GPU), the rest of the chain blitted by the device from it.
    if (fast_u8 && d.supports(out.format, kBlitMipFeatures)) {
        // The stored value of every code, through the CPU path's steps (a 256×1 level of codes);
        // a channel in `invert` stores code 255 − x where x is read (the exact complement).
        FloatLevel codes{256, 1, std::vector<float>(256 * 4)};
        for (size_t i = 0; i < codes.rgba.size(); ++i) {
            const size_t code = i / 4, c = i % 4;
            codes.rgba[i] = static_cast<float>((invert >> c) & 1u ? 255 - code : code) / 255.f;
        }
        to_domain(codes, kind, t.srgb, true);
        TextureLevel table;
        store(codes, storage, kind, encode_srgb, table);
        TextureLevel top{t.width, t.height, {}};
        switch (storage) {
            case Storage::U8: expand_codes<uint8_t>(t, table.bytes, top.bytes); break;
            case Storage::U16:
            case Storage::F16: expand_codes<uint16_t>(t, table.bytes, top.bytes); break;
            case Storage::F32: expand_codes<uint32_t>(t, table.bytes, top.bytes); break;
        }
        out.levels.push_back(std::move(top));
        out.inverted = invert;
        out.mips = 1;
        for (uint32_t w = t.width, h = t.height; w > 1 || h > 1; w = std::max(1u, w / 2), h = std::max(1u, h / 2))
            ++out.mips;
        return out;
    }

    FloatLevel level = to_rgba(t);
    to_domain(level, kind, t.srgb, t.type == TexelType::u8);  // level 0 itself is stored as read (no renormalization)
    // Levels larger than the device takes are computed (the chain averages from them) but not
    // stored: the texture starts at its first level that fits (fit_to_device says so).
    const uint32_t limit = std::max(1u, d.properties.limits.maxImageDimension2D);
    for (;;) {
        TextureLevel stored;
        if (std::max(level.width, level.height) > limit) {
            stored.width = level.width;
            stored.height = level.height;
        } else if (out.levels.empty() && storage == Storage::U8 && t.channels == 4 && kind != MipKind::normal) {
            // Level 0 of an 8-bit RGBA texture goes up exactly as read.
            stored.width = t.width;
            stored.height = t.height;
            stored.bytes = t.data;
        } else {
            store(level, storage, kind, encode_srgb, stored);
        }
        out.levels.push_back(std::move(stored));
        if (level.width == 1 && level.height == 1) break;
        level = downsample(level);
        if (kind == MipKind::normal) renormalize(level);
    }
    fit_to_device(d, out, "texture");
    out.mips = static_cast<uint32_t>(out.levels.size());
    return out;
}

void fit_to_device(const Device& d, PreparedTexture& t, const std::string& what) {
    const uint32_t limit = std::max(1u, d.properties.limits.maxImageDimension2D);
    if (t.levels.empty() || std::max(t.levels[0].width, t.levels[0].height) <= limit) return;
    const uint32_t w0 = t.levels[0].width, h0 = t.levels[0].height;
    if (t.levels.size() > 1) {
        size_t first = 0;
        while (first + 1 < t.levels.size() && std::max(t.levels[first].width, t.levels[first].height) > limit) ++first;
        t.levels.erase(t.levels.begin(), t.levels.begin() + static_cast<std::ptrdiff_t>(first));
    } else if (t.format == VK_FORMAT_R32G32B32A32_SFLOAT) {
        FloatLevel l{w0, h0, std::vector<float>(t.levels[0].bytes.size() / 4)};
        std::memcpy(l.rgba.data(), t.levels[0].bytes.data(), l.rgba.size() * 4);
        while (std::max(l.width, l.height) > limit) l = downsample(l);
        t.levels[0].width = l.width;
        t.levels[0].height = l.height;
        t.levels[0].bytes.resize(l.rgba.size() * 4);
        std::memcpy(t.levels[0].bytes.data(), l.rgba.data(), t.levels[0].bytes.size());
    }
    const TextureLevel& top = t.levels[0];
    if (std::max(top.width, top.height) > limit)
        throw Error(what + " of " + std::to_string(w0) + "x" + std::to_string(h0) +
                    " pixels is larger than this device's limit of " + std::to_string(limit) +
                    " pixels per side (maxImageDimension2D)");
    t.note = what + " of " + std::to_string(w0) + "x" + std::to_string(h0) +
             " pixels is larger than this device's limit of " + std::to_string(limit) +
             " pixels per side (maxImageDimension2D): previewed downsampled to " + std::to_string(top.width) + "x" +
             std::to_string(top.height);
}

}  // namespace mf::render::detail
