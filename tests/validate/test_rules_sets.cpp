// One tiny bad set per rule (the code fires) and a clean set (nothing fires).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "helpers.hpp"

using namespace mft;
namespace mv = mf::validate;
namespace code = mf::code;

TEST(ValidateSets, CleanSetFiresNothing) {
    const auto r = clean_set().run();
    EXPECT_TRUE(r.findings.empty()) << dump(r.findings);
    ASSERT_TRUE(r.normal.has_value());
    EXPECT_EQ(r.normal->content.convention, NormalConvention::gl);
    EXPECT_EQ(r.normal->source, "name");
}

TEST(ValidateSets, CleanSetFiresNothingWithOneRowBandsAndOneBigBand) {
    EXPECT_TRUE(clean_set().run({}, "Test", 1).findings.empty());
    EXPECT_TRUE(clean_set().run({}, "Test", 1000).findings.empty());
}

// Maps of other sizes are the planner's to judge (RESOLUTION_MISMATCH, where the set's size is
// decided: tests/cli/synthetic_sets_test.cpp); the rules measure each map at its own size.
TEST(ValidateSets, MixedSizesAreNotARuleFinding) {
    auto s = clean_set();
    Image r(32, 32, 1);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) r.at(x, y) = 0.2f + 0.02f * static_cast<float>(x);
    s.add(Role::roughness, "T_roughness.png", r);
    EXPECT_TRUE(s.run().findings.empty()) << dump(s.run().findings);
}

TEST(ValidateSets, ResampledMasksStillWork) {
    // Metalness at half resolution: the masked albedo statistics use nearest neighbour.
    auto s = clean_set();
    Image m(32, 32, 1);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) m.at(x, y) = (x >= 16 && y >= 16) ? 1.f : 0.f;
    s.add(Role::metalness, "T_metallic.png", m);
    const auto res = s.run();
    EXPECT_FALSE(has_code(res.findings, code::metal_albedo_too_dark)) << dump(res.findings);
    EXPECT_FALSE(has_code(res.findings, code::albedo_too_bright)) << dump(res.findings);
}

TEST(ValidateSets, NonfiniteValues) {
    auto s = clean_set();
    Image r = constant(64, 64, {0.5f});
    r.at(3, 3) = std::nanf("");
    r.at(4, 3) = INFINITY;
    r.at(5, 5) = 0.2f;
    s.add(Role::roughness, "T_roughness.exr", r, true);
    s.remove("T_roughness.png");
    const auto res = s.run();
    ASSERT_TRUE(has_code(res.findings, code::nonfinite_values)) << dump(res.findings);
    for (const auto& f : res.findings)
        if (f.code == code::nonfinite_values) {
            EXPECT_EQ(mf::to_json(f.figures).at("nan"), 1);
            EXPECT_EQ(mf::to_json(f.figures).at("inf"), 1);
            EXPECT_EQ(f.severity, mf::Severity::error);
        }
}

TEST(ValidateSets, OutOfRangeOnlyForFloatAndBoundedRoles) {
    auto s = clean_set();
    Image r(64, 64, 1);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) r.at(x, y) = x < 8 ? 1.5f : 0.4f + 0.001f * static_cast<float>(y);
    s.add(Role::roughness, "T_roughness.exr", r, true);
    s.remove("T_roughness.png");
    // Height in a float file may hold anything: no finding for it.
    Image h = *s.images.at("T_height.png");
    for (auto& v : h.pixels) v = v * 10.f - 5.f;
    s.add(Role::height, "T_height.png", h, true);
    const auto res = s.run();
    int n = 0;
    for (const auto& f : res.findings)
        if (f.code == code::out_of_range_values) {
            ++n;
            EXPECT_EQ(f.role, "roughness");
            EXPECT_NEAR(mf::to_json(f.figures).at("share").get<double>(), 8.0 / 64.0, 1e-9);
            EXPECT_NEAR(mf::to_json(f.figures).at("max")[0].get<double>(), 1.5, 1e-6);
        }
    EXPECT_EQ(n, 1) << dump(res.findings);
}

