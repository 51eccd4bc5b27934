// `matforge validate` as CI runs it, and the content verdict reaching ingest. On the real
// samples (sample_materials/SOURCES.md) the expected findings are the sets' true problems: no
// error (every sample is usable), a warning for each problem a technical artist should look at.
#include <map>
#include <set>

#include "cli_util.hpp"

using namespace mft;

TEST(ValidateCli, JsonReportOnSamples) {
    const fs::path out = temp_dir("out");
    const auto r = run("validate " + q(samples()) + " --report json --report-file " + q(out / "r.json"));
    ASSERT_EQ(r.code, 0) << r.output;
    const auto j = read_json(out / "r.json");
    EXPECT_EQ(j["report_version"], 1);
    ASSERT_EQ(j["materials"].size(), 4u);
    EXPECT_TRUE(j["failures"].empty());
    int counts[3] = {0, 0, 0};
    std::string previous;
    std::map<std::string, std::set<std::string>> warnings;
    std::map<std::string, std::set<std::pair<std::string, std::string>>> color_tags;  // material -> (file, severity)
    for (const auto& m : j["materials"]) {
        EXPECT_LT(previous, m["name"].get<std::string>()) << "materials sorted by name";
        previous = m["name"];
        warnings[previous];
        for (const auto& f : m["findings"]) {
            const std::string s = f["severity"];
            ++counts[s == "error" ? 2 : s == "warning" ? 1 : 0];
            if (s == "warning") warnings[previous].insert(f["code"].get<std::string>() + " " + f.value("file", ""));
            if (f["code"] == "COLOR_SPACE_MISMATCH") color_tags[previous].insert({f.value("file", ""), s});
        }
    }
    EXPECT_EQ(j["summary"]["error"], counts[2]);
    EXPECT_EQ(j["summary"]["warning"], counts[1]);
    EXPECT_EQ(j["summary"]["info"], counts[0]);
    EXPECT_EQ(counts[2], 0) << "no sample has an error-level problem";
    // The true warnings, and no other (a warning not listed would be a false positive). A dark
    // metal albedo on the damaged metal may be reported or not: dirt darkens it.
    EXPECT_EQ(warnings["Net004A"], std::set<std::string>{"ALBEDO_TOO_DARK Net004A_1K-JPG_Color.jpg"});
    auto metal = warnings["Metal_Damaged_001"];
    metal.erase("METAL_ALBEDO_TOO_DARK Metal_Damaged_001_basecolor.jpg");
    EXPECT_EQ(metal, std::set<std::string>{"METALNESS_NOT_BINARY Metal_Damaged_001_metallic.jpg"});
    EXPECT_TRUE(warnings["brown_planks_09"].empty()) << *warnings["brown_planks_09"].begin();
    EXPECT_TRUE(warnings["Crystal_003"].empty()) << *warnings["Crystal_003"].begin();
    // A colour tag on a height PNG is read by role and ignored: worth an info, no more.
    using Tag = std::set<std::pair<std::string, std::string>>;
    EXPECT_EQ(color_tags["Metal_Damaged_001"], (Tag{{"Metal_Damaged_001_height.png", "info"}}));
    EXPECT_EQ(color_tags["Crystal_003"], (Tag{{"Crystal_003_DISP.png", "info"}}));
    EXPECT_TRUE(color_tags["Net004A"].empty());
    EXPECT_TRUE(color_tags["brown_planks_09"].empty());
}

