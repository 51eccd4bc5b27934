#include "report/card.hpp"

#include <algorithm>
#include <filesystem>
#include <map>

#include "core/text.hpp"
#include "engine/engine.hpp"
#include "material/roles.hpp"
#include "report/report.hpp"

namespace mf::report {
namespace fs = std::filesystem;
using manifest::Channel;

namespace {

std::string percent(size_t part, size_t whole) {
    return whole ? mf::percent(static_cast<double>(part) / static_cast<double>(whole)) : "—";
}

std::string channel_text(const Channel& c) {
    switch (c.kind) {
        case Channel::Kind::role: return std::string(role_name(c.role));
        case Channel::Kind::smoothness: return "smoothness (1 − roughness)";
        case Channel::Kind::constant: return "constant " + fixed(c.value, 3);
        case Channel::Kind::unused: return "unused";
    }
    return "unused";
}

}  // namespace

int channel_index(const std::string& key) {
    if (key == "G") return 1;
    if (key == "B") return 2;
    if (key == "A") return 3;
    return 0;  // R, RGB
}

std::string img(const Pic& p, const std::string& alt, const std::string& cls) {
    return "<img loading=\"lazy\" decoding=\"async\" src=\"" + percent_encode_path(p.rel) + "\" width=\"" +
           std::to_string(p.width) + "\" height=\"" + std::to_string(p.height) + "\" alt=\"" + markup_escape(alt) +
           "\"" + (cls.empty() ? "" : " class=\"" + cls + "\"") + ">";
}

namespace {

// The card of one material, from its manifest entry and the pictures made for it.
class Card {
public:
    explicit Card(const CardInput& in)
        : m_(in.material),
          pics_(in.pictures),
          t_(in.thresholds),
          stem_(in.stem),
          index_(in.index),
          other_(in.other),
          other_preset_(in.other_preset) {}

    CardHtml html() {
        card();
        return {std::move(card_html), std::move(sheet_html)};
    }

private:
    void card() {
        const std::string id = "m-" + stem_;
        const auto worst_sev = worst(m_.findings);
        const std::string sev = worst_sev ? std::string(severity_name(*worst_sev)) : "none";
        std::string& h = card_html;
        h += "<section class=\"card sev-" + sev + "\" id=\"" + id + "\" data-material=\"" + markup_escape(m_.name) +
             "\" data-worst=\"" + sev + "\" data-index=\"" + std::to_string(index_) + "\">\n";
        h += "<h2><a href=\"#" + id + "\">" + markup_escape(m_.name) + "</a>";
        // The status badge says whether every output was written; "ok" beside an error would read
        // as "the material is fine": the error badge alone says it then.
        if (m_.status != manifest::Status::ok || worst_sev != Severity::error)
            h += " <span class=\"badge status-" + std::string(manifest::status_name(m_.status)) + "\">" +
                 std::string(manifest::status_name(m_.status)) + "</span>";
        size_t counts[3] = {0, 0, 0};
        for (const Finding& f : m_.findings) ++counts[static_cast<int>(f.severity)];
        for (int s = 2; s >= 0; --s)
            if (counts[s])
                h += " <span class=\"badge sev-" + std::string(severity_name(static_cast<Severity>(s))) + "\">" +
                     std::to_string(counts[s]) + " " + std::string(severity_name(static_cast<Severity>(s))) + "</span>";
        h += "</h2>\n<div class=\"cols\">\n<div class=\"col\">\n";
        sources_html(h);
        normal_html(h);
        findings_html(h);
        h += "</div>\n<div class=\"col\">\n";
        // The vendor's own preview beside matforge's render of the material.
        const Pic* vendor = vendor_preview();
        if (vendor) h += "<div class=\"previews\">";
        if (pics_.preview)
            h += "<figure class=\"preview\">" + img(*pics_.preview, m_.name + " preview") +
                 "<figcaption>preview</figcaption></figure>\n";
        if (vendor)
            h += "<figure class=\"preview vendor-preview\">" + img(*vendor, m_.name + " vendor preview") +
                 "<figcaption>the vendor's preview <code>" + markup_escape(vendor_file_) +
                 "</code></figcaption></figure>" + "</div>\n";
        if (pics_.viewer) h += Viewer::card_html(*pics_.viewer, stem_);
        outputs_html(h);
        material_files_html(h);
        h += "</div>\n</div>\n";
        checks_html(h);
        before_after_html(h);
        h += "</section>\n";

        const Pic* tile = pics_.preview ? &*pics_.preview : (pics_.sheet ? &*pics_.sheet : nullptr);
        sheet_html = "<a class=\"tile sev-" + sev + "\" href=\"#" + id + "\">" +
                     (tile ? img(*tile, m_.name) : std::string("<span class=\"noimg\"></span>")) + "<span>" +
                     markup_escape(m_.name) + "</span></a>\n";
    }

