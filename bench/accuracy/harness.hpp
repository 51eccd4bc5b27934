// The accuracy benchmark's vocabulary: each knob yields variants; a variant carries its error
// (measured once, against a double-precision reference) and the work that Google Benchmark times.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "base/srgb.hpp"

namespace mf::bench {

// Running max / mean of |error| (a non-finite error counts as huge, never as 0).
struct Acc {
    double max = 0, sum = 0;
    size_t n = 0;
    void add(double e) {
        e = std::abs(e);
        if (!std::isfinite(e)) e = 1e30;
        max = std::max(max, e), sum += e, ++n;
    }
    double mean() const { return n ? sum / static_cast<double>(n) : 0.0; }
};

// Deterministic test data (Marsaglia xorshift32).
inline uint32_t xorshift(uint32_t& s) {
    s ^= s << 13, s ^= s >> 17, s ^= s << 5;
    return s;
}

// The 8-bit display code of a radiance: clamped to [0, 1], through the exact sRGB curve. The
// unit of every "codes" error of a rendered or resampled color.
inline double display_code(double radiance) { return linear_to_srgb(std::clamp(radiance, 0.0, 1.0)) * 255.0; }

struct Config {
    bool quick = false;       // CI smoke: small inputs, short timings
    std::string ocio_config;  // path of ocio/config.ocio
};

struct Variant {
    std::string knob;  // curve of the plot
    std::string name;  // row of the table
    std::string tag;   // short label on the plot
    // Errors: `codes` in 8-bit display/encoded code units (the plot's y), `linear` in linear
    // light or data units. NaN where not meaningful.
    double max_codes = 0, mean_codes = 0, max_linear = 0, mean_linear = 0;
    std::string linear_unit;     // unit of max_linear / mean_linear ("linear", "% points", …)
    std::string note;            // banding, bytes, non-finite counts, …
    std::function<void()> work;  // what is timed (one call = one unit below)
    double pixels = 1;           // pixels one call processes (for ns/px and ms/Mpx)
    std::string unit;            // "ns/px" or "ms/map"
    double map_pixels = 0;       // for "ms/map": pixels of the named map (4K, 8K, 1K)
    std::string map_name;        // "4K", "8K", "1K"
    int iterations = 0;          // 0: let Google Benchmark decide (MinTime); >0: fixed
    double time_s = 0;           // filled by the driver: seconds per call
};

std::vector<Variant> transfer_variants(const Config& c);
std::vector<Variant> resample_variants(const Config& c);
std::vector<Variant> quantize_variants(const Config& c);
std::vector<Variant> normal_variants(const Config& c);
std::vector<Variant> brdf_variants(const Config& c);
std::vector<Variant> stats_variants(const Config& c);
// lib/texture (knobs_texture.cpp): block encoders, a cut-out's mips and edges.
std::vector<Variant> encoder_variants(const Config& c);
std::vector<Variant> cutout_mip_variants(const Config& c);
std::vector<Variant> cutout_edge_variants(const Config& c);

}  // namespace mf::bench
