// RuleConfig: defaults, presets, --rules FILE parsing, suppressions, severity overrides.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "findings/rules.hpp"

namespace mv = mf::rules;
using nlohmann::json;

TEST(RuleConfig, DefaultsAreTheCitedNumbers) {
    const mv::RuleConfig cfg;
    EXPECT_EQ(cfg.thresholds.albedo_min_srgb, 30.0);
    EXPECT_EQ(cfg.thresholds.albedo_max_srgb, 240.0);
    EXPECT_EQ(cfg.thresholds.metal_albedo_min_srgb, 180.0);
    EXPECT_EQ(mv::strict_thresholds().albedo_min_srgb, 50.0);
    EXPECT_EQ(mv::strict_thresholds().albedo_max_srgb, 243.0);
    EXPECT_EQ(cfg.severity_of(mf::code::normal_invalid), mf::Severity::error);
    EXPECT_EQ(cfg.severity_of(mf::code::constant_map), mf::Severity::info);
    EXPECT_EQ(cfg.severity_of(mf::code::albedo_too_dark), mf::Severity::warning);
}

TEST(RuleConfig, ThresholdTableRoundTripsEveryThreshold) {
    // What a manifest records of the run's thresholds gives back the same numbers, the strict
    // ones too; a code or name no rule has is an error naming it.
    for (const mv::Thresholds& t : {mv::Thresholds{}, mv::strict_thresholds()}) {
        const mv::ThresholdTable table = mv::threshold_table(t);
        EXPECT_EQ(table.at("ALBEDO_TOO_DARK").at("min_srgb"), t.albedo_min_srgb);
        EXPECT_EQ(table.at("METAL_ALBEDO_TOO_DARK").at("metal_min"), t.metal_min);
        std::string error;
        const auto back = mv::thresholds_from(table, error, mv::Thresholds{.albedo_min_srgb = 1, .albedo_max_srgb = 2});
        ASSERT_TRUE(back) << error;
        EXPECT_EQ(mv::threshold_table(*back), table);
    }
    std::string error;
    EXPECT_FALSE(mv::thresholds_from({{"ALBEDO_TOO_DARK", {{"min_srg", 3.0}}}}, error));
    EXPECT_NE(error.find("min_srg"), std::string::npos) << error;
    EXPECT_FALSE(mv::thresholds_from({{"NO_SUCH_CODE", {{"max_share", 0.1}}}}, error));
    EXPECT_NE(error.find("NO_SUCH_CODE"), std::string::npos) << error;
}

// "exclude": files that are no maps, by glob over the path or the name, per material.
TEST(RuleConfig, ExcludesFilesByName) {
    std::string err;
    auto cfg = mv::RuleConfig::from_json(json::parse(R"({"exclude": ["*_preview_big.png",
        {"file": "*_opacity.jpg", "material": "Fabric_*", "reason": "all-black placeholder"}]})"),
                                         err);
    ASSERT_TRUE(cfg) << err;
    ASSERT_EQ(cfg->exclusions.size(), 2u);
    EXPECT_EQ(cfg->excluded("Fabric_polyester_003", "Fabric_polyester_003_opacity.jpg"), &cfg->exclusions[1]);
    EXPECT_EQ(cfg->excluded("Fabric_polyester_003", "maps/Fabric_polyester_003_opacity.jpg"), &cfg->exclusions[1])
        << "the name, in a subfolder";
    EXPECT_EQ(cfg->excluded("Wall", "Wall_opacity.jpg"), nullptr) << "another material";
    EXPECT_EQ(cfg->excluded("Wall", "Wall_preview_big.png"), &cfg->exclusions[0]);
    EXPECT_EQ(cfg->excluded("Fabric_x", "Fabric_x_Color.jpg"), nullptr);
    EXPECT_EQ(mv::describe(*cfg).at("exclude").size(), 2u) << "part of the run's context";
    EXPECT_FALSE(mv::describe(mv::RuleConfig{}).contains("exclude")) << "no key without exclusions";
    for (const char* bad : {R"({"exclude": "x.png"})", R"({"exclude": [3]})", R"({"exclude": [{"material": "a"}]})",
                            R"({"exclude": [{"file": "a", "why": "b"}]})", R"({"exclude": [""]})"})
        EXPECT_FALSE(mv::RuleConfig::from_json(json::parse(bad), err)) << bad;
}

