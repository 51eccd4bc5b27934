// Internal: albedo luminance statistics split by the metalness mask (dielectric / metal) and
// restricted to visible pixels — the basis of ALBEDO_TOO_DARK, ALBEDO_TOO_BRIGHT and
// METAL_ALBEDO_TOO_DARK.
//
// Measure: relative luminance Y = 0.2126 R + 0.7152 G + 0.0722 B of the linear color (sRGB /
// Rec.709 primaries, IEC 61966-2-1), re-encoded with the sRGB curve and scaled to 0–255, so it
// compares with the PBR Guide's "sRGB value" bounds. Luminance (not the max channel) keeps
// saturated but plausible colors (red paint, gold) inside the bounds.
#pragma once
#include <array>
#include <vector>

#include "validate/rules.hpp"

namespace mf::validate::detail {

class AlbedoStats {
public:
    AlbedoStats(const Thresholds& t, bool linear_input);
    // rgb: the albedo pixel as stored (sRGB-encoded unless linear_input); metalness in [0, 1].
    void add(const float* rgb, float metalness);
    void findings(const std::string& file, bool has_metal_mask, bool has_opacity_mask,
                  std::vector<Finding>& out) const;

private:
    struct Class {
        long long n = 0, below = 0, above = 0;
        std::array<long long, 256> hist{};  // by sRGB code of the luminance
        double percentile(double p) const;
    };
    float linear(float v) const;

    Thresholds t_;
    bool linear_input_;
    float dark_lin_, bright_lin_, metal_dark_lin_;
    std::array<float, 256> edges_{};  // linear luminance at sRGB code k + 0.5
    Class dielectric_, metal_;
};

}  // namespace mf::validate::detail
