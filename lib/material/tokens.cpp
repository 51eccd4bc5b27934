#include "material/tokens.hpp"

#include <algorithm>
#include <array>
#include <charconv>

#include "base/limits.hpp"
#include "core/text.hpp"

namespace mf::naming {

std::string lower_copy(std::string_view s) {
    std::string out(s);
    for (auto& c : out) c = to_lower(c);
    return out;
}

bool all_digits(std::string_view s) { return !s.empty() && std::all_of(s.begin(), s.end(), is_digit); }

std::string_view base_name(std::string_view path) {
    const auto slash = path.find_last_of("/\\");
    return slash == std::string_view::npos ? path : path.substr(slash + 1);
}

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
    if (s.empty() || !is_digit(s.front())) return -1;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc{} || end != s.data() + s.size()) return -1;
    return v;
}

bool contains(std::span<const std::string_view> list, std::string_view s) {
    return std::find(list.begin(), list.end(), s) != list.end();
}

size_t separator_at(std::string_view s, size_t i) {
    const char c = s[i];
    if (c == '_' || c == '-' || c == '.' || c == ' ') return 1;
    const auto rest = s.substr(i);
    if (rest.starts_with("\xE2\x80\x93") || rest.starts_with("\xE2\x80\x94")) return 3;
    if (rest.starts_with("\xC2\xB7") || rest.starts_with("\xC2\xA0")) return 2;
    return 0;
}

std::string normalized_key(std::string_view s) {
    std::string out;
    out.reserve(s.size());
    for (size_t i = 0; i < s.size();) {
        if (const size_t n = separator_at(s, i)) {
            if (out.empty() || out.back() != '_') out += '_';
            i += n;
            continue;
        }
        out += s[i];
        ++i;
    }
    return fold_case(out);  // "BRÏCK WALL" and "Brïck Wall" are one name
}

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
    return n >= 256 && n <= kMaxImageSide && (n & (n - 1)) == 0 ? n : 0;
}

namespace {

constexpr std::array<std::string_view, 18> kFormatTags{"png",  "jpg",   "jpeg",  "exr",  "tif", "tiff",
                                                       "tga",  "hdr",   "bmp",   "webp", "psd", "dds",
                                                       "8bit", "16bit", "32bit", "8b",   "16b", "32b"};

void classify_kind(Token& t) {
    t.kind = Kind::word;
    t.pixels = 0;
    if (t.camel || t.glued_next) return;  // part of a camel-case word
    t.pixels = resolution_pixels(t.low);
    if (t.pixels > 0) t.kind = Kind::resolution;
    else if (contains(kFormatTags, t.low)) t.kind = Kind::format;
    else if (t.low == "16" || t.low == "32") t.kind = Kind::depth;
}

// "OpenGL" and "DirectX" split into two camel tokens; glue them back so that the API names are
// single tokens ("opengl", "directx") like their lower-case spellings.
void merge_api_names(std::vector<Token>& tokens) {
    for (size_t i = 0; i + 1 < tokens.size(); ++i) {
        auto& a = tokens[i];
        const auto& b = tokens[i + 1];
        if (!b.camel || !((a.low == "open" && b.low == "gl") || (a.low == "direct" && b.low == "x"))) continue;
        a.text += b.text;
        a.low += b.low;
        a.end = b.end;
        tokens.erase(tokens.begin() + static_cast<std::ptrdiff_t>(i) + 1);
    }
}

}  // namespace

std::vector<Token> tokenize(std::string_view stem) {
    std::vector<Token> out;
    Token cur;
    auto flush = [&](size_t at) {
        if (!cur.text.empty()) {
            cur.end = at;
            cur.low = lower_copy(cur.text);
            out.push_back(std::move(cur));
        }
        cur = Token{};
    };
    for (size_t i = 0; i < stem.size();) {
        if (const size_t n = separator_at(stem, i)) {
            flush(i);
            i += n;
            continue;
        }
        const char c = stem[i];
        if (!cur.text.empty() && is_lower(cur.text.back()) && is_upper(c)) {
            flush(i);
            cur.camel = true;
        }
        if (cur.text.empty()) cur.begin = i;
        cur.text += c;
        ++i;
    }
    flush(stem.size());
    merge_api_names(out);
    for (size_t i = 0; i < out.size(); ++i) {
        out[i].glued_next = i + 1 < out.size() && out[i + 1].camel;
        classify_kind(out[i]);
    }
    return out;
}

std::vector<size_t> word_indices(const std::vector<Token>& tokens) {
    std::vector<size_t> words;
    for (size_t i = 0; i < tokens.size(); ++i)
        if (tokens[i].kind == Kind::word) words.push_back(i);
    return words;
}

}  // namespace mf::naming
