// Normal maps that are valid but not unit length, gamma-encoded or not normal maps at all;
// flat normal maps; opacity that hides the whole material; masked albedo shares of the visible
// surface; the severity of a color tag on a data map.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "base/srgb.hpp"
#include "helpers.hpp"
#include "validate/map_stats.hpp"

using namespace mft;
namespace mv = mf::validate;
namespace code = mf::code;

namespace {

const mf::Finding* find(const std::vector<mf::Finding>& fs, std::string_view c, const std::string& file = "") {
    for (const auto& f : fs)
        if (f.code == c && (file.empty() || f.file == file)) return &f;
    return nullptr;
}

// Re-encodes every channel of an 8-bit 2c−1 normal map: c → f(c), quantized to 8 bits.
template <class F>
Image recode(const Image& n, F f) {
    Image o = n;
    for (auto& v : o.pixels) v = std::round(std::clamp(f(v), 0.f, 1.f) * 255.f) / 255.f;
    return o;
}

// A normal map whose vectors are scaled to `len` (what a blurred or resized map looks like).
Image shortened(const Image& n, float len) {
    return recode(n, [len](float c) { return 0.5f + len * (c - 0.5f); });
}

}  // namespace

TEST(NormalMaps, ShortVectorsAreInfoAndNotInvalid) {
    auto s = clean_set(128);
    const Image n = *s.images.at("T_normal_gl.png");
    s.add(Role::normal, "T_normal_gl.png", shortened(n, 0.6f), false, NormalConvention::gl);
    const auto res = s.run();
    EXPECT_FALSE(has_code(res.findings, code::normal_invalid)) << dump(res.findings);
    const mf::Finding* f = find(res.findings, code::normal_not_unit_length);
    ASSERT_NE(f, nullptr) << dump(res.findings);
    EXPECT_EQ(f->severity, mf::Severity::info);
    EXPECT_NEAR(mf::to_json(f->figures).at("mean_length").get<double>(), 0.6, 0.01);
    EXPECT_GT(mf::to_json(f->figures).at("bad_length_share").get<double>(), 0.95);
    EXPECT_NE(f->message.find("renormalized on ingest"), std::string::npos) << f->message;
    // The worst the corpus holds, mean length 0.81 with 42 % off by > 0.2, and shorter still.
    for (float len : {0.5f, 0.8f, 0.9f}) {
        s.add(Role::normal, "T_normal_gl.png", shortened(n, len), false, NormalConvention::gl);
        const auto r = s.run();
        EXPECT_FALSE(has_code(r.findings, code::normal_invalid)) << len << "\n" << dump(r.findings);
        EXPECT_EQ(mf::worst(r.findings).value_or(mf::Severity::info), mf::Severity::info) << len << dump(r.findings);
    }
    // Unit vectors: nothing.
    s.add(Role::normal, "T_normal_gl.png", n, false, NormalConvention::gl);
    EXPECT_FALSE(has_code(s.run().findings, code::normal_not_unit_length));
}

TEST(NormalMaps, GammaEncodedIsAnErrorOfItsOwn) {
    auto s = clean_set(128);
    const Image n = *s.images.at("T_normal_gl.png");
    const Image g = recode(n, [](float c) { return mf::linear_to_srgb(c); });
    s.add(Role::normal, "T_normal_gl.png", g, false, NormalConvention::gl);
    const auto res = s.run();
    const mf::Finding* f = find(res.findings, code::normal_gamma_encoded);
    ASSERT_NE(f, nullptr) << dump(res.findings);
    EXPECT_EQ(f->severity, mf::Severity::error);
    EXPECT_EQ(f->file, "T_normal_gl.png");
    // 128 stored as sRGB is 188: X/Y centred near 0.74.
    EXPECT_GT(mf::to_json(f->figures).at("mean_x").get<double>(), 0.4);
    EXPECT_GT(mf::to_json(f->figures).at("mean_y").get<double>(), 0.4);
    EXPECT_LT(std::abs(mf::to_json(f->figures).at("srgb_decoded_mean_x").get<double>()), 0.03);
    EXPECT_NEAR(mf::to_json(f->figures).at("srgb_decoded_mean_length").get<double>(), 1.0, 0.05);
    EXPECT_FALSE(has_code(res.findings, code::normal_invalid)) << "one error, the one that says what happened";
    // The encoding is monotonic: the slopes keep their signs and the GL verdict stands.
    EXPECT_FALSE(has_code(res.findings, code::normal_convention_mismatch)) << dump(res.findings);
    // The same map decoded back is clean again.
    const Image back = recode(g, [](float c) { return mf::srgb_to_linear(c); });
    s.add(Role::normal, "T_normal_gl.png", back, false, NormalConvention::gl);
    const auto r2 = s.run();
    EXPECT_FALSE(has_code(r2.findings, code::normal_gamma_encoded)) << dump(r2.findings);
    EXPECT_FALSE(has_code(r2.findings, code::normal_invalid)) << dump(r2.findings);
    // A float file is linear data, never sRGB-encoded: no gamma verdict (it is not a normal map).
    s.add(Role::normal, "T_normal_gl.exr", g, true, NormalConvention::gl);
    s.remove("T_normal_gl.png");
    EXPECT_FALSE(has_code(s.run().findings, code::normal_gamma_encoded));
}

