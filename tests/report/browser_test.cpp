// scripts/browser-check.mjs on the sample report in headless Chromium: every card and finding
// as a reader sees them, rule links that land, no console error, no network, paging.
#include <cstdlib>

#include "report_util.hpp"

using namespace mfr;

namespace {

constexpr const char* kChromium = "/usr/bin/chromium";

// Runs the checker; `json` receives its one JSON line.
::testing::AssertionResult browser_check(const SampleReport& r, const fs::path& shot, nlohmann::json& json) {
    if (!fs::exists(kChromium))
        return ::testing::AssertionFailure()
               << kChromium
               << " is missing: tests/report needs headless Chromium (Debian package `chromium`; "
                  "scripts/bootstrap.sh installs it, CI has it)";
    const auto p = mf::testbin::spawn({"node", mf::testenv::source_dir().string() + "/scripts/browser-check.mjs",
                                       "--page", (r.report / "index.html").string(), "--manifest", r.manifest.string(),
                                       "--screenshot", shot.string(), "--timeout", "150"},
                                      200);
    if (p.code == 127)
        return ::testing::AssertionFailure() << "cannot run node (Debian package `nodejs`):\n" << p.output;
    const size_t at = p.output.find("{\"");
    if (at == std::string::npos)
        return ::testing::AssertionFailure() << "browser-check printed no JSON (exit " << p.code << "):\n" << p.output;
    json = nlohmann::json::parse(p.output.substr(at, p.output.find('\n', at) - at), nullptr, false);
    if (json.is_discarded()) return ::testing::AssertionFailure() << "not JSON:\n" << p.output;
    if (p.code != 0 || json.value("ok", false) != true)
        return ::testing::AssertionFailure() << "browser-check failed (exit " << p.code << "):\n" << p.output;
    return ::testing::AssertionSuccess();
}

size_t findings_of(const nlohmann::json& manifest) {
    size_t n = 0;
    for (const auto& m : manifest["materials"]) n += m["findings"].size();
    return n;
}

}  // namespace

TEST_F(SampleReportTest, BrowserCheckPasses) {
    nlohmann::json j;
    ASSERT_TRUE(browser_check(r_, work_ / "shot.png", j));
    const size_t materials = manifest_["materials"].size();
    EXPECT_EQ(j["materials"], materials);
    EXPECT_EQ(j["cards"], materials);
    EXPECT_EQ(j["cards_without_js"], materials);
    EXPECT_EQ(j["findings_checked"], findings_of(manifest_));
    EXPECT_GE(j["rule_links"].get<int>(), 5);
    EXPECT_GT(j["pictures_checked"].get<int>(), 30);
    EXPECT_EQ(j["paging"], "one page");
    const mf::Image shot = read_pixels(work_ / "shot.png");
    EXPECT_EQ(shot.width, 1280);
    EXPECT_EQ(shot.height, 1000);
}

TEST_F(SampleReportTest, BrowserCheckPagesThroughCards) {
    // Three cards a page: two pages, page 2 holds the fourth card, #m-<last> shows its page.
    SampleReport paged = r_;
    paged.report = work_ / "report-paged";
    ASSERT_TRUE(matforge({"report", r_.manifest.string(), "-o", paged.report.string(), "--previews",
                          r_.previews.string(), "--page-size", "3", "--no-sources", "--thumb-size", "64", "-q"}));
    nlohmann::json j;
    ASSERT_TRUE(browser_check(paged, work_ / "shot-paged.png", j));
    EXPECT_EQ(j["paging"], "2 pages checked");
    EXPECT_EQ(j["cards_without_js"], manifest_["materials"].size());
}
