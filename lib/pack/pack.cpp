#include "pack/pack.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>

namespace mf {

namespace {

// Every S-th sample from `from`: S known to the compiler (no multiply per sample; GCC then
// vectorizes the gather for 8-bit codes).
template <size_t S, class T>
void every_nth(const T* from, size_t n, T* to) {
    for (size_t i = 0; i < n; ++i) to[i] = from[i * S];
}

template <class T>
BasicImage<T> extract_channel_t(const BasicImage<T>& src, int channel) {
    BasicImage<T> out(src.width, src.height, 1);
    const int c = std::min(channel, src.channels - 1);
    const T* from = src.pixels.data() + c;
    const size_t n = out.pixels.size();
    switch (src.channels) {
        case 2: every_nth<2>(from, n, out.pixels.data()); break;
        case 3: every_nth<3>(from, n, out.pixels.data()); break;
        case 4: every_nth<4>(from, n, out.pixels.data()); break;
        default:
            for (size_t i = 0; i < n; ++i) out.pixels[i] = src.pixels[i * src.channels + c];
    }
    return out;
}

template <class T>
BasicImage<T> to_rgb_t(const BasicImage<T>& src) {
    if (src.channels == 3) return src;
    BasicImage<T> out(src.width, src.height, 3);
    const size_t n = static_cast<size_t>(src.width) * src.height;
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) out.pixels[i * 3 + c] = src.pixels[i * src.channels + (src.channels >= 3 ? c : 0)];
    return out;
}

// Normal texels in blocks of kBlock, as three arrays: the float path (decode_normal,
// encode_normal) and the codes path (pack_output8) share these loops, so both run the same float
// operations in the same order and write the same codes. The loops have no branch and a fixed
// trip count, so the compiler vectorizes them; SIMD sqrt and division round exactly as the
// scalar ones do.
constexpr size_t kBlock = 64;
struct NormalBlock {
    std::array<float, kBlock> x, y, z;
};

// A length that can divide: not ~0, not Inf, not NaN.
// Both comparisons evaluated (no short circuit): the loops below stay branch-free.
inline bool usable(float len) { return (len > 1e-6f) & (len <= std::numeric_limits<float>::max()); }

// Stored colors in [0,1] -> unit vectors, Y times ysign; zero-length or non-finite -> (0,0,1).
// channels < 3: Z rebuilt from unit length (BC5-style; one channel: Y = 0.5 too). Returns how
// many had a stored length far from 1 (|len-1| > 0.2) or Z < 0.
template <bool kStoredZ>
size_t decode_block_t(NormalBlock& b, float ysign) {
    size_t bad = 0;
    for (size_t i = 0; i < kBlock; ++i) {
        const float x = b.x[i] * 2.f - 1.f;
        const float y = b.y[i] * 2.f - 1.f;
        const float z = kStoredZ ? b.z[i] * 2.f - 1.f : std::sqrt(std::max(0.f, 1.f - x * x - y * y));
        const float len = std::sqrt(x * x + y * y + z * z);
        bad += static_cast<size_t>(!(std::abs(len - 1.f) <= 0.2f) | (z < 0.f));
        const bool ok = usable(len);
        const float d = ok ? len : 1.f;  // divide unconditionally, select after
        const float nx = x / d, ny = y / d, nz = z / d;
        b.x[i] = ok ? nx : 0.f;
        b.y[i] = (ok ? ny : 0.f) * ysign;
        b.z[i] = ok ? nz : 1.f;
    }
    return bad;
}
size_t decode_block(NormalBlock& b, int channels, float ysign) {
    return channels >= 3 ? decode_block_t<true>(b, ysign) : decode_block_t<false>(b, ysign);
}

// Unit vectors (renormalized first: resampling shortens them) -> stored colors, Y times ysign.
void encode_block(NormalBlock& b, float ysign) {
    for (size_t i = 0; i < kBlock; ++i) {
        const float x = b.x[i], y = b.y[i], z = b.z[i];
        const float len = std::sqrt(x * x + y * y + z * z);
        const bool ok = usable(len);
        const float d = ok ? len : 1.f;
        const float nx = x / d, ny = y / d, nz = z / d;
        b.x[i] = (ok ? nx : 0.f) * 0.5f + 0.5f;
        b.y[i] = (ok ? ny : 0.f) * ysign * 0.5f + 0.5f;
        b.z[i] = (ok ? nz : 1.f) * 0.5f + 0.5f;
    }
}

// Texels [i0, i0 + n) of an interleaved image into a block, the rest padded with a flat normal
// (stored (0.5, 0.5, 1): decodes to (0,0,1), never counted bad).
template <class T, class F>
void load_block(NormalBlock& b, const BasicImage<T>& img, size_t i0, size_t n, F value) {
    const auto ch = static_cast<size_t>(img.channels);
    for (size_t i = 0; i < kBlock; ++i) {
        if (i >= n) {
            b.x[i] = 0.5f, b.y[i] = 0.5f, b.z[i] = 1.f;
            continue;
        }
        const T* p = &img.pixels[(i0 + i) * ch];
        b.x[i] = value(p[0]);
        b.y[i] = ch > 1 ? value(p[1]) : 0.5f;
        b.z[i] = ch > 2 ? value(p[2]) : 1.f;
    }
}

float ysign_of(NormalConvention c) { return c == NormalConvention::dx ? -1.f : 1.f; }

}  // namespace

