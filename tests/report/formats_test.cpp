// The findings reports (lib/report/formats.hpp) over a manifest: JSON shape
// (docs/validate-report.md), JUnit parsed as XML (libxml2), SARIF 2.1.0 required fields, text
// grouping; the verdict and exit codes (validate/verdict.hpp); sources rebased.
#include <gtest/gtest.h>
#include <libxml/parser.h>
#include <libxml/tree.h>

#include <memory>

#include "core/json.hpp"
#include "core/text.hpp"
#include "report/formats.hpp"

namespace mv = mf::validate;
namespace mr = mf::report;
using nlohmann::json;

namespace {

mf::Finding finding(std::string code, mf::Severity s, std::string role, std::string file, std::string msg) {
    mf::Finding f;
    f.code = std::move(code);
    f.severity = s;
    f.role = std::move(role);
    f.file = std::move(file);
    f.message = std::move(msg);
    f.figures = {{"share", 0.25}};
    return f;
}

mf::manifest::Manifest sample() {
    mf::manifest::Manifest r;
    mf::manifest::Material bricks;
    bricks.name = "Bricks059";
    bricks.source = "in/Bricks059 1K";
    bricks.findings = {finding("ALBEDO_TOO_DARK", mf::Severity::warning, "albedo", "Bricks059_Color.png",
                               "25.0 % of dielectric albedo is darker than 30 sRGB <&> \"quoted\""),
                       finding("NORMAL_INVALID", mf::Severity::error, "normal", "Bricks059_Normal.png",
                               std::string("control \x01 char")),
                       finding("CONSTANT_MAP", mf::Severity::info, "metalness", "Bricks059_Metal.png",
                               "holds one value (0)")};
    bricks.convention = "ambientcg";
    mf::manifest::Input normal;
    normal.role = mf::Role::normal;
    normal.file = "Bricks059_Normal.png";
    normal.rule = "ambientcg:_Normal";
    normal.normal = mf::manifest::NormalFacts{mf::NormalConvention::dx, "content", 0.87, "height+curl"};
    bricks.inputs.push_back(normal);
    bricks.constants.push_back({mf::Role::metalness, {0.f}});
    r.materials.push_back(std::move(bricks));
    mf::manifest::Material clean;
    clean.name = "Clean";
    clean.source = "in/Clean";
    r.materials.push_back(std::move(clean));
    r.failures.push_back({"in/Broken.zip", "UNREADABLE_FILE", "in/Broken.zip: not a zip archive"});
    return r;
}

struct XmlDoc {
    xmlDocPtr doc = nullptr;
    ~XmlDoc() {
        if (doc) xmlFreeDoc(doc);
    }
};

std::vector<xmlNodePtr> children(xmlNodePtr n, const char* name) {
    std::vector<xmlNodePtr> v;
    for (xmlNodePtr c = n->children; c; c = c->next)
        if (c->type == XML_ELEMENT_NODE && xmlStrcmp(c->name, reinterpret_cast<const xmlChar*>(name)) == 0)
            v.push_back(c);
    return v;
}

std::string attr(xmlNodePtr n, const char* name) {
    xmlChar* v = xmlGetProp(n, reinterpret_cast<const xmlChar*>(name));
    std::string s = v ? reinterpret_cast<const char*>(v) : "";
    xmlFree(v);
    return s;
}

}  // namespace

TEST(Report, JsonShape) {
    const json j = json::parse(mr::write_json(sample()));
    EXPECT_EQ(j.at("report_version"), 1);
    ASSERT_EQ(j.at("materials").size(), 2u);
    const json& m = j.at("materials")[0];
    EXPECT_EQ(m.at("name"), "Bricks059");
    EXPECT_EQ(m.at("source"), "in/Bricks059 1K");
    ASSERT_EQ(m.at("findings").size(), 3u);
    const json& f = m.at("findings")[0];
    for (const char* k : {"code", "severity", "role", "file", "message", "figures"}) EXPECT_TRUE(f.contains(k)) << k;
    EXPECT_EQ(j.at("failures")[0].at("code"), "UNREADABLE_FILE");
    EXPECT_EQ(j.at("summary"), (json{{"error", 1}, {"warning", 1}, {"info", 1}, {"failures", 1}}));
    EXPECT_EQ(mr::write_json(sample()), mr::write_json(sample())) << "deterministic";
    // Written one material at a time, the bytes of the whole tree's dump (none, one, two).
    mf::manifest::Manifest r = sample();
    EXPECT_EQ(mr::write_json(r), mf::json_text(mr::report_json(r)));
    r.materials.pop_back();
    EXPECT_EQ(mr::write_json(r), mf::json_text(mr::report_json(r)));
    r.materials.clear();
    EXPECT_EQ(mr::write_json(r), mf::json_text(mr::report_json(r)));
}

