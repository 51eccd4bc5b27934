// ingest and validate decide once (plan/plan): on the same sets they report the same
// findings, code by code, and no finding twice. Run on the bundled samples and on every set of
// the real-material corpus.
#include <cmath>
#include <map>
#include <set>
#include <tuple>

#include "cli_util.hpp"

using namespace mft;
using nlohmann::json;

namespace {

using Key = std::tuple<std::string, std::string, std::string, std::string>;  // code, severity, role, file

std::multiset<Key> keys(const json& findings) {
    std::multiset<Key> k;
    for (const auto& f : findings) {
        // Only ingest writes files, so only ingest can fail to write one.
        if (f["code"] == "OUTPUT_WRITE_FAILED") continue;
        k.insert({f["code"], f["severity"], f.value("role", ""), f.value("file", "")});
    }
    return k;
}

void expect_parity(const fs::path& input, const fs::path& work, size_t min_materials) {
    const auto in = run("ingest " + q(input) + " -o " + q(work / "out") + " --fail-on never -q");
    ASSERT_TRUE(in.code == 0 || in.code == 1) << in.output;
    const auto va = run("validate " + q(input) + " --report json --report-file " + q(work / "report.json") +
                        " --fail-on never");
    ASSERT_TRUE(va.code == 0 || va.code == 1) << va.output;
    const json manifest = read_json(work / "out/manifest.json");
    const json report = read_json(work / "report.json");
    ASSERT_GE(manifest["materials"].size(), min_materials);
    ASSERT_EQ(manifest["materials"].size(), report["materials"].size());
    std::map<std::string, const json*> reported;
    for (const auto& m : report["materials"]) reported[m["name"]] = &m;
    size_t compared = 0;
    for (const auto& m : manifest["materials"]) {
        const std::string name = m["name"];
        ASSERT_TRUE(reported.count(name)) << name << " is in the manifest, not in the report";
        const auto a = keys(m["findings"]), b = keys((*reported[name])["findings"]);
        EXPECT_EQ(a, b) << name << ": ingest and validate disagree";
        // No finding twice: the same code for the same file and role is one finding.
        const std::set<Key> unique(a.begin(), a.end());
        EXPECT_EQ(unique.size(), a.size()) << name << ": a finding appears twice";
        // validate shows the inputs ingest read, with the same roles and normal verdicts.
        EXPECT_EQ(m["inputs"], (*reported[name])["inputs"]) << name;
        EXPECT_EQ(m["constants"], (*reported[name])["constants"]) << name;
        compared += a.size();
    }
    EXPECT_GT(compared, manifest["materials"].size()) << "the sets raise findings to compare";
}

}  // namespace

TEST(Parity, IngestAndValidateAgreeOnTheSamples) { expect_parity(samples(), temp_dir("samples"), 4); }

TEST(Parity, IngestAndValidateAgreeOnTheRealCorpus) {
    const fs::path corpus = mf::testenv::corpus_dir() / "real";
    ASSERT_TRUE(fs::is_directory(corpus)) << corpus << ": the real-material corpus is missing";
    expect_parity(corpus, temp_dir("corpus"), 19);
}

TEST(Parity, OneFindingPerFactForAnUndecidedNormalMap) {
    // A normal map whose name says nothing and whose content is flat noise (no height map, no
    // integrable structure): NORMAL_CONVENTION_UNKNOWN once, from both commands.
    const fs::path work = temp_dir("unknown");
    mf::Image albedo(32, 32, 3, 0.5f), normal(32, 32, 3);
    uint32_t s = 12345;
    for (size_t i = 0; i < normal.pixels.size(); i += 3) {
        s = s * 1664525u + 1013904223u;
        const float x = static_cast<float>((s >> 8) & 0xFF) / 255.f * 0.4f - 0.2f;
        s = s * 1664525u + 1013904223u;
        const float y = static_cast<float>((s >> 8) & 0xFF) / 255.f * 0.4f - 0.2f;
        const float z = std::sqrt(1.f - x * x - y * y);
        normal.pixels[i] = x * 0.5f + 0.5f;
        normal.pixels[i + 1] = y * 0.5f + 0.5f;
        normal.pixels[i + 2] = z * 0.5f + 0.5f;
    }
    write_png(work / "in/Noise/Noise_albedo.png", albedo);
    write_png(work / "in/Noise/Noise_normal.png", normal);
    expect_parity(work / "in", work, 1);
    const json manifest = read_json(work / "out/manifest.json");
    int unknown = 0;
    for (const auto& f : manifest["materials"][0]["findings"]) unknown += f["code"] == "NORMAL_CONVENTION_UNKNOWN";
    EXPECT_EQ(unknown, 1) << manifest.dump(2);
}

