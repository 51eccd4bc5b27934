// Internal: albedo luminance statistics split by the metalness mask (dielectric / metal) and
// restricted to visible pixels — the basis of ALBEDO_TOO_DARK, ALBEDO_TOO_BRIGHT and
// METAL_ALBEDO_TOO_DARK.
//
// Measure: relative luminance Y = 0.2126 R + 0.7152 G + 0.0722 B of the linear color (sRGB /
// Rec.709 primaries, IEC 61966-2-1), re-encoded with the sRGB curve and scaled to 0–255, so it
// compares with the PBR Guide's "sRGB value" bounds. Luminance (not the max channel) keeps
// saturated but plausible colors (red paint, gold) inside the bounds.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "validate/rules.hpp"

namespace mf::validate::detail {

class AlbedoStats {
    static constexpr size_t kBuckets = 4096;

public:
    AlbedoStats(const Thresholds& t, bool linear_input);
    // rgb: the albedo pixel as stored (sRGB-encoded unless linear_input); metalness in [0, 1].
    // Inline: called once per albedo pixel.
    void add(const float* rgb, float metalness) {
        const float y = 0.2126f * linear(rgb[0]) + 0.7152f * linear(rgb[1]) + 0.0722f * linear(rgb[2]);
        if (!std::isfinite(y) || !std::isfinite(metalness)) return;
        ++visible_;
        Class* c = nullptr;
        if (metalness <= t_.dielectric_max) c = &dielectric_;
        else if (metalness >= t_.metal_min) c = &metal_;
        else return;  // blends (rust, dirt on metal): no bound applies
        ++c->n;
        ++c->hist[srgb_code(y)];
        if (c == &dielectric_) {
            if (y < dark_lin_) ++c->below;
            if (y > bright_lin_) ++c->above;
        } else if (y < metal_dark_lin_) {
            ++c->below;
        }
    }
    // The sRGB code of linear luminance y (finite, >= 0): the number of edges below y, as a
    // binary search over the edges would give, from a coarse table and one branch-free step.
    size_t srgb_code(float y) const {
        // y * 4096 is exact (a power of two): bucket b holds exactly the y in [b/4096, (b+1)/4096).
        // Edges are at least 3e-4 apart (the curve's steepest part, near 0) and a bucket is
        // 2.4e-4 wide: at most one edge lies between the bucket's start and y. y >= 1 takes the
        // last entry (255 edges lie below 1); the sentinel edge (+inf) stops the step at 256.
        size_t k = first_code_[y < 1.f ? static_cast<size_t>(y * 4096.f) : kBuckets];
        k += edges_[k] < y ? 1 : 0;
        return std::min<size_t>(k, 255);
    }
    void findings(const std::string& file, bool has_metal_mask, bool has_opacity_mask, std::vector<Finding>& out) const;

private:
    struct Class {
        long long n = 0, below = 0, above = 0;
        std::array<long long, 256> hist{};  // by sRGB code of the luminance
        double percentile(double p) const;
    };
    float linear(float v) const {
        if (linear_input_) return std::max(v, 0.f);
        if (!(v > 0.f)) return 0.f;
        if (v >= 1.f) return 1.f;
        // v in (0, 1): adding 0.5 and truncating equals lround here (checked for every float in
        // [0, 1]) without a libm call per channel per pixel.
        // NOLINTNEXTLINE(bugprone-incorrect-roundings): exhaustively equal to lround on this domain
        return decode_[static_cast<size_t>(v * 65535.f + 0.5f)];
    }

    Thresholds t_;
    bool linear_input_;
    float dark_lin_, bright_lin_, metal_dark_lin_;
    std::array<float, 257> edges_{};                   // linear luminance at sRGB code k + 0.5; [256] = +inf
    std::array<uint16_t, kBuckets + 1> first_code_{};  // edges below b / 4096 (b = kBuckets: below 1)
    const float* decode_;                              // sRGB decode of every 16-bit code
    Class dielectric_, metal_;
    // Every visible pixel, blends included: the shares a rule compares are of the visible
    // surface, so a few dark dielectric pixels in a mostly metal map (dirt in the cracks of a
    // graded metalness map) stay a few pixels, not "80 % of the dielectric".
    long long visible_ = 0;
};

}  // namespace mf::validate::detail