Image extract_channel(const Image& src, int channel) { return extract_channel_t(src, channel); }
Image8 extract_channel(const Image8& src, int channel) { return extract_channel_t(src, channel); }
Image to_rgb(const Image& src) { return to_rgb_t(src); }
Image8 to_rgb(const Image8& src) { return to_rgb_t(src); }

void invert(Image& img) {
    for (float& v : img.pixels) v = 1.f - v;
}
void invert(Image8& codes) {
    for (uint8_t& k : codes.pixels) k = static_cast<uint8_t>(255 - k);
}

double decode_normal(const Image& enc, NormalConvention from, Image& out) {
    out = Image(enc.width, enc.height, 3);
    const size_t n = static_cast<size_t>(enc.width) * enc.height;
    const float ysign = ysign_of(from);
    size_t bad = 0;
    NormalBlock b{};
    for (size_t i0 = 0; i0 < n; i0 += kBlock) {
        const size_t m = std::min(kBlock, n - i0);
        load_block(b, enc, i0, m, [](float v) { return v; });
        bad += decode_block(b, enc.channels, ysign);  // the padding (flat) is never bad
        for (size_t i = 0; i < m; ++i) {
            out.pixels[(i0 + i) * 3 + 0] = b.x[i];
            out.pixels[(i0 + i) * 3 + 1] = b.y[i];
            out.pixels[(i0 + i) * 3 + 2] = b.z[i];
        }
    }
    return n ? static_cast<double>(bad) / static_cast<double>(n) : 0.0;
}

void renormalize(Image& n) {
    for (size_t i = 0, c = static_cast<size_t>(n.width) * n.height; i < c; ++i) {
        float* v = &n.pixels[i * 3];
        const float len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        if (len > 1e-6f && std::isfinite(len)) {
            v[0] /= len, v[1] /= len, v[2] /= len;
        } else {
            v[0] = 0.f, v[1] = 0.f, v[2] = 1.f;
        }
    }
}

Image encode_normal(const Image& n, NormalConvention to) {
    Image out(n.width, n.height, 3);
    const float ysign = ysign_of(to);
    const size_t count = static_cast<size_t>(n.width) * n.height;
    NormalBlock b{};
    for (size_t i0 = 0; i0 < count; i0 += kBlock) {
        const size_t m = std::min(kBlock, count - i0);
        load_block(b, n, i0, m, [](float v) { return v; });
        encode_block(b, ysign);
        for (size_t i = 0; i < m; ++i) {
            out.pixels[(i0 + i) * 3 + 0] = b.x[i];
            out.pixels[(i0 + i) * 3 + 1] = b.y[i];
            out.pixels[(i0 + i) * 3 + 2] = b.z[i];
        }
    }
    return out;
}

Image plane_floats(Role role, const RolePlane& plane) {
    if (!plane.is_codes()) return plane.image;
    if (role != Role::normal) return to_float(plane.codes);
    Image n;
    decode_normal(to_float(plane.codes), plane.codes_convention, n);
    return n;
}

void make_floats(Role role, RolePlane& plane) {
    if (!plane.is_codes()) return;
    plane.image = plane_floats(role, plane);
    plane.codes = Image8{};
}