TEST(ValidateSets, NotGrayscaleWithJpegTolerance) {
    auto s = clean_set();
    Image r(64, 64, 3);
    std::mt19937 rng(5);
    std::uniform_int_distribution<int> d(-3, 3);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            const float v = 0.3f + 0.005f * static_cast<float>(x);
            r.at(x, y, 0) = v;
            r.at(x, y, 1) = v + static_cast<float>(d(rng)) / 255.f;  // chroma noise ±3 codes
            r.at(x, y, 2) = v + static_cast<float>(d(rng)) / 255.f;
        }
    s.remove("T_roughness.png");
    s.add(Role::roughness, "T_roughness.jpg", r);
    EXPECT_FALSE(has_code(s.run().findings, code::not_grayscale)) << "JPEG noise is tolerated";
    s.remove("T_roughness.jpg");
    s.add(Role::roughness, "T_roughness.png", r);
    EXPECT_TRUE(has_code(s.run().findings, code::not_grayscale)) << "lossless files are not";
    // A real color image stored as roughness fires in any format.
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) r.at(x, y, 1) = 0.9f;
    s.remove("T_roughness.png");
    s.add(Role::roughness, "T_roughness.jpg", r);
    const auto res = s.run();
    ASSERT_TRUE(has_code(res.findings, code::not_grayscale));
    for (const auto& f : res.findings)
        if (f.code == code::not_grayscale) {
            EXPECT_GT(mf::to_json(f.figures).at("share").get<double>(), 0.9);
        }
}

TEST(ValidateSets, ConstantMapPerChannelOfPackedInput) {
    auto s = clean_set();
    s.add(Role::metalness, "T_metallic.png", constant(64, 64, {0.f}));
    // the albedo's metal square is now dielectric and bright: lower it to keep this test to one rule
    Image a = *s.images.at("T_albedo.png");
    for (auto& v : a.pixels) v = std::min(v, 0.6f);
    s.add(Role::albedo, "T_albedo.png", a);
    auto res = s.run();
    ASSERT_TRUE(has_code(res.findings, code::constant_map)) << dump(res.findings);
    EXPECT_EQ(res.findings.size(), 1u) << dump(res.findings);
    EXPECT_EQ(res.findings[0].role, "metalness");
    EXPECT_EQ(res.findings[0].severity, mf::Severity::info);
    EXPECT_EQ(mf::to_json(res.findings[0].figures).at("value")[0], 0.0);

    // ORM with a constant B: the finding names the channel and the role it holds.
    s.remove("T_metallic.png");
    s.remove("T_roughness.png");
    s.remove("T_ao.png");
    Image orm(64, 64, 3);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            orm.at(x, y, 0) = 0.5f + 0.005f * static_cast<float>(y);
            orm.at(x, y, 1) = 0.2f + 0.01f * static_cast<float>(x);
            orm.at(x, y, 2) = 0.f;
        }
    s.add(Role::orm, "T_orm.png", orm);
    res = s.run();
    ASSERT_EQ(res.findings.size(), 1u) << dump(res.findings);
    EXPECT_EQ(res.findings[0].code, code::constant_map);
    EXPECT_EQ(res.findings[0].role, "metalness");
    EXPECT_NE(res.findings[0].message.find("channel B"), std::string::npos);
}

TEST(ValidateSets, MetalnessNotBinary) {
    auto s = clean_set();
    Image m = *s.images.at("T_metallic.png");
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 64; ++x) m.at(x, y) = 0.5f;
    s.add(Role::metalness, "T_metallic.png", m);
    const auto res = s.run();
    ASSERT_TRUE(has_code(res.findings, code::metalness_not_binary)) << dump(res.findings);
    for (const auto& f : res.findings)
        if (f.code == code::metalness_not_binary) {
            EXPECT_NEAR(mf::to_json(f.figures).at("share_between").get<double>(), 0.5, 1e-9);
        }
    // The blend area is left out of the albedo statistics: no albedo finding.
    EXPECT_FALSE(has_code(res.findings, code::albedo_too_bright));
}

