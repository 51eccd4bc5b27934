#include "material/discovery.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <map>
#include <span>
#include <tuple>

namespace mf {
namespace {

// ---------------------------------------------------------------------------------------------
// Characters and file names (ASCII only: material names in the wild are ASCII, and locale-aware
// classification would make results depend on the machine).

bool is_upper(char c) { return c >= 'A' && c <= 'Z'; }
bool is_lower(char c) { return c >= 'a' && c <= 'z'; }
bool is_alpha(char c) { return is_upper(c) || is_lower(c); }
char to_lower(char c) { return is_upper(c) ? static_cast<char>(c - 'A' + 'a') : c; }

std::string lower_copy(std::string_view s) {
    std::string out(s);
    for (auto& c : out) c = to_lower(c);
    return out;
}

std::string_view base_name(std::string_view path) {
    const auto slash = path.find_last_of("/\\");
    return slash == std::string_view::npos ? path : path.substr(slash + 1);
}

// A leading dot (".DS_Store") starts a hidden name, not an extension.
std::string_view extension_of(std::string_view path) {
    const auto name = base_name(path);
    const auto dot = name.rfind('.');
    if (dot == std::string_view::npos || dot == 0) return {};
    return name.substr(dot + 1);
}

std::string_view stem_of(std::string_view path) {
    const auto name = base_name(path);
    const auto dot = name.rfind('.');
    if (dot == std::string_view::npos || dot == 0) return name;
    return name.substr(0, dot);
}

int parse_int(std::string_view s) {
    int v = 0;
    if (s.empty() || !(s.front() >= '0' && s.front() <= '9')) return -1;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc{} || end != s.data() + s.size()) return -1;
    return v;
}

// Pixel size a single lower-case token states: "2k" 2048, "2048" (powers of two only, so that
// catalogue numbers like "001" or "059" stay part of the name), "2048px", "4096x4096".
int resolution_pixels(std::string_view low) {
    if (low.size() >= 2 && low.back() == 'k') {
        const int n = parse_int(low.substr(0, low.size() - 1));
        return n >= 1 && n <= 64 ? n * 1024 : 0;
    }
    if (low.size() > 2 && low.ends_with("px")) {
        const int n = parse_int(low.substr(0, low.size() - 2));
        return n > 0 && n <= 65536 ? n : 0;
    }
    if (const auto x = low.find('x'); x != std::string_view::npos) {
        const int w = parse_int(low.substr(0, x)), h = parse_int(low.substr(x + 1));
        return w >= 16 && h >= 16 && w <= 65536 && h <= 65536 ? std::max(w, h) : 0;
    }
    const int n = parse_int(low);
    return n >= 256 && n <= 16384 && (n & (n - 1)) == 0 ? n : 0;
}

constexpr std::array<std::string_view, 20> kFormatTags{
    "png", "jpg", "jpeg", "exr", "tif", "tiff", "tga", "hdr", "bmp", "webp",
    "psd", "dds", "8bit", "16bit", "32bit", "8b", "16b", "32b", "16", "32"};

bool contains(std::span<const std::string_view> list, std::string_view s) {
    return std::find(list.begin(), list.end(), s) != list.end();
}

// ---------------------------------------------------------------------------------------------
// Tokens

enum class Kind { word, resolution, format };

struct Token {
    std::string text;    // original spelling
    std::string low;     // lower case, used for matching
    bool camel = false;  // glued to the previous token by a camel-case boundary (no separator)
    Kind kind = Kind::word;
    int pixels = 0;  // resolution tags only
};

bool is_separator(char c) { return c == '_' || c == '-' || c == '.' || c == ' '; }

Token make_token(std::string text, bool camel) {
    Token t;
    t.low = lower_copy(text);
    t.text = std::move(text);
    t.camel = camel;
    t.pixels = resolution_pixels(t.low);
    if (t.pixels > 0)
        t.kind = Kind::resolution;
    else if (contains(kFormatTags, t.low))
        t.kind = Kind::format;
    return t;
}

// "OpenGL" and "DirectX" split into two camel tokens; glue them back so that the API names are
// single tokens ("opengl", "directx") like their lower-case spellings.
void merge_api_names(std::vector<Token>& tokens) {
    for (size_t i = 0; i + 1 < tokens.size(); ++i) {
        const auto& a = tokens[i];
        const auto& b = tokens[i + 1];
        if (!b.camel || !((a.low == "open" && b.low == "gl") || (a.low == "direct" && b.low == "x")))
            continue;
        tokens[i] = make_token(a.text + b.text, a.camel);
        tokens.erase(tokens.begin() + static_cast<std::ptrdiff_t>(i) + 1);
    }
}

std::vector<Token> tokenize(std::string_view stem) {
    std::vector<Token> out;
    std::string cur;
    bool cur_camel = false;
    auto flush = [&] {
        if (!cur.empty()) out.push_back(make_token(cur, cur_camel));
        cur.clear();
    };
    for (const char c : stem) {
        if (is_separator(c)) {
            flush();
            cur_camel = false;
            continue;
        }
        if (!cur.empty() && is_lower(cur.back()) && is_upper(c)) {
            flush();
            cur_camel = true;
        }
        cur += c;
    }
    flush();
    merge_api_names(out);
    return out;
}

// Indices of the tokens that can carry a role (resolution and format tags removed).
std::vector<size_t> word_indices(const std::vector<Token>& tokens) {
    std::vector<size_t> words;
    for (size_t i = 0; i < tokens.size(); ++i)
        if (tokens[i].kind == Kind::word) words.push_back(i);
    return words;
}

// ---------------------------------------------------------------------------------------------
// Clutter: images that are never maps.

// Anywhere in the name, as a token prefix ("Preview1", "thumbnails").
constexpr std::array<std::string_view, 2> kClutterPrefix{"preview", "thumb"};
// Anywhere in the name, as a whole token ("icon" but not "Iconic").
constexpr std::array<std::string_view, 7> kClutterAnywhere{
    "swatch", "swatches", "idmap", "matid", "screenshot", "icon", "thumbs"};
// Only as the last word, where a role tag would stand: these are also ordinary words
// ("Sphere_Tiles_Color" is a map of a material called "Sphere Tiles").
constexpr std::array<std::string_view, 8> kClutterLast{
    "render", "renders", "sphere", "cube", "flat", "id", "plane", "cylinder"};
// Trailing filler that says nothing ("Bricks_IdMap": "map" is filler, "id" is the last word).
constexpr std::array<std::string_view, 5> kFiller{"map", "tex", "texture", "img", "image"};

// Index of the token where clutter starts, if the name is clutter.
std::optional<size_t> clutter_position(const std::vector<Token>& tokens) {
    for (size_t i = 0; i < tokens.size(); ++i) {
        const auto& low = tokens[i].low;
        if (contains(kClutterAnywhere, low)) return i;
        for (const auto prefix : kClutterPrefix)
            if (low.starts_with(prefix)) return i;
    }
    auto words = word_indices(tokens);
    while (!words.empty() && contains(kFiller, tokens[words.back()].low)) words.pop_back();
    if (!words.empty() && contains(kClutterLast, tokens[words.back()].low)) return words.back();
    return std::nullopt;
}

// ---------------------------------------------------------------------------------------------
// Rule tables, one per family.

enum class Case {
    any,
    lower,          // all letters lower case ("nor_gl")
    upper,          // all letters upper case ("COL", "NRM16")
    capital,        // first letter upper case ("NormalGL", "AO")
    lower_initial,  // first letter lower case ("baseColor", "normal")
};

struct Rule {
    std::string_view tokens;  // lower-case tokens separated by ' '
    Role role;
    NormalConvention normal;
    Case casing;
    bool joined;  // the tokens must form one camel-case word ("NormalGL", not "Normal_GL")
    std::string_view display;
};

using enum Role;
constexpr auto kU = NormalConvention::unknown;
constexpr auto kGL = NormalConvention::gl;
constexpr auto kDX = NormalConvention::dx;

constexpr Rule kAmbientCG[] = {
    {"color", albedo, kU, Case::capital, false, "_Color"},
    {"normal gl", normal, kGL, Case::capital, true, "_NormalGL"},
    {"normal dx", normal, kDX, Case::capital, true, "_NormalDX"},
    {"normal", normal, kU, Case::capital, false, "_Normal"},  // older sets
    {"roughness", roughness, kU, Case::capital, false, "_Roughness"},
    {"metalness", metalness, kU, Case::capital, false, "_Metalness"},
    {"ambient occlusion", occlusion, kU, Case::capital, true, "_AmbientOcclusion"},
    {"displacement", height, kU, Case::capital, false, "_Displacement"},
    {"opacity", opacity, kU, Case::capital, false, "_Opacity"},
    {"emission", emissive, kU, Case::capital, false, "_Emission"},
};

constexpr Rule kPolyHaven[] = {
    {"diff", albedo, kU, Case::lower, false, "_diff_"},
    {"col", albedo, kU, Case::lower, false, "_col_"},
    {"nor gl", normal, kGL, Case::lower, false, "_nor_gl_"},
    {"nor dx", normal, kDX, Case::lower, false, "_nor_dx_"},
    {"nor", normal, kU, Case::lower, false, "_nor_"},
    {"rough", roughness, kU, Case::lower, false, "_rough_"},
    {"arm", orm, kU, Case::lower, false, "_arm_"},
    {"ao", occlusion, kU, Case::lower, false, "_ao_"},
    {"disp", height, kU, Case::lower, false, "_disp_"},
    {"bump", height, kU, Case::lower, false, "_bump_"},
    {"metal", metalness, kU, Case::lower, false, "_metal_"},
    {"spec", specular, kU, Case::lower, false, "_spec_"},
};

// Textures.com / Poliigon: the legacy upper-case tags first, so that "METALNESS" reads as the
// legacy rule rather than the current "Metalness".
constexpr Rule kTexturesCom[] = {
    {"col", albedo, kU, Case::upper, false, "_COL"},
    {"nrm", normal, kU, Case::upper, false, "_NRM"},
    {"nrm16", normal, kU, Case::upper, false, "_NRM16"},
    {"gloss", gloss, kU, Case::upper, false, "_GLOSS"},
    {"refl", specular, kU, Case::upper, false, "_REFL"},
    {"disp", height, kU, Case::upper, false, "_DISP"},
    {"disp16", height, kU, Case::upper, false, "_DISP16"},
    {"bump", height, kU, Case::upper, false, "_BUMP"},
    {"bump16", height, kU, Case::upper, false, "_BUMP16"},
    {"ao", occlusion, kU, Case::upper, false, "_AO"},
    {"metalness", metalness, kU, Case::upper, false, "_METALNESS"},
    {"base color", albedo, kU, Case::capital, true, "_BaseColor"},
    {"normal gl", normal, kGL, Case::capital, true, "_NormalGL"},
    {"normal dx", normal, kDX, Case::capital, true, "_NormalDX"},
    {"normal", normal, kU, Case::capital, false, "_Normal"},
    {"roughness", roughness, kU, Case::capital, false, "_Roughness"},
    {"metallic", metalness, kU, Case::capital, false, "_Metallic"},
    {"metalness", metalness, kU, Case::capital, false, "_Metalness"},
    {"ambient occlusion", occlusion, kU, Case::capital, true, "_AmbientOcclusion"},
    {"displacement", height, kU, Case::capital, false, "_Displacement"},
    {"height", height, kU, Case::capital, false, "_Height"},
};

constexpr Rule kMegascans[] = {
    {"albedo", albedo, kU, Case::capital, false, "_Albedo"},
    {"roughness", roughness, kU, Case::capital, false, "_Roughness"},
    {"gloss", gloss, kU, Case::capital, false, "_Gloss"},
    {"specular", specular, kU, Case::capital, false, "_Specular"},
    {"normal", normal, kU, Case::capital, false, "_Normal"},
    {"cavity", cavity, kU, Case::capital, false, "_Cavity"},
    {"bump", height, kU, Case::capital, false, "_Bump"},
    {"displacement", height, kU, Case::capital, false, "_Displacement"},
    {"ao", occlusion, kU, Case::capital, false, "_AO"},
    {"opacity", opacity, kU, Case::capital, false, "_Opacity"},
    {"translucency", translucency, kU, Case::capital, false, "_Translucency"},
    {"ort", Role::ort, kU, Case::any, false, "_ORT"},  // only Megascans packs ORT
};

constexpr Rule kSubstance[] = {
    {"base color", albedo, kU, Case::capital, false, "_BaseColor"},
    {"normal opengl", normal, kGL, Case::capital, false, "_Normal_OpenGL"},
    {"normal directx", normal, kDX, Case::capital, false, "_Normal_DirectX"},
    {"normal", normal, kU, Case::capital, false, "_Normal"},
    {"height", height, kU, Case::capital, false, "_Height"},
    {"emissive", emissive, kU, Case::capital, false, "_Emissive"},
    {"metallic", metalness, kU, Case::capital, false, "_Metallic"},
    {"roughness", roughness, kU, Case::capital, false, "_Roughness"},
    {"occlusion roughness metallic", orm, kU, Case::capital, true, "_OcclusionRoughnessMetallic"},
    {"mixed ao", occlusion, kU, Case::capital, false, "_Mixed_AO"},
    {"opacity", opacity, kU, Case::capital, false, "_Opacity"},
};

constexpr Rule kGltf[] = {
    {"base color", albedo, kU, Case::lower_initial, true, "baseColor"},
    {"metallic roughness", metallic_roughness, kU, Case::lower_initial, true, "metallicRoughness"},
    {"metal roughness", metallic_roughness, kU, Case::lower_initial, true, "metalRoughness"},
    {"occlusion roughness metallic", orm, kU, Case::lower_initial, true,
     "occlusionRoughnessMetallic"},
    {"occlusion", occlusion, kU, Case::lower_initial, false, "occlusion"},
    {"emissive", emissive, kU, Case::lower_initial, false, "emissive"},
    {"normal", normal, kU, Case::lower_initial, false, "normal"},
};

// Any case, any separators. Deliberately no "metal roughness" with separators: a roughness map
// of "Rusty_Metal" is named "Rusty_Metal_Roughness".
constexpr Rule kGeneric[] = {
    {"diffuse", albedo, kU, Case::any, false, "diffuse"},
    {"diff", albedo, kU, Case::any, false, "diff"},
    {"albedo", albedo, kU, Case::any, false, "albedo"},
    {"base color", albedo, kU, Case::any, false, "base_color"},
    {"base colour", albedo, kU, Case::any, false, "base_colour"},
    {"basecolor", albedo, kU, Case::any, false, "basecolor"},
    {"base", albedo, kU, Case::any, false, "base"},
    {"col", albedo, kU, Case::any, false, "col"},
    {"color", albedo, kU, Case::any, false, "color"},
    {"colour", albedo, kU, Case::any, false, "colour"},
    {"normal gl", normal, kGL, Case::any, false, "normal_gl"},
    {"normal opengl", normal, kGL, Case::any, false, "normal_opengl"},
    {"normal dx", normal, kDX, Case::any, false, "normal_dx"},
    {"normal directx", normal, kDX, Case::any, false, "normal_directx"},
    {"normalgl", normal, kGL, Case::any, false, "normalgl"},
    {"normaldx", normal, kDX, Case::any, false, "normaldx"},
    {"nrm gl", normal, kGL, Case::any, false, "nrm_gl"},
    {"nrm dx", normal, kDX, Case::any, false, "nrm_dx"},
    {"nor gl", normal, kGL, Case::any, false, "nor_gl"},
    {"nor dx", normal, kDX, Case::any, false, "nor_dx"},
    {"normal", normal, kU, Case::any, false, "normal"},
    {"norm", normal, kU, Case::any, false, "norm"},
    {"nrm", normal, kU, Case::any, false, "nrm"},
    {"nor", normal, kU, Case::any, false, "nor"},
    {"roughness", roughness, kU, Case::any, false, "roughness"},
    {"rough", roughness, kU, Case::any, false, "rough"},
    {"rgh", roughness, kU, Case::any, false, "rgh"},
    {"gloss", gloss, kU, Case::any, false, "gloss"},
    {"glossiness", gloss, kU, Case::any, false, "glossiness"},
    {"smoothness", gloss, kU, Case::any, false, "smoothness"},
    {"metalness", metalness, kU, Case::any, false, "metalness"},
    {"metallic", metalness, kU, Case::any, false, "metallic"},
    {"metal", metalness, kU, Case::any, false, "metal"},
    {"ao", occlusion, kU, Case::any, false, "ao"},
    {"occlusion", occlusion, kU, Case::any, false, "occlusion"},
    {"ambient occlusion", occlusion, kU, Case::any, false, "ambient_occlusion"},
    {"ambientocclusion", occlusion, kU, Case::any, false, "ambientocclusion"},
    {"height", height, kU, Case::any, false, "height"},
    {"heightmap", height, kU, Case::any, false, "heightmap"},
    {"disp", height, kU, Case::any, false, "disp"},
    {"displacement", height, kU, Case::any, false, "displacement"},
    {"bump", height, kU, Case::any, false, "bump"},
    {"emissive", emissive, kU, Case::any, false, "emissive"},
    {"emission", emissive, kU, Case::any, false, "emission"},
    {"opacity", opacity, kU, Case::any, false, "opacity"},
    {"alpha", opacity, kU, Case::any, false, "alpha"},
    {"specular", specular, kU, Case::any, false, "specular"},
    {"spec", specular, kU, Case::any, false, "spec"},
    {"orm", orm, kU, Case::any, false, "orm"},
    {"arm", orm, kU, Case::any, false, "arm"},
    {"occlusion roughness metallic", orm, kU, Case::any, true, "occlusion_roughness_metallic"},
    {"metallic roughness", metallic_roughness, kU, Case::any, true, "metallic_roughness"},
    {"metal roughness", metallic_roughness, kU, Case::any, true, "metal_roughness"},
    {"metallicroughness", metallic_roughness, kU, Case::any, false, "metallicroughness"},
    {"translucency", translucency, kU, Case::any, false, "translucency"},
    {"cavity", cavity, kU, Case::any, false, "cavity"},
};

// How a name is laid out around its role tag; each family has a typical layout, used to
// attribute a rule several families share ("_Roughness").
struct Layout {
    bool res_format_pair = false;  // "1K-PNG": ambientCG
    bool res_before = false;       // "_2K_Albedo": Megascans
    bool res_after = false;        // "_COL_VAR1_2K", "_nor_gl_1k": Poliigon legacy, Poly Haven
    bool poliigon_prefix = false;  // "Poliigon_…": current Poliigon
    bool no_resolution = false;    // "Mat_BaseColor": Substance, glTF
};

struct Family {
    std::string_view name;
    std::span<const Rule> rules;
    bool (*fits)(const Layout&);
};

// Priority order: also the tie-break when nothing else decides.
const std::array<Family, 7> kFamilies{{
    {"ambientcg", kAmbientCG, [](const Layout& l) { return l.res_format_pair; }},
    {"polyhaven", kPolyHaven, [](const Layout& l) { return l.res_after; }},
    {"texturescom", kTexturesCom,
     [](const Layout& l) { return l.res_after || l.poliigon_prefix; }},
    {"megascans", kMegascans, [](const Layout& l) { return l.res_before; }},
    {"substance", kSubstance, [](const Layout& l) { return l.no_resolution; }},
    {"gltf", kGltf, [](const Layout& l) { return l.no_resolution; }},
    {"generic", kGeneric, [](const Layout&) { return false; }},
}};
constexpr size_t kGenericFamily = 6;

// ---------------------------------------------------------------------------------------------
// Matching

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

// Does `rule` match the words starting at words[start]? Returns the number of words it spans.
size_t match_length(const Rule& rule, const std::vector<Token>& tokens,
                    const std::vector<size_t>& words, size_t start) {
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
        if (t.low != part) return 0;
        // Joined: each later token must be glued to its immediate predecessor.
        if (rule.joined && n > 0 && !(t.camel && ti == words[start + n - 1] + 1)) return 0;
        text += t.text;
        ++n;
    }
    return case_fits(rule.casing, text) ? n : 0;
}