TEST(ValidateCli, FailOnWarningAndSuppression) {
    // Two samples carry warnings: Net004A's dark albedo, Metal_Damaged_001's graded metalness
    // (validated together: the suppressions act per material).
    const fs::path out = temp_dir("out");
    const std::string sets = q(samples() / "Net004A_1K-JPG") + " " + q(samples() / "Metal_Damaged_001_SD");
    auto r = run("validate " + sets + " --fail-on warning");
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("ALBEDO_TOO_DARK"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("METALNESS_NOT_BINARY"), std::string::npos) << r.output;
    // Suppressing one material's warning leaves the other's: still a failure.
    write_text(out / "net.json",
               R"({"suppress": [{"material": "Net004A", "code": "ALBEDO_TOO_DARK", "reason": "black rope"}]})");
    r = run("validate " + sets + " --fail-on warning --rules " + q(out / "net.json"));
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("METALNESS_NOT_BINARY"), std::string::npos) << r.output;
    write_text(out / "rules.json",
               R"({"suppress": [{"material": "Net004A", "code": "ALBEDO_TOO_DARK", "reason": "black rope"},
                               {"material": "Metal_*", "code": "METALNESS_NOT_BINARY", "reason": "rust blends"},
                               {"material": "Metal_*", "code": "METAL_ALBEDO_TOO_DARK", "reason": "dirt"}]})");
    r = run("validate " + sets + " --fail-on warning --rules " + q(out / "rules.json"));
    EXPECT_EQ(r.code, 0) << r.output;
    write_text(out / "bad.json", R"({"rules": {"NO_SUCH_CODE": "off"}})");
    r = run("validate " + sets + " --rules " + q(out / "bad.json"));
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("bad.json"), std::string::npos);
}

TEST(ValidateCli, SarifLocationsAreImageFiles) {
    const auto r = run("validate " + q(samples() / "Metal_Damaged_001_SD") + " --report sarif");
    ASSERT_EQ(r.code, 0) << r.output;
    const auto j = nlohmann::json::parse(r.output);
    EXPECT_EQ(j["version"], "2.1.0");
    ASSERT_FALSE(j["runs"].empty());
    std::map<std::string, int> found;
    for (const auto& res : j["runs"][0]["results"]) {
        const std::string uri = res["locations"][0]["physicalLocation"]["artifactLocation"]["uri"];
        if (res["ruleId"] == "METALNESS_NOT_BINARY") {
            ++found["metal"];
            EXPECT_NE(uri.find("Metal_Damaged_001_SD/Metal_Damaged_001_metallic.jpg"), std::string::npos) << uri;
            EXPECT_EQ(res["level"], "warning");
        }
        if (res["ruleId"] == "COLOR_SPACE_MISMATCH") {
            ++found["tag"];
            EXPECT_NE(uri.find("Metal_Damaged_001_SD/Metal_Damaged_001_height.png"), std::string::npos) << uri;
            EXPECT_EQ(res["level"], "note");
        }
    }
    EXPECT_EQ(found["metal"], 1);
    EXPECT_EQ(found["tag"], 1);
}

TEST(ValidateCli, CorruptMapIsAnErrorNamingTheFile) {
    const fs::path in = temp_dir("in");
    fs::copy(samples() / "Metal_Damaged_001_SD", in / "Metal_Damaged_001_SD");
    fs::permissions(in / "Metal_Damaged_001_SD" / "Metal_Damaged_001_ambientOcclusion.jpg", fs::perms::owner_write,
                    fs::perm_options::add);
    write_text(in / "Metal_Damaged_001_SD" / "Metal_Damaged_001_ambientOcclusion.jpg", "not an image");
    const auto r = run("validate " + q(in) + " --report json");
    EXPECT_EQ(r.code, 1) << r.output;
    const auto j = nlohmann::json::parse(r.output);
    bool found = false;
    for (const auto& f : j["materials"][0]["findings"])
        if (f["code"] == "UNREADABLE_FILE" && f["file"] == "Metal_Damaged_001_ambientOcclusion.jpg") found = true;
    EXPECT_TRUE(found) << r.output;
}

