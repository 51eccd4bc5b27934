// Internal: albedo luminance statistics weighted by metalness (dielectric / metal) and
// restricted to visible pixels — the basis of ALBEDO_TOO_DARK, ALBEDO_TOO_BRIGHT and
// METAL_ALBEDO_TOO_DARK. Each pixel's judgement is validate/albedo_class.hpp's.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "findings/rules.hpp"
#include "validate/albedo_class.hpp"

namespace mf::validate::detail {

class AlbedoStats {
public:
    AlbedoStats(const rules::Thresholds& t, bool linear_input) : t_(t), classify_(t, linear_input) {}
    // rgb: the albedo pixel as stored (sRGB-encoded unless linear_input); metalness in [0, 1].
    // Inline: called once per albedo pixel.
    void add(const float* rgb, float metalness) {
        const float y = classify_.luminance(rgb);
        const AlbedoJudgement j = classify_.judge(y, metalness);
        if (!j.counted) return;
        counts_.add(j);
        const size_t code = classify_.srgb_code(y);
        dielectric_hist_[code] += j.dielectric();
        metal_hist_[code] += j.metal;
    }
    size_t srgb_code(float y) const { return classify_.srgb_code(y); }
    // Adds the pixels another accumulator of the same thresholds counted (exact: integer weights).
    void merge(const AlbedoStats& o) {
        counts_.merge(o.counts_);
        for (size_t k = 0; k < dielectric_hist_.size(); ++k) {
            dielectric_hist_[k] += o.dielectric_hist_[k];
            metal_hist_[k] += o.metal_hist_[k];
        }
    }
    void findings(const std::string& file, bool has_metal_mask, bool has_opacity_mask, std::vector<Finding>& out) const;

private:
    // Luminance by sRGB code, weighted as AlbedoCounts (units of 1/kWeightUnit of a pixel).
    using Histogram = std::array<long long, 256>;
    static double percentile(const Histogram& hist, long long n, double p);

    rules::Thresholds t_;
    AlbedoClassifier classify_;
    AlbedoCounts counts_;
    Histogram dielectric_hist_{}, metal_hist_{};
};

}  // namespace mf::validate::detail
