// `matforge validate` as CI runs it, and the content verdict reaching ingest.
#include "cli_util.hpp"

using namespace mft;

TEST(ValidateCli, JsonReportOnSamples) {
    const fs::path out = temp_dir("out");
    const auto r = run("validate " + q(samples()) + " --report json --report-file " + q(out / "r.json"));
    ASSERT_EQ(r.code, 0) << r.output;
    const auto j = read_json(out / "r.json");
    EXPECT_EQ(j["report_version"], 1);
    ASSERT_EQ(j["materials"].size(), 9u);
    EXPECT_TRUE(j["failures"].empty());
    int counts[3] = {0, 0, 0};
    std::string previous;
    for (const auto& m : j["materials"]) {
        EXPECT_LT(previous, m["name"].get<std::string>()) << "materials sorted by name";
        previous = m["name"];
        for (const auto& f : m["findings"]) {
            const std::string s = f["severity"];
            ++counts[s == "error" ? 2 : s == "warning" ? 1 : 0];
        }
    }
    EXPECT_EQ(j["summary"]["error"], counts[2]);
    EXPECT_EQ(j["summary"]["warning"], counts[1]);
    EXPECT_EQ(j["summary"]["info"], counts[0]);
    EXPECT_EQ(counts[2], 0) << "the samples are clean of errors";
}

TEST(ValidateCli, FailOnWarningAndSuppression) {
    // MarbleTiles0017's 2K albedo differs in size from its other maps: a warning.
    const fs::path out = temp_dir("out");
    auto r = run("validate " + q(samples()) + " --fail-on warning");
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("RESOLUTION_MISMATCH"), std::string::npos);
    write_text(out / "rules.json",
               R"({"suppress": [{"material": "Marble*", "code": "RESOLUTION_MISMATCH", "reason": "vendor ships 2K color"}]})");
    r = run("validate " + q(samples()) + " --fail-on warning --rules " + q(out / "rules.json"));
    EXPECT_EQ(r.code, 0) << r.output;
    write_text(out / "bad.json", R"({"rules": {"NO_SUCH_CODE": "off"}})");
    r = run("validate " + q(samples()) + " --rules " + q(out / "bad.json"));
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("bad.json"), std::string::npos);
}

TEST(ValidateCli, SarifLocationsAreImageFiles) {
    const auto r = run("validate " + q(samples() / "MarbleTiles0017") + " --report sarif");
    ASSERT_EQ(r.code, 0) << r.output;
    const auto j = nlohmann::json::parse(r.output);
    EXPECT_EQ(j["version"], "2.1.0");
    ASSERT_FALSE(j["runs"].empty());
    bool found = false;
    for (const auto& res : j["runs"][0]["results"]) {
        if (res["ruleId"] != "RESOLUTION_MISMATCH") continue;
        found = true;
        const std::string uri = res["locations"][0]["physicalLocation"]["artifactLocation"]["uri"];
        EXPECT_NE(uri.find("MarbleTiles0017_COL_2K.jpg"), std::string::npos) << uri;
        EXPECT_EQ(res["level"], "warning");
    }
    EXPECT_TRUE(found);
}

TEST(ValidateCli, CorruptMapIsAnErrorNamingTheFile) {
    const fs::path in = temp_dir("in");
    fs::copy(samples() / "WalnutInlay", in / "WalnutInlay");
    write_text(in / "WalnutInlay" / "WalnutInlay_occlusion.png", "not an image");
    const auto r = run("validate " + q(in) + " --report json");
    EXPECT_EQ(r.code, 1) << r.output;
    const auto j = nlohmann::json::parse(r.output);
    bool found = false;
    for (const auto& f : j["materials"][0]["findings"])
        if (f["code"] == "UNREADABLE_FILE" && f["file"] == "WalnutInlay_occlusion.png") found = true;
    EXPECT_TRUE(found) << r.output;
}

TEST(IngestContent, UnnamedDxNormalDecidedFromContent) {
    // ScifiPanel's "_Normal" says nothing about green; its pixels are DirectX.
    const fs::path out = temp_dir("out");
    const auto r = run("ingest " + q(samples() / "ScifiPanel") + " -o " + q(out));
    ASSERT_EQ(r.code, 0) << r.output;
    const auto m = read_json(out / "manifest.json");
    const auto& n = m["materials"][0]["inputs"]["normal"];
    EXPECT_EQ(n["normal_convention"], "dx");
    EXPECT_EQ(n["normal_convention_source"], "content");
    EXPECT_GE(n["normal_convention_confidence"].get<double>(), 0.6);
    EXPECT_TRUE(has_finding(m["materials"][0], "NORMAL_CONVENTION_CONVERTED", "normal"));
}
