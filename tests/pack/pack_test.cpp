// Pixel-exact packing for every shipped preset, on tiny planes built here.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "base/srgb.hpp"
#include "pack/pack.hpp"
#include "test_color.hpp"

namespace {

using mf::testcolor::color_context;

// A 2x1 set with distinct, known values per role and texel.
mf::Planes make_planes(bool with_metal = true) {
    mf::Planes p;
    auto scalar = [](float a, float b) {
        mf::Image img(2, 1, 1);
        img.pixels = {a, b};
        return img;
    };
    mf::RolePlane albedo;
    albedo.image = mf::Image(2, 1, 3);
    albedo.image.pixels = {100 / 255.f, 150 / 255.f, 200 / 255.f, 10 / 255.f, 20 / 255.f, 30 / 255.f};
    albedo.encoding = mf::ColorEncoding::srgb;
    p[mf::Role::albedo] = albedo;
    p[mf::Role::roughness].image = scalar(64 / 255.f, 191 / 255.f);
    if (with_metal) p[mf::Role::metalness].image = scalar(0.f, 1.f);
    p[mf::Role::occlusion].image = scalar(1.f, 128 / 255.f);
    mf::RolePlane normal;  // GL unit vectors: tilted toward +Y and toward -X
    normal.image = mf::Image(2, 1, 3);
    const float s = std::sqrt(0.5f);
    normal.image.pixels = {0.f, s, s, -s, 0.f, s};
    p[mf::Role::normal] = normal;
    return p;
}

struct Packed {
    mf::Image img;
    std::vector<mf::ChannelSpec> channels;
};

Packed pack(const std::string& preset_name, const std::string& suffix, const mf::Planes& planes) {
    std::string err;
    auto preset = mf::load_preset(preset_name, err);
    EXPECT_TRUE(preset) << err;
    for (const auto& o : preset->outputs)
        if (o.suffix == suffix) {
            const auto size = mf::output_size(o, planes, *preset);
            return {mf::pack_output(o, planes, *preset, size, *color_context()), mf::effective_channels(o, planes)};
        }
    ADD_FAILURE() << "no output " << suffix << " in " << preset_name;
    return {};
}

int code(const mf::Image& img, int x, int c) { return mf::quantize(img.at(x, 0, c), 8); }

}  // namespace

TEST(Presets, AllShippedParse) {
    const auto names = mf::shipped_presets();
    EXPECT_EQ(names, (std::vector<std::string>{"d3d11", "gltf", "godot", "separate", "unity-hdrp", "unity-urp",
                                               "unreal", "vulkan-ktx2", "vulkan-ktx2-astc"}));
    for (const auto& n : names) {
        std::string err;
        auto p = mf::load_preset(n, err);
        ASSERT_TRUE(p) << n << ": " << err;
        EXPECT_FALSE(p->sources.empty()) << n << " must cite where its convention comes from";
    }
}