namespace {

// Lanczos-3 taps of one axis, as OpenImageIO's resize places them (the filter is 6 destination
// pixels wide when shrinking, 6 source pixels when enlarging; source indices clamped at the
// edges; weights normalized per destination pixel).
struct Taps {
    int count = 0;
    std::vector<int> first;     // per destination index: the first source index (before clamping)
    std::vector<float> weight;  // per destination index: `count` weights
};

float lanczos3(float x) {
    x = std::fabs(x);
    if (x < 1e-6f) return 1.f;
    if (x >= 3.f) return 0.f;
    constexpr float kPi = 3.14159265358979f;
    const float px = kPi * x;
    return 3.f * std::sin(px) * std::sin(px / 3.f) / (px * px);
}

Taps lanczos_taps(int src, int dst) {
    const float ratio = static_cast<float>(dst) / static_cast<float>(src);
    const float width = 6.f * std::max(1.f, ratio);
    const int rad = static_cast<int>(std::ceil(width / 2.f / ratio));
    Taps t;
    t.count = 2 * rad + 1;
    t.first.resize(static_cast<size_t>(dst));
    t.weight.resize(static_cast<size_t>(dst) * static_cast<size_t>(t.count));
    for (int x = 0; x < dst; ++x) {
        const float pos = (static_cast<float>(x) + 0.5f) / static_cast<float>(dst) * static_cast<float>(src);
        const float fl = std::floor(pos);
        const float frac = pos - fl;
        t.first[static_cast<size_t>(x)] = static_cast<int>(fl) - rad;
        float* w = &t.weight[static_cast<size_t>(x) * static_cast<size_t>(t.count)];
        float total = 0.f;
        for (int i = 0; i < t.count; ++i) {
            // The filter of `width` evaluated at ratio * offset: lanczos3 over 6/width of it.
            w[i] = lanczos3(ratio * (static_cast<float>(i - rad) - (frac - 0.5f)) * 6.f / width);
            total += w[i];
        }
        if (total != 0.f)
            for (int i = 0; i < t.count; ++i) w[i] /= total;
    }
    return t;
}

// Rows, then columns: O(w·h_src·taps + w·h·taps), where OpenImageIO's 2-D evaluation of the same
// filter costs grow with the source's height when a narrow map is stretched wide (a 2x1024
// roughness to 1024x1024 takes a minute there).
Image resample_separable(const Image& src, int w, int h) {
    const int c = src.channels;
    const Taps tx = lanczos_taps(src.width, w), ty = lanczos_taps(src.height, h);
    Image rows(w, src.height, c);
    for (int y = 0; y < src.height; ++y)
        for (int x = 0; x < w; ++x) {
            const float* wt = &tx.weight[static_cast<size_t>(x) * static_cast<size_t>(tx.count)];
            float* o = &rows.pixels[rows.index(x, y)];
            for (int i = 0; i < tx.count; ++i) {
                if (wt[i] == 0.f) continue;
                const int sx = std::clamp(tx.first[static_cast<size_t>(x)] + i, 0, src.width - 1);
                const float* p = &src.pixels[src.index(sx, y)];
                for (int k = 0; k < c; ++k) o[k] += wt[i] * p[k];
            }
        }
    Image out(w, h, c);
    for (int y = 0; y < h; ++y) {
        const float* wt = &ty.weight[static_cast<size_t>(y) * static_cast<size_t>(ty.count)];
        float* o = &out.pixels[out.index(0, y)];
        for (int j = 0; j < ty.count; ++j) {
            if (wt[j] == 0.f) continue;
            const int sy = std::clamp(ty.first[static_cast<size_t>(y)] + j, 0, src.height - 1);
            const float* r = &rows.pixels[rows.index(0, sy)];
            const size_t n = static_cast<size_t>(w) * static_cast<size_t>(c);
            for (size_t i = 0; i < n; ++i) o[i] += wt[j] * r[i];
        }
    }
    return out;
}

}  // namespace