    // The picture made of the vendor's preview input (report.cpp read_sources), if shown.
    const Pic* vendor_preview() {
        for (size_t i = 0; i < pics_.sources.size() && i < m_.inputs.size(); ++i)
            if (m_.inputs[i].role == Role::preview && !pics_.sources[i].rel.empty()) {
                vendor_file_ = m_.inputs[i].file;
                return &pics_.sources[i];
            }
        return nullptr;
    }

    // A URL as text: the page links nothing outside its folder (it is read offline).
    static std::string url_text(const std::string& url) {
        const size_t scheme = url.find("://");
        return "<code>" + markup_escape(scheme == std::string::npos ? url : url.substr(scheme + 3)) + "</code>";
    }

    // Where the set comes from and under what licence (the manifest's provenance), or why no
    // licence is known (its LICENCE_UNKNOWN finding).
    void provenance_html(std::string& h) const {
        const Provenance p = m_.provenance.value_or(Provenance{});
        h += "<h3>Source and licence</h3>\n<p class=\"provenance\">";
        if (!p.vendor_name.empty()) h += "vendor <b class=\"vendor\">" + markup_escape(p.vendor_name) + "</b>";
        if (!p.asset_id.empty())
            h += std::string(p.vendor_name.empty() ? "" : " · ") + "asset <code class=\"asset\">" +
                 markup_escape(p.asset_id) + "</code>";
        if (!p.vendor_name.empty() || !p.asset_id.empty()) h += " · ";
        if (p.licence) {
            const Provenance::Licence& l = *p.licence;
            h += "licence <b class=\"licence\">" + markup_escape(l.spdx.empty() ? l.name : l.spdx) + "</b>";
            if (!l.url.empty()) h += " " + url_text(l.url);
            if (l.vendor_licence) h += " (the vendor's licence: no redistribution of the files)";
            h += "<br><span class=\"meta\">known from the " + markup_escape(l.evidence.how) +
                 (l.evidence.file.empty() ? "" : " <code>" + markup_escape(l.evidence.file) + "</code>") +
                 (l.evidence.detail.empty() ? "" : ": " + markup_escape(l.evidence.detail)) + "</span>";
            if (l.attribution_required)
                h += "<br>attribution: <span class=\"attribution\">" + markup_escape(p.attribution) + "</span>";
        } else {
            std::string why = "no licence found";
            for (const Finding& f : m_.findings)
                if (f.code == code::licence_unknown) why = f.message;
            h += "licence <b class=\"licence unknown\">unknown</b><br><span class=\"meta\">" + markup_escape(why) +
                 "</span>";
        }
        if (!p.url.empty()) h += "<br>source " + url_text(p.url);
        h += "</p>\n";
    }

    void sources_html(std::string& h) const {
        h += "<h3>Sources</h3>\n<p class=\"meta\"><code>" + markup_escape(m_.source) + "</code>";
        if (m_.archive) h += " in archive <code>" + markup_escape(*m_.archive) + "</code>";
        h += " · naming <code>" + markup_escape(m_.convention) + "</code></p>\n";
        h += "<table class=\"inputs\"><thead><tr><th>role</th><th>file</th><th>rule</th><th>size</th><th>encoding</th>"
             "</tr></thead><tbody>\n";
        for (const manifest::Input& in : m_.inputs) {
            h += "<tr class=\"input\" data-role=\"" + std::string(role_name(in.role)) + "\"><td>" +
                 std::string(role_name(in.role)) + "</td><td><code>" + markup_escape(in.file) + "</code></td><td>" +
                 markup_escape(in.rule) + "</td><td>" + std::to_string(in.width) + "×" + std::to_string(in.height) +
                 "×" + std::to_string(in.channels) + ", " + std::to_string(in.bit_depth) + "-bit" +
                 (in.is_float ? " float" : "") + "</td><td>" + markup_escape(in.color_space) + "</td></tr>\n";
        }
        for (const manifest::Constant& c : m_.constants) {
            std::string v;
            for (size_t i = 0; i < c.value.size(); ++i) v += (i ? ", " : "") + fixed(c.value[i], 3);
            h += "<tr class=\"constant\" data-role=\"" + std::string(role_name(c.role)) + "\"><td>" +
                 std::string(role_name(c.role)) + "</td><td colspan=\"4\">no map: constant " + v + "</td></tr>\n";
        }
        h += "</tbody></table>\n";
        provenance_html(h);
    }

