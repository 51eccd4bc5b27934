#include "validate/albedo_stats.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/text.hpp"
#include "validate/map_stats.hpp"

namespace mf::validate::detail {

double AlbedoStats::Class::percentile(double p) const {
    if (n == 0) return 0.0;
    const auto target = static_cast<long long>(std::ceil(p * static_cast<double>(n)));
    long long acc = 0;
    for (size_t k = 0; k < hist.size(); ++k) {
        acc += hist[k];
        if (acc >= std::max<long long>(target, 1)) return static_cast<double>(k);
    }
    return 255.0;
}

void AlbedoStats::findings(const std::string& file, bool has_metal_mask, bool has_opacity_mask,
                           std::vector<Finding>& out) const {
    auto figures = [&](const Class& c, long long count, double threshold) {
        return Figures{{"share", ratio(count, c.n)},
                       {"surface_share", ratio(count, visible_)},
                       {"pixels", c.n},
                       {"visible_pixels", visible_},
                       {"threshold_srgb", threshold},
                       {"p1_srgb", c.percentile(0.01)},
                       {"median_srgb", c.percentile(0.5)},
                       {"p99_srgb", c.percentile(0.99)},
                       {"metalness_mask", has_metal_mask},
                       {"opacity_mask", has_opacity_mask},
                       {"measure", "luminance, sRGB-encoded, 0-255"}};
    };
    auto add = [&](std::string_view code, std::string msg, Figures fig) {
        out.push_back(finding(code, "albedo", file, std::move(msg), std::move(fig)));
    };
    // Shares are of the visible albedo; with a metalness mask the share of the class is given too.
    auto amount = [&](const Class& c, long long count, const std::string& cls, const std::string& comparison) {
        if (!has_metal_mask)
            return percent(ratio(count, visible_)) +
                   " of the visible albedo (no metalness map: all taken as dielectric) is " + comparison + " (median " +
                   fixed(c.percentile(0.5), 0) + ")";
        return percent(ratio(count, visible_)) + " of the visible albedo is " + cls + " and " + comparison + " (" +
               percent(ratio(count, c.n)) + " of the " + std::to_string(c.n) + " " + cls + " pixels; median " +
               fixed(c.percentile(0.5), 0) + ")";
    };
    const Class& d = dielectric_;
    if (d.n > 0) {
        const double dark = ratio(d.below, visible_), bright = ratio(d.above, visible_);
        if (dark > t_.albedo_dark_max_share)
            add(code::albedo_too_dark,
                file + ": " +
                    amount(d, d.below, "dielectric", "darker than " + fixed(t_.albedo_min_srgb, 0) + " sRGB") +
                    "; no real dielectric is that dark — keep shadows and cavities out of the "
                    "albedo (they belong in occlusion)",
                figures(d, d.below, t_.albedo_min_srgb));
        if (bright > t_.albedo_bright_max_share)
            add(code::albedo_too_bright,
                file + ": " +
                    amount(d, d.above, "dielectric", "brighter than " + fixed(t_.albedo_max_srgb, 0) + " sRGB") +
                    "; even fresh snow reflects less — remove baked lighting or highlights",
                figures(d, d.above, t_.albedo_max_srgb));
    }
    const Class& m = metal_;
    if (m.n > 0) {
        const double dark = ratio(m.below, visible_);
        if (dark > t_.metal_albedo_max_share)
            add(code::metal_albedo_too_dark,
                file + ": " +
                    amount(m, m.below, "metallic", "darker than " + fixed(t_.metal_albedo_min_srgb, 0) + " sRGB") +
                    "; raw metals reflect 70-100 % — a dark metal is a dielectric (oxide, paint) "
                    "or its metalness is wrong",
                figures(m, m.below, t_.metal_albedo_min_srgb));
    }
}

}  // namespace mf::validate::detail
