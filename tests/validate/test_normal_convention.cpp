// The GL/DX detector on generated height→normal pairs: both conventions, with and without the
// height map, with noise, at several frequencies. Accuracy must reach 95 %.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>

#include "helpers.hpp"

using namespace mft;
namespace mv = mf::validate;

TEST(NormalConvention, AccuracyOverGeneratedPairs) {
    struct Tally {
        int n = 0, ok = 0;
    };
    Tally all, with_h, without_h;
    std::map<double, Tally> by_noise;
    std::map<double, Tally> by_freq;
    double min_conf_correct = 1.0;
    unsigned seed = 100;
    const int size = 128;
    auto run_pair = [&](const Image& h, NormalConvention conv, double freq, double slope, double noise) {
        const Image n = normal_from_height(h, conv, slope, noise, ++seed * 7);
        for (bool use_h : {true, false}) {
            const auto v = mv::detect_normal_convention(n, use_h ? &h : nullptr);
            const bool ok = v.convention == conv;
            for (Tally* t : {&all, use_h ? &with_h : &without_h, &by_noise[noise], &by_freq[freq]}) {
                ++t->n;
                t->ok += ok;
            }
            if (ok) min_conf_correct = std::min(min_conf_correct, v.confidence);
            if (!ok)
                std::printf("[ detector ] miss: freq %g slope %.2f noise %.2f conv %s height %d -> %s (%.2f)\n", freq,
                            slope, noise, std::string(mf::convention_name(conv)).c_str(), use_h,
                            std::string(mf::convention_name(v.convention)).c_str(), v.confidence);
            EXPECT_GE(v.confidence, 0.0);
            EXPECT_LE(v.confidence, 1.0);
        }
    };
    // Smooth isotropic heights at 2…48 cycles per image (period 64 px down to ~2.7 px), subtle
    // (RMS slope 0.15) and strong (0.6) bumps, 8-bit quantization plus Gaussian noise.
    for (double freq : {2.0, 8.0, 32.0, 48.0})
        for (double slope : {0.15, 0.6})
            for (double noise : {0.0, 0.03, 0.1})
                for (NormalConvention conv : {NormalConvention::gl, NormalConvention::dx})
                    run_pair(make_height(size, freq, seed), conv, freq, slope, noise);
    // Bricks (frequency = brick rows per image): slopes only on joints and corners.
    for (int rows : {4, 8, 16})
        for (double noise : {0.0, 0.03})
            for (NormalConvention conv : {NormalConvention::gl, NormalConvention::dx})
                run_pair(make_bricks(size, rows, seed), conv, rows, 0.6, noise);
    auto pct = [](const Tally& t) { return 100.0 * t.ok / std::max(1, t.n); };
    std::printf("[ detector ] %d pairs: accuracy %.1f %% (with height %.1f %% of %d, curl only %.1f %% of %d); "
                "lowest confidence when right %.2f\n",
                all.n, pct(all), pct(with_h), with_h.n, pct(without_h), without_h.n, min_conf_correct);
    for (const auto& [k, t] : by_noise) std::printf("[ detector ]   noise sigma %.2f: %.1f %%\n", k, pct(t));
    for (const auto& [k, t] : by_freq) std::printf("[ detector ]   frequency %g: %.1f %%\n", k, pct(t));
    EXPECT_GE(all.n, 40);
    std::fflush(stdout);
    EXPECT_GE(pct(all), 95.0);
}

TEST(NormalConvention, NoiseAndFlatMapsAreUnknown) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.3f, 0.7f);
    Image n(128, 128, 3);
    for (int y = 0; y < 128; ++y)
        for (int x = 0; x < 128; ++x) {
            n.at(x, y, 0) = u(rng);
            n.at(x, y, 1) = u(rng);
            n.at(x, y, 2) = 1.f;
        }
    auto v = mv::detect_normal_convention(n);
    EXPECT_EQ(v.convention, NormalConvention::unknown) << mf::to_json(v.figures).dump();
    const Image flat = constant(128, 128, {0.5f, 0.5f, 1.f});
    v = mv::detect_normal_convention(flat);
    EXPECT_EQ(v.convention, NormalConvention::unknown);
    EXPECT_EQ(v.confidence, 0.0);
    // Too small to vote.
    v = mv::detect_normal_convention(normal_from_height(make_height(8, 2, 1), NormalConvention::gl));
    EXPECT_EQ(v.convention, NormalConvention::unknown);
    EXPECT_EQ(v.method, "none");
}