    // The material files written for the set, each with the line on how to open it; the import
    // settings beside each texture (.import, .meta) counted in one row.
    void material_files_html(std::string& h) const {
        if (m_.material_files.empty()) return;
        h += "<h3>Material files</h3>\n<table class=\"material-files\"><thead><tr><th>file</th><th>format</th>"
             "<th>open with</th></tr></thead><tbody>\n";
        std::map<std::string, int> beside;  // per-texture import settings: format -> count
        for (const manifest::MaterialFile& f : m_.material_files) {
            const bool texture_settings = f.format == "import" ||
                                          (f.format == "meta" && !f.file.ends_with(".mat.meta"));
            if (texture_settings) {
                ++beside[f.format];
                continue;
            }
            h += "<tr data-format=\"" + markup_escape(f.format) + "\"><td><code>" + markup_escape(f.file) +
                 "</code></td><td>" + markup_escape(f.format) + "</td><td>" +
                 markup_escape(std::string(engine::how_to_open(f.format))) + "</td></tr>\n";
        }
        for (const auto& [format, n] : beside)
            h += "<tr data-format=\"" + format + "\"><td>" + std::to_string(n) + " <code>." + format +
                 "</code> beside the textures</td><td>" + format + "</td><td>" +
                 markup_escape(std::string(engine::how_to_open(format))) + "</td></tr>\n";
        h += "</tbody></table>\n";
    }

    void outputs_html(std::string& h) const {
        h += "<h3>Outputs</h3>\n<div class=\"outputs\">\n";
        for (size_t i = 0; i < m_.outputs.size(); ++i) output_figure(h, m_.outputs[i], pics_.outputs[i]);
        h += "</div>\n";
    }

    static void output_figure(std::string& h, const manifest::Output& o, const OutputPics& pics) {
        h += "<figure class=\"output\">";
        if (!pics.main.rel.empty()) h += img(pics.main, o.file);
        else h += "<span class=\"noimg\" title=\"" + markup_escape(pics.problem) + "\">not shown</span>";
        h += "<figcaption><code>" + markup_escape(fs::path(o.file).filename().string()) + "</code><br>" +
             std::to_string(o.width) + "×" + std::to_string(o.height) + " " + markup_escape(o.format) + " " +
             std::to_string(o.bit_depth) + "-bit " + (o.srgb ? "sRGB" : "linear");
        if (o.normal_convention) h += " · normal " + std::string(convention_name(*o.normal_convention));
        h += "<table class=\"layout\">";
        std::vector<Channel> channels = o.channels;  // the manifest's keys are sorted: show R, G, B, A
        std::stable_sort(channels.begin(), channels.end(), [](const Channel& a, const Channel& b) {
            return channel_index(a.key) < channel_index(b.key);
        });
        for (const Channel& c : channels) {
            h += "<tr><th>" + markup_escape(c.key) + "</th><td>" + markup_escape(channel_text(c)) + "</td><td>";
            for (const auto& [key, pic] : pics.channels)
                if (key == c.key) h += img(pic, o.file + " " + key, "chan");
            h += "</td></tr>";
        }
        h += "</table></figcaption></figure>\n";
    }

