// The class of one albedo pixel under the rules' thresholds: what ALBEDO_TOO_DARK,
// ALBEDO_TOO_BRIGHT and METAL_ALBEDO_TOO_DARK count (validate/albedo_stats.hpp) and what the
// report's overlay paints (report/images.hpp), decided here once so the page's shares are the
// findings'.
//
// Measure: relative luminance Y = 0.2126 R + 0.7152 G + 0.0722 B of the linear color (sRGB /
// Rec.709 primaries, IEC 61966-2-1), compared with the bounds decoded to linear once, so a
// bound of 30 sRGB is the PBR Guide's "sRGB value" 30. Luminance (not the max channel) keeps
// saturated but plausible colors (red paint, gold) inside the bounds.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "validate/rules.hpp"

namespace mf::validate {

enum class AlbedoClass : uint8_t {
    uncounted,          // luminance or metalness not finite
    dielectric,         // metalness <= dielectric_max, within the bounds
    dielectric_dark,    // ... darker than albedo_min_srgb
    dielectric_bright,  // ... brighter than albedo_max_srgb
    metal,              // metalness >= metal_min, within the bound
    metal_dark,         // ... darker than metal_albedo_min_srgb
    blend,              // metalness strictly between: no bound applies (rust, dirt on metal)
};

class AlbedoClassifier {
public:
    // linear_input: the albedo's channels are linear (float files), else sRGB-encoded.
    AlbedoClassifier(const Thresholds& t, bool linear_input);

    // The linear luminance of a pixel as stored. Inline: called once per albedo pixel.
    float luminance(const float* rgb) const {
        return 0.2126f * linear(rgb[0]) + 0.7152f * linear(rgb[1]) + 0.0722f * linear(rgb[2]);
    }
    AlbedoClass classify(float y, float metalness) const {
        if (!std::isfinite(y) || !std::isfinite(metalness)) return AlbedoClass::uncounted;
        if (metalness <= dielectric_max_) {
            if (y < dark_lin_) return AlbedoClass::dielectric_dark;
            return y > bright_lin_ ? AlbedoClass::dielectric_bright : AlbedoClass::dielectric;
        }
        if (metalness >= metal_min_) return y < metal_dark_lin_ ? AlbedoClass::metal_dark : AlbedoClass::metal;
        return AlbedoClass::blend;
    }
    // The sRGB code (0–255) of linear luminance y (finite, >= 0): the number of code edges below
    // y, as a binary search over the edges would give, from a coarse table and one branch-free step.
    size_t srgb_code(float y) const {
        // y * 4096 is exact (a power of two): bucket b holds exactly the y in [b/4096, (b+1)/4096).
        // Edges are at least 3e-4 apart (the curve's steepest part, near 0) and a bucket is
        // 2.4e-4 wide: at most one edge lies between the bucket's start and y. y >= 1 takes the
        // last entry (255 edges lie below 1); the sentinel edge (+inf) stops the step at 256.
        size_t k = first_code_[y < 1.f ? static_cast<size_t>(y * 4096.f) : kBuckets];
        k += edges_[k] < y ? 1 : 0;
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
    std::array<float, 257> edges_{};                   // linear luminance at sRGB code k + 0.5; [256] = +inf
    std::array<uint16_t, kBuckets + 1> first_code_{};  // edges below b / 4096 (b = kBuckets: below 1)
    const float* decode_;                              // sRGB decode of every 16-bit code
};

}  // namespace mf::validate