TEST(ValidateSets, AlbedoTooDarkAndTooBright) {
    auto s = clean_set();
    Image a = *s.images.at("T_albedo.png");
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 32; ++x)
            for (int c = 0; c < 3; ++c) a.at(x, y, c) = 0.04f;  // ~10 sRGB
    s.add(Role::albedo, "T_albedo.png", a);
    auto res = s.run();
    ASSERT_TRUE(has_code(res.findings, code::albedo_too_dark)) << dump(res.findings);
    for (const auto& f : res.findings)
        if (f.code == code::albedo_too_dark) {
            // 32×64 dark pixels of the 64×64 − 32×32 dielectric ones.
            EXPECT_NEAR(mf::to_json(f.figures).at("share").get<double>(), 2048.0 / 3072.0, 1e-9);
            EXPECT_EQ(mf::to_json(f.figures).at("threshold_srgb"), 30.0);
            EXPECT_TRUE(mf::to_json(f.figures).at("metalness_mask").get<bool>());
        }
    // 40 sRGB passes the tolerant bound (30) and fails the strict one (50).
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 32; ++x)
            for (int c = 0; c < 3; ++c) a.at(x, y, c) = 40.f / 255.f;
    s.add(Role::albedo, "T_albedo.png", a);
    EXPECT_FALSE(has_code(s.run().findings, code::albedo_too_dark));
    std::string err;
    auto strict = mf::rules::RuleConfig::from_json({{"preset", "strict"}}, err);
    ASSERT_TRUE(strict) << err;
    EXPECT_TRUE(has_code(s.run(*strict).findings, code::albedo_too_dark));

    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 32; ++x)
            for (int c = 0; c < 3; ++c) a.at(x, y, c) = 0.99f;
    s.add(Role::albedo, "T_albedo.png", a);
    res = s.run();
    EXPECT_TRUE(has_code(res.findings, code::albedo_too_bright)) << dump(res.findings);
    EXPECT_FALSE(has_code(res.findings, code::albedo_too_dark));
}

TEST(ValidateSets, AlbedoMaskedByOpacityAndMetalness) {
    auto s = clean_set();
    Image a = *s.images.at("T_albedo.png");
    Image op(64, 64, 1, 1.f);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 32; ++x) {
            for (int c = 0; c < 3; ++c) a.at(x, y, c) = 0.f;  // black where invisible
            op.at(x, y) = 0.f;
        }
    s.add(Role::albedo, "T_albedo.png", a);
    s.add(Role::opacity, "T_opacity.png", op);
    EXPECT_FALSE(has_code(s.run().findings, code::albedo_too_dark)) << dump(s.run().findings);
    // Same with the opacity in the albedo's alpha (glTF baseColor alpha).
    s.remove("T_opacity.png");
    Image rgba(64, 64, 4);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            for (int c = 0; c < 3; ++c) rgba.at(x, y, c) = a.at(x, y, c);
            rgba.at(x, y, 3) = op.at(x, y);
        }
    s.add(Role::albedo, "T_albedo.png", rgba);
    EXPECT_FALSE(has_code(s.run().findings, code::albedo_too_dark));
    // Without a mask it fires.
    s.add(Role::albedo, "T_albedo.png", a);
    EXPECT_TRUE(has_code(s.run().findings, code::albedo_too_dark));
}

TEST(ValidateSets, FloatAlbedoIsLinear) {
    // 0.2 linear is ~124 sRGB: plausible. The same 0.2 in an 8-bit file is 51 sRGB... and 0.01
    // linear (~25 sRGB) is too dark.
    auto s = clean_set();
    s.remove("T_metallic.png");
    Image a(64, 64, 3);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
            for (int c = 0; c < 3; ++c) a.at(x, y, c) = 0.2f + 0.001f * static_cast<float>(x);
    s.add(Role::albedo, "T_albedo.exr", a, true);
    s.remove("T_albedo.png");
    EXPECT_TRUE(s.run().findings.empty()) << dump(s.run().findings);
    for (auto& v : a.pixels) v = 0.01f + v * 0.001f;
    s.add(Role::albedo, "T_albedo.exr", a, true);
    EXPECT_TRUE(has_code(s.run().findings, code::albedo_too_dark));
}

TEST(ValidateSets, MetalAlbedoTooDark) {
    auto s = clean_set();
    Image a = *s.images.at("T_albedo.png");
    for (int y = 32; y < 64; ++y)
        for (int x = 32; x < 64; ++x)
            for (int c = 0; c < 3; ++c) a.at(x, y, c) = 0.35f;  // ~89 sRGB metal
    s.add(Role::albedo, "T_albedo.png", a);
    const auto res = s.run();
    ASSERT_TRUE(has_code(res.findings, code::metal_albedo_too_dark)) << dump(res.findings);
    EXPECT_FALSE(has_code(res.findings, code::albedo_too_dark));
    for (const auto& f : res.findings)
        if (f.code == code::metal_albedo_too_dark) {
            EXPECT_EQ(mf::to_json(f.figures).at("pixels"), 1024);
            EXPECT_NEAR(mf::to_json(f.figures).at("median_srgb").get<double>(), 89.0, 1.0);
        }
}