TEST(Report, Verdict) {
    mv::Summary s;
    EXPECT_FALSE(mv::run_fails(s, mv::FailOn::error));
    s.warning = 1;
    EXPECT_FALSE(mv::run_fails(s, mv::FailOn::error));
    EXPECT_TRUE(mv::run_fails(s, mv::FailOn::warning));
    EXPECT_FALSE(mv::run_fails(s, mv::FailOn::never));
    s.error = 1;
    EXPECT_TRUE(mv::run_fails(s, mv::FailOn::error));
    EXPECT_FALSE(mv::run_fails(s, mv::FailOn::never));
    mv::Summary f;
    f.failures = 1;
    EXPECT_TRUE(mv::run_fails(f, mv::FailOn::never)) << "inputs that could not be processed";
    mv::Summary partial;
    partial.incomplete = 1;
    EXPECT_TRUE(mv::run_fails(partial, mv::FailOn::never)) << "a map that could not be read";
    EXPECT_EQ(mv::fail_on_from_name("warning"), mv::FailOn::warning);
    EXPECT_FALSE(mv::fail_on_from_name("fatal"));
}

TEST(Report, TextGroupedByMaterial) {
    const std::string t = mr::write_text(sample(), mv::FailOn::error);
    const auto b = t.find("Bricks059  (in/Bricks059 1K)");
    const auto c = t.find("Clean  (in/Clean)");
    ASSERT_NE(b, std::string::npos) << t;
    ASSERT_NE(c, std::string::npos) << t;
    EXPECT_LT(b, t.find("ALBEDO_TOO_DARK"));
    EXPECT_LT(t.find("ALBEDO_TOO_DARK"), c);
    EXPECT_NE(t.find("ok: no findings"), std::string::npos);
    EXPECT_NE(t.find("1 error(s), 1 warning(s), 1 info; 1 input(s) failed"), std::string::npos) << t;
    EXPECT_NE(t.find("FAIL"), std::string::npos);
}

TEST(Report, JUnitParsesAsXmlWithOneCasePerMaterialAndRule) {
    const std::string x = mr::write_junit(sample(), mv::FailOn::warning);
    XmlDoc d;
    d.doc = xmlReadMemory(x.data(), static_cast<int>(x.size()), "junit.xml", nullptr, XML_PARSE_NONET);
    ASSERT_NE(d.doc, nullptr) << x;
    xmlNodePtr root = xmlDocGetRootElement(d.doc);
    ASSERT_STREQ(reinterpret_cast<const char*>(root->name), "testsuites");
    const auto suites = children(root, "testsuite");
    ASSERT_EQ(suites.size(), 3u);  // two materials + the inputs that failed
    EXPECT_EQ(attr(suites[0], "name"), "Bricks059");
    const auto cases = children(suites[0], "testcase");
    // Every validate rule is a test case, whether it fired or not.
    const auto clean_cases = children(suites[1], "testcase");
    EXPECT_EQ(cases.size(), clean_cases.size());
    EXPECT_GE(cases.size(), 14u);
    EXPECT_EQ(attr(suites[0], "tests"), std::to_string(cases.size()));
    int failures = 0, with_out = 0;
    for (xmlNodePtr c : cases) {
        EXPECT_EQ(attr(c, "classname"), "matforge.validate.Bricks059");
        const auto fl = children(c, "failure");
        failures += static_cast<int>(fl.size());
        with_out += static_cast<int>(children(c, "system-out").size());
        if (attr(c, "name") == "ALBEDO_TOO_DARK") {
            ASSERT_EQ(fl.size(), 1u);
            // Escaping round-trips.
            EXPECT_EQ(attr(fl[0], "message"), "25.0 % of dielectric albedo is darker than 30 sRGB <&> \"quoted\"");
        }
    }
    EXPECT_EQ(failures, 2);  // warning + error at --fail-on warning
    EXPECT_EQ(with_out, 1);  // the info finding is reported but passes
    EXPECT_EQ(attr(suites[0], "failures"), "2");
    EXPECT_EQ(attr(root, "failures"), "2");
    EXPECT_EQ(attr(root, "errors"), "1");
    const auto input_cases = children(suites[2], "testcase");
    ASSERT_EQ(input_cases.size(), 1u);
    EXPECT_EQ(children(input_cases[0], "error").size(), 1u);
    // At --fail-on error only the error fails.
    const std::string x2 = mr::write_junit(sample(), mv::FailOn::error);
    XmlDoc d2;
    d2.doc = xmlReadMemory(x2.data(), static_cast<int>(x2.size()), "junit.xml", nullptr, XML_PARSE_NONET);
    ASSERT_NE(d2.doc, nullptr);
    EXPECT_EQ(attr(children(xmlDocGetRootElement(d2.doc), "testsuite")[0], "failures"), "1");
}

