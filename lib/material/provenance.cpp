// Vendors, licences, and a set's provenance from its names, licence files and sidecars.
#include "material/provenance.hpp"

#include <algorithm>
#include <array>
#include <deque>
#include <map>
#include <set>

#include "material/classify.hpp"

namespace mf {
namespace {

using naming::is_digit;
using naming::Kind;
using naming::lower_copy;

// ---------------------------------------------------------------------------------------------
// The tables (docs/provenance.md gives the public page behind every row)

// Creative Commons' BY family: every version with an SPDX id, every combination of its elements.
struct CcVariant {
    std::string_view spdx, url, name;  // "-NC-SA", "by-nc-sa", "-NonCommercial-ShareAlike"
};
constexpr std::array<CcVariant, 6> kCcVariants{{
    {"", "by", ""},
    {"-SA", "by-sa", "-ShareAlike"},
    {"-NC", "by-nc", "-NonCommercial"},
    {"-ND", "by-nd", "-NoDerivatives"},
    {"-NC-SA", "by-nc-sa", "-NonCommercial-ShareAlike"},
    {"-NC-ND", "by-nc-nd", "-NonCommercial-NoDerivatives"},
}};
constexpr std::array<std::string_view, 4> kCcVersions{"2.0", "2.5", "3.0", "4.0"};

std::string_view cc_edition(std::string_view version) {
    return version == "4.0" ? " International" : version == "3.0" ? " Unported" : " Generic";
}

struct Tables {
    std::deque<std::string> text;  // what the views point at
    std::vector<LicenceInfo> licences;

    std::string_view keep(std::string s) { return text.emplace_back(std::move(s)); }