TEST(ValidateSets, NormalInvalid) {
    auto s = clean_set();
    // An object-space-like map: Z < 0 in a quarter of the pixels.
    Image n = *s.images.at("T_normal_gl.png");
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) n.at(x, y, 2) = 0.1f;  // z = −0.8
    s.add(Role::normal, "T_normal_gl.png", n, false, NormalConvention::gl);
    auto res = s.run();
    ASSERT_TRUE(has_code(res.findings, code::normal_invalid)) << dump(res.findings);
    for (const auto& f : res.findings)
        if (f.code == code::normal_invalid) {
            EXPECT_NEAR(mf::to_json(f.figures).at("negative_z_share").get<double>(), 0.25, 1e-9);
            EXPECT_EQ(f.severity, mf::Severity::error);
        }
    // A height map named as a normal map: lengths far from 1.
    Image g(64, 64, 3);
    const Image& h = *s.images.at("T_height.png");
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
            for (int c = 0; c < 3; ++c) g.at(x, y, c) = h.at(x, y);
    s.add(Role::normal, "T_normal_gl.png", g, false, NormalConvention::gl);
    res = s.run();
    ASSERT_TRUE(has_code(res.findings, code::normal_invalid)) << dump(res.findings);
    for (const auto& f : res.findings)
        if (f.code == code::normal_invalid) {
            EXPECT_GT(mf::to_json(f.figures).at("bad_length_share").get<double>(), 0.5);
        }
}

TEST(ValidateSets, NormalConventionMismatchFromContent) {
    for (bool with_height : {true, false}) {
        auto s = clean_set(128);
        const Image h = *s.images.at("T_height.png");
        s.add(Role::normal, "T_normal_gl.png", normal_from_height(h, NormalConvention::dx), false,
              NormalConvention::gl);
        if (!with_height) s.remove("T_height.png");
        const auto res = s.run();
        ASSERT_TRUE(has_code(res.findings, code::normal_convention_mismatch)) << "with_height=" << with_height << "\n"
                                                                              << dump(res.findings);
        ASSERT_TRUE(res.normal);
        EXPECT_EQ(res.normal->content.convention, NormalConvention::dx);
        EXPECT_EQ(res.normal->resolved, NormalConvention::gl) << "the name still decides";
        EXPECT_EQ(res.normal->content.method, with_height ? "height+curl" : "curl");
        for (const auto& f : res.findings)
            if (f.code == code::normal_convention_mismatch) {
                EXPECT_GE(mf::to_json(f.figures).at("confidence").get<double>(), 0.6);
                EXPECT_EQ(mf::to_json(f.figures).at("name_convention"), "gl");
            }
    }
}

TEST(ValidateSets, NormalConventionFromContentWhenNameSilent) {
    auto s = clean_set(128);
    const Image h = *s.images.at("T_height.png");
    s.add(Role::normal, "T_normal.png", normal_from_height(h, NormalConvention::dx));
    s.remove("T_normal_gl.png");
    const auto res = s.run();
    EXPECT_TRUE(res.findings.empty()) << dump(res.findings);
    ASSERT_TRUE(res.normal);
    EXPECT_EQ(res.normal->resolved, NormalConvention::dx);
    EXPECT_EQ(res.normal->source, "content");
}

TEST(ValidateSets, NormalConventionUnknown) {
    // Height varying along x only (vertical stripes): no mixed derivative, no height map, no
    // convention in the name → undecidable.
    auto s = clean_set();
    Image h(64, 64, 1);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) h.at(x, y) = 0.5f + 0.5f * std::sin(static_cast<float>(x) * 0.4f);
    s.remove("T_height.png");
    s.remove("T_normal_gl.png");
    s.add(Role::normal, "T_normal.png", normal_from_height(h, NormalConvention::gl));
    const auto res = s.run();
    ASSERT_TRUE(has_code(res.findings, code::normal_convention_unknown)) << dump(res.findings);
    EXPECT_EQ(res.normal->resolved, NormalConvention::unknown);
    EXPECT_EQ(res.normal->source, "none");
}

