// Internal: albedo luminance statistics split by the metalness mask (dielectric / metal) and
// restricted to visible pixels — the basis of ALBEDO_TOO_DARK, ALBEDO_TOO_BRIGHT and
// METAL_ALBEDO_TOO_DARK. Each pixel's class is validate/albedo_class.hpp's.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "validate/albedo_class.hpp"
#include "validate/rules.hpp"

namespace mf::validate::detail {

class AlbedoStats {
public:
    AlbedoStats(const Thresholds& t, bool linear_input) : t_(t), classify_(t, linear_input) {}
    // rgb: the albedo pixel as stored (sRGB-encoded unless linear_input); metalness in [0, 1].
    // Inline: called once per albedo pixel.
    void add(const float* rgb, float metalness) {
        const float y = classify_.luminance(rgb);
        const AlbedoClass k = classify_.classify(y, metalness);
        if (k == AlbedoClass::uncounted) return;
        ++visible_;
        if (k == AlbedoClass::blend) return;
        const bool metal = k == AlbedoClass::metal || k == AlbedoClass::metal_dark;
        Class& c = metal ? metal_ : dielectric_;
        ++c.n;
        ++c.hist[classify_.srgb_code(y)];
        c.below += k == AlbedoClass::dielectric_dark || k == AlbedoClass::metal_dark ? 1 : 0;
        c.above += k == AlbedoClass::dielectric_bright ? 1 : 0;
    }
    size_t srgb_code(float y) const { return classify_.srgb_code(y); }
    void findings(const std::string& file, bool has_metal_mask, bool has_opacity_mask, std::vector<Finding>& out) const;

private:
    struct Class {
        long long n = 0, below = 0, above = 0;
        std::array<long long, 256> hist{};  // by sRGB code of the luminance
        double percentile(double p) const;
    };

    Thresholds t_;
    AlbedoClassifier classify_;
    Class dielectric_, metal_;
    // Every visible pixel, blends included: the shares a rule compares are of the visible
    // surface, so a few dark dielectric pixels in a mostly metal map (dirt in the cracks of a
    // graded metalness map) stay a few pixels, not "80 % of the dielectric".
    long long visible_ = 0;
};

}  // namespace mf::validate::detail