TEST(NormalMaps, MapsThatAreNotNormalMapsAreInvalid) {
    const int N = 128;
    auto s = clean_set(N);
    const Image& height = *s.images.at("T_height.png");
    const Image& albedo = *s.images.at("T_albedo.png");
    // Object-space: the normals of a sphere over latitude/longitude, every direction once.
    Image object(N, N, 3);
    for (int y = 0; y < N; ++y)
        for (int x = 0; x < N; ++x) {
            const double th = M_PI * (y + 0.5) / N, ph = 2 * M_PI * (x + 0.5) / N;
            const double v[3] = {std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)};
            for (int c = 0; c < 3; ++c)
                object.at(x, y, c) = static_cast<float>(std::round((0.5 + 0.5 * v[c]) * 255) / 255);
        }
    // A height map copied to R, G and B; and a bright one (all codes ≥ 200), whose Z is high.
    Image grey(N, N, 3), bright(N, N, 3);
    for (int y = 0; y < N; ++y)
        for (int x = 0; x < N; ++x)
            for (int c = 0; c < 3; ++c) {
                grey.at(x, y, c) = height.at(x, y);
                bright.at(x, y, c) = 0.8f + 0.2f * height.at(x, y);
            }
    // A bluish color photo: blue high like a normal map, X/Y off centre, R ≠ G ≠ B.
    Image sky(N, N, 3);
    for (int y = 0; y < N; ++y)
        for (int x = 0; x < N; ++x) {
            sky.at(x, y, 0) = 0.25f + 0.2f * height.at(x, y);
            sky.at(x, y, 1) = 0.45f + 0.1f * height.at(x, y);
            sky.at(x, y, 2) = 0.9f;
        }
    struct Case {
        const char* what;
        Image img;
        const char* reason;  // a phrase of the message
    };
    const std::vector<Case> cases{{"object-space", object, "within 45 degrees"},
                                  {"height as RGB", grey, "R = G = B"},
                                  {"bright height as RGB", bright, "R = G = B"},
                                  {"albedo", albedo, "within 45 degrees"},
                                  {"sky photo", sky, "X/Y average"}};
    for (const auto& c : cases) {
        s.add(Role::normal, "T_normal_gl.png", c.img, false, NormalConvention::gl);
        const auto res = s.run();
        const mf::Finding* f = find(res.findings, code::normal_invalid);
        ASSERT_NE(f, nullptr) << c.what << "\n" << dump(res.findings);
        EXPECT_EQ(f->severity, mf::Severity::error) << c.what;
        EXPECT_NE(f->message.find(c.reason), std::string::npos) << c.what << ": " << f->message;
        EXPECT_FALSE(has_code(res.findings, code::normal_not_unit_length)) << c.what;
        EXPECT_FALSE(has_code(res.findings, code::normal_gamma_encoded)) << c.what;
        EXPECT_FALSE(has_code(res.findings, code::normal_convention_mismatch)) << c.what << ": no convention to judge";
    }
    // The object-space map's figures: the rows within 45° of the pole (a quarter of a latitude/
    // longitude map) point up, the lower half below the surface.
    s.add(Role::normal, "T_normal_gl.png", object, false, NormalConvention::gl);
    const auto obj = s.run();
    const mf::Finding* f = find(obj.findings, code::normal_invalid);
    ASSERT_NE(f, nullptr);
    EXPECT_NEAR(mf::to_json(f->figures).at("upward_share").get<double>(), 0.25, 0.02);
    EXPECT_NEAR(mf::to_json(f->figures).at("negative_z_share").get<double>(), 0.49, 0.02);
    // One channel: a height or bump map.
    Image one(N, N, 1);
    for (int y = 0; y < N; ++y)
        for (int x = 0; x < N; ++x) one.at(x, y) = height.at(x, y);
    s.add(Role::normal, "T_normal_gl.png", one, false, NormalConvention::gl);
    const auto single = s.run();
    f = find(single.findings, code::normal_invalid);
    ASSERT_NE(f, nullptr);
    EXPECT_EQ(mf::to_json(f->figures).at("channels"), 1);
}