    Tables() {
        licences.push_back({"CC0-1.0", "Creative Commons Zero v1.0 Universal",
                            "https://creativecommons.org/publicdomain/zero/1.0/", false, false});
        for (const auto version : kCcVersions)
            for (const auto& v : kCcVariants) {
                const std::string ver(version);
                licences.push_back({keep("CC-BY" + std::string(v.spdx) + "-" + ver),
                                    keep("Creative Commons Attribution" + std::string(v.name) + " " + ver +
                                         std::string(cc_edition(version))),
                                    keep("https://creativecommons.org/licenses/" + std::string(v.url) + "/" + ver +
                                         "/"),
                                    true, false});
            }
        licences.push_back({"", "Creative Commons Attribution (version not stated)",
                            "https://creativecommons.org/licenses/", true, false});
        licences.push_back({"MIT", "MIT License", "https://opensource.org/license/mit", true, false});
        licences.push_back({"", "Poliigon EULA", "https://www.poliigon.com/terms", false, true});
        licences.push_back({"", "Fab Standard License", "https://www.fab.com/eula", false, true});
    }
};

const Tables& tables() {
    static const Tables t;
    return t;
}

const LicenceInfo* licence_by_name(std::string_view name) {
    for (const auto& l : tables().licences)
        if (l.name == name) return &l;
    return nullptr;
}

const LicenceInfo* cc_by(bool nc, bool sa, bool nd, std::string_view version) {
    if (sa && nd) return nullptr;
    if (version.empty())
        return nc || sa || nd ? nullptr : licence_by_name("Creative Commons Attribution (version not stated)");
    return licence_by_spdx(std::string("CC-BY") + (nc ? "-NC" : "") + (sa ? "-SA" : "") + (nd ? "-ND" : "") + "-" +
                           std::string(version));
}

// ---------------------------------------------------------------------------------------------
// Reading a licence from text

struct Word {
    std::string low;
    size_t at = 0;
};

// Lower-case runs of letters and digits; a '.' between digits stays ("4.0"); anything else separates.
std::vector<Word> words_of(std::string_view text) {
    std::vector<Word> out;
    std::string cur;
    size_t start = 0;
    const auto flush = [&] {
        if (!cur.empty()) out.push_back({cur, start});
        cur.clear();
    };
    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        const bool keep = naming::is_alpha(c) || is_digit(c) ||
                          (c == '.' && i > 0 && i + 1 < text.size() && is_digit(text[i - 1]) && is_digit(text[i + 1]));
        if (!keep) {
            flush();
            continue;
        }
        if (cur.empty()) start = i;
        cur += naming::to_lower(c);
    }
    flush();
    return out;
}

// "4.0", "v4.0", "4" -> "4.0"; "" when `w` is no version.
std::string version_of(std::string_view w) {
    if (w.starts_with("v")) w.remove_prefix(1);
    if (w.size() == 1 && is_digit(w[0])) return std::string(w) + ".0";
    if (w.size() == 3 && is_digit(w[0]) && w[1] == '.' && is_digit(w[2])) return std::string(w);
    return {};
}

// Words that may stand between a licence's name and its version.
bool filler(std::string_view w) {
    static constexpr std::array<std::string_view, 9> kFiller{"license",       "licence",  "version",
                                                             "international", "unported", "generic",
                                                             "public",        "v",        "the"};
    return std::find(kFiller.begin(), kFiller.end(), w) != kFiller.end();
}

// The CC BY licence whose elements start at words[i] (past "cc by" / "licenses by" / "creative
// commons attribution"): its elements, then its version within a few filler words.
const LicenceInfo* cc_by_at(const std::vector<Word>& words, size_t i, bool spelled_out) {
    bool nc = false, sa = false, nd = false;
    const auto is = [&](size_t k, std::string_view w) { return k < words.size() && words[k].low == w; };
    for (;;) {
        if (!spelled_out && (is(i, "sa") || is(i, "nc") || is(i, "nd"))) {
            (is(i, "sa") ? sa : is(i, "nc") ? nc : nd) = true;
            ++i;
        } else if (spelled_out && is(i, "sharealike")) {
            sa = true, ++i;
        } else if (spelled_out && is(i, "share") && is(i + 1, "alike")) {
            sa = true, i += 2;
        } else if (spelled_out && is(i, "noncommercial")) {
            nc = true, ++i;
        } else if (spelled_out && is(i, "non") && is(i + 1, "commercial")) {
            nc = true, i += 2;
        } else if (spelled_out && (is(i, "noderivatives") || is(i, "noderivs"))) {
            nd = true, ++i;
        } else if (spelled_out && is(i, "no") && (is(i + 1, "derivatives") || is(i + 1, "derivs"))) {
            nd = true, i += 2;
        } else {
            break;
        }
    }
    for (size_t k = i; k < words.size() && k < i + 5; ++k) {
        if (const std::string v = version_of(words[k].low); !v.empty()) return cc_by(nc, sa, nd, v);
        if (!filler(words[k].low)) break;
    }
    return cc_by(nc, sa, nd, "");
}

// What names "MIT" as a licence: "MIT License" / "MIT Licence".
bool mit_at(const std::vector<Word>& words, size_t i) {
    return words[i].low == "mit" && i + 1 < words.size() &&
           (words[i + 1].low == "license" || words[i + 1].low == "licence");
}

// An SPDX-License-Identifier line's licence.
void spdx_lines(std::string_view text, std::vector<LicenceMention>& out) {
    const std::string low = lower_copy(text);
    constexpr std::string_view kTag = "spdx-license-identifier:";
    for (size_t at = low.find(kTag); at != std::string::npos; at = low.find(kTag, at + 1)) {
        size_t i = at + kTag.size();
        while (i < text.size() && (text[i] == ' ' || text[i] == '\t')) ++i;
        size_t j = i;
        while (j < text.size() &&
               (naming::is_alpha(text[j]) || is_digit(text[j]) || text[j] == '.' || text[j] == '-' || text[j] == '+'))
            ++j;
        if (const LicenceInfo* l = licence_by_spdx(text.substr(i, j - i))) out.push_back({l, at});
    }
}

// The line of `text` that names who holds the rights ("Copyright (c) 2018 A, B", "© A",
// "Author: A"): the last such line before `before` (the licence's first mention), else the first.
std::string holder_line(std::string_view text, size_t before) {
    std::string found, first;
    size_t start = 0;
    while (start <= text.size()) {
        size_t end = text.find('\n', start);
        if (end == std::string_view::npos) end = text.size();
        std::string_view line = text.substr(start, end - start);
        const std::string low = lower_copy(line);
        const auto begins = [&](std::string_view w) {
            const size_t k = low.find_first_not_of(" \t#*->");
            return k != std::string::npos && std::string_view(low).substr(k).starts_with(w);
        };
        if (low.find("copyright") != std::string::npos || low.find("(c)") != std::string::npos ||
            line.find("\xC2\xA9") != std::string_view::npos || begins("author") || begins("created by") ||
            begins("made by")) {
            // Trimmed: markdown marks and line-break backslashes, then at most 300 bytes.
            const size_t a = line.find_first_not_of(" \t#*->");
            size_t b = line.find_last_not_of(" \t\r\\");
            std::string clean(a == std::string_view::npos || b < a ? std::string_view{} : line.substr(a, b - a + 1));
            if (clean.size() > 300) {
                size_t cut = 300;
                while (cut > 0 && (static_cast<unsigned char>(clean[cut]) & 0xC0) == 0x80) --cut;
                clean = clean.substr(0, cut) + "…";
            }
            if (first.empty()) first = clean;
            if (start < before) found = clean;
        }
        if (end == text.size()) break;
        start = end + 1;
    }
    return found.empty() ? first : found;
}

std::string names_of(const std::vector<const LicenceInfo*>& ls) {
    std::string out;
    for (const LicenceInfo* l : ls) out += (out.empty() ? "" : ", ") + std::string(l->spdx.empty() ? l->name : l->spdx);
    return out;
}

// ---------------------------------------------------------------------------------------------
// The vendor, from names and sidecars

const VendorInfo& vendor(std::string_view id) {
    for (const auto& v : vendor_table())
        if (v.id == id) return v;
    return vendor_table().front();
}

struct VendorMatch {
    const VendorInfo* vendor = nullptr;
    std::string asset_id, asset_id_from, file;
};

// Every map candidate of the set with its name analysed, in file order.
struct MapName {
    std::string file;
    naming::NameAnalysis a;
    const NameMatch* match;
};
std::vector<MapName> maps_of(const SetDiscovery& d) {
    std::vector<MapName> out;
    for (const auto& c : d.choices) {
        out.push_back({c.chosen.file, naming::analyse(c.chosen.file), &c.chosen.match});
        for (const auto& r : c.rejected) out.push_back({r.file, naming::analyse(r.file), &r.match});
    }
    std::sort(out.begin(), out.end(), [](const MapName& a, const MapName& b) { return a.file < b.file; });
    return out;
}

// One name shared by every map in `names`; "" when they differ or there are none.
std::string one_of(const std::set<std::string>& names) { return names.size() == 1 ? *names.begin() : std::string(); }

bool ambientcg_id(std::string_view id) {  // "Bricks059", "Net004A": letters, then three digits, then a variant letter
    size_t i = 0;
    while (i < id.size() && (naming::is_alpha(id[i]) || is_digit(id[i]))) ++i;
    if (i != id.size() || id.size() < 4 || !naming::is_alpha(id[0])) return false;
    size_t end = id.size();
    if (naming::is_alpha(id[end - 1])) --end;
    return end >= 4 && is_digit(id[end - 1]) && is_digit(id[end - 2]) && is_digit(id[end - 3]);
}

// ambientCG: "<Id>_<res>-<FORMAT>_<Map>" ("Net004A_1K-JPG_Color.jpg").
std::optional<VendorMatch> ambientcg(const SetDiscovery& d, const std::vector<MapName>& maps) {
    if (d.convention != "ambientcg") return std::nullopt;
    std::set<std::string> ids;
    std::string file;
    for (const MapName& m : maps) {
        if (m.match->family != "ambientcg" || !m.a.tag) continue;
        const auto& t = m.a.tokens;
        bool pair = false;
        for (size_t i = 0; i + 1 < m.a.tag->first_token; ++i)
            pair = pair || (t[i].kind == Kind::resolution && t[i + 1].kind == Kind::format);
        if (!pair) return std::nullopt;  // a map of the family's tags without the vendor's layout
        ids.insert(naming::join_name(t, m.a.name_end));
        if (file.empty()) file = m.file;
    }
    const std::string id = one_of(ids);
    if (id.empty() || !ambientcg_id(id)) return std::nullopt;
    return VendorMatch{&vendor("ambientcg"), id, "name", file};
}

// Poly Haven: "<slug>_<map>_<res>" in lower case ("brown_planks_09_diff_1k.jpg").
std::optional<VendorMatch> polyhaven(const SetDiscovery& d, const std::vector<MapName>& maps) {
    if (d.convention != "polyhaven") return std::nullopt;
    std::set<std::string> slugs;
    std::string file;
    for (const MapName& m : maps) {
        if (m.match->family != "polyhaven" || !m.a.tag) continue;
        const auto& t = m.a.tokens;
        const size_t next = m.a.tag->last_token + 1;
        if (next >= t.size() || t[next].kind != Kind::resolution || t[next].text != t[next].low) return std::nullopt;
        const std::string slug = naming::name_spelling(m.file, m.a);
        if (slug.empty() || std::any_of(slug.begin(), slug.end(),
                                        [](char c) { return !(naming::is_lower(c) || is_digit(c) || c == '_'); }))
            return std::nullopt;
        slugs.insert(slug);
        if (file.empty()) file = m.file;
    }
    const std::string slug = one_of(slugs);
    if (slug.empty()) return std::nullopt;
    return VendorMatch{&vendor("polyhaven"), slug, "name", file};
}

// 3dtextures.me: "<Name>_<NNN>_<map>" (Substance Designer's map names) beside the site's preview
// render "Material_NNNN.jpg", in a folder of its own (the render names no material).
std::optional<VendorMatch> threedtextures(const std::vector<std::string>& files, const std::vector<MapName>& maps,
                                          bool shared_folder) {
    static constexpr std::array<std::string_view, 13> kTags{
        "basecolor", "normal", "roughness", "height", "ambientocclusion", "metallic", "opacity", "emissive", "color",
        "norm",      "rough",  "occ",       "disp"};
    if (shared_folder) return std::nullopt;
    const bool render = std::any_of(files.begin(), files.end(), [](const std::string& f) {
        const auto a = naming::analyse(f);
        return is_image_file(f) && a.clutter && a.clutter->kind == naming::ClutterKind::render;
    });
    if (!render || maps.empty()) return std::nullopt;
    std::set<std::string> names;
    for (const MapName& m : maps) {
        if (!m.a.tag) return std::nullopt;
        std::string tag;
        for (size_t i = m.a.tag->first_token; i <= m.a.tag->last_token; ++i) tag += m.a.tokens[i].low;
        if (std::find(kTags.begin(), kTags.end(), tag) == kTags.end()) return std::nullopt;
        if (std::any_of(m.a.tokens.begin(), m.a.tokens.end(),
                        [](const naming::Token& t) { return t.kind == Kind::resolution; }))
            return std::nullopt;
        const std::string name = naming::name_spelling(m.file, m.a);
        const size_t n = name.size();
        if (n < 5 || name[n - 4] != '_' || !is_digit(name[n - 3]) || !is_digit(name[n - 2]) || !is_digit(name[n - 1]))
            return std::nullopt;
        names.insert(name);
    }
    const std::string name = one_of(names);
    if (name.empty()) return std::nullopt;
    return VendorMatch{&vendor("3dtextures"), name, "name", maps.front().file};
}

// Poliigon: "Poliigon_<Name>_<id>_<Map>" ("Poliigon_BrickWallReclaimed_8320_BaseColor.jpg").
std::optional<VendorMatch> poliigon(const std::vector<MapName>& maps) {
    std::set<std::string> names;
    std::string file, id;
    for (const MapName& m : maps) {
        if (m.a.tokens.empty() || m.a.tokens.front().text != "Poliigon") return std::nullopt;
        names.insert(naming::name_spelling(m.file, m.a));
        for (size_t i = 1; i < m.a.name_end; ++i)
            if (m.a.tokens[i].kind == Kind::word && naming::all_digits(m.a.tokens[i].low)) id = m.a.tokens[i].text;
        if (file.empty()) file = m.file;
    }
    if (one_of(names).empty()) return std::nullopt;
    return VendorMatch{&vendor("poliigon"), id, id.empty() ? "" : "name", file};
}

// Megascans: the asset's own JSON ("<id>.json") names maps of the set and its id.
std::optional<VendorMatch> megascans(const std::vector<std::string>& files, const std::vector<SidecarRoles>& sidecars) {
    const std::set<std::string> in_set(files.begin(), files.end());
    for (const auto& s : sidecars) {
        if (s.kind != SidecarKind::megascans || s.facts.asset_id.empty()) continue;
        const bool names_a_map = std::any_of(s.maps.begin(), s.maps.end(), [&](const SidecarMap& m) {
            return in_set.count(m.file) || std::any_of(files.begin(), files.end(), [&](const std::string& f) {
                       return naming::base_name(f) == naming::base_name(m.file);
                   });
        });
        if (names_a_map) return VendorMatch{&vendor("megascans"), s.facts.asset_id, "sidecar", s.source};
    }
    return std::nullopt;
}

std::optional<VendorMatch> vendor_of(const ProvenanceInput& in) {
    const auto maps = maps_of(in.discovery);
    if (auto v = megascans(in.files, in.sidecars)) return v;
    if (auto v = poliigon(maps)) return v;
    if (auto v = ambientcg(in.discovery, maps)) return v;
    if (auto v = polyhaven(in.discovery, maps)) return v;
    return threedtextures(in.files, maps, in.shared_folder);
}

Provenance::Licence licence_of(const LicenceInfo& l, Provenance::Evidence evidence) {
    Provenance::Licence out;
    out.spdx = std::string(l.spdx);
    out.name = std::string(l.name);
    out.url = std::string(l.url);
    out.attribution_required = l.attribution;
    out.vendor_licence = l.vendor_licence;
    out.evidence = std::move(evidence);
    return out;
}

std::string licence_label(const LicenceInfo& l) { return std::string(l.spdx.empty() ? l.name : l.spdx); }

// The credit line a licence that asks for one needs: who, what licence, where its text is.
std::string credit(const std::string& who, const Provenance::Licence& l, const std::string& where) {
    std::string s = who.empty() ? "the download names no author (" + where + "): find who to credit" : who;
    return s + "; licensed under " + (l.spdx.empty() ? l.name : l.spdx) + " (" + l.url + ")";
}

}  // namespace