Image resample(const Image& src, int w, int h) {
    if (src.width == w && src.height == h) return src;
    // Both axes scaled alike by at most 4x: OpenImageIO's resize, whose bytes earlier versions
    // wrote (outputs stay byte-identical). Anything else (a map stretched to another shape, a
    // small map blown up to a large set) goes through the separable form of the same filter.
    const double rx = static_cast<double>(w) / src.width, ry = static_cast<double>(h) / src.height;
    if (std::fabs(rx - ry) > 1e-9 * std::max(rx, ry) || rx > 4.0 || rx < 0.25) return resample_separable(src, w, h);
    return resize_lanczos3(src, w, h);
}

void fit_plane(Role role, RolePlane& plane, int w, int h, const ColorContext& color) {
    if (plane.width() == w && plane.height() == h) return;
    const std::vector<float>& lut = color.srgb_codes_to_linear();
    if (plane.is_codes() && plane.encoding == ColorEncoding::srgb && !lut.empty()) {
        // 8-bit color to linear light by lookup: the processor ran once per code, not per sample.
        plane.image = to_float(plane.codes, lut.data());
        plane.codes = Image8{};
        plane.encoding = ColorEncoding::linear;
    }
    make_floats(role, plane);
    if (plane.encoding == ColorEncoding::srgb) {  // filter in linear light, never on encoded values
        color.convert(plane.image, ColorEncoding::srgb, ColorEncoding::linear);
        plane.encoding = ColorEncoding::linear;
    }
    plane.image = resample(plane.image, w, h);
    if (role == Role::normal) renormalize(plane.image);  // filtering shortens unit vectors
}

bool output_needed(const OutputSpec& o, const Planes& planes) {
    if (o.always) return true;
    for (Role r : o.roles())
        if (planes.count(r)) return true;
    return false;
}

std::vector<ChannelSpec> effective_channels(const OutputSpec& o, const Planes& planes) {
    std::vector<ChannelSpec> out;
    for (const auto& c : o.channels)
        if (!c.optional || planes.count(c.role)) out.push_back(c);
    return out;
}

Size output_size(const OutputSpec& o, const Planes& planes, const Preset& preset) {
    Size s;
    for (const auto& c : effective_channels(o, planes)) {
        if (c.kind != ChannelSpec::Kind::role && c.kind != ChannelSpec::Kind::smoothness) continue;
        auto it = planes.find(c.role);
        if (it == planes.end()) continue;
        s.width = std::max(s.width, it->second.width());
        s.height = std::max(s.height, it->second.height());
    }
    if (s.width == 0) return {preset.constant_size, preset.constant_size};
    if (preset.max_size > 0 && std::max(s.width, s.height) > preset.max_size) {
        const double k = static_cast<double>(preset.max_size) / std::max(s.width, s.height);
        s.width = std::max(1, static_cast<int>(std::lround(s.width * k)));
        s.height = std::max(1, static_cast<int>(std::lround(s.height * k)));
    }
    return s;
}

namespace {

// Channel k of the default color of a missing RGB role, in the output's encoding.
float default_rgb(const PackSpec::Written& w, int k, bool srgb, const ColorContext& color) {
    float v = w.missing[static_cast<size_t>(k)];
    if (srgb && w.channel.role != Role::normal) {
        float rgb[3] = {v, v, v};
        color.convert(rgb, 1, ColorEncoding::linear, ColorEncoding::srgb);
        v = rgb[0];
    }
    return v;
}

// The value of a missing scalar role (inverted for a smoothness channel).
float default_scalar(const PackSpec::Written& w) {
    return w.channel.kind == Channel::Kind::smoothness ? 1.f - w.missing[0] : w.missing[0];
}

int channel_count(const PackSpec& spec) {
    int n = 0;
    for (const auto& w : spec.channels) n += w.channel.key == "RGB" ? 3 : 1;
    return n;
}

// Where an 8-bit output channel's codes come from: a plane's channel (`base`, every `stride`
// codes, XOR `flip`: 0xFF is 255 - k, the smoothness inversion), a constant code, or nothing
// here (`written`: the normal blocks wrote it).
struct CodeSource {
    const uint8_t* base = nullptr;
    size_t stride = 0;
    uint8_t constant = 0;
    uint8_t flip = 0;
    bool written = false;
};

// Every output pixel's channels from their sources, pixel by pixel (N channels known to the
// compiler: the channel loop unrolls, the stores run along the output). A constant is read with
// stride 0 from its own byte: no branch per sample.
template <int N>
void assemble_pixels(uint8_t* out, size_t n, const CodeSource* s) {
    const uint8_t* base[N];
    size_t stride[N];
    uint8_t flip[N];
    for (int c = 0; c < N; ++c) {
        base[c] = s[c].base ? s[c].base : &s[c].constant;
        stride[c] = s[c].base ? s[c].stride : 0;
        flip[c] = s[c].flip;
    }
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < N; ++c) out[i * N + c] = static_cast<uint8_t>(base[c][i * stride[c]] ^ flip[c]);
}