TEST(NormalMaps, TwoChannelAndSteepMapsAreValid) {
    const int N = 128;
    auto s = clean_set(N);
    const Image& h = *s.images.at("T_height.png");
    // RG only (BC5-style): Z is rebuilt.
    const Image n = *s.images.at("T_normal_gl.png");
    Image rg(N, N, 2);
    for (int y = 0; y < N; ++y)
        for (int x = 0; x < N; ++x)
            for (int c = 0; c < 2; ++c) rg.at(x, y, c) = n.at(x, y, c);
    s.add(Role::normal, "T_normal_gl.png", rg, false, NormalConvention::gl);
    auto res = s.run();
    EXPECT_FALSE(has_code(res.findings, code::normal_invalid)) << dump(res.findings);
    // Steep relief (RMS slope 1.0, about as steep as the steepest vendor map measured, whose
    // upward share is 73 %): still a normal map.
    s.add(Role::normal, "T_normal_gl.png", normal_from_height(h, NormalConvention::gl, 1.0), false,
          NormalConvention::gl);
    res = s.run();
    EXPECT_FALSE(has_code(res.findings, code::normal_invalid)) << dump(res.findings);
}

TEST(NormalMaps, FlatMapHasNoConventionToDecide) {
    auto s = clean_set();
    s.remove("T_normal_gl.png");
    s.remove("T_height.png");
    // (128, 128, 255) with ±1 code of noise, as a JPEG of a flat map.
    Image flat = constant(64, 64, {128.f / 255.f, 128.f / 255.f, 1.f});
    std::mt19937 rng(3);
    std::uniform_int_distribution<int> d(-1, 1);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
            for (int c = 0; c < 2; ++c) flat.at(x, y, c) += static_cast<float>(d(rng)) / 255.f;
    s.add(Role::normal, "T_normal.png", flat);
    const auto res = s.run();
    ASSERT_TRUE(res.normal);
    EXPECT_TRUE(res.normal->content.flat);
    EXPECT_EQ(res.normal->resolved, NormalConvention::unknown);
    EXPECT_FALSE(has_code(res.findings, code::normal_convention_unknown)) << dump(res.findings);
    EXPECT_FALSE(has_code(res.findings, code::normal_invalid)) << dump(res.findings);
    // A map with relief whose convention is undecidable is not flat (NormalConventionUnknown).
    Image h(64, 64, 1);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) h.at(x, y) = 0.5f + 0.5f * std::sin(static_cast<float>(x) * 0.4f);
    s.add(Role::normal, "T_normal.png", normal_from_height(h, NormalConvention::gl));
    const auto r2 = s.run();
    ASSERT_TRUE(r2.normal);
    EXPECT_FALSE(r2.normal->content.flat);
    EXPECT_TRUE(has_code(r2.findings, code::normal_convention_unknown));
}

TEST(Opacity, AllTransparentIsAnError) {
    auto s = clean_set();
    s.add(Role::opacity, "T_opacity.jpg", constant(64, 64, {0.f, 0.f, 0.f}));
    auto res = s.run();
    const mf::Finding* f = find(res.findings, code::opacity_all_transparent);
    ASSERT_NE(f, nullptr) << dump(res.findings);
    EXPECT_EQ(f->severity, mf::Severity::error);
    EXPECT_EQ(f->role, "opacity");
    EXPECT_EQ(f->file, "T_opacity.jpg");
    EXPECT_EQ(mf::to_json(f->figures).at("invisible_share"), 1.0);
    EXPECT_NE(f->message.find("invisible"), std::string::npos);
    // Two visible pixels of 4096 (0.05 %) do not save it; ten (0.24 %) do.
    Image o = constant(64, 64, {0.f});
    o.at(1, 1) = o.at(2, 1) = 1.f;
    s.add(Role::opacity, "T_opacity.jpg", o);
    EXPECT_TRUE(has_code(s.run().findings, code::opacity_all_transparent));
    for (int x = 3; x < 11; ++x) o.at(x, 1) = 1.f;
    s.add(Role::opacity, "T_opacity.jpg", o);
    EXPECT_FALSE(has_code(s.run().findings, code::opacity_all_transparent));
    // Glass: opacity 0.2 everywhere is below the 0.5 cutoff but visible when blended.
    s.add(Role::opacity, "T_opacity.jpg", constant(64, 64, {0.2f}));
    EXPECT_FALSE(has_code(s.run().findings, code::opacity_all_transparent));
    // A real cut-out mask.
    Image cut = constant(64, 64, {0.f});
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 16; ++x) cut.at(x, y) = 1.f;
    s.add(Role::opacity, "T_opacity.jpg", cut);
    EXPECT_FALSE(has_code(s.run().findings, code::opacity_all_transparent));
}