const std::vector<LicenceInfo>& licence_table() { return tables().licences; }

const LicenceInfo* licence_by_spdx(std::string_view spdx) {
    if (spdx.empty()) return nullptr;
    const std::string want = lower_copy(spdx);
    for (const auto& l : tables().licences)
        if (!l.spdx.empty() && lower_copy(l.spdx) == want) return &l;
    return nullptr;
}

const std::vector<VendorInfo>& vendor_table() {
    static const std::vector<VendorInfo> t{
        {"ambientcg", "ambientCG", "CC0-1.0",
         "https://ambientcg.com/view?id=", "named the ambientCG way (<id>_<res>-<format>_<map>)"},
        {"polyhaven", "Poly Haven", "CC0-1.0", "https://polyhaven.com/a/",
         "named the Poly Haven way (<slug>_<map>_<res>, in lower case)"},
        {"3dtextures", "3dtextures.me", "CC0-1.0", "",
         "named the 3dtextures.me way (<Name>_<NNN>_<map>) beside the site's preview render Material_NNNN"},
        {"poliigon", "Poliigon", "Poliigon EULA", "", "named the Poliigon way (Poliigon_<Name>_<id>_<map>)"},
        {"megascans", "Quixel Megascans", "Fab Standard License", "",
         "a Megascans asset file names the maps and the id"},
    };
    return t;
}