    void normal_html(std::string& h) const {
        const manifest::Input* in = nullptr;
        for (const auto& i : m_.inputs)
            if (i.role == Role::normal) in = &i;
        if (!in) return;
        const manifest::Output* out = nullptr;
        for (const auto& o : m_.outputs)
            if (o.normal_convention) out = &o;
        h += "<h3>Normal convention</h3>\n<p class=\"verdict\">";
        const manifest::NormalFacts facts = in->normal.value_or(manifest::NormalFacts{});
        h += "read as <b class=\"conv\">" + std::string(convention_name(facts.convention)) + "</b>";
        if (facts.source == "name") h += ", from the file name";
        else if (facts.source == "content") {
            h += ", from the pixels";
            if (!facts.method.empty()) h += " (" + markup_escape(facts.method) + ")";
            if (facts.confidence) h += ", confidence " + fixed(*facts.confidence, 2);
        } else {
            h += ", undecided";
        }
        if (out) {
            h += "; written as <b>" + std::string(convention_name(*out->normal_convention)) + "</b>";
            h += out->normal_converted_from ? " (green flipped)" : " (green kept)";
        }
        h += "</p>\n";
        // The evidence: every finding about the convention with its measured figures.
        for (const Finding& f : m_.findings) {
            if (f.code.rfind("NORMAL_CONVENTION", 0) != 0) continue;
            h += "<div class=\"evidence\"><a href=\"" + rule_link(f.code) + "\">" + markup_escape(f.code) +
                 "</a>: " + markup_escape(f.message) + figures_html(f.figures) + "</div>\n";
        }
    }

    static std::string figures_html(const Figures& figures) {
        if (figures.empty()) return {};
        std::string h = "<details><summary>figures</summary><table class=\"figures\">";
        for (const auto& [k, v] : figures)
            h += "<tr><th>" + markup_escape(k) + "</th><td>" + markup_escape(figure_text(v)) + "</td></tr>";
        return h + "</table></details>";
    }

    void findings_html(std::string& h) const {
        h += "<h3>Findings</h3>\n";
        if (m_.findings.empty()) {
            h += "<p class=\"meta\">none</p>\n";
            return;
        }
        h += "<table class=\"findings\"><thead><tr><th>severity</th><th>code</th><th>role</th><th>message</th></tr>"
             "</thead><tbody>\n";
        for (const Finding& f : m_.findings) {
            const std::string sev(severity_name(f.severity));
            h += "<tr class=\"finding sev-" + sev + "\" data-code=\"" + markup_escape(f.code) + "\" data-severity=\"" +
                 sev + "\"><td><span class=\"badge sev-" + sev + "\">" + sev + "</span></td><td><a href=\"" +
                 rule_link(f.code) + "\">" + markup_escape(f.code) + "</a></td><td>" + markup_escape(f.role) +
                 "</td><td>" + markup_escape(f.message) +
                 (f.file.empty() ? "" : " <code>" + markup_escape(f.file) + "</code>") + figures_html(f.figures) +
                 "</td></tr>\n";
        }
        h += "</tbody></table>\n";
    }

    void checks_html(std::string& h) const {
        if (!pics_.albedo && !pics_.metalness) return;
        h += "<h3>Physically plausible ranges</h3>\n<div class=\"checks\">\n";
        const rules::Thresholds& t = t_;
        if (pics_.albedo) {
            // The shares are the findings' (surface_share: of the visible albedo), counted by the
            // rules' own classifier under the run's thresholds (manifest "thresholds").
            const AlbedoStats& st = pics_.albedo_stats;
            const validate::AlbedoCounts& s = st.counts;
            auto share = [&s](long long weighted) { return s.visible ? mf::percent(s.surface_share(weighted)) : "—"; };
            const auto visible = static_cast<size_t>(s.visible);
            h += "<figure class=\"overlay albedo-range\">" + img(*pics_.albedo, m_.name + " albedo range") +
                 "<figcaption>albedo luminance" + std::string(m_.outputs.empty() ? " of the source map" : "") +
                 ", as the rules judge it: dielectric " + fixed(t.albedo_min_srgb, 0) + "–" +
                 fixed(t.albedo_max_srgb, 0) + " sRGB, metal from " + fixed(t.metal_albedo_min_srgb, 0) +
                 " sRGB<br><span class=\"key dark\"></span> too dark: dielectric <span class=\"share\" "
                 "data-code=\"ALBEDO_TOO_DARK\">" +
                 share(s.dielectric_dark) +
                 "</span>, metal <span class=\"share\" data-code=\"METAL_ALBEDO_TOO_DARK\">" + share(s.metal_dark) +
                 "</span> <span class=\"key bright\"></span> too bright: <span class=\"share\" "
                 "data-code=\"ALBEDO_TOO_BRIGHT\">" +
                 share(s.dielectric_bright) +
                 "</span> <span class=\"meta\">(of the visible albedo)</span><br>dielectric " + share(s.dielectric) +
                 ", metal " + share(s.metal) +
                 (s.blend > 0 ? " (metalness between the classes on " + percent(static_cast<size_t>(s.blend), visible) +
                                    ": counted toward both by its weight, drawn mixed)"
                              : std::string()) +
                 (visible < st.pixels ? ", not visible " + percent(st.pixels - visible, st.pixels) : std::string()) +
                 "</figcaption></figure>\n";
        }
        if (pics_.metalness) {
            const MetalnessStats& s = pics_.metal_stats;
            h += "<figure class=\"overlay metalness\">" + img(*pics_.metalness, m_.name + " metalness") +
                 "<figcaption>metalness: 0 " + percent(s.zero, s.pixels) + ", 1 " + percent(s.one, s.pixels) +
                 "<br><span class=\"key near\"></span> near 0 or 1: " + percent(s.near_binary, s.pixels) +
                 " <span class=\"key between\"></span> between " + fixed(t.dielectric_max, 2) + " and " +
                 fixed(t.metal_min, 2) + ": " + percent(s.between, s.pixels) + "</figcaption></figure>\n";
        } else {
            std::string value = "0";
            for (const manifest::Constant& c : m_.constants)
                if (c.role == Role::metalness && !c.value.empty()) value = fixed(c.value[0], 3);
            h += "<p class=\"meta\">metalness: no map (constant " + value + ")</p>\n";
        }
        h += "</div>\n";
    }

