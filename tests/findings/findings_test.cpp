// The finding type: its JSON form and the worst severity of a list.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "findings/findings.hpp"

TEST(Findings, JsonRoundTrip) {
    mf::Finding f{"MISSING_MAP", mf::Severity::info, "metalness", "", "no metalness map", {{"generated", 0.0}}};
    const auto j = mf::to_json(f);
    EXPECT_EQ(j["severity"], "info");
    EXPECT_FALSE(j.contains("file"));
    std::string error;
    const auto g = mf::finding_from_json(j, error);
    ASSERT_TRUE(g) << error;
    EXPECT_EQ(g->code, f.code);
    EXPECT_EQ(g->role, "metalness");
    EXPECT_EQ(mf::to_json(g->figures).at("generated"), 0.0);
    // Malformed findings are refused naming the member, never a JSON type_error.
    EXPECT_FALSE(mf::finding_from_json({{"code", "X"}, {"severity", "fatal"}}, error));
    EXPECT_NE(error.find("fatal"), std::string::npos);
    EXPECT_FALSE(mf::finding_from_json({{"code", 3}, {"severity", "info"}}, error));
    EXPECT_NE(error.find("code"), std::string::npos);
    EXPECT_FALSE(mf::finding_from_json({{"severity", "info"}}, error));
    EXPECT_FALSE(mf::finding_from_json({{"code", "X"}, {"severity", "info"}, {"figures", 2}}, error));
    EXPECT_EQ(mf::worst({f, {"X", mf::Severity::error, "", "", "", {}}}), mf::Severity::error);
}
