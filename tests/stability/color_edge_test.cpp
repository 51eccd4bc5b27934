// Colour transforms at the edges: 0, 1, negatives, NaN, ±Inf, denormals and values above 1,
// through the exact IEC 61966-2-1 functions (lib/base/srgb.hpp) and the OpenColorIO context,
// then through pack_output + quantize to the codes a file gets.
//
// Intended behaviour (what the assertions pin down):
//  - 0 → 0 and 1 → 1 exactly (8-bit codes 0 and 255 survive any round trip);
//  - finite in → finite out wherever the result is representable: encoding never overflows;
//    decoding a finite value overflows only past ~1e15 (the true result exceeds float);
//  - both directions are monotonic over negatives, denormals, [0, 1] and above 1, and keep the
//    sign (negatives come from filter ringing and must not flip to bright values);
//  - NaN passes through as NaN (no exception, no crash) and ±Inf stays ±Inf;
//  - quantize gives defined codes: NaN → 0, −Inf and negatives → 0, +Inf and > 1 → max.
// The two implementations differ by design on negatives: srgb.hpp mirrors the curve
// (f(−x) = −f(x)); OpenColorIO's ExponentWithLinearTransform continues the linear segment
// (NEGATIVE_LINEAR, its default; slope 12.9232, derived for continuity). Both are monotonic and sign-preserving, and
// both quantize negatives to code 0, so no output file differs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "base/srgb.hpp"
#include "color/color.hpp"
#include "image/image.hpp"
#include "pack/pack.hpp"
#include "preset/preset.hpp"
#include "test_color.hpp"

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kDenorm = std::numeric_limits<float>::denorm_min();

std::shared_ptr<const mf::ColorContext> ctx() { return mf::testcolor::color_context(); }

// A sorted sweep from −1e6 to 1e6 through denormals, the segment breaks, 0 and 1.
std::vector<float> sweep() {
    std::vector<float> v;
    for (float m = 1e6f; m >= 1e-6f; m /= 1.37f) v.push_back(-m);
    v.insert(v.end(), {-1e-30f, -std::numeric_limits<float>::min(), -kDenorm * 1000, -kDenorm, -0.f, 0.f, kDenorm,
                       kDenorm * 1000, std::numeric_limits<float>::min(), 1e-30f});
    for (float m = 1e-6f; m <= 1e6f; m *= 1.37f) v.push_back(m);
    for (float x : {0.0031308f, 0.04045f, 0.5f, 0.99999994f, 1.f, 1.0000001f, 2.f}) v.push_back(x);
    std::sort(v.begin(), v.end());
    return v;
}

std::vector<float> ocio(const mf::ColorContext& c, std::vector<float> in, mf::ColorEncoding from,
                        mf::ColorEncoding to) {
    std::vector<float> rgb;
    for (float x : in) rgb.insert(rgb.end(), {x, x, x});
    c.convert(rgb.data(), in.size(), from, to);
    std::vector<float> out;
    for (size_t i = 0; i < in.size(); ++i) {
        // Channels independent and identical (NaN in all three where the input is NaN).
        for (size_t ch = 1; ch < 3; ++ch) {
            if (std::isnan(rgb[i * 3])) {
                EXPECT_TRUE(std::isnan(rgb[i * 3 + ch]));
            } else {
                EXPECT_EQ(rgb[i * 3], rgb[i * 3 + ch]);
            }
        }
        out.push_back(rgb[i * 3]);
    }
    return out;
}

template <class F>
void expect_monotonic_sign_preserving(const std::vector<float>& in, F f, const char* what) {
    float prev = -kInf;
    for (float x : in) {
        const float y = f(x);
        ASSERT_FALSE(std::isnan(y)) << what << "(" << x << ")";
        EXPECT_GE(y, prev) << what << " not monotonic at " << x;
        if (x > 0.f) {
            EXPECT_GE(y, 0.f) << what << "(" << x << ")";
        }
        if (x < 0.f) {
            EXPECT_LE(y, 0.f) << what << "(" << x << ")";
        }
        if (std::abs(x) <= 1e15f) {
            EXPECT_TRUE(std::isfinite(y)) << what << "(" << x << ") = " << y;
        }
        prev = y;
    }
}