TEST(IngestContent, UnnamedGlNormalDecidedFromContent) {
    // Metal_Damaged_001's "_normal" says nothing about green; its pixels (against the set's
    // height map) are OpenGL. glTF keeps it; Unreal gets it converted.
    const fs::path out = temp_dir("out");
    for (const char* preset : {"gltf", "unreal"}) {
        const auto r = run("ingest " + q(samples() / "Metal_Damaged_001_SD") + " -o " + q(out / preset) + " --preset " +
                           preset);
        ASSERT_EQ(r.code, 0) << r.output;
    }
    const auto m = read_json(out / "gltf/manifest.json");
    const auto& n = m["materials"][0]["inputs"]["normal"];
    EXPECT_EQ(n["file"], "Metal_Damaged_001_normal.jpg");
    EXPECT_EQ(n["normal_convention"], "gl");
    EXPECT_EQ(n["normal_convention_source"], "content");
    EXPECT_GE(n["normal_convention_confidence"].get<double>(), 0.6);
    EXPECT_FALSE(has_finding(m["materials"][0], "NORMAL_CONVENTION_CONVERTED"));
    const auto u = read_json(out / "unreal/manifest.json");
    EXPECT_EQ(u["materials"][0]["inputs"]["normal"]["normal_convention"], "gl");
    EXPECT_TRUE(has_finding(u["materials"][0], "NORMAL_CONVENTION_CONVERTED", "normal"));
}

// The terminal shows the signal (issue 45): without --verbose, the errors and warnings with their
// materials, how many materials and infos were left out, and the verdict; with --report-file the
// same summary still reaches the terminal (a red CI job never has an empty log), and the file
// holds every finding.
TEST(ValidateCli, TheTerminalShowsWarningsAndTheVerdict) {
    const fs::path out = temp_dir("terminal");
    const auto brief = run("validate " + q(samples()) + " --fail-on warning");
    EXPECT_EQ(brief.code, 1) << brief.output;
    EXPECT_NE(brief.output.find("METALNESS_NOT_BINARY"), std::string::npos) << brief.output;
    EXPECT_EQ(brief.output.find("  info    "), std::string::npos) << "no info line: " << brief.output;
    EXPECT_NE(brief.output.find("info finding(s) not shown"), std::string::npos) << brief.output;
    EXPECT_NE(brief.output.find("— FAIL (--fail-on warning)"), std::string::npos) << brief.output;
    const auto verbose = run("validate " + q(samples()) + " --fail-on warning --verbose");
    EXPECT_EQ(verbose.code, 1);
    EXPECT_NE(verbose.output.find("  info    "), std::string::npos) << verbose.output;
    EXPECT_GT(verbose.output.size(), 2 * brief.output.size());
    for (const std::string format : {"text", "json", "junit", "sarif"}) {
        const auto r = run("validate " + q(samples()) + " --fail-on warning --report " + format + " --report-file " +
                           q(out / ("r." + format)));
        EXPECT_EQ(r.code, 1) << format;
        EXPECT_NE(r.output.find("METALNESS_NOT_BINARY"), std::string::npos) << format << ": " << r.output;
        EXPECT_NE(r.output.find("— FAIL (--fail-on warning)"), std::string::npos) << format << ": " << r.output;
    }
    EXPECT_NE(bytes_of(out / "r.text").find("  info    "), std::string::npos) << "the file is the whole report";
}

// A shading map the preset has no output for is said (issue 45): d3d11 writes no occlusion and no
// emission texture, so a set with both gets MAP_NOT_WRITTEN (info) for each; gltf writes both.
TEST(ValidateCli, MapsThePresetCannotWriteAreSaid) {
    const fs::path set = mf::testenv::corpus_dir() / "real/ambientcg_OfficeCeiling005_1K-JPG";
    auto not_written = [&](const std::string& preset) {
        const auto r = run("validate " + q(set) + " --preset " + preset + " --report json --fail-on never");
        EXPECT_EQ(r.code, 0) << r.output;
        std::set<std::string> roles;
        const nlohmann::json report = nlohmann::json::parse(r.output);  // named: a temporary's member would dangle
        for (const auto& f : report["materials"][0]["findings"])
            if (f["code"] == "MAP_NOT_WRITTEN") {
                EXPECT_EQ(f["severity"], "info");
                roles.insert(f["role"].get<std::string>());
            }
        return roles;
    };
    EXPECT_EQ(not_written("d3d11"), (std::set<std::string>{"emissive", "occlusion"}));
    EXPECT_TRUE(not_written("gltf").empty());
}