TEST(ValidateSets, ColorSpaceMismatchFromTags) {
    auto s = clean_set();
    s.input("T_roughness.png")->color_tag = {mv::ColorTag::srgb, "png:sRGB", "sRGB"};
    auto res = s.run();
    ASSERT_TRUE(has_code(res.findings, code::color_space_mismatch)) << dump(res.findings);
    EXPECT_EQ(res.findings.size(), 1u);
    EXPECT_EQ(res.findings[0].role, "roughness");
    EXPECT_EQ(mf::to_json(res.findings[0].figures).at("tag_source"), "png:sRGB");
    // The reverse: an 8-bit albedo tagged linear.
    s.input("T_roughness.png")->color_tag = {};
    s.input("T_albedo.png")->color_tag = {mv::ColorTag::linear, "png:gAMA", "gamma 1.00"};
    res = s.run();
    ASSERT_EQ(res.findings.size(), 1u) << dump(res.findings);
    EXPECT_EQ(res.findings[0].code, code::color_space_mismatch);
    EXPECT_EQ(mf::to_json(res.findings[0].figures).at("expected"), "srgb");
    // Albedo tagged sRGB is right; roughness tagged linear is right.
    s.input("T_albedo.png")->color_tag = {mv::ColorTag::srgb, "png:sRGB", "sRGB"};
    s.input("T_roughness.png")->color_tag = {mv::ColorTag::linear, "png:gAMA", "gamma 1.00"};
    EXPECT_TRUE(s.run().findings.empty());
}

TEST(ValidateSets, UnreadableFileIsReportedAndOthersStillChecked) {
    auto s = clean_set();
    s.broken.push_back("T_metallic.png");
    Image a = *s.images.at("T_albedo.png");
    for (auto& v : a.pixels) v = 0.02f;
    s.add(Role::albedo, "T_albedo.png", a);
    const auto res = s.run();
    EXPECT_TRUE(has_code(res.findings, code::unreadable_file)) << dump(res.findings);
    EXPECT_TRUE(has_code(res.findings, code::albedo_too_dark));
}

TEST(ValidateSets, SuppressionsAndSeverityOverrides) {
    auto s = clean_set();
    Image a = *s.images.at("T_albedo.png");
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 32; ++x)
            for (int c = 0; c < 3; ++c) a.at(x, y, c) = 0.04f;
    s.add(Role::albedo, "T_albedo.png", a);
    std::string err;
    auto cfg = mf::rules::RuleConfig::from_json(
        nlohmann::json::parse(R"({"suppress": [{"material": "Coal*", "code": "ALBEDO_TOO_DARK",
                                               "reason": "coal is that dark"}],
                                  "severityOverrides": {"ALBEDO_TOO_DARK": 0}})"),
        err);
    ASSERT_TRUE(cfg) << err;
    auto res = s.run(*cfg, "Coal01");
    EXPECT_FALSE(has_code(res.findings, code::albedo_too_dark));
    EXPECT_EQ(s.dropped, 1);
    res = s.run(*cfg, "Bricks01");
    ASSERT_TRUE(has_code(res.findings, code::albedo_too_dark));
    EXPECT_EQ(res.findings[0].severity, mf::Severity::error);
    // A threshold from the config: min 5 sRGB lets it pass.
    auto loose = mf::rules::RuleConfig::from_json({{"rules", {{"ALBEDO_TOO_DARK", {{"min_srgb", 5}}}}}}, err);
    ASSERT_TRUE(loose) << err;
    EXPECT_FALSE(has_code(s.run(*loose).findings, code::albedo_too_dark));
}

TEST(ValidateSets, FindingsAreDeterministicAndOrdered) {
    auto s = clean_set();
    Image a = *s.images.at("T_albedo.png");
    for (auto& v : a.pixels) v = 0.02f;
    s.add(Role::albedo, "T_albedo.png", a);
    s.add(Role::metalness, "T_metallic.png", constant(64, 64, {0.5f}));
    const auto r1 = s.run();
    const auto r2 = s.run({}, "Test", 7);
    ASSERT_EQ(dump(r1.findings), dump(r2.findings));
    const auto& cat = mf::finding_catalog();
    auto rank = [&](const std::string& c) {
        for (size_t i = 0; i < cat.size(); ++i)
            if (cat[i].code == c) return i;
        return cat.size();
    };
    for (size_t i = 1; i < r1.findings.size(); ++i) EXPECT_LE(rank(r1.findings[i - 1].code), rank(r1.findings[i].code));
}

TEST(ValidateSets, HeaderThatDisagreesWithThePixelsIsUnreadable) {
    auto s = clean_set();
    s.input("T_roughness.png")->info.width = 128;  // the caller's header facts are stale
    const auto res = s.run();
    ASSERT_TRUE(has_code(res.findings, code::unreadable_file)) << dump(res.findings);
    EXPECT_EQ(res.findings[0].file, "T_roughness.png");
}
