// The finding catalog (findings/catalog.hpp) is the one owner of a code's default severity, title,
// stage and docs anchor: every code constant of findings/findings.hpp is in it once, and
// docs/interface.md's "Finding codes" table and docs/rules.md's rule rows say what it says.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cctype>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "findings/catalog.hpp"
#include "test_env.hpp"

namespace {

std::string read_source(const std::string& rel) {
    std::ifstream f(mf::testenv::source_dir() / rel, std::ios::binary);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

// The rows "| `CODE` | cell | cell | ..." of the markdown table under `heading` (to the next "## ").
std::map<std::string, std::vector<std::string>> table_rows(const std::string& md, const std::string& heading) {
    std::map<std::string, std::vector<std::string>> rows;
    const size_t at = md.find(heading);
    if (at == std::string::npos) return rows;
    const size_t end = md.find("\n## ", at + heading.size());
    std::istringstream lines(md.substr(at, end == std::string::npos ? std::string::npos : end - at));
    const std::regex row(R"(^\| `([A-Z][A-Z0-9_]*)` \|(.*)\|\s*$)");
    for (std::string line; std::getline(lines, line);) {
        std::smatch m;
        if (!std::regex_match(line, m, row)) continue;
        std::vector<std::string> cells;
        std::istringstream rest(m[2].str());
        for (std::string cell; std::getline(rest, cell, '|');) {
            const size_t a = cell.find_first_not_of(' '), b = cell.find_last_not_of(' ');
            cells.push_back(a == std::string::npos ? "" : cell.substr(a, b - a + 1));
        }
        EXPECT_TRUE(rows.emplace(m[1].str(), cells).second) << m[1] << " has two rows under " << heading;
    }
    return rows;
}

}  // namespace

TEST(Catalog, EveryCodeConstantIsInTheCatalogOnce) {
    const std::string header = read_source("lib/findings/findings.hpp");
    const std::regex constant(R"re(inline constexpr std::string_view \w+ =\s*"([A-Z_]+)")re");
    std::set<std::string> constants;
    for (std::sregex_iterator it(header.begin(), header.end(), constant), end; it != end; ++it)
        constants.insert((*it)[1].str());
    ASSERT_GE(constants.size(), 37u);
    std::set<std::string> listed;
    for (const auto& c : mf::finding_catalog()) {
        EXPECT_TRUE(listed.insert(std::string(c.code)).second) << c.code << " twice";
        EXPECT_FALSE(c.title.empty()) << c.code;
        EXPECT_FALSE(c.stage.empty()) << c.code;
        EXPECT_FALSE(c.anchor.empty()) << c.code;
    }
    EXPECT_EQ(listed, constants);
}

TEST(Catalog, TheInterfaceTableSaysWhatTheCatalogSays) {
    // | code | default | raised by | when |: the default cell starts with the catalog's severity
    // (MISSING_MAP: the preset's missing_severity may change it, as the cell says), the stage is
    // the catalog's word for word.
    const auto rows = table_rows(read_source("docs/interface.md"), "## Finding codes");
    for (const auto& c : mf::finding_catalog()) {
        const auto it = rows.find(std::string(c.code));
        ASSERT_NE(it, rows.end()) << c.code << " has no row in docs/interface.md \"Finding codes\"";
        ASSERT_GE(it->second.size(), 3u) << c.code;
        EXPECT_EQ(it->second[0].substr(0, mf::severity_name(c.severity).size()), mf::severity_name(c.severity))
            << c.code << ": the docs say \"" << it->second[0] << "\"";
        EXPECT_EQ(it->second[1], c.stage) << c.code;
    }
    EXPECT_EQ(rows.size(), mf::finding_catalog().size()) << "a row for a code the catalog lacks";
}

TEST(Catalog, EveryRuleRowIsACodeOfTheRulesAtItsSeverity) {
    // docs/rules.md's table lists what the rules raise: every "rules" code, with its default.
    const auto rows = table_rows(read_source("docs/rules.md"), "## Rules");
    ASSERT_GE(rows.size(), 18u);
    for (const auto& [code, cells] : rows) {
        const mf::CodeInfo* c = mf::find_code(code);
        ASSERT_NE(c, nullptr) << code << " in docs/rules.md is no code";
        EXPECT_EQ(cells.at(0), mf::severity_name(c->severity)) << code;
        std::string anchor;  // the code in lower case
        for (const char ch : code) anchor += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
        EXPECT_EQ(c->anchor, anchor) << code;
    }
    for (const auto& c : mf::finding_catalog()) {
        if (c.stage != "rules") continue;
        EXPECT_TRUE(rows.count(std::string(c.code))) << c.code << " has no rule row";
    }
}

TEST(Catalog, AFindingTakesItsSeverityFromTheCatalog) {
    EXPECT_EQ(mf::finding(mf::code::normal_invalid, "normal", "n.png", "m").severity, mf::Severity::error);
    EXPECT_EQ(mf::finding(mf::code::constant_map, "roughness", "r.png", "m").severity, mf::Severity::info);
    const mf::Finding f = mf::finding(mf::code::albedo_too_dark, "albedo", "a.png", "dark", {{"share", 0.5}});
    EXPECT_EQ(f.code, "ALBEDO_TOO_DARK");
    EXPECT_EQ(f.severity, mf::Severity::warning);
    EXPECT_EQ(mf::to_json(f.figures).at("share"), 0.5);
    EXPECT_THROW((void)mf::finding("NO_SUCH_CODE", "", "", ""), std::logic_error);
}

// Figures are typed where they are made (a count, a measure, a flag, a text, lists of them) and a
// manifest's JSON reads back to the same values, so a merge or a report rewrites the same bytes.
TEST(Catalog, FiguresAreTypedAndReadBackAsWritten) {
    const size_t level = 3;
    const std::vector<float> rgb{0.25f, 0.5f, 1.0f};
    mf::Figures fig{{"level", level},
                    {"share", 0.125},
                    {"flat", false},
                    {"decoding", "2c-1"},
                    {"from", {2048, 1024}},
                    {"value", rgb},
                    {"channels", std::vector<std::string>{"R", "G"}}};
    EXPECT_TRUE(std::holds_alternative<std::int64_t>(fig.at("level")));
    EXPECT_TRUE(std::holds_alternative<std::string>(fig.at("decoding")));  // characters are text, not a flag
    EXPECT_TRUE(std::holds_alternative<std::vector<std::int64_t>>(fig.at("from")));
    EXPECT_EQ(mf::figure_number(fig, "level"), 3.0);
    EXPECT_EQ(mf::figure_number(fig, "share"), 0.125);
    EXPECT_FALSE(mf::figure_number(fig, "decoding"));
    EXPECT_EQ(mf::figure_string(fig, "decoding"), "2c-1");
    EXPECT_EQ(mf::figure_text(fig.at("from")), "[2048,1024]");
    EXPECT_EQ(mf::figure_text(fig.at("value")), "[0.25,0.5,1.0]");

    const mf::Finding f = mf::finding(mf::code::constant_map, "roughness", "r.png", "m", fig);
    const std::string text = mf::to_json(f).dump();
    EXPECT_NE(text.find(R"("level":3,)"), std::string::npos) << text;
    EXPECT_NE(text.find(R"("from":[2048,1024])"), std::string::npos) << text;
    std::string error;
    const auto back = mf::finding_from_json(nlohmann::json::parse(text), error);
    ASSERT_TRUE(back) << error;
    EXPECT_EQ(mf::to_json(*back).dump(), text);
    EXPECT_TRUE(std::holds_alternative<double>(back->figures.at("share")));
    EXPECT_TRUE(std::holds_alternative<std::vector<double>>(back->figures.at("value")));

    // What no rule writes is refused with the figure named, not guessed at.
    EXPECT_FALSE(mf::finding_from_json(
        {{"code", "X"}, {"severity", "info"}, {"figures", {{"sizes", {{"a.png", {1, 2}}}}}}}, error));
    EXPECT_NE(error.find("\"sizes\""), std::string::npos) << error;
    EXPECT_FALSE(mf::finding_from_json({{"code", "X"}, {"severity", "info"}, {"figures", {{"n", nullptr}}}}, error));
}