// A height stored as depth (white = deep) flips both correlations: the relative sign decides,
// the verdict is the same as with the height, at no less confidence, and says the map is depth.
TEST(NormalConvention, DepthMapDecidesAsItsHeight) {
    unsigned seed = 500;
    for (const double freq : {4.0, 16.0})
        for (const NormalConvention conv : {NormalConvention::gl, NormalConvention::dx}) {
            const Image h = make_height(128, freq, ++seed);
            const Image n = normal_from_height(h, conv, 0.15, 0.03, ++seed);
            Image depth = h;
            for (float& v : depth.pixels) v = 1.f - v;
            const auto with_height = mv::detect_normal_convention(n, &h);
            const auto with_depth = mv::detect_normal_convention(n, &depth);
            SCOPED_TRACE(std::string(mf::convention_name(conv)) + " at " + std::to_string(freq));
            EXPECT_EQ(with_height.convention, conv) << mf::to_json(with_height.figures).dump();
            EXPECT_EQ(with_depth.convention, conv) << mf::to_json(with_depth.figures).dump();
            EXPECT_FALSE(with_height.height_is_depth);
            EXPECT_TRUE(with_depth.height_is_depth);
            EXPECT_NEAR(with_depth.confidence, with_height.confidence, 1e-9);
            EXPECT_EQ(with_depth.method, "height+curl");
        }
    // An unrelated map (noise) is no depth: no evidence either way.
    const Image n = normal_from_height(make_height(128, 8, 900), NormalConvention::gl);
    const Image unrelated = make_height(128, 8, 901);
    const auto other = mv::detect_normal_convention(n, &unrelated);
    EXPECT_FALSE(other.height_is_depth) << mf::to_json(other.figures).dump();
}

TEST(NormalConvention, HeightOfAnotherSizeAndTwoChannelMaps) {
    const Image h = make_height(128, 4, 11);
    const Image n = normal_from_height(h, NormalConvention::dx);
    // Height at half resolution (nearest-neighbour resampled inside).
    Image h2(64, 64, 1);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) h2.at(x, y) = h.at(2 * x, 2 * y);
    auto v = mv::detect_normal_convention(n, &h2);
    EXPECT_EQ(v.convention, NormalConvention::dx) << mf::to_json(v.figures).dump();
    // Two-channel (BC5-like) map: Z rebuilt from X and Y.
    Image rg(128, 128, 2);
    for (int y = 0; y < 128; ++y)
        for (int x = 0; x < 128; ++x) {
            rg.at(x, y, 0) = n.at(x, y, 0);
            rg.at(x, y, 1) = n.at(x, y, 1);
        }
    v = mv::detect_normal_convention(rg);
    EXPECT_EQ(v.convention, NormalConvention::dx) << mf::to_json(v.figures).dump();
}

TEST(NormalConvention, StreamingEqualsWholeImage) {
    const Image h = make_height(96, 6, 5);
    const Image n = normal_from_height(h, NormalConvention::gl, 0.5, 0.03, 9);
    const auto whole = mv::detect_normal_convention(n, &h);
    mv::NormalConventionDetector det(n.width, true);
    mv::NormalRow row;
    for (int y = 0; y < n.height; ++y) {
        mv::decode_normal_row(&n.pixels[n.index(0, y)], 3, n.width, false, row);
        det.add_row(row, &h.pixels[h.index(0, y)]);
    }
    const auto streamed = det.verdict();
    EXPECT_EQ(streamed.convention, whole.convention);
    EXPECT_DOUBLE_EQ(streamed.confidence, whole.confidence);
}
