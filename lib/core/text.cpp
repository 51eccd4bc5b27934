#include "core/text.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <vector>

#include <cctype>

namespace mf {

namespace {

struct Prefix {
    std::size_t needed;  // bytes the lead byte announces (0: not a lead byte)
    std::size_t valid;   // bytes from the lead on that still fit a well-formed sequence
};

// Unicode Table 3-7: the second byte's range depends on the lead byte, which excludes
// overlongs, surrogates (ED A0..BF) and code points above U+10FFFF.
Prefix well_formed_prefix(std::string_view s, std::size_t i) {
    const auto b = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
    const unsigned char lead = b(i);
    if (lead < 0x80) return {1, 1};
    std::size_t n = 0;
    unsigned char lo = 0x80, hi = 0xBF;
    if (lead >= 0xC2 && lead <= 0xDF) {
        n = 2;
    } else if (lead >= 0xE0 && lead <= 0xEF) {
        n = 3;
        if (lead == 0xE0) lo = 0xA0;
        if (lead == 0xED) hi = 0x9F;
    } else if (lead >= 0xF0 && lead <= 0xF4) {
        n = 4;
        if (lead == 0xF0) lo = 0x90;
        if (lead == 0xF4) hi = 0x8F;
    } else {
        return {0, 0};
    }
    std::size_t k = 1;
    for (; k < n && i + k < s.size(); ++k) {
        const unsigned char c = b(i + k);
        if (k == 1 ? (c < lo || c > hi) : (c & 0xC0) != 0x80) break;
    }
    return {n, k};
}

}  // namespace

std::string utf8_or_replacement(std::string_view s) {
    std::string out;
    out.reserve(s.size());
    for (std::size_t i = 0; i < s.size();) {
        const Prefix p = well_formed_prefix(s, i);
        if (p.needed != 0 && p.valid == p.needed) {
            out.append(s.substr(i, p.needed));
            i += p.needed;
        } else {
            out.append("\xEF\xBF\xBD");  // U+FFFD for the maximal subpart (at least the lead)
            i += p.valid > 0 ? p.valid : 1;
        }
    }
    return out;
}

std::string percent_encode_path(std::string_view path) {
    static constexpr char kHex[] = "0123456789ABCDEF";
    std::string out;
    for (const char ch : path) {
        const auto c = static_cast<unsigned char>(ch);
        if (std::isalnum(c) || c == '-' || c == '.' || c == '_' || c == '~' || c == '/') {
            out += ch;
        } else {
            out += '%';
            out += kHex[c >> 4];
            out += kHex[c & 15];
        }
    }
    return out;
}

std::string nearest(const std::string& word, const std::vector<std::string>& candidates) {
    const std::string w = ascii_lower(word);
    std::string best;
    size_t best_d = std::max<size_t>(1, w.size() / 3) + 1;
    for (const std::string& c : candidates) {
        const std::string l = ascii_lower(c);
        std::vector<size_t> row(l.size() + 1);
        for (size_t j = 0; j <= l.size(); ++j) row[j] = j;
        for (size_t i = 1; i <= w.size(); ++i) {
            size_t diag = row[0];
            row[0] = i;
            for (size_t j = 1; j <= l.size(); ++j) {
                const size_t up = row[j];
                row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (w[i - 1] == l[j - 1] ? 0 : 1)});
                diag = up;
            }
        }
        if (row[l.size()] < best_d) best_d = row[l.size()], best = c;
    }
    return best;
}

std::string terminal_safe(std::string_view s, bool keep_newlines) {
    static const char* digits = "0123456789abcdef";
    std::string out;
    out.reserve(s.size());
    for (size_t i = 0; i < s.size(); ++i) {
        const auto c = static_cast<unsigned char>(s[i]);
        // C1 controls are U+0080..U+009F, in UTF-8 the bytes C2 80..C2 9F.
        const bool c1 = c == 0xC2 && i + 1 < s.size() && static_cast<unsigned char>(s[i + 1]) >= 0x80 &&
                        static_cast<unsigned char>(s[i + 1]) <= 0x9F;
        if ((c < 0x20 && !(keep_newlines && c == '\n') && c != '\t') || c == 0x7F || c1) {
            const unsigned char v = c1 ? static_cast<unsigned char>(s[++i]) : c;
            out += {'\\', 'x', digits[v >> 4], digits[v & 15]};
        } else {
            out += static_cast<char>(c);
        }
    }
    return out;
}

std::string fixed(double v, int digits) {
    std::array<char, 64> buf{};
    std::snprintf(buf.data(), buf.size(), "%.*f", digits, v);
    return buf.data();
}

std::string percent(double share) { return fixed(100.0 * share, 1) + " %"; }

std::string markup_escape(std::string_view raw) {
    const std::string s = utf8_or_replacement(raw);
    std::string out;
    out.reserve(s.size() + s.size() / 8);
    for (const char c : s) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&#39;"; break;
            default:
                if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r') out += "\xEF\xBF\xBD";
                else out += c;
        }
    }
    return out;
}

namespace {

// The small letter of code point c, for the capitals fold_case() knows; c itself otherwise.
char32_t small_letter(char32_t c) {
    if (c >= 0xC0 && c <= 0xDE && c != 0xD7) return c + 0x20;  // Latin-1: À–Þ but ×
    if (c == 0x178) return 0xFF;                               // Ÿ
    // Latin Extended-A: capital/small pairs on even/odd code points, shifted by one in two runs.
    const bool odd_capitals = (c >= 0x139 && c <= 0x148) || (c >= 0x179 && c <= 0x17E);
    if (c >= 0x100 && c <= 0x17F && c != 0x130 && c != 0x131 && c != 0x138 && c != 0x149 && c != 0x17F)
        return (c % 2 == 1) == odd_capitals ? c + 1 : c;
    if (c >= 0x391 && c <= 0x3A9 && c != 0x3A2) return c + 0x20;  // Greek Α–Ω
    if (c >= 0x410 && c <= 0x42F) return c + 0x20;                // Cyrillic А–Я
    if (c >= 0x400 && c <= 0x40F) return c + 0x50;                // Ѐ–Џ
    return c;
}

void put_utf8(std::string& out, char32_t c) {
    if (c < 0x80) {
        out += static_cast<char>(c);
    } else if (c < 0x800) {
        out += static_cast<char>(0xC0 | (c >> 6));
        out += static_cast<char>(0x80 | (c & 0x3F));
    } else {
        out += static_cast<char>(0xE0 | (c >> 12));
        out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (c & 0x3F));
    }
}

}  // namespace

std::string fold_case(std::string_view s) {
    std::string out;
    out.reserve(s.size());
    for (size_t i = 0; i < s.size();) {
        const auto b = static_cast<unsigned char>(s[i]);
        if (b < 0x80) {
            out += b >= 'A' && b <= 'Z' ? static_cast<char>(b + 32) : static_cast<char>(b);
            ++i;
            continue;
        }
        // Two-byte sequences hold every capital folded here (U+0080–U+07FF).
        if ((b & 0xE0) == 0xC0 && i + 1 < s.size() && (static_cast<unsigned char>(s[i + 1]) & 0xC0) == 0x80) {
            const char32_t c = (char32_t{b & 0x1Fu} << 6) | (static_cast<unsigned char>(s[i + 1]) & 0x3Fu);
            if (c >= 0x80) {  // not an overlong form
                put_utf8(out, small_letter(c));
                i += 2;
                continue;
            }
        }
        out += s[i++];
    }
    return out;
}

}  // namespace mf
