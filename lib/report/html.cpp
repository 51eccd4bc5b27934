#include "report/html.hpp"

#include <cctype>
#include <optional>
#include <utility>
#include <vector>

#include "core/text.hpp"

namespace mf::report {
namespace {

bool starts_with(std::string_view s, std::string_view p) { return s.substr(0, p.size()) == p; }

std::string_view trim(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
    return s;
}

// Where a Markdown link goes once rules.md is rules.html: its own anchors stay, other .md files
// are not beside the report (nullopt: text only), web links stay.
std::optional<std::string> link_target(std::string_view url) {
    if (starts_with(url, "https://") || starts_with(url, "http://")) return std::string(url);
    if (starts_with(url, "#")) return std::string(url);
    const size_t hash = url.find('#');
    const std::string_view file = url.substr(0, hash);
    const size_t slash = file.rfind('/');
    const std::string_view base = slash == std::string_view::npos ? file : file.substr(slash + 1);
    if (base == "rules.md") return hash == std::string_view::npos ? std::string("#") : std::string(url.substr(hash));
    return std::nullopt;
}

std::string inline_html(std::string_view s) {
    std::string out;
    size_t i = 0;
    while (i < s.size()) {
        const char c = s[i];
        if (c == '\\' && i + 1 < s.size() && std::ispunct(static_cast<unsigned char>(s[i + 1]))) {
            out += markup_escape(s.substr(i + 1, 1));
            i += 2;
            continue;
        }
        if (c == '`') {
            const size_t end = s.find('`', i + 1);
            if (end != std::string_view::npos) {
                out += "<code>" + markup_escape(s.substr(i + 1, end - i - 1)) + "</code>";
                i = end + 1;
                continue;
            }
        }
        if (c == '*' && i + 1 < s.size() && s[i + 1] == '*') {
            const size_t end = s.find("**", i + 2);
            if (end != std::string_view::npos && end > i + 2) {
                out += "<strong>" + inline_html(s.substr(i + 2, end - i - 2)) + "</strong>";
                i = end + 2;
                continue;
            }
        }
        if (c == '*' && i + 1 < s.size() && s[i + 1] != ' ') {
            const size_t end = s.find('*', i + 1);
            if (end != std::string_view::npos && end > i + 1) {
                out += "<em>" + inline_html(s.substr(i + 1, end - i - 1)) + "</em>";
                i = end + 1;
                continue;
            }
        }
        if (c == '[') {
            const size_t close = s.find("](", i + 1);
            const size_t end = close == std::string_view::npos ? close : s.find(')', close + 2);
            if (end != std::string_view::npos) {
                const std::string text = inline_html(s.substr(i + 1, close - i - 1));
                if (const auto target = link_target(s.substr(close + 2, end - close - 2)))
                    out += "<a href=\"" + markup_escape(*target) + "\">" + text + "</a>";
                else out += text;
                i = end + 1;
                continue;
            }
        }
        out += markup_escape(s.substr(i, 1));
        ++i;
    }
    return out;
}

// Cells of a pipe-table row; "\|" is a literal bar (also inside code spans, as GitHub reads it).
std::vector<std::string> table_cells(std::string_view line) {
    line = trim(line);
    if (starts_with(line, "|")) line.remove_prefix(1);
    if (!line.empty() && line.back() == '|' && (line.size() < 2 || line[line.size() - 2] != '\\'))
        line.remove_suffix(1);
    std::vector<std::string> cells;
    std::string cell;
    for (size_t i = 0; i < line.size(); ++i) {
        if (line[i] == '\\' && i + 1 < line.size() && line[i + 1] == '|') {
            cell += '|';
            ++i;
        } else if (line[i] == '|') {
            cells.emplace_back(trim(cell));
            cell.clear();
        } else {
            cell += line[i];
        }
    }
    cells.emplace_back(trim(cell));
    return cells;
}

bool is_separator_row(std::string_view line) {
    line = trim(line);
    if (!starts_with(line, "|")) return false;
    bool dash = false;
    for (const char c : line) {
        if (c == '-') dash = true;
        else if (c != '|' && c != ':' && c != ' ') return false;
    }
    return dash;
}

// "- x", "* x", "12. x": the item's text, nullopt for any other line.
std::optional<std::pair<bool, std::string_view>> list_item(std::string_view line) {
    const std::string_view t = trim(line);
    if (starts_with(t, "- ") || starts_with(t, "* ")) return std::pair{false, trim(t.substr(2))};
    size_t d = 0;
    while (d < t.size() && std::isdigit(static_cast<unsigned char>(t[d]))) ++d;
    if (d > 0 && d + 1 < t.size() && t[d] == '.' && t[d + 1] == ' ') return std::pair{true, trim(t.substr(d + 2))};
    return std::nullopt;
}

int heading_level(std::string_view line) {
    int n = 0;
    while (n < static_cast<int>(line.size()) && line[static_cast<size_t>(n)] == '#') ++n;
    return n >= 1 && n <= 6 && static_cast<size_t>(n) < line.size() && line[static_cast<size_t>(n)] == ' ' ? n : 0;
}

}  // namespace

std::string heading_slug(std::string_view heading) {
    std::string out;
    for (const char ch : heading) {
        const auto c = static_cast<unsigned char>(ch);
        if (std::isalnum(c) || c == '-' || c == '_') out += static_cast<char>(std::tolower(c));
        else if (c == ' ') out += '-';
        else if (c >= 0x80) out += ch;  // letters of other scripts stay, as GitHub keeps them
    }
    return out;
}

std::string markdown_to_html(std::string_view markdown, const MarkdownOptions& options, std::set<std::string>& ids) {
    std::vector<std::string_view> lines;
    for (size_t start = 0; start <= markdown.size();) {
        const size_t end = markdown.find('\n', start);
        if (end == std::string_view::npos) {
            if (start < markdown.size()) lines.push_back(markdown.substr(start));
            break;
        }
        lines.push_back(markdown.substr(start, end - start));
        start = end + 1;
    }
    auto unique_id = [&ids](const std::string& id) {
        std::string candidate = id;
        for (int n = 1; ids.count(candidate); ++n) candidate = id + "-" + std::to_string(n);
        ids.insert(candidate);
        return candidate;
    };
    auto starts_block = [](std::string_view l) {
        const std::string_view t = trim(l);
        return t.empty() || heading_level(t) > 0 || starts_with(t, "|") || starts_with(t, "```") ||
               list_item(l).has_value();
    };
    std::string html;
    size_t i = 0;
    while (i < lines.size()) {
        const std::string_view line = lines[i];
        const std::string_view t = trim(line);
        if (t.empty()) {
            ++i;
        } else if (const int level = heading_level(t)) {
            const std::string_view text = trim(t.substr(static_cast<size_t>(level)));
            const std::string lv = std::to_string(level);
            html += "<h" + lv + " id=\"" + markup_escape(unique_id(heading_slug(utf8_or_replacement(text)))) + "\">" +
                    inline_html(utf8_or_replacement(text)) + "</h" + lv + ">\n";
            ++i;
        } else if (starts_with(t, "```")) {
            html += "<pre><code>";
            for (++i; i < lines.size() && !starts_with(trim(lines[i]), "```"); ++i)
                html += markup_escape(lines[i]) + "\n";
            html += "</code></pre>\n";
            ++i;
        } else if (starts_with(t, "|") && i + 1 < lines.size() && is_separator_row(lines[i + 1])) {
            html += "<table>\n<thead><tr>";
            for (const std::string& c : table_cells(utf8_or_replacement(t))) html += "<th>" + inline_html(c) + "</th>";
            html += "</tr></thead>\n<tbody>\n";
            for (i += 2; i < lines.size() && starts_with(trim(lines[i]), "|"); ++i) {
                const auto cells = table_cells(utf8_or_replacement(lines[i]));
                std::string id;
                if (options.row_id && !cells.empty() && cells[0].size() > 2 && cells[0].front() == '`' &&
                    cells[0].back() == '`') {
                    const std::string code = cells[0].substr(1, cells[0].size() - 2);
                    id = options.row_id(code);
                    if (!id.empty() && ids.count(id)) id.clear();  // a code in two tables: the first row
                    if (!id.empty()) ids.insert(id);
                }
                html += id.empty() ? "<tr>" : "<tr id=\"" + markup_escape(id) + "\">";
                for (const std::string& c : cells) html += "<td>" + inline_html(c) + "</td>";
                html += "</tr>\n";
            }
            html += "</tbody>\n</table>\n";
        } else if (const auto first = list_item(line)) {
            const bool ordered = first->first;
            html += ordered ? "<ol>\n" : "<ul>\n";
            while (i < lines.size()) {
                const auto item = list_item(lines[i]);
                if (!item) break;
                std::string text(item->second);
                for (++i; i < lines.size() && !starts_block(lines[i]); ++i) text.append(" ").append(trim(lines[i]));
                html += "<li>" + inline_html(utf8_or_replacement(text)) + "</li>\n";
                while (i < lines.size() && trim(lines[i]).empty() && i + 1 < lines.size() &&
                       list_item(lines[i + 1]).has_value())
                    ++i;  // a blank line between items keeps one list
            }
            html += ordered ? "</ol>\n" : "</ul>\n";
        } else {
            std::string text(t);
            for (++i; i < lines.size() && !starts_block(lines[i]); ++i) text.append(" ").append(trim(lines[i]));
            html += "<p>" + inline_html(utf8_or_replacement(text)) + "</p>\n";
        }
    }
    return html;
}

}  // namespace mf::report