// As assemble_pixels when every source is a plane of its own (stride 1) or a constant: chunks
// of pixels in which a constant is a filled row, so every source runs with unit stride (GCC then
// interleaves whole vectors; twice as fast as the strided loop on the corpus's ORM maps).
template <int N>
void assemble_planes(uint8_t* out, size_t n, const CodeSource* s) {
    constexpr size_t kChunk = 4096;
    uint8_t constants[N][kChunk];
    uint8_t flip[N];
    for (int c = 0; c < N; ++c) {
        if (!s[c].base) std::memset(constants[c], s[c].constant, kChunk);
        flip[c] = s[c].base ? s[c].flip : 0;
    }
    for (size_t i0 = 0; i0 < n; i0 += kChunk) {
        const size_t m = std::min(kChunk, n - i0);
        const uint8_t* row[N];
        for (int c = 0; c < N; ++c) row[c] = s[c].base ? s[c].base + i0 : constants[c];
        uint8_t* o = out + i0 * N;
        for (size_t i = 0; i < m; ++i)
            for (int c = 0; c < N; ++c) o[i * N + c] = static_cast<uint8_t>(row[c][i] ^ flip[c]);
    }
}

void assemble_codes(Image8& out, const std::vector<CodeSource>& sources) {
    const size_t n = static_cast<size_t>(out.width) * static_cast<size_t>(out.height);
    const size_t nch = sources.size();
    const bool all = std::none_of(sources.begin(), sources.end(), [](const CodeSource& c) { return c.written; });
    // An RGB plane copied whole into an RGB output: the same bytes.
    if (all && nch == 3 && sources[0].base && sources[0].stride == 3 && sources[1].base == sources[0].base + 1 &&
        sources[2].base == sources[0].base + 2 && !(sources[0].flip | sources[1].flip | sources[2].flip)) {
        std::memcpy(out.pixels.data(), sources[0].base, n * 3);
        return;
    }
    const bool planar = std::all_of(sources.begin(), sources.end(),
                                    [](const CodeSource& c) { return !c.base || c.stride == 1; });
    if (all && planar && nch >= 2 && nch <= 4) {
        switch (nch) {
            case 2: assemble_planes<2>(out.pixels.data(), n, sources.data()); return;
            case 3: assemble_planes<3>(out.pixels.data(), n, sources.data()); return;
            default: assemble_planes<4>(out.pixels.data(), n, sources.data()); return;
        }
    }
    if (all && nch >= 1 && nch <= 4) {
        switch (nch) {
            case 1: assemble_pixels<1>(out.pixels.data(), n, sources.data()); return;
            case 2: assemble_pixels<2>(out.pixels.data(), n, sources.data()); return;
            case 3: assemble_pixels<3>(out.pixels.data(), n, sources.data()); return;
            default: assemble_pixels<4>(out.pixels.data(), n, sources.data()); return;
        }
    }
    // Some channels written by the normal blocks (a normal map beside other channels), or more
    // than four channels: channel by channel.
    for (size_t c = 0; c < nch; ++c) {
        const CodeSource& src = sources[c];
        if (src.written) continue;
        for (size_t i = 0; i < n; ++i)
            out.pixels[i * nch + c] = src.base ? static_cast<uint8_t>(src.base[i * src.stride] ^ src.flip)
                                               : src.constant;
    }
}