TEST(Opacity, AlbedoAlphaCountsOnlyWhenItIsTheOpacity) {
    auto s = clean_set();
    Image rgba(64, 64, 4);
    const Image& a = *s.images.at("T_albedo.png");
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            for (int c = 0; c < 3; ++c) rgba.at(x, y, c) = a.at(x, y, c);
            rgba.at(x, y, 3) = 0.f;  // an exporter's empty alpha
        }
    s.add(Role::albedo, "T_albedo.png", rgba);
    auto res = s.run();
    const mf::Finding* f = find(res.findings, code::opacity_all_transparent);
    ASSERT_NE(f, nullptr) << dump(res.findings);
    EXPECT_EQ(f->file, "T_albedo.png");
    EXPECT_EQ(mf::to_json(f->figures).at("channel"), "A");
    EXPECT_NE(f->message.find("the alpha of T_albedo.png"), std::string::npos) << f->message;
    // With an opacity map the alpha is not the opacity: no finding.
    s.add(Role::opacity, "T_opacity.png", constant(64, 64, {1.f}));
    res = s.run();
    EXPECT_FALSE(has_code(res.findings, code::opacity_all_transparent)) << dump(res.findings);
}

TEST(AlbedoShares, DarkDielectricSpecksInAMetalDoNotCount) {
    // A graded, mostly metallic map whose few dielectric pixels are dark dirt: 80 % of the
    // dielectric class but 1.2 % of the surface.
    auto s = clean_set();
    Image a = constant(64, 64, {0.8f, 0.78f, 0.75f});
    Image m = constant(64, 64, {1.f});
    for (int i = 0; i < 60; ++i) {
        const int x = (i * 7) % 64, y = (i * 13) % 64;
        m.at(x, y) = 0.f;
        if (i < 48)
            for (int c = 0; c < 3; ++c) a.at(x, y, c) = 0.05f;
    }
    s.add(Role::albedo, "T_albedo.png", a);
    s.add(Role::metalness, "T_metallic.png", m);
    auto res = s.run();
    EXPECT_FALSE(has_code(res.findings, code::albedo_too_dark)) << dump(res.findings);
    // Half the surface dielectric and dark: it fires, with both shares in the figures.
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 32; ++x) {
            m.at(x, y) = 0.f;
            for (int c = 0; c < 3; ++c) a.at(x, y, c) = 0.05f;
        }
    s.add(Role::albedo, "T_albedo.png", a);
    s.add(Role::metalness, "T_metallic.png", m);
    res = s.run();
    const mf::Finding* f = find(res.findings, code::albedo_too_dark);
    ASSERT_NE(f, nullptr) << dump(res.findings);
    const double dielectric = mf::to_json(f->figures).at("pixels").get<double>();
    EXPECT_NEAR(mf::to_json(f->figures).at("surface_share").get<double>(),
                mf::to_json(f->figures).at("share").get<double>() * dielectric / 4096.0, 1e-12);
    EXPECT_GT(mf::to_json(f->figures).at("surface_share").get<double>(), 0.5);
    EXPECT_NE(f->message.find("of the visible albedo is dielectric"), std::string::npos) << f->message;
}

TEST(ColorTags, DataMapTaggedSrgbIsInfo) {
    auto s = clean_set();
    s.input("T_height.png")->color_tag = {mv::ColorTag::srgb, "png:sRGB", "sRGB"};
    const auto res = s.run();
    const mf::Finding* f = find(res.findings, code::color_space_mismatch);
    ASSERT_NE(f, nullptr) << dump(res.findings);
    EXPECT_EQ(f->severity, mf::Severity::info);
    EXPECT_NE(f->message.find("ignores the tag"), std::string::npos) << f->message;
    // An ICC profile whose name says nothing (3dtextures.me heights: iCCP "ICC profile").
    s.input("T_height.png")->color_tag = {mv::ColorTag::other, "png:iCCP", "ICC profile"};
    const auto r2 = s.run();
    f = find(r2.findings, code::color_space_mismatch);
    ASSERT_NE(f, nullptr) << dump(r2.findings);
    EXPECT_EQ(f->severity, mf::Severity::info);
    EXPECT_NE(f->message.find("carries a color profile (png:iCCP \"ICC profile\")"), std::string::npos) << f->message;
    // The same profile on the albedo says nothing matforge could contradict.
    s.input("T_height.png")->color_tag = {};
    s.input("T_albedo.png")->color_tag = {mv::ColorTag::other, "png:iCCP", "ICC profile"};
    EXPECT_FALSE(has_code(s.run().findings, code::color_space_mismatch));
}
