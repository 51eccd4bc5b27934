#include "manifest/attribution.hpp"

#include <map>

#include "core/text.hpp"

namespace mf::manifest {
namespace {

// A table cell: one line, no column break.
std::string cell(std::string_view s) {
    if (s.empty()) return "—";
    std::string out;
    out.reserve(s.size());
    for (const char c : s) {
        if (c == '\n' || c == '\r' || c == '\t') out += ' ';
        else if (c == '|') out += "\\|";
        else out += c;
    }
    return out;
}

std::string licence_label(const Provenance::Licence& l) { return l.spdx.empty() ? l.name : l.spdx; }

std::string row(const Material& m) {
    const Provenance p = m.provenance.value_or(Provenance{});
    std::string licence = "unknown", how, credit = "—";
    if (p.licence) {
        const Provenance::Licence& l = *p.licence;
        licence = licence_label(l) + (l.vendor_licence ? " (" + std::string(kVendorLicenceTerms) + ")" : "");
        how = l.evidence.how + (l.evidence.file.empty() ? "" : " (" + l.evidence.file + ")") +
              (l.evidence.detail.empty() ? "" : ": " + l.evidence.detail);
        credit = l.attribution_required ? p.attribution : "not required";
    } else {
        for (const Finding& f : m.findings)
            if (f.code == code::licence_unknown) how = f.message;
    }
    return "| " + cell(m.name) + " | " + cell(p.vendor_name) + " | " + cell(p.asset_id) + " | " + cell(licence) +
           " | " + cell(how) + " | " + cell(credit) + " | " + cell(p.url) + " |\n";
}

// One line of valid UTF-8: a material file's field is displayed as one line (and a USD string
// literal cannot hold a line break).
std::string one_line(std::string_view s) {
    std::string out = utf8_or_replacement(s);
    for (char& c : out)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = ' ';
    return out;
}

}  // namespace

std::optional<Credit> material_credit(const Provenance& p) {
    if (!p.licence) return std::nullopt;
    const Provenance::Licence& l = *p.licence;
    Credit c;
    const bool attribution = l.attribution_required && !p.attribution.empty();
    c.author = one_line(attribution ? p.attribution : p.vendor_name);
    std::string facts = l.spdx;
    if (!l.url.empty()) facts += (facts.empty() ? "" : ", ") + l.url;
    c.licence = one_line(l.name + (facts.empty() ? "" : " (" + facts + ")") +
                         (l.vendor_licence ? ", " + std::string(kVendorLicenceTerms) : ""));
    c.url = one_line(p.url);
    std::string source = p.vendor_name;
    if (!p.asset_id.empty()) source += (source.empty() ? "asset " : " asset ") + p.asset_id;
    if (!c.url.empty()) source += source.empty() ? c.url : " (" + c.url + ")";
    c.source = one_line(source);
    const std::string given = attribution ? one_line(p.attribution) : "licensed under " + c.licence;
    c.line = c.source.empty() ? given : c.source + "; " + given;
    return c;
}

bool attribution_text(const MaterialVisitor& materials, const ByteSink& sink) {
    if (!sink("# Attribution\n\n"
              "The source and licence of every material in this folder, as `matforge ingest` found them in\n"
              "the downloads (`manifest.json`, `materials[].provenance`). Ship this file with the textures:\n"
              "a licence that asks for credit (CC BY) is credited in the attribution column; a vendor's own\n"
              "licence (Poliigon, Fab) lets you use the textures in your work, not pass the files on.\n"
              "\"unknown\": no licence file, sidecar or vendor naming said one (`LICENCE_UNKNOWN`).\n\n"
              "| material | vendor | asset | licence | how it is known | attribution | source |\n"
              "| --- | --- | --- | --- | --- | --- | --- |\n"))
        return false;
    std::map<std::string, size_t> counts;
    size_t n = 0;
    const bool ok = materials([&](const Material& m) {
        ++n;
        ++counts[m.provenance && m.provenance->licence ? licence_label(*m.provenance->licence) : "unknown"];
        return sink(row(m));
    });
    if (!ok) return false;
    std::string total = "\n" + std::to_string(n) + (n == 1 ? " material" : " materials");
    size_t i = 0;
    for (const auto& [licence, count] : counts) total += (i++ ? ", " : ": ") + licence + " " + std::to_string(count);
    return sink(total + ".\n");
}

bool attribution_text(const MaterialSpool& spool, const ByteSink& sink, std::string& error) {
    return attribution_text(
        [&](const std::function<bool(const Material&)>& visit) {
            return spool.for_each([&](Material&& m) { return visit(m); }, error);
        },
        sink);
}

std::string attribution_text(const std::vector<Material>& materials) {
    std::string out;
    attribution_text(
        [&](const std::function<bool(const Material&)>& visit) {
            for (const Material& m : materials)
                if (!visit(m)) return false;
            return true;
        },
        [&](std::string_view piece) {
            out += piece;
            return true;
        });
    return out;
}

}  // namespace mf::manifest