TEST(Report, SarifRequiredFields) {
    const json s = json::parse(mr::write_sarif(sample()));
    EXPECT_EQ(s.at("version"), "2.1.0");
    EXPECT_TRUE(s.at("$schema").get<std::string>().find("sarif-2.1.0") != std::string::npos);
    ASSERT_EQ(s.at("runs").size(), 1u);
    const json& run = s.at("runs")[0];
    const json& driver = run.at("tool").at("driver");
    EXPECT_EQ(driver.at("name"), "matforge");
    std::vector<std::string> ids;
    for (const auto& r : driver.at("rules")) {
        ids.push_back(r.at("id"));
        EXPECT_TRUE(r.at("shortDescription").at("text").is_string());
        const std::string lvl = r.at("defaultConfiguration").at("level");
        EXPECT_TRUE(lvl == "error" || lvl == "warning" || lvl == "note");
    }
    const json& results = run.at("results");
    ASSERT_EQ(results.size(), 4u);
    for (const auto& r : results) {
        const std::string id = r.at("ruleId");
        const int idx = r.at("ruleIndex");
        ASSERT_LT(static_cast<size_t>(idx), ids.size());
        EXPECT_EQ(ids[static_cast<size_t>(idx)], id);
        const std::string lvl = r.at("level");
        EXPECT_TRUE(lvl == "error" || lvl == "warning" || lvl == "note");
        EXPECT_TRUE(r.at("message").at("text").is_string());
        EXPECT_TRUE(r.at("locations")[0].at("physicalLocation").at("artifactLocation").at("uri").is_string());
    }
    EXPECT_EQ(results[0].at("locations")[0]["physicalLocation"]["artifactLocation"]["uri"],
              "in/Bricks059%201K/Bricks059_Color.png");
    EXPECT_EQ(results[2].at("level"), "note");
    EXPECT_EQ(results[0].at("properties").at("material"), "Bricks059");
}

TEST(Report, ShowsWhatWasDecided) {
    const json j = json::parse(mr::write_json(sample()));
    const json& m = j.at("materials")[0];
    EXPECT_EQ(m.at("convention"), "ambientcg");
    EXPECT_EQ(m.at("inputs").at("normal").at("file"), "Bricks059_Normal.png");
    EXPECT_EQ(m.at("inputs").at("normal").at("normal_convention"), "dx");
    EXPECT_EQ(m.at("inputs").at("normal").at("normal_convention_source"), "content");
    EXPECT_EQ(m.at("inputs").at("normal").at("normal_convention_method"), "height+curl");
    EXPECT_EQ(m.at("constants").at("metalness"), 0.0);
    const std::string text = mr::write_text(sample(), mv::FailOn::error);
    EXPECT_NE(text.find("normal              Bricks059_Normal.png  [ambientcg:_Normal]  dx (from the content: "
                        "height+curl test, confidence 87 %)"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("generated on ingest: metalness 0"), std::string::npos) << text;
    const json sarif = json::parse(mr::write_sarif(sample()));
    const json& run = sarif.at("runs")[0];
    ASSERT_EQ(run.at("artifacts").size(), 1u);
    EXPECT_EQ(run.at("artifacts")[0].at("location").at("uri"), "in/Bricks059%201K/Bricks059_Normal.png");
    EXPECT_EQ(run.at("artifacts")[0].at("properties").at("role"), "normal");
    EXPECT_EQ(run.at("artifacts")[0].at("properties").at("normal_convention_confidence"), 0.87);
    EXPECT_EQ(run.at("properties").at("materials")[0].at("constants").at("metalness"), 0.0);
}

TEST(Report, Escaping) {
    EXPECT_EQ(mf::markup_escape("a<b>&\"'"), "a&lt;b&gt;&amp;&quot;&#39;");
    EXPECT_EQ(mf::markup_escape(std::string("\x01")), "\xEF\xBF\xBD");
    EXPECT_EQ(mf::percent_encode_path("a b/c#d.png"), "a%20b/c%23d.png");
}

TEST(Report, SourcesRebasedToWhereTheReaderStands) {
    // An ingest manifest keeps sources relative to its folder; its reports name them from here.
    mf::manifest::Manifest m = sample();
    m.materials[0].source = "../in/Bricks059 1K";
    m.materials[1].source = ".";
    mr::rebase_sources(m, "out/gltf");
    EXPECT_EQ(m.materials[0].source, "out/in/Bricks059 1K");
    EXPECT_EQ(m.materials[1].source, "out/gltf");
    EXPECT_EQ(m.failures[0].source, "out/gltf/in/Broken.zip");
    const json s = json::parse(mr::write_sarif(m));
    EXPECT_EQ(s.at("runs")[0].at("results")[0]["locations"][0]["physicalLocation"]["artifactLocation"]["uri"],
              "out/in/Bricks059%201K/Bricks059_Color.png");
    EXPECT_EQ(mr::format_from_name("sarif"), mr::Format::sarif);
    EXPECT_FALSE(mr::format_from_name("html")) << "the page is report.hpp's, not a findings format";
    EXPECT_EQ(mr::write_findings(m, mr::Format::junit, mv::FailOn::error), mr::write_junit(m, mv::FailOn::error));
}