TEST(Presets, RejectsBrokenDocuments) {
    std::string err;
    auto bad = [&](const char* text) {
        err.clear();
        mf::Preset p;
        return !mf::parse_preset(nlohmann::json::parse(text), p, err) && !err.empty();
    };
    EXPECT_TRUE(bad(R"({"name":"x","outputs":[]})"));
    EXPECT_TRUE(bad(R"({"name":"x","outputs":[{"suffix":"a","channels":{"R":"albedo"}}]})"));  // color in one channel
    EXPECT_TRUE(bad(R"({"name":"x","outputs":[{"suffix":"a","channels":{"RGB":"roughness"}}]})"));
    EXPECT_TRUE(bad(R"({"name":"x","outputs":[{"suffix":"a","channels":{"R":"wetness"}}]})"));
    EXPECT_TRUE(bad(R"({"name":"x","outputs":[{"suffix":"a","channels":{"R":"roughness","B":"metalness"}}]})"));  // gap
    EXPECT_TRUE(bad(
        R"({"name":"x","file_pattern":"../{suffix}.{ext}","outputs":[{"suffix":"a","channels":{"R":"roughness"}}]})"));
    EXPECT_TRUE(
        bad(R"({"name":"x","normal_convention":"up","outputs":[{"suffix":"a","channels":{"R":"roughness"}}]})"));
    // Numbers out of their field's range are errors, never narrowed (undefined behaviour the
    // preset fuzzer found with "preset_version": 1e100).
    const std::string ok_outputs = R"("outputs":[{"suffix":"a","channels":{"R":"roughness"}}])";
    for (const std::string field :
         {R"("preset_version":1e100)", R"("preset_version":18446744073709551615)", R"("preset_version":1.0)",
          R"("max_size":99999999999)", R"("max_size":-1)", R"("constant_size":1e300)", R"("constant_size":0)"}) {
        EXPECT_TRUE(bad(("{\"name\":\"x\"," + field + "," + ok_outputs + "}").c_str())) << field;
    }
    EXPECT_TRUE(bad(R"({"name":"x","outputs":[{"suffix":"a","bit_depth":1e100,"channels":{"R":"roughness"}}]})"));
    EXPECT_TRUE(bad(R"({"name":"x","outputs":[{"suffix":"a","bit_depth":8.5,"channels":{"R":"roughness"}}]})"));
    EXPECT_TRUE(bad(R"({"name":"x","outputs":[{"suffix":"a","channels":{"R":1e300}}]})"));
    EXPECT_TRUE(
        bad(R"({"name":"x","defaults":{"roughness":1e300},"outputs":[{"suffix":"a","channels":{"R":"roughness"}}]})"));
    EXPECT_TRUE(bad(
        R"({"name":"x","defaults":{"albedo":[0.5,"red",0.5]},"outputs":[{"suffix":"a","channels":{"R":"roughness"}}]})"));
    // A suffix or file_pattern that the material files could not name the output by (a newline,
    // a tab, USD's '@', a space, a '#'): refused, the suffix named (issue 45).
    for (const std::string suffix : {"a\\nb", "a\\tb", "a@b", "a b", "a#b", "a\\u00e9"}) {
        EXPECT_TRUE(bad(("{\"name\":\"x\",\"outputs\":[{\"suffix\":\"" + suffix +
                         "\",\"channels\":{\"R\":\"roughness\"}}]}")
                            .c_str()))
            << suffix;
    }
    EXPECT_NE(err.find("suffix may hold only"), std::string::npos) << err;
    EXPECT_TRUE(bad(
        ("{\"name\":\"x\",\"file_pattern\":\"{material}/@{material}_{suffix}.{ext}\"," + ok_outputs + "}").c_str()));
    EXPECT_FALSE(bad(("{\"name\":\"x\",\"file_pattern\":\"out-2/{material}/T_{material}.v1_{suffix}.{ext}\"," +
                      ok_outputs + "}")
                         .c_str()))
        << err;
    EXPECT_FALSE(bad(("{\"name\":\"x\",\"preset_version\":1,\"max_size\":4096," + ok_outputs + "}").c_str())) << err;
    auto missing = mf::load_preset("no-such-preset", err);
    EXPECT_FALSE(missing);
    EXPECT_NE(err.find("no-such-preset"), std::string::npos);
    EXPECT_NE(err.find("gltf"), std::string::npos) << "the error lists the shipped presets";
}

TEST(PackGltf, OrmChannels) {
    const auto p = pack("gltf", "orm", make_planes());
    ASSERT_EQ(p.img.channels, 3);
    EXPECT_EQ(code(p.img, 0, 0), 255);  // R occlusion
    EXPECT_EQ(code(p.img, 1, 0), 128);
    EXPECT_EQ(code(p.img, 0, 1), 64);  // G roughness
    EXPECT_EQ(code(p.img, 1, 1), 191);
    EXPECT_EQ(code(p.img, 0, 2), 0);  // B metalness
    EXPECT_EQ(code(p.img, 1, 2), 255);
}

TEST(PackGltf, MissingMetalnessIsExplicitZero) {
    // glTF's metallicFactor defaults to 1: an omitted metalness would make everything metal.
    const auto p = pack("gltf", "orm", make_planes(false));
    EXPECT_EQ(code(p.img, 0, 2), 0);
    EXPECT_EQ(code(p.img, 1, 2), 0);
}