// One packing walk for both sample types: floats (any plane; codes planes decoded) or 8-bit
// codes (codes planes only, checked by pack_output8). The codes walk writes what quantizing the
// float walk's result gives: constants are quantized once, codes copied (inverted as 255 - k),
// normals decoded and re-encoded through the same block loops.
template <class T>
BasicImage<T> pack_walk(const PackSpec& spec, const Planes& planes, const ColorContext& color) {
    constexpr bool kCodes = std::is_same_v<T, uint8_t>;
    const int nch = channel_count(spec);
    BasicImage<T> out(spec.size.width, spec.size.height, nch);
    const size_t n = static_cast<size_t>(spec.size.width) * spec.size.height;
    // Codes: each output channel's source is recorded, and the pixels are then assembled in one
    // pass (assemble_codes), not one strided pass over the whole output per channel.
    std::vector<CodeSource> sources(static_cast<size_t>(nch));
    auto fill = [&](int ch, float v) {
        if constexpr (kCodes) {
            sources[static_cast<size_t>(ch)] = {nullptr, 0, quantize8(v), 0};
        } else {
            for (size_t i = 0; i < n; ++i) out.pixels[i * nch + ch] = v;
        }
    };
    auto copy = [&](int ch, const BasicImage<T>& src, int sc, bool inv) {
        if constexpr (kCodes) {
            sources[static_cast<size_t>(ch)] = {src.pixels.data() + sc, static_cast<size_t>(src.channels), 0,
                                                static_cast<uint8_t>(inv ? 0xFF : 0)};
        } else {
            for (size_t i = 0; i < n; ++i) {
                const T v = src.pixels[i * src.channels + sc];
                out.pixels[i * nch + ch] = inv ? 1.f - v : v;
            }
        }
    };
    // The plane's samples in T, copied only when they must be made: codes as they are, a float
    // plane's image, or a codes plane decoded into `scratch`.
    auto view = [](Role role, const RolePlane& p, BasicImage<T>& scratch) -> const BasicImage<T>& {
        if constexpr (kCodes) {
            return p.codes;
        } else {
            if (!p.is_codes()) return p.image;
            scratch = plane_floats(role, p);
            return scratch;
        }
    };
    int dst = 0;
    for (const auto& w : spec.channels) {
        const Channel& c = w.channel;
        if (c.kind == ChannelSpec::Kind::constant || c.kind == ChannelSpec::Kind::unused) {
            fill(dst++, c.kind == ChannelSpec::Kind::constant ? c.value : 0.f);
            continue;
        }
        const auto it = planes.find(c.role);
        if (c.key != "RGB") {
            BasicImage<T> scratch;
            if (it == planes.end()) fill(dst++, default_scalar(w));
            else copy(dst++, view(c.role, it->second, scratch), 0, c.kind == ChannelSpec::Kind::smoothness);
            continue;
        }
        if (it == planes.end()) {  // default color or flat normal
            for (int k = 0; k < 3; ++k) fill(dst + k, default_rgb(w, k, spec.srgb, color));
        } else if (c.role == Role::normal) {
            const RolePlane& p = it->second;
            const float to = ysign_of(spec.normal_to.value_or(NormalConvention::gl));
            const std::array<float, 256>& unorm = unorm8_values();
            BasicImage<T> scratch;
            const BasicImage<T>& stored = view(c.role, p, scratch);  // codes, or unit GL vectors
            NormalBlock b{};
            if constexpr (kCodes)
                for (size_t k = 0; k < 3; ++k) sources[static_cast<size_t>(dst) + k].written = true;
            for (size_t i0 = 0; i0 < n; i0 += kBlock) {
                const size_t m = std::min(kBlock, n - i0);
                if constexpr (kCodes) {  // decode the stored codes here, as plane_floats would
                    load_block(b, stored, i0, m, [&unorm](uint8_t k) { return unorm[k]; });
                    decode_block(b, stored.channels, ysign_of(p.codes_convention));
                } else {
                    load_block(b, stored, i0, m, [](float v) { return v; });
                }
                encode_block(b, to);
                if constexpr (kCodes) {
                    // Each component quantized in a loop of its own (GCC vectorizes those), then
                    // interleaved: the same codes as quantizing pixel by pixel.
                    std::array<uint8_t, kBlock> q[3];
                    for (size_t i = 0; i < kBlock; ++i) q[0][i] = quantize8(b.x[i]);
                    for (size_t i = 0; i < kBlock; ++i) q[1][i] = quantize8(b.y[i]);
                    for (size_t i = 0; i < kBlock; ++i) q[2][i] = quantize8(b.z[i]);
                    for (size_t i = 0; i < m; ++i) {
                        T* px = &out.pixels[(i0 + i) * nch + dst];
                        px[0] = q[0][i], px[1] = q[1][i], px[2] = q[2][i];
                    }
                } else {
                    for (size_t i = 0; i < m; ++i) {
                        T* px = &out.pixels[(i0 + i) * nch + dst];
                        px[0] = b.x[i], px[1] = b.y[i], px[2] = b.z[i];
                    }
                }
            }
        } else {
            BasicImage<T> scratch;
            const BasicImage<T>* rgb = &view(c.role, it->second, scratch);
            const ColorEncoding want = spec.srgb ? ColorEncoding::srgb : ColorEncoding::linear;
            if constexpr (!kCodes) {  // codes are already in the output's encoding (pack_output8)
                if (it->second.encoding != want) {
                    if (rgb != &scratch) scratch = *rgb;
                    color.convert(scratch, it->second.encoding, want);
                    rgb = &scratch;
                }
            }
            for (int k = 0; k < 3; ++k) copy(dst + k, *rgb, k, false);
        }
        dst += 3;
    }
    if constexpr (kCodes) assemble_codes(out, sources);
    return out;
}

}  // namespace

