// One file name: clutter, role tag, material name part. And the public per-name functions.
#include "material/classify.hpp"

#include <algorithm>
#include <array>

#include "material/families.hpp"

namespace mf {
namespace naming {
namespace {

// ---------------------------------------------------------------------------------------------
// Clutter: images that are never maps.

// Anywhere in the name, as a token prefix ("Preview1", "thumbnails").
constexpr std::array<std::string_view, 2> kClutterPrefix{"preview", "thumb"};
// Anywhere in the name, as a whole token ("icon" but not "Iconic").
constexpr std::array<std::string_view, 5> kClutterAnywhere{"swatch", "swatches", "screenshot", "icon", "thumbs"};
constexpr std::array<std::string_view, 2> kMaskAnywhere{"idmap", "matid"};
// A billboard map of a Megascans plant, also "Billboards" folders' files.
constexpr std::array<std::string_view, 2> kBillboard{"billboard", "billboards"};
// Only as the last word, where a role tag would stand: these are also ordinary words
// ("Sphere_Tiles_Color" is a map of a material called "Sphere Tiles").
constexpr std::array<std::string_view, 7> kClutterLast{"render", "renders", "sphere",  "cube",
                                                       "flat",   "plane",   "cylinder"};
constexpr std::array<std::string_view, 2> kMaskLast{"id", "mask"};
constexpr std::array<std::string_view, 1> kPlaceholderLast{"black"};
// Trailing filler that says nothing ("Bricks_IdMap": "map" is filler, "id" is the last word).
constexpr std::array<std::string_view, 5> kFiller{"map", "tex", "texture", "img", "image"};

// Where clutter starts, if the name is clutter. A role tag ending on the last word keeps that
// word from being read as last-word clutter ("Leaf_OpacityMask" is opacity, "Leaf_Mask" a mask).
std::optional<Clutter> find_clutter(const std::vector<Token>& tokens, const std::optional<RoleTag>& tag) {
    for (size_t i = 0; i < tokens.size(); ++i) {
        const auto& low = tokens[i].low;
        if (contains(kBillboard, low)) return Clutter{i, ClutterKind::billboard};
        if (contains(kClutterAnywhere, low)) return Clutter{i, ClutterKind::preview};
        if (contains(kMaskAnywhere, low)) return Clutter{i, ClutterKind::mask};
        for (const auto prefix : kClutterPrefix)
            if (low.starts_with(prefix)) return Clutter{i, ClutterKind::preview};
    }
    // "Material_1639": the word "Material" and numbers only (3dtextures.me's preview render).
    if (tokens.size() >= 2 && tokens.front().low == "material" &&
        std::all_of(tokens.begin() + 1, tokens.end(), [](const Token& t) { return all_digits(t.low); }))
        return Clutter{0, ClutterKind::render};
    auto words = word_indices(tokens);
    while (!words.empty() && contains(kFiller, tokens[words.back()].low)) words.pop_back();
    if (words.empty()) return std::nullopt;
    const size_t last = words.back();
    if (tag && tag->last_token >= last) return std::nullopt;
    const auto& low = tokens[last].low;
    if (contains(kClutterLast, low)) return Clutter{last, ClutterKind::preview};
    if (contains(kMaskLast, low)) return Clutter{last, ClutterKind::mask};
    if (contains(kPlaceholderLast, low)) return Clutter{last, ClutterKind::placeholder};
    return std::nullopt;
}

// ---------------------------------------------------------------------------------------------
// Matching rules against tokens

bool case_fits(Case c, std::string_view text) {
    const auto first = std::find_if(text.begin(), text.end(), is_alpha);
    const bool has_upper = std::any_of(text.begin(), text.end(), is_upper);
    const bool has_lower = std::any_of(text.begin(), text.end(), is_lower);
    switch (c) {
        case Case::any: return true;
        case Case::lower: return !has_upper;
        case Case::upper: return has_upper && !has_lower;
        case Case::capital: return first != text.end() && is_upper(*first);
        case Case::lower_initial: return first != text.end() && is_lower(*first);
    }
    return false;
}

// Only tags and variant numbers after `last_token` ("_2K", "_PNG", "_01").
bool last_word(const std::vector<Token>& tokens, size_t last_token) {
    return std::all_of(tokens.begin() + static_cast<std::ptrdiff_t>(last_token) + 1, tokens.end(),
                       [](const Token& t) { return t.kind != Kind::word || all_digits(t.low); });
}

bool need_met(Need need, const std::vector<Token>& tokens, size_t first_token, size_t last_token) {
    switch (need) {
        case Need::none: return true;
        case Need::at_end: return last_word(tokens, last_token);
        case Need::unreal_suffix: return tokens.front().text == "T" && first_token > 0 && last_word(tokens, last_token);
        case Need::glued_at_end: return tokens[first_token].camel && last_word(tokens, last_token);
        case Need::unreal_texture:
            return tokens.front().text == "T" && first_token > 0 && tokens[first_token - 1].kind == Kind::resolution;
        case Need::res_after: return last_token + 1 < tokens.size() && tokens[last_token + 1].kind == Kind::resolution;
    }
    return false;
}

// Does `rule` match the words starting at words[start]? Returns the number of words it spans.
size_t match_length(const Rule& rule, const std::vector<Token>& tokens, const std::vector<size_t>& words,
                    size_t start) {
    std::string text;
    size_t n = 0;
    std::string_view rest = rule.tokens;
    while (!rest.empty()) {
        const auto space = rest.find(' ');
        const auto part = rest.substr(0, space);
        rest = space == std::string_view::npos ? std::string_view{} : rest.substr(space + 1);
        if (start + n >= words.size()) return 0;
        const size_t ti = words[start + n];
        const Token& t = tokens[ti];
        // A one-word tag of two or more letters in capitals may carry a variant letter in lower
        // case ("Rock_DISPa", "Rock_NRMb"): the tag without it.
        const bool variant = rule.tokens.size() >= 2 && rule.tokens.find(' ') == std::string_view::npos &&
                             t.low.size() == part.size() + 1 && t.low.starts_with(part) && is_lower(t.text.back()) &&
                             std::all_of(t.text.begin(), t.text.end() - 1, is_upper);
        if (t.low != part && !variant) return 0;
        // Joined: each later token must be glued to its immediate predecessor.
        if (rule.joined && n > 0 && !(t.camel && ti == words[start + n - 1] + 1)) return 0;
        text += variant ? t.text.substr(0, part.size()) : t.text;
        ++n;
    }
    if (!case_fits(rule.casing, text)) return 0;
    return need_met(rule.need, tokens, words[start], words[start + n - 1]) ? n : 0;
}

struct Hit {
    size_t family;
    const Rule* rule;
};

bool is_format_like(Kind k) { return k == Kind::format || k == Kind::depth; }

Layout layout_around(const std::vector<Token>& tokens, size_t first, size_t last) {
    Layout l;
    l.no_resolution = std::none_of(tokens.begin(), tokens.end(),
                                   [](const Token& t) { return t.kind == Kind::resolution; });
    for (size_t i = 0; i + 1 < tokens.size(); ++i)
        if (tokens[i].kind == Kind::resolution && is_format_like(tokens[i + 1].kind)) l.res_format_pair = true;
    l.res_before = first > 0 && tokens[first - 1].kind == Kind::resolution;
    size_t next = last + 1;
    // Poliigon variant tags ("_COL_VAR1_2K") sit between the role and the resolution.
    while (next < tokens.size() && tokens[next].low.starts_with("var")) ++next;
    l.res_after = next < tokens.size() && tokens[next].kind == Kind::resolution;
    l.poliigon_prefix = !tokens.empty() && tokens.front().low == "poliigon";
    l.unreal_prefix = !tokens.empty() && tokens.front().text == "T";
    return l;
}

// The role tag is the match ending nearest the end; on a tie the longer match wins, then a
// family rule over the generic one. Among families sharing the winning rule, the file is
// attributed to the first (priority order) whose layout the name follows, else the first.
std::optional<RoleTag> find_role_tag(const std::vector<Token>& tokens) {
    const auto words = word_indices(tokens);
    std::pair<size_t, size_t> best_key{0, 0};  // (end position + 1, length)
    size_t best_start = 0;
    std::vector<Hit> hits;
    for (size_t fi = 0; fi < kFamilies.size(); ++fi)
        for (const Rule& rule : kFamilies[fi].rules)
            for (size_t s = 0; s < words.size(); ++s) {
                const size_t n = match_length(rule, tokens, words, s);
                if (n == 0) continue;
                const std::pair<size_t, size_t> key{s + n, n};
                if (key > best_key) {
                    best_key = key;
                    best_start = s;
                    hits.clear();
                }
                if (key == best_key) hits.push_back({fi, &rule});
            }
    if (hits.empty()) return std::nullopt;

    // Hits come in family priority order, so the generic one is last.
    const Hit& lead = hits.front();
    RoleTag tag;
    tag.first_token = words[best_start];
    tag.last_token = words[best_start + best_key.second - 1];
    const Layout layout = layout_around(tokens, tag.first_token, tag.last_token);
    const Hit* chosen = nullptr;
    for (const Hit& h : hits) {
        const bool same = h.rule->role == lead.rule->role && h.rule->normal == lead.rule->normal;
        const auto name = kFamilies[h.family].name;
        if (!same || h.family == kGenericFamily || (!tag.families.empty() && tag.families.back() == name))
            continue;  // one entry per family: its first rule in table order
        tag.families.push_back(name);
        if (kFamilies[h.family].fits(layout)) {
            tag.fitting.push_back(name);
            if (!chosen) chosen = &h;
        }
    }
    if (!chosen) chosen = &lead;
    tag.match.role = chosen->rule->role;
    tag.match.normal = chosen->rule->normal;
    tag.match.opacity_in_alpha = chosen->rule->opacity_in_alpha;
    tag.match.space = chosen->rule->space;
    tag.match.family = std::string(kFamilies[chosen->family].name);
    tag.match.rule = tag.match.family + ":" + std::string(chosen->rule->display);
    return tag;
}

}  // namespace

std::string_view clutter_reason(ClutterKind k) {
    switch (k) {
        case ClutterKind::preview: return "preview/thumbnail image";
        case ClutterKind::render: return "preview render (Material_NNNN)";
        case ClutterKind::mask: return "ID or mask image with no PBR role";
        case ClutterKind::placeholder: return "all-black placeholder (_black) with no PBR role";
        case ClutterKind::billboard: return "billboard map (a plant's far-LOD impostor, not part of the material)";
    }
    return "clutter";
}

std::optional<int> preview_rank(const NameAnalysis& a) {
    if (!a.clutter) return std::nullopt;
    if (a.clutter->kind == ClutterKind::render) return 2;
    if (a.clutter->kind != ClutterKind::preview) return std::nullopt;
    const std::string& w = a.tokens[a.clutter->token].low;
    if (w.starts_with("preview")) return 1;
    if (w == "render" || w == "renders") return 2;
    if (w == "sphere") return 3;
    if (w == "cube") return 4;
    if (w == "flat" || w == "plane" || w == "cylinder") return 5;
    return 6;  // thumb…, icon, swatch(es), screenshot
}

NameAnalysis analyse(std::string_view filename) {
    NameAnalysis a;
    a.tokens = tokenize(stem_of(filename));
    a.tag = find_role_tag(a.tokens);
    a.clutter = find_clutter(a.tokens, a.tag);
    a.name_end = a.tag ? a.tag->first_token : a.clutter ? a.clutter->token : a.tokens.size();
    for (size_t i = 0; i < a.tokens.size(); ++i)
        if (a.tokens[i].kind == Kind::depth) a.tokens[i].kind = i < a.name_end ? Kind::word : Kind::format;
    return a;
}

std::string join_name(const std::vector<Token>& tokens, size_t end) {
    std::string out;
    std::optional<size_t> prev;
    for (size_t i = 0; i < end && i < tokens.size(); ++i) {
        if (tokens[i].kind != Kind::word) continue;
        if (prev && !(tokens[i].camel && *prev + 1 == i)) out += '_';
        out += tokens[i].text;
        prev = i;
    }
    return out;
}

std::string name_spelling(std::string_view filename, const NameAnalysis& a) {
    const auto stem = stem_of(filename);
    size_t end = a.name_end < a.tokens.size() ? a.tokens[a.name_end].begin : stem.size();
    // Drop the separators between the name part and the tag (multi-byte ones too).
    while (end > 0) {
        size_t start = end - 1;
        while (start > 0 && (static_cast<unsigned char>(stem[start]) & 0xC0) == 0x80) --start;
        if (separator_at(stem, start) != end - start) break;
        end = start;
    }
    return std::string(stem.substr(0, end));
}

int name_bit_depth(const std::vector<Token>& tokens) {
    int depth = 0;
    for (const auto& t : tokens) {
        const auto& s = t.low;
        if (s == "nrm16" || s == "disp16" || s == "bump16") depth = std::max(depth, 16);
        if (t.kind == Kind::word || t.kind == Kind::resolution) continue;
        if (s == "8bit" || s == "8b") depth = std::max(depth, 8);
        if (s == "16bit" || s == "16b" || s == "16") depth = std::max(depth, 16);
        if (s == "32bit" || s == "32b" || s == "32") depth = std::max(depth, 32);
    }
    return depth;
}

}  // namespace naming

bool is_image_file(std::string_view filename) {
    static constexpr std::array<std::string_view, 12> kExt{"png", "jpg", "jpeg", "tga", "tif", "tiff",
                                                           "exr", "hdr", "webp", "bmp", "dds", "psd"};
    return naming::contains(kExt, naming::lower_copy(naming::extension_of(filename)));
}

bool is_clutter(std::string_view filename) { return naming::analyse(filename).clutter.has_value(); }

std::optional<NameMatch> classify_name(std::string_view filename) { return classify_name(filename, false); }

std::optional<NameMatch> classify_name(std::string_view filename, bool billboards_are_maps) {
    if (!is_image_file(filename)) return std::nullopt;
    auto a = naming::analyse(filename);
    const bool billboard = a.clutter && a.clutter->kind == naming::ClutterKind::billboard;
    if ((a.clutter && !(billboard && billboards_are_maps)) || !a.tag) return std::nullopt;
    return std::move(a.tag->match);
}

bool billboards_only(const std::vector<std::string>& files) {
    bool billboard_map = false;
    for (const auto& f : files) {
        if (!is_image_file(f)) continue;
        const auto a = naming::analyse(f);
        if (!a.tag) continue;
        if (!a.clutter) return false;  // a map of the asset itself
        billboard_map = billboard_map || a.clutter->kind == naming::ClutterKind::billboard;
    }
    return billboard_map;
}

std::string material_stem(std::string_view filename) {
    const auto a = naming::analyse(filename);
    return naming::join_name(a.tokens, a.name_end);
}

int resolution_hint(std::string_view filename) {
    int pixels = 0;  // the last tag wins: it is the one nearest the role tag in every family
    for (const auto& t : naming::tokenize(naming::stem_of(filename)))
        if (t.kind == naming::Kind::resolution) pixels = t.pixels;
    return pixels;
}

}  // namespace mf