TEST(PackGltf, BaseColorSrgbIsBitExactCopy) {
    const auto p = pack("gltf", "basecolor", make_planes());
    ASSERT_EQ(p.img.channels, 3) << "no opacity map: the alpha channel is dropped";
    const int expect[2][3] = {{100, 150, 200}, {10, 20, 30}};
    for (int x = 0; x < 2; ++x)
        for (int c = 0; c < 3; ++c) EXPECT_EQ(code(p.img, x, c), expect[x][c]);
}

TEST(PackGltf, BaseColorFromLinearIsEncoded) {
    auto planes = make_planes();
    planes[mf::Role::albedo].encoding = mf::ColorEncoding::linear;
    planes[mf::Role::albedo].image.pixels = {0.214041140f, 0.f, 1.f, 0.0031308f, 0.5f, 0.01f};
    const auto p = pack("gltf", "basecolor", planes);
    EXPECT_EQ(code(p.img, 0, 0), 128);  // linear 0.2140 -> sRGB 0.5 -> 127.5 rounds up
    EXPECT_EQ(code(p.img, 0, 1), 0);
    EXPECT_EQ(code(p.img, 0, 2), 255);
    EXPECT_EQ(code(p.img, 1, 1), mf::quantize(static_cast<float>(mf::linear_to_srgb(0.5)), 8));
    EXPECT_EQ(code(p.img, 1, 2), mf::quantize(static_cast<float>(mf::linear_to_srgb(0.01)), 8));
}

TEST(PackGltf, OpacityGoesToAlpha) {
    auto planes = make_planes();
    planes[mf::Role::opacity].image = mf::Image(2, 1, 1);
    planes[mf::Role::opacity].image.pixels = {0.f, 1.f};
    const auto p = pack("gltf", "basecolor", planes);
    ASSERT_EQ(p.img.channels, 4);
    EXPECT_EQ(code(p.img, 0, 3), 0);
    EXPECT_EQ(code(p.img, 1, 3), 255);
    EXPECT_EQ(code(p.img, 1, 0), 10) << "color untouched by alpha (unassociated)";
}

TEST(PackNormals, GlAndDxEncodings) {
    const auto gl = pack("gltf", "normal", make_planes());
    const auto dx = pack("unreal", "N", make_planes());
    // texel 0: (0, .707, .707): GL green above 128, DX green below.
    EXPECT_EQ(code(gl.img, 0, 0), 128);
    EXPECT_EQ(code(gl.img, 0, 1), mf::quantize(0.70710678f * 0.5f + 0.5f, 8));   // 218
    EXPECT_EQ(code(dx.img, 0, 1), mf::quantize(-0.70710678f * 0.5f + 0.5f, 8));  // 37
    EXPECT_EQ(code(gl.img, 0, 2), code(dx.img, 0, 2));
    // texel 1: (-.707, 0, .707): red identical in both conventions.
    EXPECT_EQ(code(gl.img, 1, 0), code(dx.img, 1, 0));
    EXPECT_EQ(code(gl.img, 1, 1), 128);
}

TEST(PackUnreal, OrmMatchesGltfLayout) {
    const auto u = pack("unreal", "ORM", make_planes());
    const auto g = pack("gltf", "orm", make_planes());
    EXPECT_EQ(u.img.pixels, g.img.pixels);
}

TEST(PackUnityHdrp, MaskMap) {
    const auto p = pack("unity-hdrp", "MaskMap", make_planes());
    ASSERT_EQ(p.img.channels, 4);
    EXPECT_EQ(code(p.img, 1, 0), 255);       // R metallic
    EXPECT_EQ(code(p.img, 1, 1), 128);       // G occlusion
    EXPECT_EQ(code(p.img, 0, 2), 255);       // B detail mask = 1
    EXPECT_EQ(code(p.img, 0, 3), 255 - 64);  // A smoothness = 1 - roughness
    EXPECT_EQ(code(p.img, 1, 3), 255 - 191);
}

TEST(PackUnityUrp, MetallicGlossAndOcclusion) {
    const auto p = pack("unity-urp", "MetallicGlossMap", make_planes());
    ASSERT_EQ(p.img.channels, 4);
    EXPECT_EQ(code(p.img, 1, 0), 255);
    EXPECT_EQ(code(p.img, 1, 1), 0);  // unused
    EXPECT_EQ(code(p.img, 0, 3), 191);
    const auto o = pack("unity-urp", "OcclusionMap", make_planes());
    ASSERT_EQ(o.img.channels, 1);
    EXPECT_EQ(code(o.img, 1, 0), 128);
}