struct Hit {
    size_t family;
    const Rule* rule;
};

// The role tag of a tokenized name.
struct RoleTag {
    size_t first_token = 0, last_token = 0;  // indices into the token list
    NameMatch match;
    std::vector<std::string_view> families;  // every family with a rule for this tag
    std::vector<std::string_view> fitting;   // those whose naming layout the name also follows
};

Layout layout_around(const std::vector<Token>& tokens, size_t first, size_t last) {
    Layout l;
    l.no_resolution = std::none_of(tokens.begin(), tokens.end(),
                                   [](const Token& t) { return t.kind == Kind::resolution; });
    for (size_t i = 0; i + 1 < tokens.size(); ++i)
        if (tokens[i].kind == Kind::resolution && tokens[i + 1].kind == Kind::format)
            l.res_format_pair = true;
    l.res_before = first > 0 && tokens[first - 1].kind == Kind::resolution;
    size_t next = last + 1;
    // Poliigon variant tags ("_COL_VAR1_2K") sit between the role and the resolution.
    while (next < tokens.size() && tokens[next].low.starts_with("var")) ++next;
    l.res_after = next < tokens.size() && tokens[next].kind == Kind::resolution;
    l.poliigon_prefix = !tokens.empty() && tokens.front().low == "poliigon";
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
        if (!same || h.family == kGenericFamily ||
            (!tag.families.empty() && tag.families.back() == name))
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
    tag.match.family = std::string(kFamilies[chosen->family].name);
    tag.match.rule = tag.match.family + ":" + std::string(chosen->rule->display);
    return tag;
}

