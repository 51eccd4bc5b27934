// HTML text for the report: escaping, and the small Markdown subset docs/rules.md is written in.
//
// Conventions of this module (decided once here):
//  - every text that reaches the page goes through mf::markup_escape() (core/text.hpp): names
//    come from the file system as bytes; every link path through mf::percent_encode_path();
//  - the page loads nothing from the network: no external script, style, font or image.
#pragma once
#include <set>
#include <string>
#include <string_view>

namespace mf::report {

// The anchor GitHub gives a Markdown heading: lower case, letters/digits/'-'/'_' kept, spaces
// to '-', everything else dropped ("Normal convention (GL vs DX)" -> "normal-convention-gl-vs-dx").
std::string heading_slug(std::string_view heading);

// The Markdown of docs/rules.md as HTML (the body only): ATX headings (with heading_slug() ids),
// pipe tables, lists, fenced code blocks, paragraphs; inline `code`, **bold**, *italic* and
// [links](url). A table row whose first cell is a `CODE` that `row_ids` knows gets
// id = row_id(CODE). Links to rules.md#x become #x; links to other .md files, which do not
// travel with the report, keep their text only. `ids` receives every id written.
struct MarkdownOptions {
    // code -> the id of its table row (empty: none)
    std::string (*row_id)(std::string_view code) = nullptr;
};
std::string markdown_to_html(std::string_view markdown, const MarkdownOptions& options, std::set<std::string>& ids);

}  // namespace mf::report