TEST(PackGodot, Orm) {
    const auto p = pack("godot", "orm", make_planes());
    EXPECT_EQ(p.img.pixels, pack("gltf", "orm", make_planes()).img.pixels);
}

TEST(PackSeparate, ConstantMetalnessIsTwoByTwo) {
    std::string err;
    auto preset = mf::load_preset("separate", err);
    ASSERT_TRUE(preset);
    const auto planes = make_planes(false);
    for (const auto& o : preset->outputs) {
        if (o.suffix != "metalness") continue;
        const auto size = mf::output_size(o, planes, *preset);
        EXPECT_EQ(size.width, 2);
        EXPECT_EQ(size.height, 2);
        const auto img = mf::pack_output(o, planes, *preset, size, *color_context());
        for (float v : img.pixels) EXPECT_EQ(v, 0.f);
    }
    const auto r = pack("separate", "roughness", planes);
    EXPECT_EQ(code(r.img, 0, 0), 64);
    EXPECT_EQ(code(r.img, 1, 0), 191);
}

TEST(Normals, DecodeFlipsDxAndRenormalizes) {
    mf::Image enc(3, 1, 3);
    // DX texel with green low = tilted toward +Y in GL; a zero vector; an unnormalized vector.
    enc.pixels = {0.5f, 0.2f, 0.9f, 0.5f, 0.5f, 0.5f, 1.f, 0.5f, 1.f};
    mf::Image n;
    const double bad = mf::decode_normal(enc, mf::NormalConvention::dx, n);
    EXPECT_GT(n.at(0, 0, 1), 0.f);
    EXPECT_NEAR(n.at(0, 0, 0) * n.at(0, 0, 0) + n.at(0, 0, 1) * n.at(0, 0, 1) + n.at(0, 0, 2) * n.at(0, 0, 2), 1.f,
                1e-6f);
    EXPECT_EQ(n.at(1, 0, 2), 1.f) << "zero-length -> flat";
    EXPECT_NEAR(n.at(2, 0, 0), std::sqrt(0.5f), 1e-6f);
    EXPECT_NEAR(bad, 2.0 / 3.0, 1e-9) << "zero vector and length 1.41 are both off";
    // Round trip GL -> encode -> decode within one 8-bit code.
    const auto back = mf::encode_normal(n, mf::NormalConvention::dx);
    EXPECT_NEAR(back.at(0, 0, 1), 0.2f, 0.006f);
}

TEST(Normals, TwoChannelRebuildsZ) {
    mf::Image enc(1, 1, 2);
    enc.pixels = {0.5f, 0.5f};
    mf::Image n;
    mf::decode_normal(enc, mf::NormalConvention::gl, n);
    EXPECT_FLOAT_EQ(n.pixels[2], 1.f);
}

TEST(Resample, LinearLightForColor) {
    // A black/white checker averaged in linear light is 0.5 linear = sRGB 188, not 128.
    auto c = color_context();
    mf::RolePlane plane;
    plane.image = mf::Image(2, 2, 3);
    plane.image.pixels = {0, 0, 0, 1, 1, 1, 1, 1, 1, 0, 0, 0};
    plane.encoding = mf::ColorEncoding::srgb;
    mf::fit_plane(mf::Role::albedo, plane, 1, 1, *c);
    EXPECT_EQ(plane.encoding, mf::ColorEncoding::linear);
    EXPECT_NEAR(plane.image.pixels[0], 0.5f, 0.02f);
}