// Material name tokens in [0, end), resolution and format tags dropped, joined by '_' except
// across a camel-case boundary ("DamagedHelmet" stays one word).
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

// Bit depth a name states ("16bit", "_16", Poliigon's "NRM16"), 0 when none.
int name_bit_depth(const std::vector<Token>& tokens) {
    int depth = 0;
    for (const auto& t : tokens) {
        const auto& s = t.low;
        if (s == "8bit" || s == "8b") depth = std::max(depth, 8);
        if (s == "16bit" || s == "16b" || s == "16" || s == "nrm16" || s == "disp16" ||
            s == "bump16")
            depth = std::max(depth, 16);
        if (s == "32bit" || s == "32b" || s == "32") depth = std::max(depth, 32);
    }
    return depth;
}

// ---------------------------------------------------------------------------------------------
// Choosing among candidates

// Lossless first, then lossy; the order of the header's contract (exr tif png tga bmp webp jpg),
// with the other readable formats placed by how much they lose.
int format_rank(std::string_view file) {
    static constexpr std::array<std::string_view, 12> kOrder{
        "exr", "tif", "tiff", "png", "tga", "bmp", "psd", "hdr", "webp", "jpg", "jpeg", "dds"};
    const auto ext = lower_copy(extension_of(file));
    const auto it = std::find(kOrder.begin(), kOrder.end(), ext);
    int rank = static_cast<int>(it - kOrder.begin());
    if (ext == "tiff") rank -= 1;  // same rank as tif
    if (ext == "jpeg") rank -= 1;  // same rank as jpg
    return rank;
}

