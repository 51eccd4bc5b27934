// OpenColorIO conversions against the IEC 61966-2-1 formula, evaluated in double precision.
#include <gtest/gtest.h>

#include <cmath>

#include "base/srgb.hpp"
#include "color/color.hpp"
#include "image/image.hpp"
#include "test_color.hpp"

using mf::testcolor::color_context;

TEST(SrgbFormula, ReferencePoints) {
    // IEC 61966-2-1: the segments meet at 0.04045 (encoded) / 0.0031308 (linear).
    EXPECT_NEAR(mf::srgb_to_linear(0.04045), 0.04045 / 12.92, 1e-12);
    EXPECT_NEAR(mf::srgb_to_linear(0.5), 0.214041140482232, 1e-12);
    EXPECT_NEAR(mf::linear_to_srgb(0.214041140482232), 0.5, 1e-12);
    EXPECT_DOUBLE_EQ(mf::srgb_to_linear(1.0), 1.0);
    EXPECT_DOUBLE_EQ(mf::linear_to_srgb(0.0), 0.0);
    EXPECT_TRUE(std::isnan(mf::srgb_to_linear(std::nan(""))));
    EXPECT_NEAR(mf::srgb_to_linear(-0.5), -0.214041140482232, 1e-12);  // mirrored, not clamped
}

TEST(OcioColor, DecodeMatchesIecFormula) {
    auto c = color_context();
    ASSERT_TRUE(c);
    mf::Image img(1024, 1, 3);
    for (int i = 0; i < 1024; ++i)
        for (int k = 0; k < 3; ++k) img.at(i, 0, k) = static_cast<float>(i) / 1023.f;
    c->convert(img, mf::ColorEncoding::srgb, mf::ColorEncoding::linear);
    double max_err = 0;
    for (int i = 0; i < 1024; ++i) {
        const double ref = mf::srgb_to_linear(static_cast<double>(static_cast<float>(i) / 1023.f));
        max_err = std::max(max_err, std::abs(img.at(i, 0, 1) - ref));
    }
    EXPECT_LT(max_err, 2e-6) << "max abs error vs IEC 61966-2-1";
}

// OpenColorIO's ExponentWithLinearTransform derives the linear slope for continuity (12.9232)
// where IEC 61966-2-1 states 12.92: encoded values differ by up to ~1e-5 just above the break,
// 0.003 of an 8-bit code and under one 16-bit code.
TEST(OcioColor, EncodeMatchesIecFormula) {
    auto c = color_context();
    ASSERT_TRUE(c);
    std::vector<float> rgb;
    for (int i = 0; i <= 1000; ++i) {
        const float v = static_cast<float>(i) / 1000.f;
        rgb.insert(rgb.end(), {v, v, v});
    }
    c->convert(rgb.data(), 1001, mf::ColorEncoding::linear, mf::ColorEncoding::srgb);
    for (int i = 0; i <= 1000; ++i)
        EXPECT_NEAR(rgb[static_cast<size_t>(i) * 3],
                    mf::linear_to_srgb(static_cast<double>(static_cast<float>(i) / 1000.f)), 1.2e-5)
            << i;
}

TEST(OcioColor, EightBitRoundTripIsExact) {
    // Every sRGB code decoded to linear float and encoded again lands on the same code.
    auto c = color_context();
    ASSERT_TRUE(c);
    mf::Image img(256, 1, 3);
    for (int i = 0; i < 256; ++i)
        for (int k = 0; k < 3; ++k) img.at(i, 0, k) = static_cast<float>(i) / 255.f;
    c->convert(img, mf::ColorEncoding::srgb, mf::ColorEncoding::linear);
    c->convert(img, mf::ColorEncoding::linear, mf::ColorEncoding::srgb);
    for (int i = 0; i < 256; ++i) EXPECT_EQ(mf::quantize(img.at(i, 0, 0), 8), i);
}

TEST(OcioColor, SixteenBitEncodeWithinOneCode) {
    auto c = color_context();
    ASSERT_TRUE(c);
    std::vector<float> rgb;
    for (int i = 0; i <= 4096; ++i) {
        const float v = static_cast<float>(i) / 4096.f;
        rgb.insert(rgb.end(), {v, v, v});
    }
    c->convert(rgb.data(), 4097, mf::ColorEncoding::linear, mf::ColorEncoding::srgb);
    for (int i = 0; i <= 4096; ++i) {
        const int ref = mf::quantize(static_cast<float>(mf::linear_to_srgb(i / 4096.0)), 16);
        EXPECT_LE(std::abs(mf::quantize(rgb[static_cast<size_t>(i) * 3], 16) - ref), 1) << i;
    }
}

TEST(OcioColor, AlphaUntouched) {
    auto c = color_context();
    ASSERT_TRUE(c);
    mf::Image img(1, 1, 4);
    img.pixels = {0.5f, 0.5f, 0.5f, 0.25f};
    c->convert(img, mf::ColorEncoding::srgb, mf::ColorEncoding::linear);
    EXPECT_FLOAT_EQ(img.pixels[3], 0.25f);
    EXPECT_NEAR(img.pixels[0], 0.2140411, 1e-6);
}

TEST(OcioColor, HonorsOcioEnvironmentVariable) {
    // A config without an sRGB texture space is a configuration error naming the file.
    const std::string path = ::testing::TempDir() + "/bad.ocio";
    FILE* f = std::fopen(path.c_str(), "w");
    ASSERT_TRUE(f);
    std::fputs("ocio_profile_version: 2\nroles:\n  default: raw\n  scene_linear: raw\ncolorspaces:\n"
               "  - !<ColorSpace>\n    name: raw\n    isdata: true\n",
               f);
    std::fclose(f);
    ::setenv("OCIO", path.c_str(), 1);
    std::string err;
    auto c = mf::ColorContext::create(err);
    ::unsetenv("OCIO");
    EXPECT_FALSE(c);
    EXPECT_NE(err.find("bad.ocio"), std::string::npos) << err;
}