TEST(Quantize, MatchesClampAndRoundHalfUp) {
    // The encoder's fast path must equal the definition: clamp to [0,1] (NaN -> 0), scale, floor(x + 0.5).
    auto reference = [](float v, float maxv) -> int {
        if (!(v > 0.f)) return 0;
        if (v >= 1.f) return static_cast<int>(maxv);
        return static_cast<int>(std::floor(v * maxv + 0.5f));
    };
    for (int bits : {8, 16}) {
        const float maxv = bits == 16 ? 65535.f : 255.f;
        for (int i = -1000; i <= 1001000; ++i) {
            const float v = static_cast<float>(i) / 1e6f;
            ASSERT_EQ(mf::quantize(v, bits), reference(v, maxv)) << v << " at " << bits << " bits";
        }
        for (int code = 0; code <= static_cast<int>(maxv); ++code) {  // exact codes and the half-way points
            const float v = static_cast<float>(code) / maxv, h = (static_cast<float>(code) + 0.5f) / maxv;
            ASSERT_EQ(mf::quantize(v, bits), code);
            ASSERT_EQ(mf::quantize(h, bits), reference(h, maxv)) << code;
        }
        EXPECT_EQ(mf::quantize(std::numeric_limits<float>::quiet_NaN(), bits), 0);
        EXPECT_EQ(mf::quantize(std::numeric_limits<float>::infinity(), bits), static_cast<int>(maxv));
        EXPECT_EQ(mf::quantize(-std::numeric_limits<float>::infinity(), bits), 0);
    }
}

// The pack spec is what lets two presets of one run share an output (process/ingest's SetShare):
// over every shipped preset's outputs (which differ in channels, order, constants, defaults,
// encoding, bit depth and normal convention), equal specs must pack equal images, and the packer
// reads nothing but the spec and the planes (an image packed from a spec equals the one packed
// from the output and preset it came from). Planes with and without metalness and albedo
// (defaults written), and a plane that differs in one code, which same_plane tells apart.
TEST(PackSpec, EqualSpecsPackEqualImages) {
    auto color = color_context();
    for (const bool metal : {true, false})
        for (const bool albedo : {true, false}) {
            mf::Planes planes = make_planes(metal);
            if (!albedo) planes.erase(mf::Role::albedo);
            struct Out {
                std::string name;
                mf::PackSpec spec;
                mf::Image img;
            };
            std::vector<Out> outs;
            for (const auto& name : mf::shipped_presets()) {
                std::string err;
                const auto preset = mf::load_preset(name, err);
                ASSERT_TRUE(preset) << err;
                for (const auto& o : preset->outputs) {
                    const mf::Size size{2, 1};
                    Out out{name + "/" + o.suffix + "/" + std::to_string(o.bit_depth),
                            mf::pack_spec(o, planes, *preset, size), mf::pack_output(o, planes, *preset, size, *color)};
                    const mf::Image from_spec = mf::pack_output(out.spec, planes, *color);
                    EXPECT_EQ(from_spec.pixels, out.img.pixels) << out.name;
                    outs.push_back(std::move(out));
                }
            }
            int equal_specs = 0, different_images = 0;
            for (size_t i = 0; i < outs.size(); ++i)
                for (size_t j = i + 1; j < outs.size(); ++j) {
                    const bool same_image = outs[i].img.channels == outs[j].img.channels &&
                                            outs[i].img.pixels == outs[j].img.pixels;
                    if (outs[i].spec == outs[j].spec) {
                        ++equal_specs;
                        EXPECT_TRUE(same_image) << outs[i].name << " and " << outs[j].name;
                    }
                    different_images += same_image ? 0 : 1;
                }
            // The shipped presets share outputs (glTF's and HDRP's base color and normal map) and
            // differ in most: both sides of the property are exercised.
            EXPECT_GT(equal_specs, 0);
            EXPECT_GT(different_images, 100);
        }
    mf::Planes a = make_planes(), b = make_planes();
    EXPECT_TRUE(mf::same_plane(a.at(mf::Role::roughness), b.at(mf::Role::roughness)));
    b.at(mf::Role::roughness).image.pixels[1] = 190 / 255.f;
    EXPECT_FALSE(mf::same_plane(a.at(mf::Role::roughness), b.at(mf::Role::roughness)));
    b.at(mf::Role::albedo).encoding = mf::ColorEncoding::linear;
    EXPECT_FALSE(mf::same_plane(a.at(mf::Role::albedo), b.at(mf::Role::albedo)));
    mf::OutputSpec smooth;  // a smoothness channel reads the roughness plane
    mf::ChannelSpec c;
    c.key = "R", c.kind = mf::Channel::Kind::smoothness, c.role = mf::Role::roughness;
    smooth.channels = {c};
    mf::Preset preset;
    EXPECT_EQ(mf::pack_spec(smooth, a, preset, {2, 1}).roles, std::vector<mf::Role>{mf::Role::roughness});
}