struct Ranked {
    Candidate cand;
    int normal_rank = 0;  // 0 policy's convention, 1 other known, 2 unknown
    bool over_limit = false;
    int size = 0;  // longest side, header else name hint; 0 unknown
    int format = 0;
    int depth = 0;

    // Smaller is better.
    auto key() const {
        return std::make_tuple(normal_rank, over_limit, over_limit ? size : -size, format, -depth,
                               std::string_view(cand.file));
    }
};

Ranked rank_candidate(const Candidate& c, const ChoicePolicy& policy) {
    Ranked r;
    r.cand = c;
    if (c.match.role == Role::normal) {
        const auto n = c.match.normal;
        const bool preferred = n != NormalConvention::unknown && n == policy.preferred_normal;
        r.normal_rank = preferred ? 0 : n != NormalConvention::unknown ? 1 : 2;
    }
    r.size = c.header.width > 0 || c.header.height > 0 ? std::max(c.header.width, c.header.height)
                                                       : resolution_hint(c.file);
    r.over_limit = policy.max_size > 0 && r.size > policy.max_size;
    r.format = format_rank(c.file);
    r.depth = c.header.bit_depth > 0 ? c.header.bit_depth : name_bit_depth(tokenize(stem_of(c.file)));
    return r;
}

// Why `a` ranks before `b`: the first criterion that separates them.
std::string why_first(const Ranked& a, const Ranked& b, const ChoicePolicy& policy) {
    const auto conv = [](const Ranked& r) { return std::string(convention_name(r.cand.match.normal)); };
    if (a.normal_rank != b.normal_rank)
        return a.normal_rank == 0 ? "its normal convention (" + conv(a) + ") is the preset's"
                                  : "its name states a normal convention (" + conv(a) + ")";
    if (a.over_limit != b.over_limit)
        return "it fits the size limit of " + std::to_string(policy.max_size) + " px";
    if (a.size != b.size)
        return a.over_limit ? "it is the smallest above the size limit (" + std::to_string(a.size) +
                                  " px vs " + std::to_string(b.size) + " px)"
                            : "it is the largest (" + std::to_string(a.size) + " px vs " +
                                  std::to_string(b.size) + " px)";
    if (a.format != b.format)
        return "its format (" + lower_copy(extension_of(a.cand.file)) + ") ranks above " +
               lower_copy(extension_of(b.cand.file)) + " (lossless first)";
    if (a.depth != b.depth)
        return "higher bit depth (" + std::to_string(a.depth) + " vs " + std::to_string(b.depth) + ")";
    return "equal otherwise; first by name";
}

