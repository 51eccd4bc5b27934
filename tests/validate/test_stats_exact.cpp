// The shortcuts in the per-pixel statistics give exactly what the plain computations give:
// AlbedoStats' coarse-table sRGB code against a binary search over the code edges, and MapStats'
// integer-file sums (kept in codes) against summing the values.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "base/srgb.hpp"
#include "validate/albedo_stats.hpp"
#include "validate/map_stats.hpp"

namespace mv = mf::validate;
namespace md = mf::validate::detail;

namespace {

// The reference: the number of code edges (linear luminance of sRGB code k + 0.5) below y.
size_t reference_code(float y) {
    static const std::array<float, 256> edges = [] {
        std::array<float, 256> e{};
        for (int k = 0; k < 256; ++k) e[k] = mf::srgb_to_linear(static_cast<float>((k + 0.5) / 255.0));
        return e;
    }();
    return std::min<size_t>(static_cast<size_t>(std::lower_bound(edges.begin(), edges.end(), y) - edges.begin()), 255);
}

TEST(StatsExact, AlbedoCodeEqualsBinarySearchAtEveryEdgeAndBetween) {
    const md::AlbedoStats acc(mf::rules::Thresholds{}, false);
    std::vector<float> ys = {0.f, 1e-30f, 1e-7f, 0.5f, 1.f, 1.0001f, 2.f, 1e30f};
    for (int k = 0; k < 256; ++k) {  // each edge, and the floats either side of it
        const float e = mf::srgb_to_linear(static_cast<float>((k + 0.5) / 255.0));
        ys.insert(ys.end(), {e, std::nextafter(e, 0.f), std::nextafter(e, 2.f)});
    }
    for (int b = 0; b <= 4096; ++b) {  // each bucket boundary of the coarse table, and either side
        const float lo = static_cast<float>(b) / 4096.f;
        ys.insert(ys.end(), {lo, std::nextafter(lo, 0.f), std::nextafter(lo, 2.f)});
    }
    for (int i = 0; i <= 1000000; ++i) ys.push_back(static_cast<float>(i) / 1000000.f);
    size_t checked = 0;
    for (float y : ys) {
        ASSERT_EQ(acc.srgb_code(y), reference_code(y)) << "y = " << y;
        ++checked;
    }
    EXPECT_GT(checked, 1000000u);
}

md::MapStats stats_for(int bit_depth, bool is_float, int channels) {
    mv::MapInput in;
    in.role = mf::Role::roughness;
    in.info = {4, 1, channels, bit_depth, is_float, "png", {}};
    return md::MapStats(in, in.info, mf::rules::Thresholds{});
}

TEST(StatsExact, IntegerFileMeansAreExactAndMatchTheFloatSum) {
    for (int depth : {8, 16}) {
        const double scale = depth == 8 ? 255.0 : 65535.0;
        md::MapStats s = stats_for(depth, false, 2);
        ASSERT_GT(s.code_scale, 0.f);
        // Codes 0..max in channel 0, max..0 in channel 1, over many bands of 4 pixels.
        const int max_code = depth == 8 ? 255 : 65535;
        long long sum0 = 0, count = 0;
        double float_sum = 0;
        for (int start = 0; start <= max_code; start += 4) {
            std::vector<float> band;
            for (int i = 0; i < 4; ++i) {
                const int k = std::min(start + i, max_code);
                band.push_back(static_cast<float>(k / scale));
                band.push_back(static_cast<float>((max_code - k) / scale));
                sum0 += k;
                float_sum += static_cast<float>(k / scale);
                ++count;
            }
            s.add_band(0, 1, band.data());
        }
        EXPECT_EQ(s.code_sum[0], sum0) << depth;
        EXPECT_EQ(s.finite[0], count);
        EXPECT_DOUBLE_EQ(s.mean(0), static_cast<double>(sum0) / scale / static_cast<double>(count));
        // Summing the floats instead carries their rounding (float k / 65535 is off by up to
        // 3e-8 relative); the code sum is the exact mean.
        EXPECT_NEAR(s.mean(0), float_sum / static_cast<double>(count), 1e-7);
        EXPECT_EQ(s.mean(0), 0.5);
        EXPECT_EQ(s.min[0], 0.0);
        EXPECT_EQ(s.max[0], 1.0);
        EXPECT_EQ(s.min[1], 0.0);
        EXPECT_EQ(s.max[1], 1.0);
    }
}

TEST(StatsExact, FloatFilesStillCountNonFiniteValues) {
    md::MapStats s = stats_for(32, true, 1);
    EXPECT_EQ(s.code_scale, 0.f);
    const float band[4] = {0.25f, std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                           0.75f};
    s.add_band(0, 1, band);
    EXPECT_EQ(s.nan, 1);
    EXPECT_EQ(s.inf, 1);
    EXPECT_EQ(s.finite[0], 2);
    EXPECT_DOUBLE_EQ(s.mean(0), 0.5);
    EXPECT_EQ(s.min[0], 0.25);
    EXPECT_EQ(s.max[0], 0.75);
}

}  // namespace