    void before_after_html(std::string& h) const {
        const bool any_source = std::any_of(pics_.sources.begin(), pics_.sources.end(),
                                            [](const Pic& p) { return !p.rel.empty(); });
        if (!any_source && !other_ && !m_.archive) return;
        h += "<details class=\"before-after\"><summary>Before / after</summary>\n";
        if (m_.archive) h += "<p class=\"meta\">the sources are entries of a .zip: not shown</p>\n";
        for (size_t i = 0; i < pics_.sources.size() && i < m_.inputs.size(); ++i) {
            const manifest::Input& in = m_.inputs[i];
            if (pics_.sources[i].rel.empty() || in.role == Role::preview) continue;  // beside the preview
            h += "<div class=\"pair\"><figure>" + img(pics_.sources[i], in.file) + "<figcaption>source " +
                 std::string(role_name(in.role)) + ": <code>" + markup_escape(in.file) +
                 "</code></figcaption></figure>";
            // The outputs this input's roles went into.
            std::vector<Role> roles{in.role};
            for (const auto& c : packed_layout(in.role))
                if (c) roles.push_back(c->role);
            if (in.role == Role::gloss) roles.push_back(Role::roughness);
            for (size_t k = 0; k < m_.outputs.size(); ++k) {
                const bool holds = std::any_of(m_.outputs[k].channels.begin(), m_.outputs[k].channels.end(),
                                               [&](const Channel& c) {
                                                   return (c.kind == Channel::Kind::role ||
                                                           c.kind == Channel::Kind::smoothness) &&
                                                          std::find(roles.begin(), roles.end(), c.role) != roles.end();
                                               });
                if (!holds || pics_.outputs[k].main.rel.empty()) continue;
                h += "<span class=\"arrow\">→</span><figure>" + img(pics_.outputs[k].main, m_.outputs[k].file) +
                     "<figcaption>output <code>" + markup_escape(fs::path(m_.outputs[k].file).filename().string()) +
                     "</code></figcaption></figure>";
            }
            h += "</div>\n";
        }
        if (other_) {
            h += "<h4>" + markup_escape(other_preset_) + " (--compare)</h4>\n<div class=\"pair\">";
            if (pics_.preview || pics_.compare_preview) {
                if (pics_.preview)
                    h += "<figure>" + img(*pics_.preview, "preview") +
                         "<figcaption>this report's preset</figcaption></figure>";
                if (pics_.compare_preview)
                    h += "<figure>" + img(*pics_.compare_preview, "compare preview") + "<figcaption>" +
                         markup_escape(other_preset_) + "</figcaption></figure>";
            }
            h += "</div>\n<div class=\"outputs\">";
            for (size_t k = 0; k < other_->outputs.size(); ++k) output_figure(h, other_->outputs[k], pics_.compare[k]);
            h += "</div>\n";
        }
        h += "</details>\n";
    }

