#include "validate/albedo_stats.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "validate/map_stats.hpp"

namespace mf::validate::detail {
namespace {

std::string fmt0(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.0f", v);
    return buf;
}
std::string pct(double share) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f %%", 100.0 * share);
    return buf;
}

}  // namespace

AlbedoStats::AlbedoStats(const Thresholds& t, bool linear_input) : t_(t), linear_input_(linear_input) {
    auto lin = [](double srgb255) { return srgb_to_linear(static_cast<float>(srgb255 / 255.0)); };
    dark_lin_ = lin(t.albedo_min_srgb);
    bright_lin_ = lin(t.albedo_max_srgb);
    metal_dark_lin_ = lin(t.metal_albedo_min_srgb);
    for (int k = 0; k < 256; ++k) edges_[k] = lin(k + 0.5);
    edges_[256] = std::numeric_limits<float>::infinity();
    for (size_t b = 0; b <= kBuckets; ++b) {
        const float lo = static_cast<float>(b) / static_cast<float>(kBuckets);
        first_code_[b] = static_cast<uint16_t>(std::lower_bound(edges_.begin(), edges_.end(), lo) - edges_.begin());
    }
    decode_ = srgb_decode_table().data();
}

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
        return nlohmann::json{{"share", ratio(count, c.n)},
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
    auto add = [&](std::string_view code, std::string msg, nlohmann::json fig) {
        Finding f;
        f.code = std::string(code);
        f.role = "albedo";
        f.file = file;
        f.message = std::move(msg);
        f.figures = std::move(fig);
        out.push_back(std::move(f));
    };
    // Shares are of the visible albedo; with a metalness mask the share of the class is given too.
    auto amount = [&](const Class& c, long long count, const std::string& cls, const std::string& comparison) {
        if (!has_metal_mask)
            return pct(ratio(count, visible_)) +
                   " of the visible albedo (no metalness map: all taken as dielectric) is " + comparison + " (median " +
                   fmt0(c.percentile(0.5)) + ")";
        return pct(ratio(count, visible_)) + " of the visible albedo is " + cls + " and " + comparison + " (" +
               pct(ratio(count, c.n)) + " of the " + std::to_string(c.n) + " " + cls + " pixels; median " +
               fmt0(c.percentile(0.5)) + ")";
    };
    const Class& d = dielectric_;
    if (d.n > 0) {
        const double dark = ratio(d.below, visible_), bright = ratio(d.above, visible_);
        if (dark > t_.albedo_max_share)
            add(code::albedo_too_dark,
                file + ": " + amount(d, d.below, "dielectric", "darker than " + fmt0(t_.albedo_min_srgb) + " sRGB") +
                    "; no real dielectric is that dark — keep shadows and cavities out of the "
                    "albedo (they belong in occlusion)",
                figures(d, d.below, t_.albedo_min_srgb));
        if (bright > t_.albedo_max_share)
            add(code::albedo_too_bright,
                file + ": " + amount(d, d.above, "dielectric", "brighter than " + fmt0(t_.albedo_max_srgb) + " sRGB") +
                    "; even fresh snow reflects less — remove baked lighting or highlights",
                figures(d, d.above, t_.albedo_max_srgb));
    }
    const Class& m = metal_;
    if (m.n > 0) {
        const double dark = ratio(m.below, visible_);
        if (dark > t_.metal_albedo_max_share)
            add(code::metal_albedo_too_dark,
                file + ": " +
                    amount(m, m.below, "metallic", "darker than " + fmt0(t_.metal_albedo_min_srgb) + " sRGB") +
                    "; raw metals reflect 70-100 % — a dark metal is a dielectric (oxide, paint) "
                    "or its metalness is wrong",
                figures(m, m.below, t_.metal_albedo_min_srgb));
    }
}

}  // namespace mf::validate::detail