std::vector<LicenceMention> licences_named(std::string_view text) {
    std::vector<LicenceMention> found;
    spdx_lines(text, found);
    const auto words = words_of(text);
    const auto is = [&](size_t k, std::string_view w) { return k < words.size() && words[k].low == w; };
    const LicenceInfo* cc0 = licence_by_spdx("CC0-1.0");
    const LicenceInfo* mit = licence_by_spdx("MIT");
    for (size_t i = 0; i < words.size(); ++i) {
        const LicenceInfo* l = nullptr;
        if (is(i, "cc0") || (is(i, "cc") && (is(i + 1, "0") || is(i + 1, "zero"))) ||
            (is(i, "creative") && is(i + 1, "commons") && is(i + 2, "zero")) ||
            (is(i, "publicdomain") && is(i + 1, "zero")))
            l = cc0;
        else if (is(i + 1, "by") && (is(i, "cc") || (i >= 2 && is(i - 2, "creativecommons") && is(i, "licenses"))))
            l = cc_by_at(words, i + 2, false);  // "CC BY-SA 4.0", creativecommons.org/licenses/by-sa/4.0/
        else if (is(i, "creative") && is(i + 1, "commons") && is(i + 2, "attribution"))
            l = cc_by_at(words, i + 3, true);
        else if (mit_at(words, i)) l = mit;
        if (l) found.push_back({l, words[i].at});
    }
    std::stable_sort(found.begin(), found.end(),
                     [](const LicenceMention& a, const LicenceMention& b) { return a.at < b.at; });
    std::vector<LicenceMention> out;
    for (const auto& m : found)
        if (std::none_of(out.begin(), out.end(), [&](const LicenceMention& o) { return o.licence == m.licence; }))
            out.push_back(m);
    // "CC BY 4.0" also reads as a version-less "CC BY" nowhere: the versioned one is kept alone.
    const bool versioned = std::any_of(out.begin(), out.end(), [](const LicenceMention& m) {
        return m.licence->attribution && !m.licence->spdx.empty() && m.licence->spdx.starts_with("CC-BY");
    });
    if (versioned)
        std::erase_if(out,
                      [](const LicenceMention& m) { return m.licence->spdx.empty() && !m.licence->vendor_licence; });
    return out;
}

