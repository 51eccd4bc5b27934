// Internal: albedo luminance statistics weighted by metalness (dielectric / metal) and
// restricted to visible pixels — the basis of ALBEDO_TOO_DARK, ALBEDO_TOO_BRIGHT and
// METAL_ALBEDO_TOO_DARK. Each pixel's judgement is validate/albedo_class.hpp's.
#pragma once
#include <array>
#include <string>
#include <type_traits>
#include <vector>

#include "findings/rules.hpp"
#include "validate/albedo_class.hpp"

namespace mf::validate::detail {

class AlbedoStats {
public:
    AlbedoStats(const rules::Thresholds& t, bool linear_input) : t_(t), classify_(t, linear_input) {}
    // One row of n albedo pixels as stored (sRGB-encoded unless linear_input): pixel i's RGB at
    // rgb + i * stride, 3 floats or 3 8-bit codes (validate.hpp's Samples); its metalness
    // metal[i] in [0, 1] (nullptr: 0). With `keep`, only the pixels whose keep[i] is `want`.
    // The counts are summed in locals and added once a row; the histograms alternate between two
    // lanes by pixel, so that a run of one luminance code does not wait on its own last add.
    // Every sum is an integer: the same figures in any order.
    template <class T>
    void add_row(const T* rgb, size_t stride, const float* metal, size_t n, const uint8_t* keep = nullptr,
                 uint8_t want = 1) {
        if constexpr (std::is_same_v<T, uint8_t>) {
            if (!metal) {
                add_plain_row(rgb, stride, n, keep, want);
                return;
            }
        }
        AlbedoCounts c;
        for (size_t i = 0; i < n; ++i) {
            if (keep && keep[i] != want) continue;
            const float y = classify_.luminance(rgb + i * stride);
            const AlbedoJudgement j = classify_.judge(y, metal ? metal[i] : 0.f);
            if (!j.counted) continue;
            c.add(j);
            const size_t code = classify_.srgb_code(y);
            Lanes& lane = lanes_[i & 1];
            lane.dielectric[code] += j.dielectric();
            lane.metal[code] += j.metal;
        }
        counts_.merge(c);
    }
    // add_row of 8-bit codes without a metalness map: 8-bit codes have a finite luminance, and
    // every pixel has the same metal weight (metal_weight(0)); judged four at a time, counted by
    // code in `plain_` (weighted when the histograms are read). The same figures.
    void add_plain_row(const uint8_t* rgb, size_t stride, size_t n, const uint8_t* keep, uint8_t want);
    size_t srgb_code(float y) const { return classify_.srgb_code(y); }
    // Adds the pixels another accumulator of the same thresholds counted (exact: integer weights).
    void merge(const AlbedoStats& o) {
        counts_.merge(o.counts_);
        for (size_t l = 0; l < lanes_.size(); ++l)
            for (size_t k = 0; k < 256; ++k) {
                lanes_[l].dielectric[k] += o.lanes_[l].dielectric[k];
                lanes_[l].metal[k] += o.lanes_[l].metal[k];
            }
        for (size_t l = 0; l < plain_.size(); ++l)
            for (size_t k = 0; k < 256; ++k) plain_[l][k] += o.plain_[l][k];
    }
    void findings(const std::string& file, bool has_metal_mask, bool has_opacity_mask, std::vector<Finding>& out) const;

private:
    // Luminance by sRGB code, weighted as AlbedoCounts (units of 1/kWeightUnit of a pixel).
    using Histogram = std::array<long long, 256>;
    static double percentile(const Histogram& hist, long long n, double p);

    struct Lanes {
        Histogram dielectric{}, metal{};
    };
    // The dielectric or metal histogram: the lanes' sum, and the plain counts weighted.
    Histogram total(Histogram Lanes::*which) const;

    rules::Thresholds t_;
    AlbedoClassifier classify_;
    AlbedoCounts counts_;
    std::array<Lanes, 2> lanes_{};
    std::array<Histogram, 4> plain_{};  // pixels of weight metal_weight(0), by code
};

}  // namespace mf::validate::detail
