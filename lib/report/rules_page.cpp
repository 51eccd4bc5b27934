// rules.html: docs/rules.md as it was when this binary was built, so a report opened far from
// the repository (a CI artifact, a copied folder) still explains every finding it links to.
#include <cctype>

#include "core/text.hpp"
#include "findings/catalog.hpp"
#include "report/html.hpp"
#include "report/report.hpp"

namespace mf::report {
namespace {

#include "rules_md_embedded.inc"

std::string anchor_of(std::string_view code) {
    if (const auto* r = find_code(code)) return std::string(r->anchor);
    std::string a;
    for (const char c : code) a += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return a;
}

// A table row's first cell names a code when it is one word of capitals, digits and '_'.
std::string row_anchor(std::string_view code) {
    if (code.empty()) return {};
    for (const char c : code)
        if (!(std::isupper(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) || c == '_'))
            return {};
    return anchor_of(code);
}

}  // namespace

std::string rule_link(const std::string& code) { return "rules.html#" + percent_encode_path(anchor_of(code)); }

std::string rules_page(const std::set<std::string>& codes) {
    std::set<std::string> ids;
    MarkdownOptions mo;
    mo.row_id = &row_anchor;
    const std::string body = markdown_to_html(kRulesMarkdown, mo, ids);
    // Codes rules.md has no row for (other stages' codes, named in its prose), catalog order
    // first, then any other code the manifest holds.
    std::string others;
    auto add = [&](const std::string& code, const CodeInfo* r) {
        const std::string id = anchor_of(code);
        if (ids.count(id)) return;
        ids.insert(id);
        others += "<tr id=\"" + markup_escape(id) + "\"><td><code>" + markup_escape(code) + "</code></td><td>" +
                  (r ? std::string(severity_name(r->severity)) : std::string("—")) + "</td><td>" +
                  (r ? markup_escape(r->title)
                     : std::string("reported by ingest or set finding; docs/interface.md, "
                                   "\"Finding codes\", says when")) +
                  "</td></tr>\n";
    };
    for (const auto& r : finding_catalog()) add(std::string(r.code), &r);
    for (const std::string& c : codes) add(c, find_code(c));
    std::string html =
        "<!doctype html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
        "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; style-src 'unsafe-inline'\">\n"
        "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
        "<title>matforge — validation rules</title>\n<style>\n"
        "body{font:15px/1.5 system-ui,sans-serif;max-width:1100px;margin:0 auto;padding:1em 2em;color:#1b1f24}"
        "table{border-collapse:collapse;margin:1em 0;font-size:13px}td,th{border:1px solid #ccd;padding:4px 6px;"
        "vertical-align:top;text-align:left}th{background:#eef}code{background:#f2f3f5;padding:0 3px;border-radius:3px}"
        "pre{background:#f2f3f5;padding:8px;overflow:auto}tr:target{background:#fff3b0}a{color:#0b5cad}\n"
        "</style>\n</head>\n<body>\n<p><a href=\"index.html\">← report</a></p>\n";
    html += body;
    if (!others.empty())
        html += "<h2 id=\"codes-of-other-stages\">Codes of other stages</h2>\n<table>\n<thead><tr><th>code</th>"
                "<th>default</th><th>meaning</th></tr></thead>\n<tbody>\n" +
                others + "</tbody>\n</table>\n";
    html += "</body>\n</html>\n";
    return html;
}

}  // namespace mf::report