TEST(ColorEdges, ExactFunctionsFixedPoints) {
    EXPECT_EQ(mf::srgb_to_linear(0.f), 0.f);
    EXPECT_EQ(mf::srgb_to_linear(1.f), 1.f);
    EXPECT_EQ(mf::linear_to_srgb(0.f), 0.f);
    EXPECT_NEAR(mf::linear_to_srgb(1.f), 1.f, 1e-7f);
    EXPECT_TRUE(std::signbit(mf::srgb_to_linear(-0.f)));  // −0 stays −0
    // Denormals stay on the linear segment: exact scaling, no flush to a wrong value.
    EXPECT_EQ(mf::linear_to_srgb(kDenorm * 1000), kDenorm * 1000 * 12.92f);
    EXPECT_GE(mf::srgb_to_linear(kDenorm), 0.f);
    EXPECT_LE(mf::srgb_to_linear(kDenorm), kDenorm);
    // Above 1 the curve continues (HDR emissive in a float file).
    EXPECT_NEAR(mf::srgb_to_linear(2.0), std::pow(2.055 / 1.055, 2.4), 1e-12);
    EXPECT_GT(mf::linear_to_srgb(2.f), 1.f);
}

TEST(ColorEdges, ExactFunctionsNanInf) {
    EXPECT_TRUE(std::isnan(mf::srgb_to_linear(kNaN)));
    EXPECT_TRUE(std::isnan(mf::linear_to_srgb(kNaN)));
    EXPECT_EQ(mf::srgb_to_linear(kInf), kInf);
    EXPECT_EQ(mf::srgb_to_linear(-kInf), -kInf);
    EXPECT_EQ(mf::linear_to_srgb(kInf), kInf);
    EXPECT_EQ(mf::linear_to_srgb(-kInf), -kInf);
}

TEST(ColorEdges, ExactFunctionsMonotonicEverywhere) {
    const auto in = sweep();
    expect_monotonic_sign_preserving(
        in, [](float x) { return mf::srgb_to_linear(x); }, "srgb_to_linear");
    expect_monotonic_sign_preserving(
        in, [](float x) { return mf::linear_to_srgb(x); }, "linear_to_srgb");
    // Encoding never overflows: even the largest float encodes to a finite value.
    EXPECT_TRUE(std::isfinite(mf::linear_to_srgb(std::numeric_limits<float>::max())));
    // Mirrored: f(−x) = −f(x) exactly.
    for (float x : in) EXPECT_EQ(mf::srgb_to_linear(-x), -mf::srgb_to_linear(x));
}

TEST(ColorEdges, OcioFixedPointsAndSpecials) {
    auto c = ctx();
    ASSERT_TRUE(c);
    for (auto [from, to] : {std::pair{mf::ColorEncoding::srgb, mf::ColorEncoding::linear},
                            std::pair{mf::ColorEncoding::linear, mf::ColorEncoding::srgb}}) {
        const auto out = ocio(*c, {0.f, 1.f, kNaN, kInf, -kInf}, from, to);
        EXPECT_EQ(out[0], 0.f);
        EXPECT_NEAR(out[1], 1.f, 6e-8f);          // 1 → 1 within one float ulp
        EXPECT_EQ(mf::quantize(out[1], 8), 255);  // and the code survives
        EXPECT_EQ(mf::quantize(out[1], 16), 65535);
        EXPECT_TRUE(std::isnan(out[2])) << "NaN passes through (no exception)";
        EXPECT_EQ(out[3], kInf);
        EXPECT_EQ(out[4], -kInf);
    }
}

TEST(ColorEdges, OcioMonotonicSignPreservingFinite) {
    auto c = ctx();
    ASSERT_TRUE(c);
    const auto in = sweep();
    const auto dec = ocio(*c, in, mf::ColorEncoding::srgb, mf::ColorEncoding::linear);
    const auto enc = ocio(*c, in, mf::ColorEncoding::linear, mf::ColorEncoding::srgb);
    size_t i = 0;
    expect_monotonic_sign_preserving(
        in, [&](float) { return dec[i++]; }, "OCIO decode");
    i = 0;
    expect_monotonic_sign_preserving(
        in, [&](float) { return enc[i++]; }, "OCIO encode");
    // In [0, 1] and above, OCIO agrees with the IEC formula; negatives: linear segment (by design).
    for (size_t k = 0; k < in.size(); ++k) {
        const double x = in[k];
        if (x >= 0.0 && x <= 4.0) {
            EXPECT_NEAR(dec[k], mf::srgb_to_linear(x), 2e-6 * std::max(1.0, mf::srgb_to_linear(x))) << x;
        }
        // OpenColorIO derives the linear slope for continuity: 12.9232 rather than 12.92.
        if (x < 0.0 && x > -1.0) {
            EXPECT_NEAR(dec[k], x / 12.9232, 1e-5 * std::abs(x) + 1e-30) << x;
        }
    }
}

