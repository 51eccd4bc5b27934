// Every real set of the corpus through the binary, judged against truth.json: the role of every
// file, the normal map's convention, the findings (no false error or warning, every true problem
// at warning/error reported at its expected severity) and `validate --fail-on error`'s exit code.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <map>
#include <set>
#include <sstream>

#include "corpus.hpp"
#include "test_files.hpp"

namespace {

using corpus::fs::path;
using nlohmann::json;

struct SetRun {
    std::string folder;  // as truth.json names it: real/<set>
    const json* truth = nullptr;
    corpus::RunResult validate_text;  // validate <set> --fail-on error
    int validate_json_code = -1;
    json report;  // validate --report json
    int ingest_code = -1;
    json manifest;  // ingest -o <tmp> --preset gltf
    std::string ingest_output;
};

json read_json_file(const path& p) {
    std::ifstream f(p);
    if (!f) return json();
    auto j = json::parse(f, nullptr, false);
    return j.is_discarded() ? json() : j;
}

// Runs each set once for all the tests below.
const std::vector<SetRun>& runs() {
    static const std::vector<SetRun> all = [] {
        std::vector<SetRun> v;
        const json* t = corpus::truth();
        if (!t) return v;
        const path tmp = corpus::temp_dir("sets");
        int i = 0;
        for (const auto& s : t->at("sets")) {
            SetRun r;
            r.folder = s.at("folder").get<std::string>();
            r.truth = &s;
            const path in = corpus::dir() / r.folder;
            r.validate_text = corpus::run("validate " + corpus::q(in) + " --fail-on error");
            const path rep = tmp / ("report" + std::to_string(i) + ".json");
            r.validate_json_code =
                corpus::run("validate " + corpus::q(in) + " --report json --report-file " + corpus::q(rep)).code;
            r.report = read_json_file(rep);
            const path out = tmp / ("out" + std::to_string(i));
            const auto ing = corpus::run("ingest " + corpus::q(in) + " -o " + corpus::q(out) + " --preset gltf");
            r.ingest_code = ing.code;
            r.ingest_output = ing.output;
            r.manifest = read_json_file(out / "manifest.json");
            v.push_back(std::move(r));
            ++i;
        }
        std::error_code ec;
        corpus::fs::remove_all(tmp, ec);
        return v;
    }();
    return all;
}

// Every finding of every material of a report (the flat folder holds two materials).
std::vector<json> findings_of(const json& doc) {
    std::vector<json> out;
    if (!doc.is_object() || !doc.contains("materials")) return out;
    for (const auto& m : doc.at("materials"))
        for (const auto& f : m.value("findings", json::array())) out.push_back(f);
    return out;
}

// The role matforge gave a file: a manifest input's role; else the role of an AMBIGUOUS_MAP that
// names it among the candidates; else "ignore" when validate reported UNRECOGNIZED_FILE; else "".
std::string found_role(const SetRun& r, const std::string& file) {
    if (r.manifest.contains("materials"))
        for (const auto& m : r.manifest.at("materials")) {
            const json inputs = m.value("inputs", json::object());
            for (const auto& [role, in] : inputs.items())
                if (in.value("file", "") == file) return role;
        }
    for (const auto& f : findings_of(r.report)) {
        if (f.value("code", "") != "AMBIGUOUS_MAP") continue;
        const json fig = f.value("figures", json::object());
        for (const auto& c : fig.value("candidates", json::array()))
            if (c.is_string() && c.get<std::string>() == file) return f.value("role", "");
    }
    for (const auto& f : findings_of(r.report))
        if (f.value("code", "") == "UNRECOGNIZED_FILE" && f.value("file", "") == file) return "ignore";
    return "";
}

// Whether an input's rule cites the MaterialX document `file` (its rule names an mtlx input).
bool cited_sidecar(const SetRun& r, const std::string& file) {
    if (!file.ends_with(".mtlx") || !r.manifest.contains("materials")) return false;
    for (const auto& m : r.manifest.at("materials")) {
        const json inputs = m.value("inputs", json::object());
        for (const auto& in : inputs)
            if (in.value("rule", "").find("mtlx:") != std::string::npos) return true;
    }
    return false;
}

// Whether a material's licence was read from the licence file `file` (provenance.licence.evidence).
bool cited_licence(const SetRun& r, const std::string& file) {
    if (!r.manifest.contains("materials")) return false;
    for (const auto& m : r.manifest.at("materials")) {
        const json p = m.value("provenance", json::object());
        if (p.contains("licence") && p.at("licence").at("evidence").value("how", "") == "file" &&
            p.at("licence").at("evidence").value("file", "") == file)
            return true;
    }
    return false;
}

// The manifest's normal convention for a normal input file, "" when it is not an input.
std::string found_convention(const SetRun& r, const std::string& file) {
    if (!r.manifest.contains("materials")) return "";
    for (const auto& m : r.manifest.at("materials")) {
        const json inputs = m.value("inputs", json::object());
        if (inputs.contains("normal") && inputs.at("normal").value("file", "") == file)
            return inputs.at("normal").value("normal_convention", "?");
    }
    return "";
}

std::string set_name(const std::string& folder) { return folder.substr(folder.find('/') + 1); }

bool is_blocking(const std::string& s) { return s == "error" || s == "warning"; }

// A finding is explained by truth.json when a true problem or an acceptable entry on its file maps
// to its code.
bool explained(const json& set, const json& f) {
    const std::string file = f.value("file", ""), c = f.value("code", "");
    for (const char* key : {"true_problems", "acceptable"})
        for (const auto& p : set.value(key, json::array()))
            if (p.value("file", "") == file && corpus::code_of_problem(p.value("problem", "")) == c) return true;
    return false;
}

TEST(RealCorpus, EveryTrueProblemKindHasACode) {
    const json* t = corpus::truth();
    ASSERT_TRUE(t);
    for (const auto& s : t->at("sets"))
        for (const char* key : {"true_problems", "acceptable"})
            for (const auto& p : s.value(key, json::array()))
                EXPECT_TRUE(corpus::code_of_problem(p.value("problem", "")))
                    << s.at("folder") << ": no code for \"" << p.value("problem", "")
                    << "\" (add it to problem_codes())";
}

void check_every_set_runs() {
    for (const auto& r : runs()) {
        EXPECT_TRUE(r.report.contains("materials")) << r.folder << ": no JSON report";
        EXPECT_TRUE(r.manifest.contains("materials")) << r.folder << ": no manifest\n" << r.ingest_output;
        EXPECT_TRUE(r.ingest_code == 0 || r.ingest_code == 1) << r.folder << ": ingest exit " << r.ingest_code;
        EXPECT_EQ(r.validate_json_code, r.validate_text.code)
            << r.folder << ": the report format changed the exit code";
    }
}

void check_roles() {
    for (const auto& r : runs())
        for (const auto& [file, info] : r.truth->at("files").items()) {
            const std::string want = info.at("role").get<std::string>(), got = found_role(r, file);
            if (want == "ignore")
                EXPECT_EQ(got, "ignore") << r.folder << "/" << file << ": truth says not a material map";
            else if (want == "sidecar")  // read as evidence: not reported, and cited by an input's rule
                EXPECT_TRUE(got.empty() && cited_sidecar(r, file))
                    << r.folder << "/" << file << ": a sidecar, got " << (got.empty() ? "(none)" : got);
            else if (want == "licence")  // read as the licence's evidence: not reported, and cited by it
                EXPECT_TRUE(got.empty() && cited_licence(r, file))
                    << r.folder << "/" << file << ": a licence file, got " << (got.empty() ? "(none)" : got);
            else
                EXPECT_TRUE(corpus::role_matches(want, got)) << r.folder << "/" << file << ": truth role " << want
                                                             << ", matforge " << (got.empty() ? "(none)" : got);
        }
}

void check_normal_conventions() {
    int checked = 0;
    for (const auto& r : runs())
        for (const auto& [file, info] : r.truth->at("files").items()) {
            if (info.at("role") != "normal") continue;
            const std::string got = found_convention(r, file);
            if (got.empty()) continue;  // not the chosen normal map (RolesMatchTruth checks its role)
            ++checked;
            EXPECT_EQ(got, info.at("normal_convention").get<std::string>()) << r.folder << "/" << file;
        }
    // One normal map per material: 19 materials in 18 folders (two of them hand-named copies).
    EXPECT_EQ(checked, 19);
}

// The LICENCE_UNKNOWN findings of a material entry (manifest or report).
std::vector<json> licence_unknown(const json& m) {
    std::vector<json> out;
    for (const auto& f : m.value("findings", json::array()))
        if (f.value("code", "") == "LICENCE_UNKNOWN") out.push_back(f);
    return out;
}

// Every material's provenance as truth.json's `provenance` says the folder proves it: vendor,
// asset id, licence with its evidence, the page, the credit, the vendor's preview; where no
// licence can be known, none and one LICENCE_UNKNOWN (info). The same in validate's report.
void check_provenance() {
    int known = 0, unknown = 0;
    for (const auto& r : runs()) {
        if (!r.manifest.contains("materials") || !r.report.contains("materials")) continue;  // every set runs fails
        const json& want_all = r.truth->at("provenance");
        EXPECT_EQ(r.manifest.at("materials").size(), want_all.size()) << r.folder << ": one provenance per material";
        for (const auto& m : r.manifest.at("materials")) {
            const std::string name = m.at("name").get<std::string>();
            SCOPED_TRACE(r.folder + " " + name);
            ASSERT_TRUE(want_all.contains(name)) << "truth.json has no provenance for this material";
            const json& want = want_all.at(name);
            const json got = m.value("provenance", json::object());
            const auto text = [](const json& o, const char* key) {
                return o.contains(key) && o.at(key).is_string() ? o.at(key).get<std::string>() : std::string("(none)");
            };
            for (const char* key : {"vendor", "asset_id", "url", "attribution"})
                EXPECT_EQ(text(got, key), text(want, key)) << key;
            const json inputs = m.value("inputs", json::object());
            EXPECT_EQ(inputs.contains("preview") ? inputs.at("preview").value("file", "") : "(none)",
                      text(want, "preview"));
            if (want.at("licence").is_null()) {
                ++unknown;
                EXPECT_FALSE(got.contains("licence")) << got.dump();
                const auto found = licence_unknown(m);
                ASSERT_EQ(found.size(), 1u) << m.at("findings").dump(1);
                EXPECT_EQ(found[0].at("severity"), "info");
                EXPECT_TRUE(found[0].at("message").get<std::string>().starts_with("no licence found: ") ||
                            found[0].at("message").get<std::string>().starts_with("the set's licence files"));
            } else {
                ++known;
                ASSERT_TRUE(got.contains("licence")) << got.dump();
                const json& l = got.at("licence");
                EXPECT_EQ(text(l, "spdx"), want.at("licence").get<std::string>());
                EXPECT_EQ(l.at("evidence").at("how"), want.at("evidence").at("how"));
                EXPECT_EQ(l.at("evidence").at("file"), want.at("evidence").at("file"));
                EXPECT_EQ(l.at("attribution_required"), want.contains("attribution"));
                EXPECT_TRUE(licence_unknown(m).empty());
            }
            // validate reports what ingest records.
            for (const auto& v : r.report.at("materials"))
                if (v.at("name") == name) {
                    EXPECT_EQ(v.value("provenance", json::object()), got);
                    EXPECT_EQ(licence_unknown(v).size(), licence_unknown(m).size());
                }
        }
    }
    // 19 materials: 10 with a licence the folder proves, 9 without.
    EXPECT_EQ(known, 10);
    EXPECT_EQ(unknown, 9);
}

void check_good_sets_have_no_error() {
    for (const auto& r : runs()) {
        if (!r.truth->at("good_set").get<bool>()) continue;
        for (const auto& f : findings_of(r.report))
            EXPECT_NE(f.value("severity", ""), "error") << r.folder << ": " << f.dump();
    }
}

void check_no_false_error_or_warning() {
    for (const auto& r : runs())
        for (const auto& f : findings_of(r.report)) {
            if (!is_blocking(f.value("severity", ""))) continue;
            EXPECT_TRUE(explained(*r.truth, f))
                << r.folder << ": false " << f.value("severity", "") << " " << f.value("code", "") << " on "
                << f.value("file", "") << ": " << f.value("message", "");
        }
}

void check_true_problems_reported() {
    for (const auto& r : runs())
        for (const auto& p : r.truth->at("true_problems")) {
            const std::string sev = p.at("expected_severity").get<std::string>();
            if (!is_blocking(sev)) continue;
            const std::string file = p.at("file").get<std::string>();
            const auto c = corpus::code_of_problem(p.at("problem").get<std::string>());
            if (!c) continue;  // EveryTrueProblemKindHasACode fails
            std::string seen;
            for (const auto& f : findings_of(r.report))
                if (f.value("file", "") == file && f.value("code", "") == *c) seen = f.value("severity", "");
            EXPECT_EQ(seen, sev) << r.folder << "/" << file << ": " << *c << " for \""
                                 << p.at("problem").get<std::string>() << "\"" << (seen.empty() ? " not reported" : "");
        }
}

void check_fail_on_error() {
    for (const auto& r : runs()) {
        const bool good = r.truth->at("good_set").get<bool>();
        EXPECT_EQ(r.validate_text.code, good ? 0 : 1) << r.folder << "\n" << r.validate_text.output;
        if (good) continue;
        for (const auto& p : r.truth->at("true_problems")) {
            if (p.at("expected_severity") != "error") continue;
            const auto c = corpus::code_of_problem(p.at("problem").get<std::string>());
            if (!c) continue;
            const std::string file = p.at("file").get<std::string>();
            bool named = false;
            std::istringstream lines(r.validate_text.output);
            for (std::string line; std::getline(lines, line);)
                named = named || (line.find("error") != std::string::npos && line.find(*c) != std::string::npos &&
                                  line.find(file) != std::string::npos);
            EXPECT_TRUE(named) << r.folder << ": the text report names no error " << *c << " on " << file << "\n"
                               << r.validate_text.output;
        }
    }
}

// The summary table (printed; the checks above assert): roles right/total, normal verdicts,
// error/warning findings true/false, true problems at warning/error missed.
void print_table() {
    std::printf("\n%-42s %-7s %-26s %-11s %s\n", "set", "roles", "normal (got/truth)", "err+warn", "missed");
    for (const auto& r : runs()) {
        int right = 0, total = 0;
        std::string normals, wrong_roles;
        for (const auto& [file, info] : r.truth->at("files").items()) {
            const std::string want = info.at("role").get<std::string>(), got = found_role(r, file);
            ++total;
            const bool ok = want == "ignore"    ? got == "ignore"
                            : want == "sidecar" ? got.empty() && cited_sidecar(r, file)
                            : want == "licence" ? got.empty() && cited_licence(r, file)
                                                : corpus::role_matches(want, got);
            right += ok ? 1 : 0;
            if (!ok) wrong_roles += " " + file + "(" + want + "->" + (got.empty() ? "none" : got) + ")";
            if (want == "normal") {
                const std::string c = found_convention(r, file);
                if (!c.empty())
                    normals += (normals.empty() ? "" : ",") + c + "/" +
                               info.at("normal_convention").get<std::string>() +
                               (c == info.at("normal_convention") ? "" : "!");
            }
        }
        int true_f = 0, false_f = 0;
        for (const auto& f : findings_of(r.report))
            if (is_blocking(f.value("severity", ""))) ++(explained(*r.truth, f) ? true_f : false_f);
        int missed = 0;
        for (const auto& p : r.truth->at("true_problems")) {
            if (!is_blocking(p.at("expected_severity"))) continue;
            const auto c = corpus::code_of_problem(p.at("problem").get<std::string>());
            bool seen = false;
            for (const auto& f : findings_of(r.report))
                seen = seen || (c && f.value("file", "") == p.at("file") && f.value("code", "") == *c &&
                                f.value("severity", "") == p.at("expected_severity"));
            missed += seen ? 0 : 1;
        }
        std::printf("%-42s %2d/%-4d %-26s %3d/%-7d %d%s\n", set_name(r.folder).c_str(), right, total, normals.c_str(),
                    true_f, false_f, missed, wrong_roles.empty() ? "" : ("   roles:" + wrong_roles).c_str());
    }
}

// One test: every set runs once (three binary runs per set), and ctest starts one process per
// test. Each check says which one failed.
TEST(RealCorpus, EverySetAgreesWithTruth) {
    ASSERT_TRUE(corpus::truth());
    ASSERT_FALSE(runs().empty());
    const std::vector<std::pair<const char*, void (*)()>> checks{
        {"every set runs", check_every_set_runs},
        {"roles match truth", check_roles},
        {"normal conventions match truth", check_normal_conventions},
        {"provenance matches truth", check_provenance},
        {"good sets have no error", check_good_sets_have_no_error},
        {"every error and warning is a true problem", check_no_false_error_or_warning},
        {"every true problem is reported at its severity", check_true_problems_reported},
        {"--fail-on error passes good sets and names the error of the others", check_fail_on_error},
        {"summary table", print_table},
    };
    for (const auto& [what, check] : checks) {
        SCOPED_TRACE(what);
        check();
    }
}

}  // namespace