    std::string card_html, sheet_html;
    std::string vendor_file_;  // the vendor preview's file (vendor_preview)
    const manifest::Material& m_;
    const MaterialPictures& pics_;
    const rules::Thresholds& t_;
    const std::string& stem_;
    size_t index_;
    const manifest::Material* other_;
    const std::string& other_preset_;
};

}  // namespace

CardHtml write_card(const CardInput& in) { return Card(in).html(); }

const char* const kStyle =
    "body{font:14px/1.45 system-ui,sans-serif;margin:0;color:#1b1f24;background:#f6f7f9}"
    "header{background:#1e2a38;color:#fff;padding:12px 24px}header h1{margin:0 0 4px;font-size:20px}"
    "header .meta{color:#c9d3de}header code{color:#fff;background:none}main{padding:12px 24px}"
    "code{background:#eceef1;padding:0 3px;border-radius:3px;font-size:12px;word-break:break-all}"
    "table{border-collapse:collapse;font-size:12px}td,th{border:1px solid #d5d9df;padding:2px 5px;vertical-align:top;"
    "text-align:left}th{background:#eef1f5}a{color:#0b5cad}.meta{color:#5a6470}"
    ".badge{display:inline-block;font-size:11px;padding:0 6px;border-radius:8px;background:#dfe3e8;vertical-align:middle;"
    "font-weight:normal}.badge.sev-error{background:#c62828;color:#fff}.badge.sev-warning{background:#f0a000}"
    ".badge.sev-info{background:#cfe0f5}.badge.status-partial{background:#c62828;color:#fff}"
    ".sheet{display:grid;grid-template-columns:repeat(auto-fill,minmax(112px,1fr));gap:6px}"
    ".tile{display:block;text-decoration:none;color:#1b1f24;background:#fff;border:2px solid #d5d9df;border-radius:4px;"
    "padding:3px;font-size:11px;overflow:hidden;white-space:nowrap;text-overflow:ellipsis}"
    ".tile img,.tile .noimg{display:block;width:100%;height:auto;aspect-ratio:1;object-fit:cover;background:#222}"
    ".tile.sev-error{border-color:#c62828}.tile.sev-warning{border-color:#f0a000}"
    ".card{background:#fff;border:1px solid #d5d9df;border-left:6px solid #9aa5b1;border-radius:4px;margin:14px 0;"
    "padding:8px 14px}.card.sev-error{border-left-color:#c62828}.card.sev-warning{border-left-color:#f0a000}"
    ".card.sev-info{border-left-color:#6fa3dc}.card h2{font-size:17px;margin:4px 0}.card h3{font-size:14px;margin:10px 0 4px}"
    ".cols{display:flex;flex-wrap:wrap;gap:16px}.col{flex:1 1 420px;min-width:0}"
    ".outputs,.checks{display:flex;flex-wrap:wrap;gap:10px}figure{margin:0}figure img{display:block;width:160px;height:auto;"
    "image-rendering:pixelated;background:#222}.preview img{width:200px}figcaption{font-size:11px;color:#3a434d;max-width:260px}"
    ".layout img.chan{width:40px;display:inline-block;vertical-align:middle}.layout td,.layout th{border:none;padding:1px 4px}"
    ".overlay img{width:200px}.key{display:inline-block;width:10px;height:10px;border:1px solid #555;vertical-align:middle}"
    ".key.dark{background:rgb(219,31,31)}.key.bright{background:rgb(41,82,235)}"
    ".key.near{background:rgb(250,179,140)}.key.between{background:rgb(230,26,204)}"
    ".pair{display:flex;flex-wrap:wrap;align-items:center;gap:8px;margin:6px 0}.arrow{font-size:20px;color:#5a6470}"
    ".evidence{font-size:12px;margin:2px 0}details summary{cursor:pointer;color:#0b5cad}"
    "table.findings td:nth-child(4){max-width:520px}nav.pager{margin:10px 0;display:flex;flex-wrap:wrap;gap:4px;align-items:center}"
    "nav.pager button{font:inherit;padding:2px 8px}nav.pager button[aria-current]{font-weight:bold;background:#1e2a38;color:#fff}"
    ".verdict .conv{font-size:15px}.previews{display:flex;flex-wrap:wrap;gap:10px}.provenance{font-size:12px}\n";

// Paging, filtering and the interactive views' loader (report/viewer.hpp): when a card's view is
// opened, the viewer with its look-dev data and then the card's material, each by a <script>
// element (a page opened from disk may not fetch). No comment inside: the page holds no "//".
const char* const kScript = R"js(
(function () {
  "use strict";
  var per = parseInt(document.body.getAttribute("data-page-size"), 10) || 50;
  var cards = Array.prototype.slice.call(document.querySelectorAll("section.card"));
  var pagers = Array.prototype.slice.call(document.querySelectorAll("nav.pager"));
  var filter = document.getElementById("filter");
  var shown = cards, page = 1;
  function rank(c) { return {error: 3, warning: 2, info: 1}[c.getAttribute("data-worst")] || 0; }
  function pages() { return Math.max(1, Math.ceil(shown.length / per)); }
  function draw() {
    var n = pages();
    page = Math.min(Math.max(page, 1), n);
    var first = (page - 1) * per, last = first + per;
    cards.forEach(function (c) { c.hidden = true; });
    shown.forEach(function (c, i) { c.hidden = i < first || i >= last; });
    pagers.forEach(function (nav) {
      nav.hidden = false;
      var box = nav.querySelector(".pages");
      box.textContent = "";
      for (var p = 1; p <= n; p++) {
        var b = document.createElement("button");
        b.type = "button";
        b.textContent = String(p);
        b.setAttribute("data-page", String(p));
        if (p === page) b.setAttribute("aria-current", "page");
        box.appendChild(b);
      }
      nav.querySelector(".count").textContent = shown.length + " of " + cards.length + " materials, page " + page + " of " + n;
    });
    document.body.setAttribute("data-page", String(page));
  }
  function apply() {
    var min = filter ? parseInt(filter.value, 10) : 0;
    shown = cards.filter(function (c) { return rank(c) >= min; });
  }
  function go(hash) {
    var id = decodeURIComponent((hash || "").replace(/^#/, ""));
    var m = /^page-(\d+)$/.exec(id);
    if (m) { page = parseInt(m[1], 10); draw(); return; }
    var el = id ? document.getElementById(id) : null;
    if (el && el.classList.contains("card")) {
      var i = shown.indexOf(el);
      if (i < 0) { if (filter) filter.value = "0"; apply(); i = shown.indexOf(el); }
      page = Math.floor(i / per) + 1;
      draw();
      el.scrollIntoView();
      return;
    }
    draw();
  }
  pagers.forEach(function (nav) {
    nav.addEventListener("click", function (e) {
      var p = e.target.getAttribute && e.target.getAttribute("data-page");
      if (p) { page = parseInt(p, 10); draw(); nav.scrollIntoView(); }
      else if (e.target.classList.contains("prev")) { page--; draw(); }
      else if (e.target.classList.contains("next")) { page++; draw(); }
    });
  });
  if (filter) {
    filter.hidden = false;
    filter.addEventListener("change", function () { apply(); page = 1; draw(); });
  }
  window.addEventListener("hashchange", function () { go(location.hash); });
  Array.prototype.forEach.call(document.querySelectorAll("div.viewer"), function (v) { v.hidden = false; });
  function load(src, box, then) {
    var s = document.createElement("script");
    s.src = src;
    s.onload = then;
    s.onerror = function () { box.querySelector(".viewer-status").textContent = src + " did not load"; };
    document.head.appendChild(s);
  }
  document.addEventListener("click", function (e) {
    var b = e.target.closest ? e.target.closest("button.viewer-open") : null;
    if (!b) return;
    var box = b.closest("div.viewer"), stem = box.getAttribute("data-stem");
    var open = function () { window.mfViewer.open(box).catch(function () {}); };
    var material = function () {
      if (window.mfViewer.materials[stem]) open(); else load(box.getAttribute("data-src"), box, open);
    };
    if (window.mfViewer) material(); else load(box.getAttribute("data-lookdev"), box, material);
  });
  apply();
  go(location.hash);
})();
)js";

std::string pager_html() {
    return "<nav class=\"pager\" hidden><button type=\"button\" class=\"prev\">‹ previous</button><span class=\"pages\">"
           "</span><button type=\"button\" class=\"next\">next ›</button> <span class=\"count meta\"></span></nav>\n";
}

}  // namespace mf::report