namespace {
// A 128 x 128 map of noise (its PNG does not compress to a few bytes), as `file`, cut to its
// first half when `truncated`: the header reads, the pixels do not.
void noise_map(const fs::path& file, int channels, bool truncated) {
    mf::Image img(128, 128, channels);
    uint32_t s = 777;
    for (float& v : img.pixels) {
        s = s * 1664525u + 1013904223u;
        v = 0.3f + 0.4f * static_cast<float>((s >> 8) & 0xFF) / 255.f;
    }
    write_png(file, img);
    if (truncated) fs::resize_file(file, fs::file_size(file) / 2);
}
}  // namespace

TEST(Parity, ATruncatedMapIsMissingForBothCommands) {
    // validate reads a map's header first and its pixels later: a truncated roughness is
    // unreadable and missing (a constant generated) for validate as for ingest, which decodes it
    // at once; with a readable copy beside it both take the copy.
    const fs::path work = temp_dir("truncated");
    noise_map(work / "in/Cut/Cut_albedo.png", 3, false);
    noise_map(work / "in/Cut/Cut_roughness.png", 1, true);
    expect_parity(work / "in", work, 1);
    json mat = read_json(work / "out/manifest.json")["materials"][0];
    EXPECT_TRUE(has_finding(mat, "UNREADABLE_FILE", "roughness")) << mat.dump(2);
    EXPECT_TRUE(has_finding(mat, "MISSING_MAP", "roughness")) << mat.dump(2);
    EXPECT_FALSE(mat["inputs"].contains("roughness")) << mat.dump(2);

    const fs::path copy = temp_dir("truncated-copy");
    noise_map(copy / "in/Cut/Cut_albedo.png", 3, false);
    noise_map(copy / "in/Cut/Cut_roughness.png", 1, true);
    noise_map(copy / "in/Cut/Cut_roughness.tif", 1, false);
    expect_parity(copy / "in", copy, 1);
    mat = read_json(copy / "out/manifest.json")["materials"][0];
    EXPECT_TRUE(has_finding(mat, "UNREADABLE_FILE", "roughness")) << mat.dump(2);
    EXPECT_FALSE(has_finding(mat, "MISSING_MAP", "roughness")) << mat.dump(2);
    ASSERT_TRUE(mat["inputs"].contains("roughness")) << mat.dump(2);
    EXPECT_EQ(mat["inputs"]["roughness"]["file"], "Cut_roughness.tif");
}

// A JPEG cut short decodes "successfully" in libjpeg (grey past the end, a warning): it is
// unreadable for both commands, named with its problem, never a grey map used as albedo.
TEST(Parity, AJpegCutShortIsUnreadableNotGrey) {
    const fs::path work = temp_dir("jpeg");
    const fs::path set = work / "in/Net";
    fs::create_directories(set);
    for (const auto& e : fs::directory_iterator(samples() / "Net004A_1K-JPG"))
        if (e.path().extension() == ".jpg") fs::copy_file(e.path(), set / e.path().filename());
    const fs::path color = set / "Net004A_1K-JPG_Color.jpg";
    fs::resize_file(color, 2000);
    expect_parity(work / "in", work, 1);
    const json mat = read_json(work / "out/manifest.json")["materials"][0];
    EXPECT_TRUE(has_finding(mat, "UNREADABLE_FILE", "albedo")) << mat.dump(2);
    EXPECT_FALSE(mat["inputs"].contains("albedo")) << mat.dump(2);
    bool said = false;
    for (const auto& f : mat["findings"])
        said = said || (f["code"] == "UNREADABLE_FILE" &&
                        f["message"].get<std::string>().find("cut short") != std::string::npos);
    EXPECT_TRUE(said) << mat.dump(2);
}