bool is_licence_file_name(std::string_view filename) {
    const std::string base = lower_copy(naming::base_name(filename));
    const std::string ext = lower_copy(naming::extension_of(filename));
    if (!(ext.empty() || ext == "txt" || ext == "md")) return false;
    static constexpr std::array<std::string_view, 6> kStarts{"license", "licence", "copying",
                                                             "readme",  "credits", "attribution"};
    return std::any_of(kStarts.begin(), kStarts.end(), [&](std::string_view s) { return base.starts_with(s); });
}

ProvenanceResult find_provenance(const ProvenanceInput& in) {
    ProvenanceResult r;
    Provenance& p = r.provenance;
    const auto v = vendor_of(in);
    if (v) {
        p.vendor = std::string(v->vendor->id);
        p.vendor_name = std::string(v->vendor->name);
        p.asset_id = v->asset_id;
        p.asset_id_from = v->asset_id_from;
        if (!v->vendor->url_prefix.empty() && !v->asset_id.empty())
            p.url = std::string(v->vendor->url_prefix) + v->asset_id;
    }

    // 1. The download's licence files.
    std::vector<const LicenceInfo*> from_files;
    std::map<const LicenceInfo*, std::pair<const SetText*, size_t>> first_file;  // licence -> file, offset
    std::vector<std::string> silent, unread;
    for (const SetText& t : in.licence_files) {
        if (!t.error.empty()) {
            unread.push_back(t.file + " (" + t.error + ")");
            continue;
        }
        const auto named = licences_named(t.text);
        if (named.empty()) silent.push_back(t.file);
        for (const auto& m : named)
            if (first_file.try_emplace(m.licence, &t, m.at).second) from_files.push_back(m.licence);
    }
    if (from_files.size() > 1) {
        r.unknown = "the set's licence files name several licences (" + names_of(from_files) +
                    "): which one covers these maps is not said";
        r.unknown_file = first_file.at(from_files.front()).first->file;
        std::vector<std::string> names;
        names.reserve(from_files.size());
        for (const auto* l : from_files) names.push_back(licence_label(*l));
        r.figures = {{"licences", std::move(names)}};
        return r;
    }
    if (from_files.size() == 1) {
        const auto& [t, at] = first_file.at(from_files.front());
        p.licence = licence_of(*from_files.front(), {"file", t->file, "", t->file + " names it"});
        if (p.licence->attribution_required) p.attribution = credit(holder_line(t->text, at), *p.licence, t->file);
        return r;
    }

    // 2. A sidecar member.
    for (const SidecarRoles& s : in.sidecars) {
        const SidecarFacts& f = s.facts;
        for (const auto& [field, text] : {std::pair<std::string, std::string>{f.licence_field, f.licence},
                                          std::pair<std::string, std::string>{"asset.copyright", f.copyright}}) {
            if (text.empty()) continue;
            const auto named = licences_named(text);
            if (named.size() != 1) continue;
            p.licence = licence_of(*named.front().licence, {"sidecar", s.source, field,
                                                            s.source + "'s " + field + " states it: \"" + text + "\""});
            if (p.licence->attribution_required) {
                std::string who = f.copyright;  // glTF's "message … to credit the content creator"
                if (who.empty()) {
                    who = f.title.empty() ? std::string() : "\"" + f.title + "\"";
                    if (!f.author.empty()) who += (who.empty() ? "by " : " by ") + f.author;
                }
                if (!f.source_url.empty()) who += (who.empty() ? "" : " ") + ("(" + f.source_url + ")");
                p.attribution = credit(who, *p.licence, s.source);
            }
            return r;
        }
    }

    // 3. The vendor.
    if (v) {
        const LicenceInfo* l = licence_by_spdx(v->vendor->licence);
        if (!l) l = licence_by_name(v->vendor->licence);
        if (l) {
            std::string detail = std::string(v->vendor->naming) + "; " + std::string(v->vendor->name) +
                                 (l->vendor_licence ? " licenses its assets under the " + std::string(l->name) +
                                                          ": use in your own work, no redistribution of the files"
                                                    : " publishes every asset under " + licence_label(*l));
            p.licence = licence_of(*l, {"vendor", v->file, "", std::move(detail)});
            return r;
        }
    }

    // None: say why, naming what was looked at.
    std::vector<std::string> why;
    if (!silent.empty()) {
        std::string list;
        for (const auto& f : silent) list += (list.empty() ? "" : ", ") + f;
        why.emplace_back(list + (silent.size() == 1 ? " names" : " name") + " no licence matforge recognises");
        r.unknown_file = silent.front();
    }
    for (const auto& u : unread) why.emplace_back("could not read " + u);
    if (in.licence_files.empty()) why.emplace_back("no licence or readme file in the set");
    why.emplace_back("no sidecar states one");
    const std::string& conv = in.discovery.convention;
    if (conv == "texturescom")
        why.emplace_back("the names follow the Textures.com / Poliigon legacy scheme (<Name>_COL_<res>), which both "
                         "use under different licences");
    else if (conv == "megascans")
        why.emplace_back("the names follow Megascans' scheme, but no Megascans asset file (<id>.json) names the asset");
    else if (const auto it = std::find_if(vendor_table().begin(), vendor_table().end(),
                                          [&](const VendorInfo& vi) { return vi.id == conv; });
             it != vendor_table().end())
        // Tags alone are no vendor's name: Godot's demo textures ("rock_metal.jpg") share Poly
        // Haven's "_metal_" without its "<slug>_<map>_<res>".
        why.emplace_back("its names use " + std::string(it->name) + "'s map tags (naming: " + conv + ") but are not " +
                         std::string(it->naming) + ", so no vendor is proven");
    else why.emplace_back("its names (naming: " + conv + ") follow no vendor's scheme with a known licence");
    r.unknown = "no licence found: ";
    for (size_t i = 0; i < why.size(); ++i) r.unknown += (i ? (i + 1 == why.size() ? ", and " : ", ") : "") + why[i];
    r.figures = {{"naming", conv}};
    if (!in.licence_files.empty()) {
        std::vector<std::string> files;
        for (const auto& t : in.licence_files) files.push_back(t.file);
        r.figures.emplace("licence_files", std::move(files));
    }
    return r;
}

}  // namespace mf