// One way an output role can be fed: a dedicated map, a channel of a packed one, or gloss.
}  // namespace

// Best first: a dedicated map, then packed inputs (Role order), then gloss. Packed roughness
// beats gloss because it needs no inversion ("roughness beats gloss").
std::vector<Provider> providers_of(Role out) {
    std::vector<Provider> list{{out, -1, false}};
    for (const Role packed : {Role::orm, Role::metallic_roughness, Role::ort}) {
        const auto layout = packed_layout(packed);
        for (int ch = 0; ch < 3; ++ch)
            if (layout[static_cast<size_t>(ch)] == out) list.push_back({packed, ch, false});
    }
    if (out == Role::roughness) list.push_back({Role::gloss, -1, true});
    return list;
}

namespace {

std::string why_provider(Role out, const Provider& a, const Provider& b) {
    const auto name = [](Role r) { return std::string(role_name(r)); };
    if (a.from == out && traits(b.from).packed)
        return "a dedicated " + name(out) + " map beats the packed " + name(b.from) + " map";
    if (a.from == out && b.from == Role::gloss) return "a roughness map beats a gloss map";
    if (traits(a.from).packed && b.from == Role::gloss)
        return "the packed " + name(a.from) + " map's roughness beats a gloss map (no inversion)";
    return "the " + name(a.from) + " map comes before the " + name(b.from) + " map";
}

// Everything one AMBIGUOUS_MAP says; built up per role, emitted once.
struct Ambiguity {
    std::vector<std::string> candidates;  // chosen first
    std::string chosen;
    std::vector<std::string> reasons;

