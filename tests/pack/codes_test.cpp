// The 8-bit codes path (Decoded codes, RolePlane::codes, pack_output8) against the float path it
// replaces: every code of every kind of plane, every shipped preset, both normal conventions
// each way. Ingest takes the codes path for 8-bit inputs, so it must write the very same codes.
#include <gtest/gtest.h>

#include <algorithm>

#include "pack/pack.hpp"
#include "test_color.hpp"

namespace {

using mf::testcolor::color_context;

const char* const kPresets[] = {"gltf", "godot", "separate", "unity-hdrp", "unity-urp", "unreal"};

// 256 x 256 texels; channel c of texel (x, y) is f(x, y, c): every code appears in every channel.
mf::Image8 codes(int channels, uint8_t (*f)(int, int, int)) {
    mf::Image8 img(256, 256, channels);
    for (int y = 0; y < 256; ++y)
        for (int x = 0; x < 256; ++x)
            for (int c = 0; c < channels; ++c) img.at(x, y, c) = f(x, y, c);
    return img;
}

uint8_t color_code(int x, int y, int c) {
    return static_cast<uint8_t>(c == 0 ? x : c == 1 ? y : (x * 7 + y * 3) & 255);
}
uint8_t scalar_code(int x, int y, int) { return static_cast<uint8_t>((x + y * 31) & 255); }
uint8_t other_scalar_code(int x, int y, int) { return static_cast<uint8_t>((x * 13 + y) & 255); }
// Normals: every (X, Y) pair, with Z over its whole range along the diagonal; alpha varied.
uint8_t normal_code(int x, int y, int c) {
    return static_cast<uint8_t>(c == 0 ? x : c == 1 ? y : c == 2 ? (x + y) & 255 : 255 - x);
}

TEST(Codes, Unorm8ValuesAreWhatReadImageGives) {
    mf::Image8 all(256, 1, 1);
    for (int k = 0; k < 256; ++k) all.pixels[static_cast<size_t>(k)] = static_cast<uint8_t>(k);
    std::vector<unsigned char> png;
    std::string err;
    ASSERT_TRUE(mf::encode_image(all, {mf::FileFormat::png, 8}, png, err)) << err;
    mf::InputFile in;
    in.display = "all-codes.png";
    in.bytes = std::make_shared<const std::vector<unsigned char>>(png);

    mf::Image floats;
    mf::ImageInfo info;
    ASSERT_TRUE(mf::read_image(in, floats, info, err)) << err;
    mf::Decoded decoded;
    ASSERT_TRUE(mf::read_image(in, decoded, info, err)) << err;
    ASSERT_TRUE(decoded.is_codes());
    EXPECT_EQ(decoded.codes.pixels, all.pixels);
    const auto& unorm = mf::unorm8_values();
    for (size_t k = 0; k < 256; ++k) {
        EXPECT_EQ(floats.pixels[k], unorm[k]) << "code " << k;  // bit for bit
        EXPECT_NEAR(unorm[k], static_cast<double>(k) / 255.0, 1e-7);
    }
    EXPECT_EQ(mf::to_float(decoded.codes).pixels, floats.pixels);
    for (size_t n : {1, 7, 13, 255}) {  // the 8-wide loop and its scalar tail
        std::vector<float> out(n);
        mf::to_float(all.pixels.data() + 1, n, out.data());
        EXPECT_EQ(out, std::vector<float>(floats.pixels.begin() + 1, floats.pixels.begin() + 1 + static_cast<long>(n)));
    }
    EXPECT_EQ(unorm[0], 0.f);
    EXPECT_EQ(unorm[255], 1.f);
}

TEST(Codes, FloatFilesAnd16BitFilesStayFloat) {
    for (const auto& [format, depth] : {std::pair<const char*, int>{"png", 16}, {"exr", 16}}) {
        mf::Image img(3, 2, 3, 0.25f);
        std::vector<unsigned char> bytes;
        std::string err;
        ASSERT_TRUE(mf::encode_image(img, {*mf::from_word<mf::FileFormat>(format), depth}, bytes, err)) << err;
        mf::InputFile in;
        in.display = std::string("f.") + format;
        in.bytes = std::make_shared<const std::vector<unsigned char>>(bytes);
        mf::Decoded d;
        mf::ImageInfo info;
        ASSERT_TRUE(mf::read_image(in, d, info, err)) << err;
        EXPECT_FALSE(d.is_codes()) << format;
        EXPECT_EQ(d.floats.width, 3);
        EXPECT_NEAR(d.floats.pixels[0], 0.25f, 1e-4f) << format;
    }
}

TEST(Codes, QuantizeGivesBackEveryCodeAndItsInverse) {
    const auto& unorm = mf::unorm8_values();
    for (int k = 0; k < 256; ++k) {
        const float v = unorm[static_cast<size_t>(k)];
        EXPECT_EQ(mf::quantize8(v), k);
        EXPECT_EQ(mf::quantize8(1.f - v), 255 - k);    // gloss -> roughness
        EXPECT_EQ(mf::quantize8(1.f - (1.f - v)), k);  // ... -> smoothness output
        EXPECT_EQ(mf::quantize(v, 8), k);
    }
}

// Every output of `preset` from codes planes, through pack_output8 and through the float path
// (pack_output of the planes' floats, quantized): the same codes.
void expect_same_outputs(const mf::Preset& preset, const mf::Planes& code_planes, const std::string& what) {
    auto c = color_context();
    ASSERT_TRUE(c);
    mf::Planes float_planes;
    for (const auto& [role, p] : code_planes) float_planes[role] = {mf::plane_floats(role, p), p.encoding};
    for (const auto& o : preset.outputs) {
        if (!mf::output_needed(o, code_planes)) continue;
        const mf::Size size = mf::output_size(o, code_planes, preset);
        const auto fast = mf::pack_output8(o, code_planes, preset, size, *c);
        const mf::Image slow = mf::pack_output(o, float_planes, preset, size, *c);
        // The float path over codes planes (what 16-bit outputs take) decodes them the same way.
        const mf::Image slow_codes = mf::pack_output(o, code_planes, preset, size, *c);
        EXPECT_EQ(slow_codes.pixels, slow.pixels) << what << " " << preset.name << "/" << o.suffix;
        if (o.bit_depth != 8) {
            EXPECT_FALSE(fast) << what << " " << o.suffix << ": a " << o.bit_depth << "-bit output";
            continue;
        }
        ASSERT_TRUE(fast) << what << " " << preset.name << "/" << o.suffix;
        ASSERT_EQ(fast->pixels.size(), slow.pixels.size());
        size_t differing = 0, first = 0;
        for (size_t i = 0; i < slow.pixels.size(); ++i)
            if (fast->pixels[i] != mf::quantize8(slow.pixels[i]) && differing++ == 0) first = i;
        EXPECT_EQ(differing, 0u) << what << " " << preset.name << "/" << o.suffix << ": first at sample " << first
                                 << " (" << int(fast->pixels[first]) << " vs " << slow.pixels[first] << ")";
    }
}

mf::Planes code_planes(int normal_channels, mf::NormalConvention stored, bool roughness_from_gloss) {
    mf::Planes p;
    for (mf::Role r : {mf::Role::albedo, mf::Role::emissive}) {
        p[r].codes = codes(3, color_code);
        p[r].encoding = mf::ColorEncoding::srgb;
    }
    p[mf::Role::roughness].codes = codes(1, scalar_code);
    if (roughness_from_gloss) mf::invert(p[mf::Role::roughness].codes);
    p[mf::Role::metalness].codes = codes(1, other_scalar_code);
    p[mf::Role::occlusion].codes = codes(1, scalar_code);
    p[mf::Role::height].codes = codes(1, other_scalar_code);
    p[mf::Role::opacity].codes = codes(1, scalar_code);
    p[mf::Role::normal].codes = codes(normal_channels, normal_code);
    p[mf::Role::normal].codes_convention = stored;
    return p;
}

TEST(Codes, PackOutput8EqualsTheFloatPathForEveryPresetAndCode) {
    for (const char* name : kPresets) {
        std::string err;
        auto preset = mf::load_preset(name, err);
        ASSERT_TRUE(preset) << err;
        for (mf::NormalConvention target : {mf::NormalConvention::gl, mf::NormalConvention::dx}) {
            mf::Preset p = *preset;
            p.normal_convention = target;
            for (mf::NormalConvention stored : {mf::NormalConvention::gl, mf::NormalConvention::dx})
                for (int nc : {2, 3, 4})
                    expect_same_outputs(p, code_planes(nc, stored, nc == 3),
                                        std::to_string(nc) + "-channel normals stored " +
                                            std::string(mf::convention_name(stored)));
        }
        // Missing roles: defaults and constants quantized once, as the float path does.
        mf::Planes only_albedo;
        only_albedo[mf::Role::albedo].codes = codes(3, color_code);
        only_albedo[mf::Role::albedo].encoding = mf::ColorEncoding::srgb;
        expect_same_outputs(*preset, only_albedo, "albedo only");
    }
}

TEST(Codes, PackOutput8DeclinesWhatNeedsFloats) {
    auto c = color_context();
    ASSERT_TRUE(c);
    std::string err;
    auto preset = mf::load_preset("gltf", err);
    ASSERT_TRUE(preset) << err;
    const mf::OutputSpec* orm = nullptr;
    const mf::OutputSpec* base = nullptr;
    for (const auto& o : preset->outputs) {
        if (o.suffix == "orm") orm = &o;
        if (o.suffix == "basecolor") base = &o;
    }
    ASSERT_TRUE(orm && base);
    mf::Planes planes = code_planes(3, mf::NormalConvention::gl, false);
    ASSERT_TRUE(mf::pack_output8(*orm, planes, *preset, {256, 256}, *c));
    // A float plane among the output's roles.
    mf::Planes mixed = planes;
    mf::make_floats(mf::Role::roughness, mixed[mf::Role::roughness]);
    EXPECT_TRUE(mixed[mf::Role::roughness].codes.empty());
    EXPECT_FALSE(mf::pack_output8(*orm, mixed, *preset, {256, 256}, *c));
    // An EXR output (half or float samples), whatever its declared depth.
    mf::Preset exr = *preset;
    exr.format = mf::FileFormat::exr;
    EXPECT_FALSE(mf::pack_output8(*orm, planes, exr, {256, 256}, *c));
    // A plane not at the output's size (fit_plane resamples it in floats first).
    EXPECT_FALSE(mf::pack_output8(*orm, planes, *preset, {128, 128}, *c));
    // Linear-encoded color codes cannot go into an sRGB output as they are.
    mf::Planes linear = planes;
    linear[mf::Role::albedo].encoding = mf::ColorEncoding::linear;
    EXPECT_FALSE(mf::pack_output8(*base, linear, *preset, {256, 256}, *c));
}

TEST(Codes, FitPlaneKeepsCodesAtTheirSizeAndDecodesToResample) {
    auto c = color_context();
    ASSERT_TRUE(c);
    mf::RolePlane n;
    n.codes = codes(3, normal_code);
    n.codes_convention = mf::NormalConvention::dx;
    mf::fit_plane(mf::Role::normal, n, 256, 256, *c);
    EXPECT_TRUE(n.is_codes());
    const mf::Image expected = mf::plane_floats(mf::Role::normal, n);
    mf::fit_plane(mf::Role::normal, n, 64, 64, *c);
    ASSERT_FALSE(n.is_codes());
    EXPECT_EQ(n.image.width, 64);
    EXPECT_EQ(n.image.channels, 3);
    // Decoded to GL vectors (DX's green flipped), then resampled and renormalized.
    mf::Image gl;
    mf::decode_normal(mf::to_float(codes(3, normal_code)), mf::NormalConvention::dx, gl);
    EXPECT_EQ(expected.pixels, gl.pixels);
    for (size_t i = 0; i < n.image.pixels.size(); i += 3) {
        const float* v = &n.image.pixels[i];
        EXPECT_NEAR(v[0] * v[0] + v[1] * v[1] + v[2] * v[2], 1.f, 1e-4f);
    }

    mf::RolePlane albedo;
    albedo.codes = codes(3, color_code);
    albedo.encoding = mf::ColorEncoding::srgb;
    mf::fit_plane(mf::Role::albedo, albedo, 100, 50, *c);
    EXPECT_FALSE(albedo.is_codes());
    EXPECT_EQ(albedo.encoding, mf::ColorEncoding::linear);  // filtered in linear light
    EXPECT_EQ(albedo.image.width, 100);
}

TEST(Codes, SrgbLookupEqualsTheProcessorForEveryCode) {
    auto c = color_context();
    ASSERT_TRUE(c);
    const std::vector<float>& lut = c->srgb_codes_to_linear();
    ASSERT_EQ(lut.size(), 256u) << "the built-in config converts channel by channel";
    const mf::Image8 rgb = codes(3, color_code);
    mf::Image f = mf::to_float(rgb);
    c->convert(f, mf::ColorEncoding::srgb, mf::ColorEncoding::linear);
    size_t differing = 0;
    for (size_t i = 0; i < f.pixels.size(); ++i) differing += lut[rgb.pixels[i]] != f.pixels[i] ? 1 : 0;
    EXPECT_EQ(differing, 0u);
    EXPECT_EQ(lut[0], 0.f);
    EXPECT_NEAR(lut[255], 1.f, 1e-6f);
    EXPECT_NEAR(lut[128], 0.2158605f, 1e-5f);  // IEC 61966-2-1 at 128/255

    // fit_plane resamples codes (looked up) and floats (converted) to the same linear image.
    mf::RolePlane from_codes;
    from_codes.codes = rgb;
    from_codes.encoding = mf::ColorEncoding::srgb;
    mf::RolePlane from_floats{mf::to_float(rgb), mf::ColorEncoding::srgb};
    mf::fit_plane(mf::Role::albedo, from_codes, 100, 60, *c);
    mf::fit_plane(mf::Role::albedo, from_floats, 100, 60, *c);
    EXPECT_EQ(from_codes.encoding, mf::ColorEncoding::linear);
    EXPECT_EQ(from_codes.image.pixels, from_floats.image.pixels);
}

}  // namespace