PackSpec pack_spec(const OutputSpec& o, const Planes& planes, const Preset& preset, Size size) {
    PackSpec spec{size, o.srgb, o.bit_depth, preset.format, std::nullopt, {}, {}};
    for (const auto& c : effective_channels(o, planes)) {
        PackSpec::Written w{static_cast<const Channel&>(c), {}};
        const bool reads = c.kind == Channel::Kind::role || c.kind == Channel::Kind::smoothness;
        if (reads && c.role == Role::normal) spec.normal_to = preset.normal_convention;
        if (reads && planes.count(c.role) &&
            std::find(spec.roles.begin(), spec.roles.end(), c.role) == spec.roles.end())
            spec.roles.push_back(c.role);
        if (reads && !planes.count(c.role)) {
            if (c.key != "RGB") w.missing[0] = preset.default_value(c.role);
            else if (c.role == Role::normal) w.missing = {0.5f, 0.5f, 1.f};
            else if (c.role == Role::albedo) w.missing = preset.default_albedo;
        }
        spec.channels.push_back(std::move(w));
    }
    return spec;
}

Image pack_output(const PackSpec& spec, const Planes& planes, const ColorContext& color) {
    return pack_walk<float>(spec, planes, color);
}

std::optional<Image8> pack_output8(const PackSpec& spec, const Planes& planes, const ColorContext& color) {
    if (spec.bit_depth != 8 || spec.format == FileFormat::exr) return std::nullopt;  // 8-bit integer formats only
    for (const auto& w : spec.channels) {
        const Channel& c = w.channel;
        const auto it = planes.find(c.role);
        if (c.kind == ChannelSpec::Kind::constant || c.kind == ChannelSpec::Kind::unused || it == planes.end())
            continue;
        const RolePlane& p = it->second;
        if (!p.is_codes() || p.width() != spec.size.width || p.height() != spec.size.height) return std::nullopt;
        // Color codes are sRGB-encoded: only an sRGB output takes them as they are.
        if (c.key == "RGB" && c.role != Role::normal &&
            p.encoding != (spec.srgb ? ColorEncoding::srgb : ColorEncoding::linear))
            return std::nullopt;
    }
    return pack_walk<uint8_t>(spec, planes, color);
}

Image pack_output(const OutputSpec& o, const Planes& planes, const Preset& preset, Size size,
                  const ColorContext& color) {
    return pack_output(pack_spec(o, planes, preset, size), planes, color);
}

std::optional<Image8> pack_output8(const OutputSpec& o, const Planes& planes, const Preset& preset, Size size,
                                   const ColorContext& color) {
    return pack_output8(pack_spec(o, planes, preset, size), planes, color);
}

bool same_plane(const RolePlane& a, const RolePlane& b) {
    auto same = [](const auto& x, const auto& y) {
        return x.width == y.width && x.height == y.height && x.channels == y.channels && x.pixels == y.pixels;
    };
    return a.encoding == b.encoding && a.codes_convention == b.codes_convention && same(a.codes, b.codes) &&
           same(a.image, b.image);
}

}  // namespace mf