    void add(const std::string& file) {
        if (std::find(candidates.begin(), candidates.end(), file) == candidates.end())
            candidates.push_back(file);
    }
    void put_first(const std::string& file) {
        std::erase(candidates, file);
        candidates.insert(candidates.begin(), file);
    }
};

std::string join(const std::vector<std::string>& parts, std::string_view sep) {
    std::string out;
    for (size_t i = 0; i < parts.size(); ++i) out += (i ? std::string(sep) : "") + parts[i];
    return out;
}

Finding ambiguity_finding(Role role, const Ambiguity& a) {
    Finding f;
    f.code = std::string(code::ambiguous_map);
    f.severity = Severity::info;
    f.role = std::string(role_name(role));
    f.file = a.chosen;
    const auto reason = join(a.reasons, "; ");
    f.message = std::to_string(a.candidates.size()) + " files could be the " + f.role +
                " map (" + join(a.candidates, ", ") + "); chose " + a.chosen + ": " + reason;
    f.figures = {{"candidates", a.candidates}, {"chosen", a.chosen}, {"reason", reason}};
    return f;
}

Finding unrecognized_finding(const std::string& file, std::string_view reason) {
    Finding f;
    f.code = std::string(code::unrecognized_file);
    f.severity = Severity::info;
    f.file = file;
    f.message = std::string(reason) + "; not used as a map";
    f.figures = {{"reason", std::string(reason)}};
    return f;
}

// The set's convention: the family compatible with the most files; ties go to the family more
// files name distinctively (only it has the rule), then to the one whose layout more names
// follow, then to priority order. A family that is not compatible with a strict majority of the
// maps means a mixed set: "generic".
std::string vote_convention(const std::vector<RoleTag>& tags) {
    std::tuple<int, int, int> best{0, 0, 0};
    std::string_view winner = "generic";
    for (size_t fi = 0; fi < kGenericFamily; ++fi) {
        const auto name = kFamilies[fi].name;
        int votes = 0, distinct = 0, fitting = 0;
        for (const auto& t : tags) {
            const bool in = std::find(t.families.begin(), t.families.end(), name) != t.families.end();
            votes += in;
            distinct += in && t.families.size() == 1;
            fitting += std::find(t.fitting.begin(), t.fitting.end(), name) != t.fitting.end();
        }
        const std::tuple<int, int, int> score{votes, distinct, fitting};
        if (score > best) {
            best = score;
            winner = name;
        }
    }
    const auto votes = static_cast<size_t>(std::get<0>(best));
    return votes * 2 > tags.size() ? std::string(winner) : "generic";
}

std::string normalized_key(std::string_view s) {
    std::string out = lower_copy(s);
    for (auto& c : out)
        if (is_separator(c)) c = '_';
    return out;
}

}  // namespace

