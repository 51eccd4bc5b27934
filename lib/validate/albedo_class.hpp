// The class of one albedo pixel under the rules' thresholds: what ALBEDO_TOO_DARK,
// ALBEDO_TOO_BRIGHT and METAL_ALBEDO_TOO_DARK count (validate/albedo_stats.hpp) and what the
// report's overlay paints (report/images.hpp), decided here once so the page's shares are the
// findings'.
//
// Measure: relative luminance Y = 0.2126 R + 0.7152 G + 0.0722 B of the linear color (sRGB /
// Rec.709 primaries, IEC 61966-2-1), compared with the bounds decoded to linear once, so a
// bound of 30 sRGB is the PBR Guide's "sRGB value" 30. Luminance (not the max channel) keeps
// saturated but plausible colors (red paint, gold) inside the bounds.
//
// Metalness weights each pixel between the two classes instead of dropping the blends: at or
// below dielectric_max a pixel is all dielectric, at or above metal_min all metal, and between
// the two its metal weight rises linearly (0.5 -> half each). A map painted 0.8 everywhere is
// then judged 7/8 as metal (it used to escape every check, issue 26 item 5), and binary maps
// count exactly as before. Weights are integers in units of 1/kWeightUnit of a pixel, so sums
// are exact and never depend on the order pixels are added in.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "base/simd.hpp"
#include "findings/rules.hpp"

namespace mf::validate {

inline constexpr long long kWeightUnit = 65536;  // one whole pixel

// One pixel judged: its metal weight (the rest of kWeightUnit is dielectric) and which bounds
// its luminance breaks. A pixel whose luminance or metalness is not finite is not counted.
struct AlbedoJudgement {
    bool counted = false;
    long long metal = 0;      // 0 .. kWeightUnit
    bool dark = false;        // below albedo_min_srgb (the dielectric bound)
    bool bright = false;      // above albedo_max_srgb
    bool metal_dark = false;  // below metal_albedo_min_srgb
    long long dielectric() const { return kWeightUnit - metal; }
    bool blend() const { return metal > 0 && metal < kWeightUnit; }
    // The weight of the pixel that breaks a bound of its class: too dark, too bright.
    long long dark_weight() const { return (dark ? dielectric() : 0) + (metal_dark ? metal : 0); }
    long long bright_weight() const { return bright ? dielectric() : 0; }
};

// Weighted sums of judged pixels: what the three rules compare and the report's legend shows.
// Shares are of the visible surface (every counted pixel), so a few dark dielectric pixels in a
// mostly metal map (dirt in the cracks) stay a few pixels, not "80 % of the dielectric".
struct AlbedoCounts {
    long long visible = 0;  // whole pixels
    long long blend = 0;    // whole pixels with metalness strictly between the classes
    // Weighted, in units of 1/kWeightUnit of a pixel:
    long long dielectric = 0, dielectric_dark = 0, dielectric_bright = 0, metal = 0, metal_dark = 0;
    void add(const AlbedoJudgement& j) {
        if (j.counted) add(1, j.dark ? 1 : 0, j.bright ? 1 : 0, j.metal_dark ? 1 : 0, j.metal);
    }
    // `pixels` counted pixels of one metal weight, of which `dark`, `bright` and `dark_metal`
    // break those bounds (judged as AlbedoJudgement: dark and bright only where dielectric,
    // dark_metal only where metal).
    void add(long long pixels, long long dark, long long bright, long long dark_metal, long long metal_weight) {
        const long long dielectric_weight = kWeightUnit - metal_weight;
        visible += pixels;
        blend += metal_weight > 0 && metal_weight < kWeightUnit ? pixels : 0;
        dielectric += pixels * dielectric_weight;
        dielectric_dark += dark * dielectric_weight;
        dielectric_bright += bright * dielectric_weight;
        metal += pixels * metal_weight;
        metal_dark += dark_metal * metal_weight;
    }
    // Both counts together (a surface counted in two parts).
    void merge(const AlbedoCounts& o) {
        visible += o.visible;
        blend += o.blend;
        dielectric += o.dielectric;
        dielectric_dark += o.dielectric_dark;
        dielectric_bright += o.dielectric_bright;
        metal += o.metal;
        metal_dark += o.metal_dark;
    }
    // A weighted sum as a share of the visible surface.
    double surface_share(long long weighted) const {
        return visible > 0 ? static_cast<double>(weighted) / (static_cast<double>(visible) * kWeightUnit) : 0.0;
    }
};

class AlbedoClassifier {
public:
    // linear_input: the albedo's channels are linear (float files), else sRGB-encoded.
    AlbedoClassifier(const rules::Thresholds& t, bool linear_input);

