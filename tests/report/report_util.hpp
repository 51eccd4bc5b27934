// Helpers of tests/report: running matforge, a fresh folder per test, the sample report
// (ingest + preview + report of sample_materials), and reading the page back.
#pragma once
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include <unistd.h>

#include "run_binary.hpp"
#include "test_files.hpp"

namespace mfr {
namespace fs = std::filesystem;

using mf::testfiles::read_json;
using mf::testfiles::read_pixels;

// Runs `matforge ARGS...` (no shell); a failure message carries the output.
inline ::testing::AssertionResult matforge(const std::vector<std::string>& args, int want = 0) {
    std::vector<std::string> argv{mf::testenv::bin()};
    argv.insert(argv.end(), args.begin(), args.end());
    const auto p = mf::testbin::spawn(argv, 300);
    if (!p.hung && p.signal == 0 && p.code == want) return ::testing::AssertionSuccess();
    std::string cmd;
    for (const auto& a : args) cmd += " " + a;
    return ::testing::AssertionFailure() << "matforge" << cmd << ": exit " << p.code << " (signal " << p.signal
                                         << (p.hung ? ", hung" : "") << "), want " << want << ":\n"
                                         << p.output;
}

inline fs::path samples() { return mf::testenv::source_dir() / "sample_materials"; }

// A fresh, empty folder per test (its manifests go to the schema spool when the test ends).
inline fs::path temp_dir(const std::string& name) { return mf::testdirs::fresh_for_test("matforge-report-", name); }

inline std::string read_text(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(f), {}};
}

// The sample report's sizes: previews rendered larger than the thumbnails, so every picture of
// the page (all from 1K maps) is reduced to exactly kThumb on its long side.
inline constexpr int kThumb = 160;
inline constexpr int kPreviewSize = 192;

struct SampleReport {
    fs::path manifest, previews, report;
};

// ingest (gltf) + preview (lavapipe) + report of sample_materials under `work`.
inline ::testing::AssertionResult make_sample_report(const fs::path& work, SampleReport& r) {
    r.manifest = work / "out" / "manifest.json";
    r.previews = work / "out" / "preview";
    r.report = work / "report";
    if (auto a = matforge({"ingest", samples().string(), "-o", (work / "out").string(), "--preset", "gltf", "-q"}); !a)
        return a;
    if (auto a = matforge({"preview", r.manifest.string(), "-o", r.previews.string(), "--device", "cpu", "--size",
                           std::to_string(kPreviewSize)});
        !a)
        return a;
    return matforge({"report", r.manifest.string(), "-o", r.report.string(), "--previews", r.previews.string(),
                     "--thumb-size", std::to_string(kThumb), "-q"});
}

// One <img> of the page.
struct Img {
    std::string src, cls;
    int width = 0, height = 0;
};

// The value of attribute `name` (` name="..."`) in a tag's text, or "" (no std::regex: GCC 12's
// <regex> trips -Wmaybe-uninitialized in the sanitizer build).
inline std::string attribute_of(const std::string& tag, const std::string& name) {
    const std::string key = " " + name + "=\"";
    const size_t at = tag.find(key);
    if (at == std::string::npos) return {};
    const size_t start = at + key.size(), end = tag.find('"', start);
    return end == std::string::npos ? std::string() : tag.substr(start, end - start);
}

inline std::vector<Img> images_of(const std::string& html) {
    std::vector<Img> out;
    for (size_t at = html.find("<img "); at != std::string::npos; at = html.find("<img ", at + 1)) {
        const size_t end = html.find('>', at);
        if (end == std::string::npos) break;
        const std::string t = html.substr(at, end - at + 1);
        Img i;
        i.src = attribute_of(t, "src");
        i.cls = attribute_of(t, "class");
        const std::string w = attribute_of(t, "width"), h = attribute_of(t, "height");
        if (!w.empty()) i.width = std::stoi(w);
        if (!h.empty()) i.height = std::stoi(h);
        out.push_back(i);
    }
    return out;
}

// The HTML of the card whose data-material is `escaped_name` (empty when there is none).
inline std::string card_of(const std::string& html, const std::string& escaped_name) {
    const std::string key = "data-material=\"" + escaped_name + "\"";
    const size_t at = html.find(key);
    if (at == std::string::npos) return {};
    const size_t start = html.rfind("<section class=\"card", at);
    const size_t end = html.find("</section>", at);
    if (start == std::string::npos || end == std::string::npos) return {};
    return html.substr(start, end - start);
}

}  // namespace mfr

namespace mfr {

// The sample report, made once per test program (ctest runs each test in its own process, so
// each of them makes it; running test_report alone makes it once).
class SampleReportTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        work_ = fs::temp_directory_path() / ("matforge-report-sample-" + std::to_string(::getpid()));
        fs::remove_all(work_);
        fs::create_directories(work_);
        made_ = make_sample_report(work_, r_);
        if (made_) manifest_ = read_json(r_.manifest);
    }
    static void TearDownTestSuite() {
        std::error_code ec;
        fs::remove_all(work_, ec);
    }
    void SetUp() override { ASSERT_TRUE(made_) << made_.message(); }

    static inline fs::path work_;
    static inline SampleReport r_;
    static inline ::testing::AssertionResult made_ = ::testing::AssertionFailure();
    static inline nlohmann::json manifest_;
};

}  // namespace mfr