TEST(RuleConfig, ParsesEveryForm) {
    std::string err;
    auto cfg = mv::RuleConfig::from_json(json::parse(R"({
        "preset": "strict",
        "rules": {
            "ALBEDO_TOO_BRIGHT": {"max_srgb": 245, "severity": "error"},
            "CONSTANT_MAP": "off",
            "NOT_GRAYSCALE": "info",
            "NORMAL_INVALID": {"enabled": false}
        },
        "severityOverrides": {"METALNESS_NOT_BINARY": 2},
        "ignore": ["RESOLUTION_MISMATCH"],
        "suppress": [{"material": "Metal*", "code": "*"}]
    })"),
                                         err);
    ASSERT_TRUE(cfg) << err;
    EXPECT_EQ(cfg->thresholds.albedo_min_srgb, 50.0);
    EXPECT_EQ(cfg->thresholds.albedo_max_srgb, 245.0);
    EXPECT_EQ(cfg->severity_of("ALBEDO_TOO_BRIGHT"), mf::Severity::error);
    EXPECT_EQ(cfg->severity_of("NOT_GRAYSCALE"), mf::Severity::info);
    EXPECT_EQ(cfg->severity_of("METALNESS_NOT_BINARY"), mf::Severity::info);
    EXPECT_FALSE(cfg->enabled("CONSTANT_MAP"));
    EXPECT_FALSE(cfg->enabled("NORMAL_INVALID"));
    EXPECT_FALSE(cfg->enabled("RESOLUTION_MISMATCH"));
    EXPECT_TRUE(cfg->enabled("ALBEDO_TOO_DARK"));
    EXPECT_TRUE(cfg->suppressed("Metal007", "ALBEDO_TOO_DARK"));
    EXPECT_FALSE(cfg->suppressed("Bricks", "ALBEDO_TOO_DARK"));

    // Layering: a preset's block, then --rules FILE on top.
    auto layered = mv::RuleConfig::from_json(json::parse(R"({"rules": {"CONSTANT_MAP": "warning"}})"), err, *cfg);
    ASSERT_TRUE(layered) << err;
    EXPECT_TRUE(layered->enabled("CONSTANT_MAP"));
    EXPECT_EQ(layered->severity_of("CONSTANT_MAP"), mf::Severity::warning);
    EXPECT_EQ(layered->thresholds.albedo_max_srgb, 245.0);
}

TEST(RuleConfig, RejectsTyposAndBadTypes) {
    for (const char* bad : {
             R"([])",
             R"({"rulez": {}})",
             R"({"preset": "lenient"})",
             R"({"rules": {"ALBEDO_TO_DARK": "off"}})",
             R"({"rules": {"ALBEDO_TOO_DARK": {"min_rgb": 3}}})",
             R"({"rules": {"ALBEDO_TOO_DARK": {"min_srgb": "3"}}})",
             R"({"rules": {"ALBEDO_TOO_DARK": "fatal"}})",
             R"({"severityOverrides": {"ALBEDO_TOO_DARK": 7}})",
             R"({"ignore": ["NOPE"]})",
             R"({"suppress": [{"material": "x"}]})",
             R"({"suppress": [{"code": "CONSTANT_MAP", "materal": "x"}]})",
         }) {
        std::string err;
        EXPECT_FALSE(mv::RuleConfig::from_json(json::parse(bad), err)) << bad;
        EXPECT_FALSE(err.empty()) << bad;
    }
}

TEST(RuleConfig, GlobMatch) {
    EXPECT_TRUE(mv::glob_match("*", ""));
    EXPECT_TRUE(mv::glob_match("Metal*", "Metal007"));
    EXPECT_TRUE(mv::glob_match("*0?7", "Metal007"));
    EXPECT_TRUE(mv::glob_match("a*b*c", "axxbyyc"));
    EXPECT_FALSE(mv::glob_match("a*b*c", "axxbyy"));
    EXPECT_FALSE(mv::glob_match("metal*", "Metal007"));
}

TEST(RuleConfig, ApplyConfigToOtherStagesFindings) {
    std::string err;
    auto cfg = mv::RuleConfig::from_json(
        json::parse(R"({"ignore": ["UNRECOGNIZED_FILE"], "severityOverrides": {"MISSING_MAP": "warning"}})"), err);
    ASSERT_TRUE(cfg) << err;
    std::vector<mf::Finding> fs(3);
    fs[0].code = "UNRECOGNIZED_FILE";
    fs[1].code = "MISSING_MAP";
    fs[1].severity = mf::Severity::info;
    fs[2].code = "AMBIGUOUS_MAP";
    EXPECT_EQ(mv::apply_config(fs, "M", *cfg), 1);
    ASSERT_EQ(fs.size(), 2u);
    EXPECT_EQ(fs[0].code, "MISSING_MAP");
    EXPECT_EQ(fs[0].severity, mf::Severity::warning);
}

TEST(RuleConfig, DescribeListsEveryRule) {
    const json d = mv::describe(mv::RuleConfig{});
    for (const auto& r : mf::finding_catalog()) EXPECT_TRUE(d.at("rules").contains(std::string(r.code)));
    EXPECT_EQ(d.at("rules").at("ALBEDO_TOO_DARK").at("min_srgb"), 30.0);
}