    // The linear luminance of a pixel as stored. Inline: called once per albedo pixel.
    float luminance(const float* rgb) const {
        return 0.2126f * linear(rgb[0]) + 0.7152f * linear(rgb[1]) + 0.0722f * linear(rgb[2]);
    }
    // The same of a pixel held as 8-bit codes (unorm8_values): bit for bit the floats' luminance.
    float luminance(const uint8_t* rgb) const {
        return 0.2126f * linear8_[rgb[0]] + 0.7152f * linear8_[rgb[1]] + 0.0722f * linear8_[rgb[2]];
    }
    // The bounds a luminance breaks, whatever its class: of one float (bools) or of four lanes
    // (simd::F4: masks). The one place the three comparisons are written.
    template <class Y>
    auto bounds(Y y) const {
        struct Broken {
            decltype(y < dark_lin_) dark, bright, metal_dark;
        };
        return Broken{y<dark_lin_, y> bright_lin_, y < metal_dark_lin_};
    }
    // luminance() of four pixels of 8-bit codes, pixel l at rgb + l * stride: lane by lane the
    // same float operations, so the same values.
    simd::F4 luminance4(const uint8_t* rgb, size_t stride) const {
        auto channel = [&](size_t c) {
            return simd::F4{linear8_[rgb[c]], linear8_[rgb[stride + c]], linear8_[rgb[2 * stride + c]],
                            linear8_[rgb[3 * stride + c]]};
        };
        return 0.2126f * channel(0) + 0.7152f * channel(1) + 0.0722f * channel(2);
    }
    // judge_weighted() of four finite luminances of one metal weight: the lanes that are too
    // dark, too bright, and (metal) too dark, as masks.
    struct Judgements4 {
        simd::I4 dark, bright, metal_dark;
    };
    Judgements4 judge_weighted4(simd::F4 y, long long metal) const {
        const auto b = bounds(y);
        const simd::I4 dielectric = simd::I4{} - (metal < kWeightUnit ? 1 : 0);  // all lanes -1 or 0
        const simd::I4 metallic = simd::I4{} - (metal > 0 ? 1 : 0);
        return {dielectric & b.dark, dielectric & b.bright, metallic & b.metal_dark};
    }
    AlbedoJudgement judge(float y, float metalness) const {
        if (!std::isfinite(y) || !std::isfinite(metalness)) return {};
        return judge_weighted(y, metal_weight(metalness));
    }
    // judge() of a finite luminance whose metal weight is known (a row without a metalness map:
    // metal_weight(0) for every pixel).
    AlbedoJudgement judge_weighted(float y, long long metal) const {
        const auto b = bounds(y);
        AlbedoJudgement j;
        j.counted = true;
        j.metal = metal;
        j.dark = j.metal < kWeightUnit && b.dark;
        j.bright = j.metal < kWeightUnit && b.bright;
        j.metal_dark = j.metal > 0 && b.metal_dark;
        return j;
    }
    // The metal weight of a finite metalness, compared in double as MapStats'
    // METALNESS_NOT_BINARY compares it.
    long long metal_weight(double m) const {
        if (m <= dielectric_max_) return 0;
        if (m >= metal_min_) return kWeightUnit;
        return std::llround((m - dielectric_max_) / (metal_min_ - dielectric_max_) * kWeightUnit);
    }
    // The sRGB code (0–255) of linear luminance y (finite, >= 0): the number of code edges below
    // y, as a binary search over the edges would give, from a coarse table and one branch-free step.
    size_t srgb_code(float y) const {
        // y * 4096 is exact (a power of two): bucket b holds exactly the y in [b/4096, (b+1)/4096).
        // Edges are at least 3e-4 apart (the curve's steepest part, near 0) and a bucket is
        // 2.4e-4 wide: at most one edge lies between the bucket's start and y, the bucket's next
        // edge. y >= 1 takes the last entry (255 edges lie below 1). Both entries are read by the
        // bucket: neither load waits on the other.
        const size_t b = y < 1.f ? static_cast<size_t>(y * 4096.f) : kBuckets;
        const size_t k = first_code_[b] + (next_edge_[b] < y ? 1 : 0);
        return std::min<size_t>(k, 255);
    }

private:
    static constexpr size_t kBuckets = 4096;
    float linear(float v) const {
        if (linear_input_) return std::max(v, 0.f);
        if (!(v > 0.f)) return 0.f;
        if (v >= 1.f) return 1.f;
        // v in (0, 1): adding 0.5 and truncating equals lround here (checked for every float in
        // [0, 1]) without a libm call per channel per pixel.
        // NOLINTNEXTLINE(bugprone-incorrect-roundings): exhaustively equal to lround on this domain
        return decode_[static_cast<size_t>(v * 65535.f + 0.5f)];
    }

    bool linear_input_;
    double dielectric_max_, metal_min_;  // compared in double, as MapStats' METALNESS_NOT_BINARY
    float dark_lin_, bright_lin_, metal_dark_lin_;
    // Code edges (the linear luminance at sRGB code k + 0.5) below b / 4096 (b = kBuckets: below
    // 1), and the first edge at or above b / 4096 (+inf past the last).
    std::array<uint8_t, kBuckets + 1> first_code_{};
    std::array<float, kBuckets + 1> next_edge_{};
    const float* decode_;               // sRGB decode of every 16-bit code
    std::array<float, 256> linear8_{};  // linear() of every 8-bit code's float
};

}  // namespace mf::validate
