// Degenerate and odd image sizes (1×1, 1×N, N×1, odd × odd) through every step of a conversion:
// decode_normal, resample, fit_plane, pack_output (every glTF output), encode_image and the
// read-back. Each step must keep the size it promises, stay finite, keep unit normals unit and
// keep constants constant (a filter's weights sum to one at the borders too).
#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

#include "base/srgb.hpp"
#include "pack/pack.hpp"
#include "stability_util.hpp"

namespace {

using mf::stability::color_context;
using mf::stability::encode_and_read;

struct Dim {
    int w, h;
};
const Dim kSizes[] = {{1, 1}, {1, 2}, {2, 1}, {1, 7}, {7, 1}, {3, 5}, {5, 3}, {17, 9}, {1, 33}};

// Deterministic values in [0, 1] (no RNG state to share between tests).
float hash01(int x, int y, int c) {
    uint32_t h = static_cast<uint32_t>(x) * 73856093u ^ static_cast<uint32_t>(y) * 19349663u ^
                 static_cast<uint32_t>(c + 1) * 83492791u;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return static_cast<float>(h & 0xffffu) / 65535.f;
}

mf::Image pattern(Dim d, int channels) {
    mf::Image img(d.w, d.h, channels);
    for (int y = 0; y < d.h; ++y)
        for (int x = 0; x < d.w; ++x)
            for (int c = 0; c < channels; ++c) img.at(x, y, c) = hash01(x, y, c);
    return img;
}

// An encoded normal map whose texels are unit vectors tilted up to ~60°.
mf::Image normal_pattern(Dim d) {
    mf::Image img(d.w, d.h, 3);
    for (int y = 0; y < d.h; ++y)
        for (int x = 0; x < d.w; ++x) {
            const float nx = hash01(x, y, 0) * 1.6f - 0.8f, ny = hash01(x, y, 1) * 1.0f - 0.5f;
            const float nz = std::sqrt(std::max(0.05f, 1.f - nx * nx - ny * ny));
            const float len = std::sqrt(nx * nx + ny * ny + nz * nz);
            img.at(x, y, 0) = nx / len * 0.5f + 0.5f;
            img.at(x, y, 1) = ny / len * 0.5f + 0.5f;
            img.at(x, y, 2) = nz / len * 0.5f + 0.5f;
        }
    return img;
}

void expect_all_finite(const mf::Image& img, const char* what) {
    size_t bad = 0;
    for (float v : img.pixels) bad += !std::isfinite(v);
    EXPECT_EQ(bad, 0u) << what << " " << img.width << "x" << img.height;
}

void expect_unit(const mf::Image& n, const char* what) {
    ASSERT_EQ(n.channels, 3);
    for (size_t i = 0; i < n.pixels.size(); i += 3) {
        const double len = std::sqrt(double{n.pixels[i]} * n.pixels[i] + double{n.pixels[i + 1]} * n.pixels[i + 1] +
                                     double{n.pixels[i + 2]} * n.pixels[i + 2]);
        ASSERT_NEAR(len, 1.0, 1e-5) << what << " " << n.width << "x" << n.height << " texel " << i / 3;
    }
}

std::vector<Dim> targets(Dim d) {
    return {{d.w, d.h},   {1, 1}, {2 * d.w + 1, 2 * d.h + 1}, {(d.w + 1) / 2, (d.h + 1) / 2}, {1, d.h}, {d.w, 1},
            {d.w + 2, 1}, {3, 3}};
}

TEST(OddSizes, DecodeNormalKeepsSizeAndUnitLength) {
    for (Dim d : kSizes) {
        for (int channels : {2, 3, 4}) {
            mf::Image enc = normal_pattern(d);
            if (channels != 3) {
                mf::Image e(d.w, d.h, channels, 1.f);
                for (int y = 0; y < d.h; ++y)
                    for (int x = 0; x < d.w; ++x)
                        for (int c = 0; c < std::min(channels, 3); ++c) e.at(x, y, c) = enc.at(x, y, c);
                enc = e;
            }
            mf::Image n;
            const double bad = mf::decode_normal(enc, mf::NormalConvention::dx, n);
            EXPECT_EQ(n.width, d.w);
            EXPECT_EQ(n.height, d.h);
            EXPECT_GE(bad, 0.0);
            EXPECT_LE(bad, 1.0);
            expect_unit(n, "decode_normal");
        }
    }
}

TEST(OddSizes, ResampleKeepsConstantsAndFiniteness) {
    for (Dim d : kSizes)
        for (Dim t : targets(d)) {
            // A constant stays that constant (weights normalized at the borders too).
            const mf::Image flat(d.w, d.h, 3, 0.25f);
            const mf::Image r = mf::resample(flat, t.w, t.h);
            ASSERT_EQ(r.width, t.w);
            ASSERT_EQ(r.height, t.h);
            ASSERT_EQ(r.channels, 3);
            for (float v : r.pixels) ASSERT_NEAR(v, 0.25f, 1e-6f) << d.w << "x" << d.h << " -> " << t.w << "x" << t.h;
            // A pattern stays finite and within Lanczos-3's overshoot of its range.
            const mf::Image p = mf::resample(pattern(d, 1), t.w, t.h);
            expect_all_finite(p, "resample");
            for (float v : p.pixels) {
                EXPECT_GE(v, -0.25f);
                EXPECT_LE(v, 1.25f);
            }
        }
}

TEST(OddSizes, FitPlaneEveryRole) {
    auto ctx = color_context();
    ASSERT_TRUE(ctx);
    for (Dim d : kSizes)
        for (Dim t : targets(d)) {
            mf::RolePlane albedo{pattern(d, 3), mf::ColorEncoding::srgb};
            mf::fit_plane(mf::Role::albedo, albedo, t.w, t.h, *ctx);
            EXPECT_EQ(albedo.image.width, t.w);
            EXPECT_EQ(albedo.image.height, t.h);
            // Resized color is linear; an unchanged size stays sRGB (bit-exact copy).
            EXPECT_EQ(albedo.encoding,
                      (t.w == d.w && t.h == d.h) ? mf::ColorEncoding::srgb : mf::ColorEncoding::linear);
            expect_all_finite(albedo.image, "fit_plane albedo");

            mf::RolePlane normal;
            mf::decode_normal(normal_pattern(d), mf::NormalConvention::gl, normal.image);
            mf::fit_plane(mf::Role::normal, normal, t.w, t.h, *ctx);
            EXPECT_EQ(normal.image.width, t.w);
            expect_unit(normal.image, "fit_plane normal");

            mf::RolePlane rough{pattern(d, 1), mf::ColorEncoding::linear};
            mf::fit_plane(mf::Role::roughness, rough, t.w, t.h, *ctx);
            EXPECT_EQ(rough.image.height, t.h);
            expect_all_finite(rough.image, "fit_plane roughness");
        }
}

TEST(OddSizes, PackEncodeReadBackEveryGltfOutput) {
    auto ctx = color_context();
    ASSERT_TRUE(ctx);
    std::string err;
    auto preset = mf::load_preset("gltf", err);
    ASSERT_TRUE(preset) << err;
    for (Dim d : kSizes) {
        // Roles at different sizes: the output takes the largest, the others are fitted.
        mf::Planes planes;
        planes[mf::Role::albedo] = {pattern(d, 3), mf::ColorEncoding::srgb};
        planes[mf::Role::roughness] = {pattern({1, 1}, 1), mf::ColorEncoding::linear};
        planes[mf::Role::occlusion] = {pattern(d, 1), mf::ColorEncoding::linear};
        planes[mf::Role::normal].image = mf::Image();
        mf::decode_normal(normal_pattern(d), mf::NormalConvention::gl, planes[mf::Role::normal].image);
        for (const auto& o : preset->outputs) {
            if (!mf::output_needed(o, planes)) continue;
            const mf::Size size = mf::output_size(o, planes, *preset);
            ASSERT_EQ(size.width, d.w) << o.suffix;
            ASSERT_EQ(size.height, d.h) << o.suffix;
            mf::Planes fitted = planes;
            for (auto& [role, plane] : fitted) mf::fit_plane(role, plane, size.width, size.height, *ctx);
            const mf::Image out = mf::pack_output(o, fitted, *preset, size, *ctx);
            ASSERT_EQ(out.width, d.w);
            ASSERT_EQ(out.height, d.h);
            expect_all_finite(out, o.suffix.c_str());
            for (auto [format, bits] : {std::pair<const char*, int>{"png", 8}, {"png", 16}, {"exr", 16}, {"tif", 8}}) {
                const mf::Image back = encode_and_read(out, {*mf::from_word<mf::FileFormat>(format), bits});
                ASSERT_EQ(back.width, d.w) << format;
                ASSERT_EQ(back.height, d.h) << format;
                ASSERT_EQ(back.channels, out.channels) << format;
                const bool is_float = std::string(format) == "exr";
                for (size_t i = 0; i < out.pixels.size(); ++i) {
                    const float src = out.pixels[i];
                    if (is_float) {  // half: 11 significant bits
                        EXPECT_NEAR(back.pixels[i], src, std::abs(src) * 1e-3f + 1e-7f) << o.suffix;
                    } else {
                        EXPECT_EQ(mf::quantize(back.pixels[i], bits), mf::quantize(src, bits))
                            << o.suffix << " " << format;
                    }
                }
            }
        }
        // The decoded normal plane round-trips through its 8-bit file within a code's angle.
        const mf::Image enc = mf::encode_normal(planes[mf::Role::normal].image, preset->normal_convention);
        mf::Image dec;
        mf::decode_normal(encode_and_read(enc, {mf::FileFormat::png, 8}), preset->normal_convention, dec);
        for (size_t i = 0; i < dec.pixels.size(); i += 3) {
            const auto& a = planes[mf::Role::normal].image.pixels;
            EXPECT_GT(a[i] * dec.pixels[i] + a[i + 1] * dec.pixels[i + 1] + a[i + 2] * dec.pixels[i + 2], 0.9998f);
        }
    }
}

TEST(OddSizes, ConstantTwoByTwoAndOneByOneMetalness) {
    // A material with no map at all: every output is constant_size² and encodes.
    auto ctx = color_context();
    std::string err;
    auto preset = mf::load_preset("separate", err);
    ASSERT_TRUE(preset) << err;
    mf::Planes none;
    for (const auto& o : preset->outputs) {
        if (!mf::output_needed(o, none)) continue;
        const mf::Size s = mf::output_size(o, none, *preset);
        EXPECT_EQ(s.width, preset->constant_size);
        const mf::Image out = mf::pack_output(o, none, *preset, s, *ctx);
        const mf::Image back = encode_and_read(out, {mf::FileFormat::png, o.bit_depth == 16 ? 16 : 8});
        EXPECT_EQ(back.width, s.width);
        expect_all_finite(back, o.suffix.c_str());
    }
    // max_size scaling never yields a 0-pixel side for 1×N inputs.
    mf::Preset small = *preset;
    small.max_size = 4;
    mf::Planes tall;
    tall[mf::Role::roughness] = {pattern({1, 1000}, 1), mf::ColorEncoding::linear};
    for (const auto& o : small.outputs) {
        if (o.suffix != "roughness") continue;  // the others hold constants only (2×2)
        const mf::Size s = mf::output_size(o, tall, small);
        EXPECT_GE(s.width, 1) << o.suffix;
        EXPECT_EQ(s.height, 4) << o.suffix;
    }
}

}  // namespace
