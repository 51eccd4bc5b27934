#include "validate/albedo_stats.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/text.hpp"
#include "validate/map_stats.hpp"

namespace mf::validate::detail {

double AlbedoStats::percentile(const Histogram& hist, long long n, double p) {
    if (n <= 0) return 0.0;
    // The first code whose running sum reaches p of the weight. For whole-pixel weights this is
    // the pixel-count percentile: x * kWeightUnit is exact, so acc >= p * n holds exactly when
    // it holds for the counts.
    const double target = p * static_cast<double>(n);
    long long acc = 0;
    for (size_t k = 0; k < hist.size(); ++k) {
        acc += hist[k];
        if (static_cast<double>(acc) >= target && acc > 0) return static_cast<double>(k);
    }
    return 255.0;
}

void AlbedoStats::add_plain_row(const uint8_t* rgb, size_t stride, size_t n, const uint8_t* keep, uint8_t want) {
    const long long weight = classify_.metal_weight(0.0);
    simd::I4 counted{}, dark{}, bright{}, metal_dark{};
    size_t i = 0;
    for (; i + 4 <= n; i += 4) {
        const simd::F4 y = classify_.luminance4(rgb + i * stride, stride);
        simd::I4 kept = simd::I4{} - 1;
        if (keep) kept = simd::I4{keep[i], keep[i + 1], keep[i + 2], keep[i + 3]} == static_cast<int32_t>(want);
        const AlbedoClassifier::Judgements4 j = classify_.judge_weighted4(y, weight);
        counted += kept;
        dark += kept & j.dark;
        bright += kept & j.bright;
        metal_dark += kept & j.metal_dark;
        for (size_t l = 0; l < 4; ++l)
            if (kept[l]) ++plain_[l][classify_.srgb_code(y[l])];
    }
    AlbedoCounts c;
    for (; i < n; ++i) {  // the last 0-3 pixels
        if (keep && keep[i] != want) continue;
        const float y = classify_.luminance(rgb + i * stride);
        c.add(classify_.judge_weighted(y, weight));
        ++plain_[i & 3][classify_.srgb_code(y)];
    }
    c.add(simd::count(counted), simd::count(dark), simd::count(bright), simd::count(metal_dark), weight);
    counts_.merge(c);
}

AlbedoStats::Histogram AlbedoStats::total(Histogram Lanes::*which) const {
    Histogram h{};
    for (const Lanes& l : lanes_)
        for (size_t k = 0; k < h.size(); ++k) h[k] += (l.*which)[k];
    const long long metal = classify_.metal_weight(0.0);
    const long long weight = which == &Lanes::metal ? metal : kWeightUnit - metal;
    for (const Histogram& p : plain_)
        for (size_t k = 0; k < h.size(); ++k) h[k] += p[k] * weight;
    return h;
}

void AlbedoStats::findings(const std::string& file, bool has_metal_mask, bool has_opacity_mask,
                           std::vector<Finding>& out) const {
    const AlbedoCounts& c = counts_;
    const Histogram dielectric_hist = total(&Lanes::dielectric), metal_hist = total(&Lanes::metal);
    // Weighted sums reported as pixels: whole numbers whenever the metalness map is binary.
    auto pixels = [](long long weighted) {
        return static_cast<long long>(std::llround(static_cast<double>(weighted) / kWeightUnit));
    };
    auto figures = [&](const Histogram& hist, long long n, long long count, double threshold) {
        Figures f{{"share", n > 0 ? static_cast<double>(count) / static_cast<double>(n) : 0.0},
                  {"surface_share", c.surface_share(count)},
                  {"pixels", pixels(n)},
                  {"visible_pixels", c.visible},
                  {"threshold_srgb", threshold},
                  {"p1_srgb", percentile(hist, n, 0.01)},
                  {"median_srgb", percentile(hist, n, 0.5)},
                  {"p99_srgb", percentile(hist, n, 0.99)},
                  {"metalness_mask", has_metal_mask},
                  {"opacity_mask", has_opacity_mask},
                  {"measure", "luminance, sRGB-encoded, 0-255"}};
        if (c.blend > 0) f.emplace("blend_pixels", c.blend);
        return f;
    };
    auto add = [&](std::string_view code, std::string msg, Figures fig) {
        out.push_back(finding(code, "albedo", file, std::move(msg), std::move(fig)));
    };
    // Shares are of the visible albedo; with a metalness mask the share of the class is given too.
    auto amount = [&](const Histogram& hist, long long n, long long count, const std::string& cls,
                      const std::string& comparison) {
        const std::string median = fixed(percentile(hist, n, 0.5), 0);
        if (!has_metal_mask)
            return percent(c.surface_share(count)) +
                   " of the visible albedo (no metalness map: all taken as dielectric) is " + comparison + " (median " +
                   median + ")";
        const std::string weighted =
            c.blend > 0 ? "; the " + std::to_string(c.blend) +
                              " pixels of metalness between the classes count toward both, weighted by it"
                        : "";
        return percent(c.surface_share(count)) + " of the visible albedo is " + cls + " and " + comparison + " (" +
               percent(static_cast<double>(count) / static_cast<double>(n)) + " of the " + std::to_string(pixels(n)) +
               " " + cls + " pixels; median " + median + weighted + ")";
    };
    // The three rules: what each compares, against which bound, and what to do about it.
    struct Rule {
        std::string_view code;
        const Histogram& hist;
        long long n, count;
        double max_share, bound_srgb;
        const char *cls, *relation, *advice;
    };
    const Rule rules[] = {
        {code::albedo_too_dark, dielectric_hist, c.dielectric, c.dielectric_dark, t_.albedo_dark_max_share,
         t_.albedo_min_srgb, "dielectric", "darker",
         "no real dielectric is that dark — keep shadows and cavities out of the albedo (they belong in occlusion)"},
        {code::albedo_too_bright, dielectric_hist, c.dielectric, c.dielectric_bright, t_.albedo_bright_max_share,
         t_.albedo_max_srgb, "dielectric", "brighter",
         "even fresh snow reflects less — remove baked lighting or highlights"},
        {code::metal_albedo_too_dark, metal_hist, c.metal, c.metal_dark, t_.metal_albedo_max_share,
         t_.metal_albedo_min_srgb, "metallic", "darker",
         "raw metals reflect 70-100 % — a dark metal is a dielectric (oxide, paint) or its metalness is wrong"},
    };
    for (const Rule& r : rules) {
        if (r.n <= 0 || !(c.surface_share(r.count) > r.max_share)) continue;
        const std::string comparison = std::string(r.relation) + " than " + fixed(r.bound_srgb, 0) + " sRGB";
        add(r.code, file + ": " + amount(r.hist, r.n, r.count, r.cls, comparison) + "; " + r.advice,
            figures(r.hist, r.n, r.count, r.bound_srgb));
    }
}

}  // namespace mf::validate::detail
