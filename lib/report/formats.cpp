#include "report/formats.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <set>

#include "core/json.hpp"
#include "core/text.hpp"
#include "core/version.hpp"
#include "findings/catalog.hpp"

namespace mf::report {

using validate::FailOn;
using validate::fails;
using validate::Summary;

namespace {

// The codes validate_set() evaluates: a JUnit test case each, per material.
std::vector<std::string> default_rules() {
    std::vector<std::string> v;
    for (const auto& r : finding_catalog()) {
        if (r.code == code::missing_map) break;  // the rest are other stages' codes
        v.emplace_back(r.code);
    }
    return v;
}

std::string join_path(const std::string& source, const std::string& file) {
    if (file.empty()) return source;
    if (source.empty() || source == ".") return file;
    return source.back() == '/' ? source + file : source + "/" + file;
}

// "  albedo      Bricks_Color.png  [ambientcg:_Color]" per input, the normal verdict, constants.
std::string decisions_text(const manifest::Material& m) {
    std::string out = m.convention.empty() ? "" : "  naming: " + m.convention + "\n";
    for (const auto& in : m.inputs) {
        std::string role(role_name(in.role));
        role.resize(std::max<size_t>(role.size() + 1, 20), ' ');
        out += "  " + role + in.file + "  [" + in.rule + "]";
        if (in.normal) {
            out += "  " + std::string(convention_name(in.normal->convention));
            if (in.normal->source == "name") out += " (from the name)";
            else if (in.normal->source == "content")
                out += " (from the content: " + in.normal->method + " test, confidence " +
                       std::to_string(static_cast<int>(std::lround(in.normal->confidence.value_or(0) * 100))) + " %)";
            else out += " (undecided)";
        }
        out += "\n";
    }
    if (!m.constants.empty()) {
        std::string list;
        for (const auto& c : m.constants) {
            std::string v;
            for (float x : c.value) {
                char buf[32];
                std::snprintf(buf, sizeof buf, "%g", static_cast<double>(x));
                v += (v.empty() ? "" : ", ") + std::string(buf);
            }
            list += (list.empty() ? "" : "; ") + std::string(role_name(c.role)) + " " + v;
        }
        out += "  generated on ingest: " + list + "\n";
    }
    return out;
}

std::string finding_line(const Finding& f) {
    std::string s = std::string(severity_name(f.severity)) + " " + f.code;
    if (!f.role.empty()) s += " [" + f.role + "]";
    return s + ": " + f.message;
}

}  // namespace

namespace {

nlohmann::json material_json(const manifest::Material& m) {
    nlohmann::json fs = nlohmann::json::array();
    for (const auto& f : m.findings) fs.push_back(to_json(f));
    nlohmann::json j{{"name", m.name},
                     {"source", m.source},
                     {"convention", m.convention},
                     {"inputs", manifest::to_json(m.inputs)},
                     {"constants", manifest::to_json(m.constants)},
                     {"findings", fs}};
    if (m.provenance) j["provenance"] = manifest::to_json(*m.provenance);
    return j;
}

// The report without its materials (an empty array in their place).
nlohmann::json report_head(const manifest::Manifest& r) {
    nlohmann::json j;
    j["report_version"] = 1;
    j["generator"] = std::string(kGenerator);
    j["materials"] = nlohmann::json::array();
    nlohmann::json fl = nlohmann::json::array();
    for (const auto& f : r.failures) fl.push_back({{"source", f.source}, {"code", f.code}, {"message", f.message}});
    j["failures"] = fl;
    const Summary s = validate::summarize(r);
    j["summary"] = {{"error", s.error}, {"warning", s.warning}, {"info", s.info}, {"failures", s.failures}};
    return j;
}

}  // namespace

nlohmann::json report_json(const manifest::Manifest& r) {
    nlohmann::json j = report_head(r);
    for (const auto& m : r.materials) j["materials"].push_back(material_json(m));
    return j;
}

// One material at a time: a report of 50,000 sets holds its text, not a JSON tree of it.
std::string write_json(const manifest::Manifest& r) {
    return json_text_with_array(report_head(r), "materials", r.materials.size(),
                                [&](size_t i) { return material_json(r.materials[i]); });
}

namespace {

// "  warning NAME_OF_CODE   role      message  [file]": one finding's line, codes in a column.
std::string finding_line(const Finding& f, size_t code_w) {
    std::string sev(severity_name(f.severity));
    sev.resize(8, ' ');
    std::string c = f.code;
    c.resize(code_w + 2, ' ');
    std::string role = f.role.empty() ? "-" : f.role;
    role.resize(std::max<size_t>(role.size() + 1, 10), ' ');
    return "  " + sev + c + role + f.message + (f.file.empty() ? "" : "  [" + f.file + "]") + "\n";
}

// "4 material(s): 0 error(s), 2 warning(s), 9 info — FAIL (--fail-on warning)"
std::string verdict_text(const manifest::Manifest& r, FailOn fail_on) {
    const Summary s = validate::summarize(r);
    std::string out = std::to_string(r.materials.size()) + " material(s): " + std::to_string(s.error) + " error(s), " +
                      std::to_string(s.warning) + " warning(s), " + std::to_string(s.info) + " info";
    if (s.failures) out += "; " + std::to_string(s.failures) + " input(s) failed";
    out += run_fails(s, fail_on) ? " — FAIL" : " — PASS";
    return out + " (--fail-on " + std::string(fail_on_name(fail_on)) + ")\n";
}

size_t code_width(const manifest::Manifest& r) {
    size_t code_w = 0;
    for (const auto& m : r.materials)
        for (const auto& f : m.findings) code_w = std::max(code_w, f.code.size());
    return code_w;
}

}  // namespace

std::string write_text(const manifest::Manifest& r, FailOn fail_on) {
    std::string out;
    const size_t code_w = code_width(r);
    for (const auto& m : r.materials) {
        out += m.name + "  (" + m.source + ")\n";
        out += decisions_text(m);
        if (m.findings.empty()) out += "  ok: no findings\n";
        for (const auto& f : m.findings) out += finding_line(f, code_w);
        out += "\n";
    }
    if (!r.failures.empty()) {
        out += "Inputs that could not be processed\n";
        for (const auto& f : r.failures) out += "  " + f.source + "  " + f.code + "  " + f.message + "\n";
        out += "\n";
    }
    return out + verdict_text(r, fail_on);
}

std::string write_terminal_summary(const manifest::Manifest& r, FailOn fail_on) {
    std::string out;
    const size_t code_w = code_width(r);
    size_t quiet = 0, infos = 0;
    for (const auto& m : r.materials) {
        std::string lines;
        for (const auto& f : m.findings) {
            if (f.severity == Severity::info) ++infos;
            else lines += finding_line(f, code_w);
        }
        if (lines.empty()) ++quiet;
        else out += m.name + "  (" + m.source + ")\n" + lines;
    }
    for (const auto& f : r.failures) out += f.source + "  " + f.code + "  " + f.message + "\n";
    if (quiet || infos)
        out += std::to_string(quiet) + " material(s) without an error or warning; " + std::to_string(infos) +
               " info finding(s) not shown (the report holds them; --verbose prints the whole report)\n";
    return out + verdict_text(r, fail_on);
}

std::string write_junit(const manifest::Manifest& r, FailOn fail_on) {
    // One <testsuite> per material, one <testcase> per rule evaluated on it: a dashboard shows
    // which rule failed for which material, and a passing rule as a passing test.
    struct Case {
        std::string name;
        std::vector<const Finding*> failing, passing;
    };
    std::string body;
    int total = 0, total_fail = 0, total_err = 0;
    for (const auto& m : r.materials) {
        std::vector<std::string> rules = default_rules();
        for (const auto& f : m.findings)
            if (std::find(rules.begin(), rules.end(), f.code) == rules.end()) rules.push_back(f.code);
        std::vector<Case> cases;
        for (const auto& c : rules) {
            Case k{c, {}, {}};
            for (const auto& f : m.findings)
                if (f.code == c) (fails(f.severity, fail_on) ? k.failing : k.passing).push_back(&f);
            cases.push_back(std::move(k));
        }
        int fail = 0;
        for (const auto& k : cases) fail += k.failing.empty() ? 0 : 1;
        total += static_cast<int>(cases.size());
        total_fail += fail;
        body += "  <testsuite name=\"" + markup_escape(m.name) + "\" tests=\"" + std::to_string(cases.size()) +
                "\" failures=\"" + std::to_string(fail) + "\" errors=\"0\" skipped=\"0\">\n";
        body += "    <properties>\n      <property name=\"source\" value=\"" + markup_escape(m.source) +
                "\"/>\n    </properties>\n";
        const std::string classname = "matforge.validate." + m.name;
        for (const auto& k : cases) {
            body += "    <testcase name=\"" + markup_escape(k.name) + "\" classname=\"" + markup_escape(classname) +
                    "\"";
            if (k.failing.empty() && k.passing.empty()) {
                body += "/>\n";
                continue;
            }
            body += ">\n";
            if (!k.failing.empty()) {
                std::string text;
                for (const Finding* f : k.failing)
                    text += finding_line(*f) + (f->file.empty() ? "" : " (" + join_path(m.source, f->file) + ")") +
                            "\n";
                body += "      <failure type=\"" + markup_escape(k.name) + "\" message=\"" +
                        markup_escape(k.failing.front()->message) + "\">" + markup_escape(text) + "</failure>\n";
            }
            if (!k.passing.empty()) {
                std::string text;
                for (const Finding* f : k.passing) text += finding_line(*f) + "\n";
                body += "      <system-out>" + markup_escape(text) + "</system-out>\n";
            }
            body += "    </testcase>\n";
        }
        body += "  </testsuite>\n";
    }
    if (!r.failures.empty()) {
        body += "  <testsuite name=\"inputs\" tests=\"" + std::to_string(r.failures.size()) +
                "\" failures=\"0\" errors=\"" + std::to_string(r.failures.size()) + "\" skipped=\"0\">\n";
        for (const auto& f : r.failures)
            body += "    <testcase name=\"" + markup_escape(f.source) + "\" classname=\"matforge.validate.inputs\">\n" +
                    "      <error type=\"" + markup_escape(f.code) + "\" message=\"" + markup_escape(f.message) +
                    "\"/>\n" + "    </testcase>\n";
        body += "  </testsuite>\n";
        total += static_cast<int>(r.failures.size());
        total_err += static_cast<int>(r.failures.size());
    }
    return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"matforge validate\" tests=\"" +
           std::to_string(total) + "\" failures=\"" + std::to_string(total_fail) + "\" errors=\"" +
           std::to_string(total_err) + "\">\n" + body + "</testsuites>\n";
}

std::string write_sarif(const manifest::Manifest& r) {
    // SARIF 2.1.0 (OASIS, 2020): §3.13 sarifLog, §3.19 tool, §3.49 reportingDescriptor,
    // §3.27 result, §3.28 location, §3.4 artifactLocation. Levels: error, warning, note.
    auto level = [](Severity s) {
        return s == Severity::error ? "error" : s == Severity::warning ? "warning" : "note";
    };
    std::vector<std::string> ids;
    for (const auto& rule : finding_catalog()) ids.emplace_back(rule.code);
    std::set<std::string> extra;
    for (const auto& m : r.materials)
        for (const auto& f : m.findings)
            if (!find_code(f.code)) extra.insert(f.code);
    for (const auto& f : r.failures)
        if (!find_code(f.code)) extra.insert(f.code);
    ids.insert(ids.end(), extra.begin(), extra.end());

    nlohmann::json rules = nlohmann::json::array();
    for (const auto& id : ids) {
        const CodeInfo* info = find_code(id);
        nlohmann::json d{{"id", id},
                         {"shortDescription", {{"text", info ? std::string(info->title) : id}}},
                         {"defaultConfiguration", {{"level", level(info ? info->severity : Severity::warning)}}}};
        if (info) d["help"] = {{"text", "See docs/rules.md#" + std::string(info->anchor)}};
        rules.push_back(d);
    }
    auto index_of = [&](const std::string& id) {
        return static_cast<int>(std::find(ids.begin(), ids.end(), id) - ids.begin());
    };
    auto location = [](const std::string& path) {
        std::string uri = percent_encode_path(path);
        if (!path.empty() && path.front() == '/') uri = "file://" + uri;
        return nlohmann::json::array({{{"physicalLocation", {{"artifactLocation", {{"uri", uri}}}}}}});
    };
    nlohmann::json results = nlohmann::json::array();
    for (const auto& m : r.materials)
        for (const auto& f : m.findings) {
            nlohmann::json res{{"ruleId", f.code},
                               {"ruleIndex", index_of(f.code)},
                               {"level", level(f.severity)},
                               {"message", {{"text", f.message}}},
                               {"locations", location(join_path(m.source, f.file))}};
            nlohmann::json props{{"material", m.name}};
            if (!f.role.empty()) props["role"] = f.role;
            if (!f.figures.empty()) props["figures"] = to_json(f.figures);
            res["properties"] = props;
            results.push_back(res);
        }
    for (const auto& f : r.failures)
        results.push_back({{"ruleId", f.code},
                           {"ruleIndex", index_of(f.code)},
                           {"level", "error"},
                           {"message", {{"text", f.message}}},
                           {"locations", location(f.source)}});
    // The decisions (SARIF §3.24 artifact, §3.8 property bag): each input file with its role,
    // the naming rule that matched and the normal map's verdict; each material's constants.
    nlohmann::json artifacts = nlohmann::json::array(), decided = nlohmann::json::array();
    for (const auto& m : r.materials) {
        for (const auto& in : m.inputs) {
            nlohmann::json props = manifest::to_json(in);
            props.erase("file");
            props["material"] = m.name;
            props["role"] = role_name(in.role);
            artifacts.push_back({{"location",
                                  location(join_path(m.source, in.file))[0]["physicalLocation"]["artifactLocation"]},
                                 {"properties", props}});
        }
        decided.push_back({{"material", m.name},
                           {"convention", m.convention},
                           {"constants", manifest::to_json(m.constants)}});
    }
    nlohmann::json run{{"tool",
                        {{"driver",
                          {{"name", "matforge"},
                           {"semanticVersion", std::string(kVersion)},
                           {"version", std::string(kVersion)},
                           {"rules", rules}}}}},
                       {"artifacts", artifacts},
                       {"properties", {{"materials", decided}}},
                       {"results", results}};
    nlohmann::json log{{"$schema", "https://json.schemastore.org/sarif-2.1.0.json"},
                       {"version", "2.1.0"},
                       {"runs", nlohmann::json::array({run})}};
    return json_text(log);
}

std::optional<Format> format_from_name(std::string_view n) {
    if (n == "text") return Format::text;
    if (n == "json") return Format::json;
    if (n == "junit") return Format::junit;
    if (n == "sarif") return Format::sarif;
    return std::nullopt;
}

std::string write_findings(const manifest::Manifest& m, Format format, FailOn fail_on) {
    switch (format) {
        case Format::json: return write_json(m);
        case Format::junit: return write_junit(m, fail_on);
        case Format::sarif: return write_sarif(m);
        case Format::text: break;
    }
    return write_text(m, fail_on);
}

void rebase_sources(manifest::Manifest& m, const std::filesystem::path& manifest_dir) {
    auto rebase = [&](std::string& source) {
        std::string s = (manifest_dir / source).lexically_normal().generic_string();
        while (s.size() > 1 && s.back() == '/') s.pop_back();  // "a/b/" from a source of "."
        source = s.empty() ? "." : s;
    };
    for (auto& mm : m.materials) rebase(mm.source);
    for (auto& f : m.failures) rebase(f.source);
}

}  // namespace mf::report
