#include "report/images.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "color/srgb.hpp"

namespace mf::report {
namespace {

// The sRGB curves through 65536-step tables with linear interpolation: within 1e-6 of the exact
// IEC 61966-2-1 functions (color/srgb.hpp) on [0, 1], a few ns per value instead of a pow.
constexpr int kSteps = 65536;
struct Curve {
    std::vector<float> table;
    explicit Curve(bool decode) : table(kSteps + 1) {
        for (int i = 0; i <= kSteps; ++i) {
            const double v = static_cast<double>(i) / kSteps;
            table[static_cast<size_t>(i)] = static_cast<float>(decode ? srgb_to_linear(v) : linear_to_srgb(v));
        }
    }
    float operator()(float v) const {
        const float c = v > 0.f ? (v < 1.f ? v : 1.f) : 0.f;  // NaN -> 0
        const float f = c * kSteps;
        const auto i = static_cast<size_t>(f);
        if (i >= kSteps) return table[kSteps];
        const float t = f - static_cast<float>(i);
        return table[i] + t * (table[i + 1] - table[i]);
    }
};
const Curve& decode_curve() {
    static const Curve c(true);
    return c;
}
const Curve& encode_curve() {
    static const Curve c(false);
    return c;
}

float clamp01(float v) { return v > 0.f ? (v < 1.f ? v : 1.f) : 0.f; }

// Output size of a box reduction to at most max_size on the long side (never larger).
void reduced_size(int w, int h, int max_size, int& ow, int& oh) {
    const int longest = std::max(w, h);
    if (longest <= max_size) {
        ow = w;
        oh = h;
        return;
    }
    const double s = static_cast<double>(max_size) / longest;
    ow = std::max(1, static_cast<int>(std::lround(w * s)));
    oh = std::max(1, static_cast<int>(std::lround(h * s)));
}

// Box reduction of an RGB image (values averaged as they are).
Image box_reduce(const Image& rgb, int max_size) {
    int ow = 0, oh = 0;
    reduced_size(rgb.width, rgb.height, max_size, ow, oh);
    if (ow == rgb.width && oh == rgb.height) return rgb;
    Image out(ow, oh, 3);
    std::vector<double> acc(static_cast<size_t>(ow) * 3);
    std::vector<size_t> count(static_cast<size_t>(ow));
    std::vector<int> col_of(static_cast<size_t>(rgb.width));
    for (int x = 0; x < rgb.width; ++x)
        col_of[static_cast<size_t>(x)] = static_cast<int>(static_cast<int64_t>(x) * ow / rgb.width);
    for (int oy = 0; oy < oh; ++oy) {
        const int y0 = static_cast<int>(static_cast<int64_t>(oy) * rgb.height / oh);
        const int y1 = std::max(y0 + 1, static_cast<int>(static_cast<int64_t>(oy + 1) * rgb.height / oh));
        std::fill(acc.begin(), acc.end(), 0.0);
        std::fill(count.begin(), count.end(), 0);
        for (int y = y0; y < y1; ++y) {
            const float* row = &rgb.pixels[rgb.index(0, y)];
            for (int x = 0; x < rgb.width; ++x) {
                const auto ox = static_cast<size_t>(col_of[static_cast<size_t>(x)]);
                for (size_t c = 0; c < 3; ++c) acc[ox * 3 + c] += row[static_cast<size_t>(x) * 3 + c];
                ++count[ox];
            }
        }
        for (int ox = 0; ox < ow; ++ox) {
            const auto o = static_cast<size_t>(ox);
            for (size_t c = 0; c < 3; ++c)
                out.at(ox, oy,
                       static_cast<int>(c)) = static_cast<float>(acc[o * 3 + c] / static_cast<double>(count[o]));
        }
    }
    return out;
}

}  // namespace

Image thumbnail(const Image& src, int max_size, bool srgb) {
    Image rgb(src.width, src.height, 3);
    const Curve& dec = decode_curve();
    const size_t n = static_cast<size_t>(src.width) * static_cast<size_t>(src.height);
    const auto sc = static_cast<size_t>(src.channels);
    for (size_t p = 0; p < n; ++p) {
        const float* s = &src.pixels[p * sc];
        float v[3] = {s[0], sc > 1 ? s[1] : s[0], sc > 2 ? s[2] : (sc == 2 ? 0.f : s[0])};
        for (float& x : v) x = srgb ? dec(x) : clamp01(x);
        for (size_t c = 0; c < 3; ++c) rgb.pixels[p * 3 + c] = v[c];
    }
    Image out = box_reduce(rgb, max_size);
    if (srgb) {
        const Curve& enc = encode_curve();
        for (float& x : out.pixels) x = enc(x);
    }
    return out;
}

Image channel_thumbnail(const Image& src, int channel, int max_size) {
    Image rgb(src.width, src.height, 3);
    const size_t n = static_cast<size_t>(src.width) * static_cast<size_t>(src.height);
    const auto sc = static_cast<size_t>(src.channels);
    const auto ch = static_cast<size_t>(std::clamp(channel, 0, src.channels - 1));
    for (size_t p = 0; p < n; ++p) {
        const float v = clamp01(src.pixels[p * sc + ch]);
        rgb.pixels[p * 3] = rgb.pixels[p * 3 + 1] = rgb.pixels[p * 3 + 2] = v;
    }
    return box_reduce(rgb, max_size);
}

float Scalar::at(int x, int y, int w, int h) const {
    if (!image || image->empty()) return constant;
    const int sx = image->width == w ? x : static_cast<int>(static_cast<int64_t>(x) * image->width / w);
    const int sy = image->height == h ? y : static_cast<int>(static_cast<int64_t>(y) * image->height / h);
    const float v = image->at(sx, sy, std::min(channel, image->channels - 1));
    return invert ? 1.f - v : v;
}

Image albedo_overlay(const Image& albedo, bool albedo_srgb, const Scalar& metalness, const Scalar& opacity,
                     const AlbedoBounds& b, AlbedoStats& stats) {
    stats = {};
    const int w = albedo.width, h = albedo.height;
    Image out(w, h, 3);
    const Curve& dec = decode_curve();
    const Curve& enc = encode_curve();
    const int cell = std::max(1, std::max(w, h) / 32);  // checkerboard of invisible pixels: 32 cells across
    const auto ac = static_cast<size_t>(albedo.channels);
    auto put = [&out](int x, int y, const float* rgb, float scale) {
        for (int c = 0; c < 3; ++c) out.at(x, y, c) = rgb[c] * scale;
    };
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            ++stats.pixels;
            if (opacity.at(x, y, w, h) < static_cast<float>(b.opacity_visible)) {
                const float g = ((x / cell + y / cell) % 2) ? 0.30f : 0.18f;
                const float rgb[3] = {g, g, g};
                put(x, y, rgb, 1.f);
                continue;
            }
            ++stats.visible;
            const float* s = &albedo.pixels[albedo.index(x, y)];
            float lin[3] = {s[0], ac > 1 ? s[1] : s[0], ac > 2 ? s[2] : s[0]};
            for (float& v : lin) v = albedo_srgb ? dec(v) : clamp01(v);
            const float luminance = 0.2126f * lin[0] + 0.7152f * lin[1] + 0.0722f * lin[2];
            const float shown = enc(luminance);  // display value of the luminance
            const double srgb255 = static_cast<double>(shown) * 255.0;
            const float m = metalness.at(x, y, w, h);
            const float grey[3] = {shown, shown, shown};
            if (m <= static_cast<float>(b.dielectric_metalness)) {
                ++stats.dielectric;
                if (srgb255 < b.dielectric_min) {
                    ++stats.dielectric_dark;
                    put(x, y, kTooDark, 1.f);
                } else if (srgb255 > b.dielectric_max) {
                    ++stats.dielectric_bright;
                    put(x, y, kTooBright, 1.f);
                } else {
                    put(x, y, grey, 1.f);
                }
            } else if (m >= static_cast<float>(b.metal_metalness)) {
                ++stats.metal;
                if (srgb255 < b.metal_min) {
                    ++stats.metal_dark;
                    put(x, y, kTooDark, 1.f);
                } else if (srgb255 > b.metal_max) {
                    ++stats.metal_bright;
                    put(x, y, kTooBright, 1.f);
                } else {
                    put(x, y, grey, 1.f);
                }
            } else {
                ++stats.blend;
                put(x, y, kBlend, 0.35f + 0.65f * shown);
            }
        }
    }
    return out;
}

Image metalness_overlay(const Scalar& metalness, int width, int height, double dielectric, double metal,
                        MetalnessStats& stats) {
    stats = {};
    Image out(width, height, 3);
    constexpr float kHalfCode = 0.5f / 255.f;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            ++stats.pixels;
            const float m = metalness.at(x, y, width, height);
            const float* rgb = nullptr;
            float g = 0.f;
            if (m < kHalfCode) {
                ++stats.zero;
                g = 0.06f;
            } else if (m > 1.f - kHalfCode) {
                ++stats.one;
                g = 0.94f;
            } else if (m <= static_cast<float>(dielectric) || m >= static_cast<float>(metal)) {
                ++stats.near_binary;
                rgb = kNearBinary;
            } else {
                ++stats.between;
                rgb = kBetween;
            }
            for (int c = 0; c < 3; ++c) out.at(x, y, c) = rgb ? rgb[c] : g;
        }
    }
    return out;
}

}  // namespace mf::report