// The batch tells which sets need attention: on a terminal each set's progress line says
// "errors" / "warnings" (never "ok" for a set with findings to act on), and the summary names
// the sets with errors. Run under script(1) for a pseudo-terminal, over one defective and one
// good set of the corpus.
TEST(RealCorpus, BatchOutputNamesTheSetsThatNeedAttention) {
    const path tmp = corpus::temp_dir("attention");
    const path bad = corpus::dir() / "real/polyhaven_broken_wall_1k_jpg+webp";
    const path good = corpus::dir() / "real/ambientcg_Net004A_1K-JPG";
    const std::string cmd = mf::testenv::bin() + " ingest " + corpus::q(bad) + " " + corpus::q(good) + " -o " +
                            corpus::q(tmp / "out") + " --no-cache";
    const std::string log = (tmp / "tty.log").string();
    const int status =
        std::system(("script -qec " + corpus::q(cmd) + " " + corpus::q(log) + " >/dev/null 2>&1").c_str());
    ASSERT_NE(status, -1);
    std::ifstream f(log);
    const std::string out((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    EXPECT_NE(out.find("broken_wall errors"), std::string::npos) << out;
    // The net's one warning is a true problem truth.json lists (albedo very dark: ALBEDO_TOO_DARK).
    EXPECT_NE(out.find("Net004A warnings"), std::string::npos) << out;
    EXPECT_EQ(out.find("Net004A ok"), std::string::npos) << out;
    EXPECT_NE(out.find("sets with errors: broken_wall"), std::string::npos) << out;
    EXPECT_NE(out.find("sets with warnings: Net004A"), std::string::npos) << out;
    // Without a terminal: no progress lines, the same summary.
    const auto r = corpus::run("ingest " + corpus::q(bad) + " " + corpus::q(good) + " -o " + corpus::q(tmp / "out2") +
                               " --no-cache");
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_EQ(r.output.find("broken_wall errors"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("sets with errors: broken_wall"), std::string::npos) << r.output;
    std::filesystem::remove_all(tmp);
}

// 3dtextures.me ships an all-black `_opacity` placeholder with Sci-Fi_Wall_014: applied, it made
// the material invisible (glTF alphaMode MASK, alpha 0 everywhere) and the report card said "ok"
// beside "1 error". The map keeps its role (the manifest's inputs) and is not applied: the base color is written
// without alpha, the glTF material is opaque, the error names the file and says so, and no "ok" badge sits beside it.
TEST(RealCorpus, PlaceholderOpacityIsNotApplied) {
    const path tmp = corpus::temp_dir("placeholder");
    const path set = corpus::dir() / "real/3dtextures_Sci-Fi_Wall_014";
    const auto r = corpus::run("ingest " + corpus::q(set) + " -o " + corpus::q(tmp / "out") +
                               " --preset gltf --no-cache");
    EXPECT_EQ(r.code, 1) << r.output;  // the error stays: the set ships a broken file
    const nlohmann::json m = mf::testfiles::read_json(tmp / "out/manifest.json");
    ASSERT_EQ(m["materials"].size(), 1u) << m.dump(1);
    const nlohmann::json& mat = m["materials"][0];
    EXPECT_EQ(mat["inputs"]["opacity"]["file"], "Sci-Fi_Wall_014_opacity.jpg") << "its role, unused";
    int said = 0;
    for (const auto& f : mat["findings"])
        if (f["code"] == "OPACITY_ALL_TRANSPARENT") {
            ++said;
            EXPECT_EQ(f["file"], "Sci-Fi_Wall_014_opacity.jpg");
            EXPECT_EQ(f["severity"], "error");
            EXPECT_NE(f["message"].get<std::string>().find("not applied (the material is written opaque)"),
                      std::string::npos)
                << f.dump();
        }
    EXPECT_EQ(said, 1) << mat["findings"].dump(1);
    const std::string base = mat["name"].get<std::string>() + "/" + mat["name"].get<std::string>() + "_basecolor.png";
    EXPECT_EQ(mf::testfiles::read_pixels(tmp / "out" / base).channels, 3) << base;
    const nlohmann::json gltf = mf::testfiles::read_json(tmp / "out" / mat["name"].get<std::string>() /
                                                         (mat["name"].get<std::string>() + ".gltf"));
    const nlohmann::json& material = gltf["materials"][0];
    EXPECT_EQ(material.value("alphaMode", "OPAQUE"), "OPAQUE") << material.dump();
    // The report card: the error badge, and no "ok" status badge beside it.
    const auto rep = corpus::run("report " + corpus::q(tmp / "out/manifest.json") + " -o " + corpus::q(tmp / "report"));
    ASSERT_EQ(rep.code, 0) << rep.output;
    std::ifstream page(tmp / "report/index.html");
    const std::string html((std::istreambuf_iterator<char>(page)), std::istreambuf_iterator<char>());
    EXPECT_NE(html.find("1 error</span>"), std::string::npos);
    EXPECT_EQ(html.find("badge status-ok"), std::string::npos);
    std::filesystem::remove_all(tmp);
}