TEST(ColorEdges, OcioGreyPathHandlesSpecials) {
    // One-channel images take the per-sample path of ColorContext::convert.
    auto c = ctx();
    ASSERT_TRUE(c);
    mf::Image img(6, 1, 1);
    img.pixels = {0.f, 1.f, -0.25f, kNaN, kInf, kDenorm};
    c->convert(img, mf::ColorEncoding::srgb, mf::ColorEncoding::linear);
    EXPECT_EQ(img.pixels[0], 0.f);
    EXPECT_EQ(img.pixels[1], 1.f);
    EXPECT_LT(img.pixels[2], 0.f);
    EXPECT_TRUE(std::isnan(img.pixels[3]));
    EXPECT_EQ(img.pixels[4], kInf);
    EXPECT_TRUE(std::isfinite(img.pixels[5]));
}

TEST(ColorEdges, QuantizeDefinedCodes) {
    for (int bits : {8, 16}) {
        const uint16_t maxc = bits == 8 ? 255 : 65535;
        EXPECT_EQ(mf::quantize(kNaN, bits), 0);
        EXPECT_EQ(mf::quantize(-kNaN, bits), 0);
        EXPECT_EQ(mf::quantize(-kInf, bits), 0);
        EXPECT_EQ(mf::quantize(-1e30f, bits), 0);
        EXPECT_EQ(mf::quantize(-0.f, bits), 0);
        EXPECT_EQ(mf::quantize(kDenorm, bits), 0);
        EXPECT_EQ(mf::quantize(kInf, bits), maxc);
        EXPECT_EQ(mf::quantize(1e30f, bits), maxc);
        EXPECT_EQ(mf::quantize(1.0000001f, bits), maxc);
        EXPECT_EQ(mf::quantize(1.f, bits), maxc);
        EXPECT_EQ(mf::quantize(0.99999994f, bits), maxc);
        // Round half up at every code boundary, and every code reproduces itself.
        for (int k = 0; k <= maxc; k += bits == 8 ? 1 : 257) {
            EXPECT_EQ(mf::quantize(static_cast<float>(k) / maxc, bits), k);
        }
    }
    EXPECT_EQ(mf::quantize(0.5f / 255.f, 8), 1);
    EXPECT_EQ(mf::quantize(0.49f / 255.f, 8), 0);
}

// Albedo planes holding the edge values, packed by the glTF preset (basecolor is sRGB) and
// encoded to 8 and 16 bit: every value lands on a defined code.
TEST(ColorEdges, PackOutputGivesDefinedCodes) {
    auto c = ctx();
    ASSERT_TRUE(c);
    std::string err;
    auto preset = mf::load_preset("gltf", err);
    ASSERT_TRUE(preset) << err;
    const mf::OutputSpec* base = nullptr;
    for (const auto& o : preset->outputs)
        if (o.suffix == "basecolor") base = &o;
    ASSERT_TRUE(base);
    const std::vector<float> values = {0.f, 1.f, -0.5f, kNaN, kInf, -kInf, kDenorm, 4.f, 0.5f};
    // Expected 8-bit codes: NaN → 0, negatives → 0, > 1 → 255; 0.5 linear → sRGB 188.
    const std::vector<int> expected8 = {0, 255, 0, 0, 255, 0, 0, 255, 188};
    for (auto enc : {mf::ColorEncoding::linear, mf::ColorEncoding::srgb}) {
        mf::Planes planes;
        mf::RolePlane p;
        p.encoding = enc;
        p.image = mf::Image(static_cast<int>(values.size()), 1, 3);
        for (size_t i = 0; i < values.size(); ++i)
            for (int k = 0; k < 3; ++k) p.image.pixels[i * 3 + static_cast<size_t>(k)] = values[i];
        planes[mf::Role::albedo] = p;
        const mf::Image out = mf::pack_output(*base, planes, *preset, {p.image.width, 1}, *c);
        ASSERT_EQ(out.width, p.image.width);
        for (size_t i = 0; i < values.size(); ++i) {
            const float v = out.pixels[i * static_cast<size_t>(out.channels)];
            const int code = mf::quantize(v, 8);
            if (enc == mf::ColorEncoding::linear) {
                EXPECT_EQ(code, expected8[i]) << "linear value " << values[i];
            } else {  // already sRGB: copied, quantized directly
                const int direct = mf::quantize(values[i], 8);
                EXPECT_EQ(code, direct) << "sRGB value " << values[i];
            }
            EXPECT_LE(mf::quantize(v, 16), 65535);
        }
        // And the bytes encode without error.
        std::vector<unsigned char> bytes;
        std::string e;
        for (int bits : {8, 16}) {
            EXPECT_TRUE(mf::encode_image(out, {mf::FileFormat::png, bits}, bytes, e)) << e;
            EXPECT_FALSE(bytes.empty());
        }
    }
}

}  // namespace
