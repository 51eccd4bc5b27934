// Mip chains in the filtering domain of each channel (texture.hpp's conventions).
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "base/srgb.hpp"
#include "texture/texture.hpp"

namespace mf::texture {
namespace {

// sRGB code k -> linear light (exact IEC 61966-2-1 curve, once).
const std::array<float, 256>& srgb_decode() {
    static const std::array<float, 256> t = [] {
        std::array<float, 256> a{};
        for (size_t k = 0; k < 256; ++k) a[k] = static_cast<float>(srgb_to_linear(static_cast<double>(k) / 255.0));
        return a;
    }();
    return t;
}

// Linear light -> sRGB code, rounded to nearest in the encoded domain: code k covers linear values
// from decode((k - 0.5) / 255) up, so the code is the number of those thresholds at or below v.
// Eight comparisons instead of a pow per sample.
uint8_t srgb_encode(float v) {
    static const std::array<float, 255> thresholds = [] {
        std::array<float, 255> t{};
        for (size_t k = 1; k < 256; ++k)
            t[k - 1] = static_cast<float>(srgb_to_linear((static_cast<double>(k) - 0.5) / 255.0));
        return t;
    }();
    if (!(v > 0.f)) return 0;  // NaN and negatives (a filter's lobes) to black
    return static_cast<uint8_t>(std::upper_bound(thresholds.begin(), thresholds.end(), v) - thresholds.begin());
}

struct Tap {
    int index;
    float weight;
};
using Taps = std::vector<std::vector<Tap>>;  // per destination texel

double bessel_i0(double x) {  // power series; converges fast for the small arguments used here
    double sum = 1.0, term = 1.0;
    for (int k = 1; k < 30; ++k) {
        term *= (x / (2.0 * k)) * (x / (2.0 * k));
        sum += term;
    }
    return sum;
}

// Weights of source texels for each destination texel, `src` texels shrinking to `dst`, wrapping.
Taps make_taps(int src, int dst, MipFilter filter) {
    Taps taps(static_cast<size_t>(dst));
    const double scale = static_cast<double>(src) / dst;
    for (int i = 0; i < dst; ++i) {
        auto& t = taps[static_cast<size_t>(i)];
        if (filter == MipFilter::box || scale <= 1.0) {  // area overlap: exact at odd sizes too
            const double a = i * scale, b = (i + 1) * scale;
            for (auto s = static_cast<int>(std::floor(a)); s < b; ++s) {
                const double w = (std::min<double>(s + 1, b) - std::max<double>(s, a)) / scale;
                if (w > 1e-9) t.push_back({((s % src) + src) % src, static_cast<float>(w)});
            }
            continue;
        }
        // Kaiser-windowed sinc, half-width 3 destination texels, alpha 4.
        constexpr double kHalfWidth = 3.0, kAlpha = 4.0;
        const double center = (i + 0.5) * scale;
        const auto lo = static_cast<int>(std::floor(center - kHalfWidth * scale)),
                   hi = static_cast<int>(std::ceil(center + kHalfWidth * scale));
        double sum = 0.0;
        std::vector<std::pair<int, double>> raw;
        for (int s = lo; s <= hi; ++s) {
            const double x = (s + 0.5 - center) / scale;
            if (std::abs(x) >= kHalfWidth) continue;
            const double px = std::numbers::pi * x;
            const double sinc = std::abs(x) < 1e-9 ? 1.0 : std::sin(px) / px;
            const double r = x / kHalfWidth;
            const double w = sinc * bessel_i0(kAlpha * std::sqrt(1.0 - r * r)) / bessel_i0(kAlpha);
            raw.emplace_back(((s % src) + src) % src, w);
            sum += w;
        }
        for (const auto& [s, w] : raw) t.push_back({s, static_cast<float>(w / sum)});
    }
    return taps;
}

// Separable resampling to w x h: `sample(x, y, k)` reads the source (w0 x h0, c channels).
template <class Sample>
Image filter_with(int w0, int h0, int c, Sample&& sample, int w, int h, MipFilter filter) {
    const Taps tx = make_taps(w0, w, filter), ty = make_taps(h0, h, filter);
    Image mid(w, h0, c);  // horizontal pass first: the full-size source is never held as floats
    for (int y = 0; y < h0; ++y) {
        float* out = &mid.pixels[mid.index(0, y)];
        for (int x = 0; x < w; ++x)
            for (const Tap& t : tx[static_cast<size_t>(x)])
                for (int k = 0; k < c; ++k) out[x * c + k] += t.weight * sample(t.index, y, k);
    }
    Image dst(w, h, c);
    for (int y = 0; y < h; ++y) {
        float* out = &dst.pixels[dst.index(0, y)];
        for (const Tap& t : ty[static_cast<size_t>(y)]) {
            const float* row = &mid.pixels[mid.index(0, t.index)];
            const size_t n = static_cast<size_t>(w) * static_cast<size_t>(c);
            for (size_t i = 0; i < n; ++i) out[i] += t.weight * row[i];
        }
    }
    return dst;
}

Image filter_image(const Image& src, int w, int h, MipFilter filter) {
    return filter_with(
        src.width, src.height, src.channels, [&](int x, int y, int k) { return src.at(x, y, k); }, w, h, filter);
}

// Per channel: code -> the filtering domain (sRGB color to linear light, normals to [-1, 1],
// the rest k/255).
std::vector<std::array<float, 256>> domain_tables(const std::vector<ChannelKind>& kinds) {
    std::vector<std::array<float, 256>> t(kinds.size());
    for (size_t k = 0; k < kinds.size(); ++k)
        for (size_t v = 0; v < 256; ++v)
            t[k][v] = kinds[k] == ChannelKind::srgb_color ? srgb_decode()[v]
                      : kinds[k] == ChannelKind::normal   ? static_cast<float>(v) / 127.5f - 1.f
                                                          : static_cast<float>(v) / 255.f;
    return t;
}

Image filter_codes(const Image8& src, const std::vector<ChannelKind>& kinds, int w, int h, MipFilter filter) {
    const auto tables = domain_tables(kinds);
    return filter_with(
        src.width, src.height, src.channels,
        [&](int x, int y, int k) { return tables[static_cast<size_t>(k)][src.at(x, y, k)]; }, w, h, filter);
}

void renormalize_normals(Image& img, const std::vector<ChannelKind>& kinds) {
    const auto first = std::find(kinds.begin(), kinds.end(), ChannelKind::normal);
    if (first == kinds.end()) return;
    const auto k0 = static_cast<size_t>(first - kinds.begin());
    const auto c = static_cast<size_t>(img.channels);
    const size_t n = static_cast<size_t>(img.width) * static_cast<size_t>(img.height);
    for (size_t p = 0; p < n; ++p) {
        float* v = &img.pixels[p * c + k0];
        const float len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        if (len > 1e-6f && std::isfinite(len)) {
            v[0] /= len, v[1] /= len, v[2] /= len;
        } else {
            v[0] = v[1] = 0.f, v[2] = 1.f;
        }
    }
}

// A value of the filtering domain (domain_tables) back to a code; `alpha_scale` for alpha_tested.
uint8_t code_of(ChannelKind kind, float v, float alpha_scale = 1.f) {
    return kind == ChannelKind::srgb_color     ? srgb_encode(v)
           : kind == ChannelKind::normal       ? quantize8(v * 0.5f + 0.5f)
           : kind == ChannelKind::alpha_tested ? quantize8(v * alpha_scale)
                                               : quantize8(v);
}

Image8 to_codes(const Image& img, const std::vector<ChannelKind>& kinds, const std::vector<float>& alpha_scale) {
    Image8 out(img.width, img.height, img.channels);
    const auto c = static_cast<size_t>(img.channels);
    const size_t n = static_cast<size_t>(img.width) * static_cast<size_t>(img.height);
    for (size_t k = 0; k < c; ++k)
        for (size_t p = 0; p < n; ++p) out.pixels[p * c + k] = code_of(kinds[k], img.pixels[p * c + k], alpha_scale[k]);
    return out;
}

double coverage_of(const Image& img, size_t channel, float cutoff, float scale) {
    const auto c = static_cast<size_t>(img.channels);
    const size_t n = static_cast<size_t>(img.width) * static_cast<size_t>(img.height);
    size_t above = 0;
    // The stored code is what the alpha test sees: compare quantized values.
    const int kept = first_kept_code(cutoff);
    for (size_t p = 0; p < n; ++p) above += quantize8(img.pixels[p * c + channel] * scale) >= kept;
    return n ? static_cast<double>(above) / static_cast<double>(n) : 0.0;
}

// The scale whose alpha test keeps `target` coverage (Castaño 2010: bisection on the scale;
// coverage grows with it).
float coverage_scale(const Image& img, size_t channel, float cutoff, double target) {
    float lo = 0.f, hi = 8.f;
    for (int i = 0; i < 24; ++i) {
        const float mid = 0.5f * (lo + hi);
        (coverage_of(img, channel, cutoff, mid) < target ? lo : hi) = mid;
    }
    // The closer of the two ends.
    const double elo = std::abs(coverage_of(img, channel, cutoff, lo) - target);
    const double ehi = std::abs(coverage_of(img, channel, cutoff, hi) - target);
    return elo < ehi ? lo : hi;
}

// Toksvig (2005) for GGX, as bench/accuracy measures it: alpha'^2 = alpha^2 + 2 (1 - |n|) / |n|
// (Walter et al. 2007's exponent correspondence), perceptual roughness r' = alpha'^(1/2).
float toksvig_roughness(float r, float len) {
    const double l = std::clamp(static_cast<double>(len), 1e-4, 1.0);
    const auto rr = static_cast<double>(r);
    const double a2 = rr * rr * rr * rr + 2.0 * (1.0 - l) / l;
    return static_cast<float>(std::min(1.0, std::pow(a2, 0.25)));
}

}  // namespace

std::vector<ChannelKind> channel_kinds(const std::vector<ChannelSpec>& written, bool srgb, bool cutout) {
    std::vector<ChannelKind> kinds;
    for (const auto& c : written) {
        if (c.key == "RGB") {
            const bool normal = c.kind == ChannelSpec::Kind::role && c.role == Role::normal;
            const ChannelKind k = normal ? ChannelKind::normal : srgb ? ChannelKind::srgb_color : ChannelKind::data;
            kinds.insert(kinds.end(), 3, k);
        } else if (c.kind == ChannelSpec::Kind::role && c.role == Role::opacity && cutout) {
            kinds.push_back(ChannelKind::alpha_tested);
        } else {
            kinds.push_back(ChannelKind::data);
        }
    }
    return kinds;
}

Image normals_from_codes(const Image8& codes) {
    Image out(codes.width, codes.height, 3);
    const auto c = static_cast<size_t>(codes.channels);
    for (size_t p = 0; p < static_cast<size_t>(codes.width) * static_cast<size_t>(codes.height); ++p) {
        std::array<float, 3> n{};
        float len = 0;
        for (size_t k = 0; k < 3; ++k) {
            n[k] = static_cast<float>(codes.pixels[p * c + k]) / 127.5f - 1.f;
            len += n[k] * n[k];
        }
        len = len > 0 ? 1.f / std::sqrt(len) : 0.f;
        for (size_t k = 0; k < 3; ++k) out.pixels[p * 3 + k] = n[k] * len;
    }
    return out;
}

int mip_count(int width, int height) {
    int n = 1;
    for (int m = std::max(width, height); m > 1; m /= 2) ++n;
    return n;
}

std::vector<Image8> make_mips(const Image8& level0, const std::vector<ChannelKind>& kinds, const MipOptions& options) {
    std::vector<Image8> chain;
    chain.push_back(level0);
    if (level0.width <= 1 && level0.height <= 1) return chain;
    std::vector<float> alpha_scale(kinds.size(), 1.f);
    std::vector<double> coverage(kinds.size(), 0.0);
    for (size_t k = 0; k < kinds.size(); ++k)
        if (kinds[k] == ChannelKind::alpha_tested)
            coverage[k] = alpha_coverage(level0, static_cast<int>(k), options.alpha_cutoff);
    const bool toksvig = options.roughness_channel >= 0 && options.normals && options.normals->width == level0.width &&
                         options.normals->height == level0.height;
    Image spread = toksvig ? *options.normals : Image{};  // unnormalized: its shortening is the spread
    Image cur;  // the previous level in the filtering domain (level 0 is read from its codes)
    for (int w0 = level0.width, h0 = level0.height; w0 > 1 || h0 > 1;) {
        const int w = std::max(1, w0 / 2), h = std::max(1, h0 / 2);
        cur = cur.empty() ? filter_codes(level0, kinds, w, h, options.filter) : filter_image(cur, w, h, options.filter);
        w0 = w, h0 = h;
        renormalize_normals(cur, kinds);
        Image stored = cur;
        for (size_t k = 0; k < kinds.size(); ++k)
            if (kinds[k] == ChannelKind::alpha_tested)
                alpha_scale[k] = coverage_scale(cur, k, options.alpha_cutoff, coverage[k]);
        if (toksvig) {
            spread = filter_image(spread, w, h, options.filter);
            const auto c = static_cast<size_t>(stored.channels), rc = static_cast<size_t>(options.roughness_channel);
            for (size_t p = 0; p < static_cast<size_t>(w) * static_cast<size_t>(h); ++p) {
                const float* n = &spread.pixels[p * 3];
                const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
                float& v = stored.pixels[p * c + rc];
                const float r = options.smoothness ? 1.f - v : v;
                const float adjusted = toksvig_roughness(std::clamp(r, 0.f, 1.f), len);
                v = options.smoothness ? 1.f - adjusted : adjusted;
            }
        }
        chain.push_back(to_codes(stored, kinds, alpha_scale));
    }
    return chain;
}

size_t dilate_under_alpha(Image8& img, const std::vector<ChannelKind>& kinds, int alpha_channel, uint8_t shown_from) {
    const int w = img.width, h = img.height;
    const auto c = static_cast<size_t>(img.channels), a = static_cast<size_t>(alpha_channel);
    const size_t n = static_cast<size_t>(w) * static_cast<size_t>(h);
    // 0: not shown and not yet filled; 1: shown or filled by an earlier ring; 2: in the ring.
    std::vector<uint8_t> state(n);
    size_t shown = 0;
    for (size_t p = 0; p < n; ++p) {
        state[p] = img.pixels[p * c + a] >= shown_from ? 1 : 0;
        shown += state[p];
    }
    if (shown == 0 || shown == n) return 0;
    const auto tables = domain_tables(kinds);
    // The 8 neighbours of p, wrapping as the mips do (materials tile).
    auto each_neighbour = [&](size_t p, auto&& f) {
        const auto x = static_cast<int>(p % static_cast<size_t>(w)), y = static_cast<int>(p / static_cast<size_t>(w));
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
                if (dx || dy)
                    f(static_cast<size_t>((y + dy + h) % h) * static_cast<size_t>(w) +
                      static_cast<size_t>((x + dx + w) % w));
    };
    std::vector<size_t> ring;
    for (size_t p = 0; p < n; ++p) {
        if (state[p]) continue;
        bool next_to_filled = false;
        each_neighbour(p, [&](size_t q) { next_to_filled = next_to_filled || state[q] == 1; });
        if (next_to_filled) ring.push_back(p), state[p] = 2;
    }
    std::vector<uint8_t> codes;
    size_t filled = 0;
    while (!ring.empty()) {
        // Every texel of the ring from the texels filled before it, then the ring is filled.
        codes.assign(ring.size() * c, 0);
        for (size_t i = 0; i < ring.size(); ++i) {
            std::array<float, 4> sum{};
            int count = 0;
            each_neighbour(ring[i], [&](size_t q) {
                if (state[q] != 1) return;
                for (size_t k = 0; k < c; ++k) sum[k] += tables[k][img.pixels[q * c + k]];
                ++count;
            });
            for (size_t k = 0; k < c; ++k)
                if (k != a) codes[i * c + k] = code_of(kinds[k], sum[k] / static_cast<float>(count));
        }
        for (size_t i = 0; i < ring.size(); ++i) {
            for (size_t k = 0; k < c; ++k)
                if (k != a) img.pixels[ring[i] * c + k] = codes[i * c + k];
            state[ring[i]] = 1;
        }
        filled += ring.size();
        std::vector<size_t> next;
        for (const size_t p : ring)
            each_neighbour(p, [&](size_t q) {
                if (state[q] == 0) next.push_back(q), state[q] = 2;
            });
        ring = std::move(next);
    }
    return filled;
}

Image8 resize(const Image8& level, const std::vector<ChannelKind>& kinds, int w, int h) {
    Image img = filter_codes(level, kinds, w, h, MipFilter::kaiser);
    renormalize_normals(img, kinds);
    return to_codes(img, kinds, std::vector<float>(kinds.size(), 1.f));
}

int first_kept_code(float cutoff) {
    int code = 0;
    while (code < 256 && static_cast<float>(code) / 255.f < cutoff) ++code;
    return code;
}

double alpha_coverage(const Image8& img, int channel, float cutoff) {
    const auto c = static_cast<size_t>(img.channels);
    const size_t n = static_cast<size_t>(img.width) * static_cast<size_t>(img.height);
    const int kept = first_kept_code(cutoff);
    size_t above = 0;
    for (size_t p = 0; p < n; ++p) above += img.pixels[p * c + static_cast<size_t>(channel)] >= kept;
    return n ? static_cast<double>(above) / static_cast<double>(n) : 0.0;
}

AlphaUse classify_opacity(const Image& opacity) {
    const size_t n = static_cast<size_t>(opacity.width) * static_cast<size_t>(opacity.height);
    const auto c = static_cast<size_t>(std::max(1, opacity.channels));
    size_t binary = 0, opaque = 0;
    for (size_t p = 0; p < n; ++p) {
        const float v = opacity.pixels[p * c];
        opaque += v >= 1.f - 0.5f / 255.f;
        binary += v <= 0.1f || v >= 0.9f;
    }
    if (opaque == n) return AlphaUse::opaque;
    return static_cast<double>(binary) >= 0.95 * static_cast<double>(n) ? AlphaUse::cutout : AlphaUse::blend;
}

}  // namespace mf::texture