// ---------------------------------------------------------------------------------------------

bool is_image_file(std::string_view filename) {
    static constexpr std::array<std::string_view, 12> kExt{
        "png", "jpg", "jpeg", "tga", "tif", "tiff", "exr", "hdr", "webp", "bmp", "dds", "psd"};
    return contains(kExt, lower_copy(extension_of(filename)));
}

bool is_clutter(std::string_view filename) {
    return clutter_position(tokenize(stem_of(filename))).has_value();
}

std::optional<NameMatch> classify_name(std::string_view filename) {
    if (!is_image_file(filename)) return std::nullopt;
    const auto tokens = tokenize(stem_of(filename));
    if (clutter_position(tokens)) return std::nullopt;
    auto tag = find_role_tag(tokens);
    if (!tag) return std::nullopt;
    return tag->match;
}

std::string material_stem(std::string_view filename) {
    const auto tokens = tokenize(stem_of(filename));
    size_t end = tokens.size();
    if (const auto tag = find_role_tag(tokens))
        end = tag->first_token;
    else if (const auto clutter = clutter_position(tokens))
        end = *clutter;
    return join_name(tokens, end);
}

int resolution_hint(std::string_view filename) {
    int pixels = 0;  // the last tag wins: it is the one nearest the role tag in every family
    for (const auto& t : tokenize(stem_of(filename)))
        if (t.kind == Kind::resolution) pixels = t.pixels;
    return pixels;
}

