// Packing, gloss and normal conversions round-tripping at the boundaries: values 0 and 1,
// codes 0 and 255 (0 and 65535), axis-aligned, grazing and Z ≈ 0 normals, DX ↔ GL twice.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "pack/pack.hpp"
#include "stability_util.hpp"

namespace {

using mf::NormalConvention;
using mf::stability::color_context;
using mf::stability::encode_and_read;

TEST(GlossRoundTrip, EveryEightBitCodeInvertsExactly) {
    // gloss code k → roughness 1 − k/255 → code 255 − k, and back to k: no drift at 0 or 255.
    for (int k = 0; k <= 255; ++k) {
        mf::Image img(1, 1, 1);
        img.pixels[0] = static_cast<float>(k) / 255.f;
        mf::invert(img);
        ASSERT_EQ(mf::quantize(img.pixels[0], 8), 255 - k) << k;
        mf::invert(img);
        ASSERT_EQ(mf::quantize(img.pixels[0], 8), k) << k;
    }
}

TEST(GlossRoundTrip, SixteenBitCodesInvertExactly) {
    for (int k = 0; k <= 65535; ++k) {
        const float r = 1.f - static_cast<float>(k) / 65535.f;
        ASSERT_EQ(mf::quantize(r, 16), 65535 - k) << k;
    }
}

TEST(GlossRoundTrip, SmoothnessChannelThroughPresetAndFile) {
    // Roughness 0 and 1 (and two interior codes) into Unity HDRP's MaskMap A = smoothness, PNG,
    // read back, inverted again: the original codes.
    std::string err;
    auto preset = mf::load_preset("unity-hdrp", err);
    ASSERT_TRUE(preset) << err;
    const mf::OutputSpec* mask = nullptr;
    for (const auto& o : preset->outputs)
        if (o.suffix == "MaskMap") mask = &o;
    ASSERT_TRUE(mask);
    mf::Planes planes;
    planes[mf::Role::roughness].image = mf::Image(4, 1, 1);
    planes[mf::Role::roughness].image.pixels = {0.f, 1.f, 1.f / 255.f, 254.f / 255.f};
    planes[mf::Role::metalness].image = mf::Image(4, 1, 1);
    planes[mf::Role::metalness].image.pixels = {0.f, 1.f, 0.f, 1.f};
    const auto out = mf::pack_output(*mask, planes, *preset, {4, 1}, *color_context());
    const mf::Image back = encode_and_read(out, {mf::FileFormat::png, 8});
    ASSERT_EQ(back.channels, 4);
    const int expected_smooth[] = {255, 0, 254, 1};
    const int expected_metal[] = {0, 255, 0, 255};
    for (int x = 0; x < 4; ++x) {
        EXPECT_EQ(mf::quantize(back.at(x, 0, 3), 8), expected_smooth[x]) << x;
        EXPECT_EQ(mf::quantize(1.f - back.at(x, 0, 3), 8),
                  mf::quantize(planes[mf::Role::roughness].image.pixels[static_cast<size_t>(x)], 8));
        EXPECT_EQ(mf::quantize(back.at(x, 0, 0), 8), expected_metal[x]) << x;
    }
}

TEST(PackRoundTrip, OrmBoundaryCodesSurviveEightAndSixteenBit) {
    std::string err;
    auto preset = mf::load_preset("gltf", err);
    ASSERT_TRUE(preset) << err;
    const mf::OutputSpec* orm = nullptr;
    for (const auto& o : preset->outputs)
        if (o.suffix == "orm") orm = &o;
    ASSERT_TRUE(orm);
    mf::Planes planes;
    const std::vector<float> values = {0.f, 1.f, 1.f / 255.f, 254.f / 255.f, 0.5f, -0.1f, 1.1f};
    for (mf::Role r : {mf::Role::occlusion, mf::Role::roughness, mf::Role::metalness}) {
        planes[r].image = mf::Image(static_cast<int>(values.size()), 1, 1);
        planes[r].image.pixels = values;
    }
    // Metalness reversed so the channels differ.
    std::reverse(planes[mf::Role::metalness].image.pixels.begin(), planes[mf::Role::metalness].image.pixels.end());
    const auto out = mf::pack_output(*orm, planes, *preset, {static_cast<int>(values.size()), 1}, *color_context());
    for (int bits : {8, 16}) {
        const mf::Image back = encode_and_read(out, {mf::FileFormat::png, bits});
        ASSERT_EQ(back.channels, 3);
        for (int x = 0; x < out.width; ++x)
            for (int c = 0; c < 3; ++c) {
                const float src = out.at(x, 0, c);
                EXPECT_EQ(mf::quantize(back.at(x, 0, c), bits), mf::quantize(src, bits)) << x << " " << c;
                if (src == 0.f || src == 1.f) {
                    EXPECT_EQ(back.at(x, 0, c), src) << "0 and 1 exact";
                }
            }
    }
}

// Unit GL vectors at the boundaries: axis-aligned (±X, ±Y, +Z), grazing (Z = 0 and Z = 1e-7),
// below the surface (Z < 0: invalid in tangent space, still defined), diagonals.
std::vector<std::array<float, 3>> boundary_normals() {
    std::vector<std::array<float, 3>> v = {{0, 0, 1},  {1, 0, 0},  {-1, 0, 0},    {0, 1, 0},
                                           {0, -1, 0}, {0, 0, -1}, {1, 0, 1e-7f}, {0, -1, 1e-7f}};
    for (int i = 0; i < 16; ++i) {  // around the horizon and at 45°
        const double phi = i * std::numbers::pi / 8.0;
        for (double theta : {std::numbers::pi / 2.0, std::numbers::pi / 4.0, 1e-3})
            v.push_back({static_cast<float>(std::sin(theta) * std::cos(phi)),
                         static_cast<float>(std::sin(theta) * std::sin(phi)), static_cast<float>(std::cos(theta))});
    }
    return v;
}

mf::Image vectors_image(const std::vector<std::array<float, 3>>& v) {
    mf::Image img(static_cast<int>(v.size()), 1, 3);
    for (size_t i = 0; i < v.size(); ++i)
        for (size_t c = 0; c < 3; ++c) img.pixels[i * 3 + c] = v[i][c];
    return img;
}

TEST(NormalRoundTrip, EncodeDecodeWithinOneCode) {
    const auto dirs = boundary_normals();
    const mf::Image unit = vectors_image(dirs);
    for (NormalConvention conv : {NormalConvention::gl, NormalConvention::dx}) {
        const mf::Image enc = mf::encode_normal(unit, conv);
        for (float c : enc.pixels) {
            EXPECT_GE(c, 0.f);
            EXPECT_LE(c, 1.f);
        }
        // Through an 8-bit file and back.
        const mf::Image back = encode_and_read(enc, {mf::FileFormat::png, 8});
        mf::Image dec;
        mf::decode_normal(back, conv, dec);
        const mf::Image re = mf::encode_normal(dec, conv);
        for (size_t i = 0; i < enc.pixels.size(); ++i)
            EXPECT_LE(std::abs(mf::quantize(re.pixels[i], 8) - mf::quantize(enc.pixels[i], 8)), 1) << i;
        // The decoded directions are within one code's angle of the originals (8 bits: 2/255
        // per component, ≈ 0.5° … 0.7°); axis-aligned ones are exact.
        for (size_t i = 0; i < dirs.size(); ++i) {
            const double d = dirs[i][0] * dec.pixels[i * 3] + dirs[i][1] * dec.pixels[i * 3 + 1] +
                             dirs[i][2] * dec.pixels[i * 3 + 2];
            EXPECT_GT(d, std::cos(1.2 * std::numbers::pi / 180.0)) << i;
        }
    }
}

TEST(NormalRoundTrip, DxToGlTwiceIsIdentityWithinACode) {
    // All 8-bit codes of unit vectors on a dense grid, DX → GL → DX → GL → DX.
    std::vector<std::array<float, 3>> dirs = boundary_normals();
    for (int i = 0; i <= 32; ++i)
        for (int j = 0; j <= 32; ++j) {
            const double x = i / 16.0 - 1.0, y = j / 16.0 - 1.0, r2 = x * x + y * y;
            if (r2 <= 1.0) dirs.push_back({float(x), float(y), float(std::sqrt(1.0 - r2))});
        }
    const mf::Image dx_codes = encode_and_read(mf::encode_normal(vectors_image(dirs), NormalConvention::dx),
                                               {mf::FileFormat::png, 8});
    mf::Image cur = dx_codes;
    for (int round = 0; round < 2; ++round) {
        mf::Image n;
        mf::decode_normal(cur, NormalConvention::dx, n);
        const mf::Image gl = encode_and_read(mf::encode_normal(n, NormalConvention::gl), {mf::FileFormat::png, 8});
        mf::decode_normal(gl, NormalConvention::gl, n);
        cur = encode_and_read(mf::encode_normal(n, NormalConvention::dx), {mf::FileFormat::png, 8});
    }
    int worst = 0;
    for (size_t i = 0; i < cur.pixels.size(); ++i)
        worst = std::max(worst, std::abs(mf::quantize(cur.pixels[i], 8) - mf::quantize(dx_codes.pixels[i], 8)));
    EXPECT_LE(worst, 1) << "codes drift by more than one after two DX↔GL round trips";
    // Green flips exactly: GL code g ↔ DX code 255 − g for the flat normal's neighbours.
    mf::Image flat(1, 1, 3);
    flat.pixels = {0.f, 0.f, 1.f};
    EXPECT_EQ(mf::quantize(mf::encode_normal(flat, NormalConvention::dx).pixels[1], 8), 128);
    EXPECT_EQ(mf::quantize(mf::encode_normal(flat, NormalConvention::gl).pixels[1], 8), 128);
}

TEST(NormalRoundTrip, DegenerateInputsGiveDefinedNormals) {
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    // Encoded: exact zero vector, NaN, Inf, all-zero code (−1,−1,−1), Z ≈ 0 code.
    mf::Image enc(5, 1, 3);
    enc.pixels = {0.5f, 0.5f, 0.5f, nan, 0.5f, 1.f, inf, 0.5f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.5f, 0.5f};
    mf::Image n;
    const double bad = mf::decode_normal(enc, NormalConvention::gl, n);
    for (float v : n.pixels) EXPECT_TRUE(std::isfinite(v));
    EXPECT_EQ(n.at(0, 0, 2), 1.f);                             // zero length → flat
    EXPECT_EQ(n.at(1, 0, 2), 1.f);                             // NaN → flat
    EXPECT_EQ(n.at(2, 0, 2), 1.f);                             // Inf → flat
    EXPECT_NEAR(n.at(3, 0, 2), -1.f / std::sqrt(3.f), 1e-6f);  // below the surface, reported
    EXPECT_NEAR(n.at(4, 0, 0), 1.f, 1e-6f);                    // grazing +X, Z = 0 exactly
    EXPECT_EQ(n.at(4, 0, 2), 0.f);
    EXPECT_NEAR(bad, 4.0 / 5.0, 1e-9);  // all but the grazing unit vector are off
    // Vectors: NaN, zero, Inf and tiny ones through renormalize and encode_normal.
    mf::Image v(4, 1, 3);
    v.pixels = {nan, 0.f, 1.f, 0.f, 0.f, 0.f, inf, inf, 0.f, 1e-20f, 0.f, 0.f};
    mf::Image r = v;
    mf::renormalize(r);
    for (int x = 0; x < 4; ++x) EXPECT_EQ(r.at(x, 0, 2), 1.f) << x;
    const mf::Image e = mf::encode_normal(v, NormalConvention::dx);
    for (int x = 0; x < 4; ++x) {
        EXPECT_EQ(mf::quantize(e.at(x, 0, 0), 8), 128);
        EXPECT_EQ(mf::quantize(e.at(x, 0, 1), 8), 128);
        EXPECT_EQ(mf::quantize(e.at(x, 0, 2), 8), 255);
    }
}

TEST(NormalRoundTrip, TwoChannelOutsideUnitDisc) {
    // BC5-style input whose XY lies outside the unit disc: Z = 0, the vector renormalized.
    mf::Image enc(3, 1, 2);
    enc.pixels = {1.f, 1.f, 0.f, 0.f, 0.5f, 1.f};
    mf::Image n;
    mf::decode_normal(enc, NormalConvention::gl, n);
    EXPECT_NEAR(n.at(0, 0, 0), std::sqrt(0.5f), 1e-6f);
    EXPECT_EQ(n.at(0, 0, 2), 0.f);
    EXPECT_NEAR(n.at(1, 0, 1), -std::sqrt(0.5f), 1e-6f);
    EXPECT_NEAR(n.at(2, 0, 1), 1.f, 1e-6f);
    for (float x : n.pixels) EXPECT_TRUE(std::isfinite(x));
}

TEST(NormalRoundTrip, SixteenBitIsTighter) {
    const auto dirs = boundary_normals();
    const mf::Image enc = mf::encode_normal(vectors_image(dirs), NormalConvention::gl);
    const mf::Image back = encode_and_read(enc, {mf::FileFormat::png, 16});
    mf::Image dec;
    mf::decode_normal(back, NormalConvention::gl, dec);
    for (size_t i = 0; i < dirs.size(); ++i) {
        const double d = dirs[i][0] * dec.pixels[i * 3] + dirs[i][1] * dec.pixels[i * 3 + 1] +
                         dirs[i][2] * dec.pixels[i * 3 + 2];
        EXPECT_GT(d, std::cos(0.05 * std::numbers::pi / 180.0)) << i;  // float dot resolution
    }
}

}  // namespace
