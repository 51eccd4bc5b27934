// Internal to lib/material (not a public API): characters, file-name parts and the tokenizer that
// classification (classify.cpp), choice (choose.cpp) and grouping (group.cpp) share.
#pragma once
#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace mf::naming {

// ASCII only: locale-aware classification would make results depend on the machine. Bytes of
// non-ASCII letters stay inside their token.
inline bool is_upper(char c) { return c >= 'A' && c <= 'Z'; }
inline bool is_lower(char c) { return c >= 'a' && c <= 'z'; }
inline bool is_alpha(char c) { return is_upper(c) || is_lower(c); }
inline bool is_digit(char c) { return c >= '0' && c <= '9'; }
inline char to_lower(char c) { return is_upper(c) ? static_cast<char>(c - 'A' + 'a') : c; }
std::string lower_copy(std::string_view s);
bool all_digits(std::string_view s);  // non-empty and only 0-9

std::string_view base_name(std::string_view path);     // after the last '/' or '\'
std::string_view extension_of(std::string_view path);  // without the dot; ".DS_Store" has none
std::string_view stem_of(std::string_view path);       // base name without its extension
int parse_int(std::string_view s);                     // whole string as a decimal, else -1
bool contains(std::span<const std::string_view> list, std::string_view s);

// Length in bytes of the separator starting at s[i], 0 when there is none: '_' '-' '.' ' ' and
// the UTF-8 en dash (E2 80 93), em dash (E2 80 94), middle dot (C2 B7) and no-break space (C2 A0)
// that web downloads and hand-renamed files put between a name and its tag.
size_t separator_at(std::string_view s, size_t i);

// Case-folded (core fold_case: non-ASCII capitals too), every run of separators replaced by
// one '_' ("Wood – Planks" -> "wood_planks", "BRÏCK" -> "brïck").
std::string normalized_key(std::string_view s);

enum class Kind {
    word,
    resolution,  // "2K", "2048", "2048px", "4096x4096"
    format,      // "png", "jpg", "16bit", "8b", …
    depth,       // a bare "16" or "32": a bit-depth tag after the role tag, a word before it
};

struct Token {
    std::string text;         // original spelling
    std::string low;          // lower case, used for matching
    bool camel = false;       // glued to the previous token by a camel-case boundary (no separator)
    bool glued_next = false;  // the next token is glued to this one by a camel-case boundary
    Kind kind = Kind::word;
    int pixels = 0;             // resolution tags only
    size_t begin = 0, end = 0;  // byte range in the stem
};

// Pixel size a single lower-case token states ("2k" 2048, "2048", "2048px", "4096x4096"), 0 when
// none. Bare numbers count only as powers of two from 256 to 16384, so catalogue numbers like
// "001" or "059" stay part of the name.
int resolution_pixels(std::string_view low);

// Split a stem on separators and lower->upper camel-case boundaries. A camel-case piece is never
// a tag ("TgaRle" is one name, not the format tag "tga" and a word). Bare "16"/"32" come out as
// Kind::depth; analyse() (classify.hpp) decides which side of the role tag they are on.
std::vector<Token> tokenize(std::string_view stem);

// Indices of the tokens that can carry a role (tags removed).
std::vector<size_t> word_indices(const std::vector<Token>& tokens);

}  // namespace mf::naming