SetDiscovery discover_set(const std::vector<std::string>& files,
                          const std::function<std::optional<HeaderInfo>(const std::string&)>& header,
                          const ChoicePolicy& policy) {
    SetDiscovery out;
    std::vector<std::string> sorted = files;  // directory order must not change the result
    std::sort(sorted.begin(), sorted.end());
    sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());

    std::vector<Finding> unrecognized;
    std::vector<RoleTag> tags;
    std::map<Role, std::vector<Ranked>> by_role;
    for (const auto& file : sorted) {
        const auto tokens = tokenize(stem_of(file));
        if (!is_image_file(file)) {
            unrecognized.push_back(unrecognized_finding(file, "not an image"));
            continue;
        }
        if (clutter_position(tokens)) {
            unrecognized.push_back(unrecognized_finding(file, "preview/thumbnail image"));
            continue;
        }
        auto tag = find_role_tag(tokens);
        if (!tag) {
            unrecognized.push_back(unrecognized_finding(file, "no role tag in the name"));
            continue;
        }
        Candidate c{file, tag->match, {}};
        if (header)
            if (auto h = header(file)) c.header = *h;
        by_role[c.match.role].push_back(rank_candidate(c, policy));
        tags.push_back(std::move(*tag));
    }
    out.convention = vote_convention(tags);

    std::map<Role, Ambiguity> ambiguities;
    std::map<Role, std::string> chosen_file;
    for (auto& [role, ranked] : by_role) {
        std::sort(ranked.begin(), ranked.end(),
                  [](const Ranked& a, const Ranked& b) { return a.key() < b.key(); });
        RoleChoice choice{role, ranked.front().cand, {}};
        for (size_t i = 1; i < ranked.size(); ++i) choice.rejected.push_back(ranked[i].cand);
        chosen_file[role] = choice.chosen.file;
        if (ranked.size() > 1) {
            auto& a = ambiguities[role];
            for (const auto& r : ranked) a.add(r.cand.file);
            a.chosen = choice.chosen.file;
            a.reasons.push_back(why_first(ranked[0], ranked[1], policy));
        }
        out.choices.push_back(std::move(choice));
    }

    std::vector<Role> targets;
    targets.reserve(kOutputRoleCount + 1);
    for (int i = 0; i < kOutputRoleCount; ++i) targets.push_back(static_cast<Role>(i));
    targets.push_back(Role::translucency);
    for (const Role target : targets) {
        std::vector<Provider> available;
        for (const auto& p : providers_of(target))
            if (chosen_file.count(p.from)) available.push_back(p);
        if (available.empty()) continue;
        const Provider& best = available.front();
        out.sources.push_back({target, chosen_file[best.from], best.from, best.channel, best.invert});
        if (available.size() < 2) continue;
        auto& a = ambiguities[target];
        const std::string& file = chosen_file[best.from];
        a.put_first(file);
        for (const auto& p : available) a.add(chosen_file[p.from]);
        a.chosen = file;
        a.reasons.push_back(why_provider(target, best, available[1]));
    }

    for (const auto& [role, a] : ambiguities) out.findings.push_back(ambiguity_finding(role, a));
    for (auto& f : unrecognized) out.findings.push_back(std::move(f));
    return out;
}

std::vector<FileGroup> group_files(const std::vector<std::string>& files,
                                   const std::string& fallback_name) {
    std::map<std::string, FileGroup> groups;  // by case-insensitive stem
    std::vector<std::string> loose;
    for (const auto& file : files) {
        const std::string stem = classify_name(file) ? material_stem(file) : std::string();
        if (stem.empty()) {
            loose.push_back(file);
            continue;
        }
        auto [it, inserted] = groups.try_emplace(normalized_key(stem));
        if (inserted) it->second.name = stem;
        it->second.files.push_back(file);
    }
    if (groups.empty()) {
        if (files.empty()) return {};
        groups.emplace("", FileGroup{fallback_name, {}});
    }
    for (const auto& file : loose) {
        // Keys and names compare with separators unified: "Wood-Planks 2K.json" belongs to
        // the stem "Wood_Planks".
        const auto key = normalized_key(base_name(file));
        auto target = groups.begin();
        size_t best = 0;
        for (auto it = groups.begin(); it != groups.end(); ++it) {
            const auto& stem = it->first;
            if (stem.size() > best && key.starts_with(stem)) {
                best = stem.size();
                target = it;
            }
        }
        target->second.files.push_back(file);
    }
    std::vector<FileGroup> out;
    for (auto& [key, group] : groups) {
        std::sort(group.files.begin(), group.files.end());
        out.push_back(std::move(group));
    }
    return out;
}

}  // namespace mf