TEST(Parity, SchemaSpoolReceivesWhatTheRunsWrote) {
    // The schema check at the end of the suite sees this test's manifest (the spool works).
    const fs::path work = temp_dir("spool");
    ASSERT_EQ(run("ingest " + q(samples() / "Metal_Damaged_001_SD") + " -o " + q(work / "out") + " -q").code, 0);
    const std::optional<fs::path> spool = mf::testenv::schema_spool();
    ASSERT_TRUE(spool) << "ctest sets MATFORGE_SCHEMA_SPOOL for the tests that run the binary";
    mf::testbin::spool_folder(work, "Parity.spool");
    const std::string mine = "Parity.spool-" + std::to_string(::getpid()) + "-";
    int found = 0;
    for (const auto& e : fs::directory_iterator(*spool))
        if (e.path().filename().string().rfind(mine, 0) == 0) {
            ++found;
            EXPECT_NE(read_json(e.path()).value("manifest_version", 0), 0) << e.path();
        }
    EXPECT_EQ(found, 1);
}

// ingest --report writes validate's reports from the manifest it wrote, with the sources rebased
// to where the user stands: on the samples its SARIF names the same results at the same files
// as validate's (but for the writing stage's codes), and every location is a file that exists.
TEST(Parity, IngestReportsAsValidateDoes) {
    const fs::path work = temp_dir("sarif");
    const auto in = run("ingest " + q(samples()) + " -o " + q(work / "out") +
                        " --fail-on never -q --report sarif --report-file " + q(work / "ingest.sarif"));
    ASSERT_EQ(in.code, 0) << in.output;
    const auto va = run("validate " + q(samples()) + " --report sarif --report-file " + q(work / "validate.sarif") +
                        " --fail-on never");
    ASSERT_EQ(va.code, 0) << va.output;
    using Result = std::tuple<std::string, std::string, std::string, std::string>;  // rule, level, uri, material
    auto results = [](const json& sarif) {
        std::multiset<Result> r;
        for (const auto& x : sarif["runs"][0]["results"])
            if (x["ruleId"] != "OUTPUT_WRITE_FAILED")
                r.insert({x["ruleId"].get<std::string>(), x["level"].get<std::string>(),
                          x["locations"][0]["physicalLocation"]["artifactLocation"]["uri"].get<std::string>(),
                          x["properties"]["material"].get<std::string>()});
        return r;
    };
    const json a = read_json(work / "ingest.sarif"), b = read_json(work / "validate.sarif");
    EXPECT_EQ(results(a), results(b));
    EXPECT_GE(results(a).size(), 4u);
    EXPECT_EQ(a["runs"][0]["artifacts"], b["runs"][0]["artifacts"]) << "the same inputs, roles and verdicts";
    for (const auto& [rule, level, uri, material] : results(a)) {
        ASSERT_EQ(uri.rfind("file://", 0), 0u) << uri;
        std::string path = uri.substr(7);
        for (size_t p; (p = path.find("%20")) != std::string::npos;) path.replace(p, 3, " ");
        EXPECT_TRUE(fs::exists(path)) << rule << " " << uri;
    }
    // The report file is checked before anything is read: never an input.
    const fs::path victim = samples() / "Net004A_1K-JPG/Net004A_1K-JPG_Color.jpg";
    const auto bad = run("ingest " + q(samples()) + " -o " + q(work / "out2") + " -q --report json --report-file " +
                         q(victim));
    EXPECT_EQ(bad.code, 2) << bad.output;
    EXPECT_FALSE(fs::exists(work / "out2"));
}
