// Text helpers for names that come from the file system: bytes, not necessarily UTF-8.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "base/ascii.hpp"  // ascii_lower, for every user of these helpers

namespace mf {

// `s` with every ill-formed UTF-8 sequence replaced by U+FFFD (one per maximal invalid
// subpart, Unicode 15 §3.9 "U+FFFD Substitution of Maximal Subparts"); valid text is unchanged.
// XML and JSON writers call it so a Latin-1 file name cannot make the whole report unreadable.
std::string utf8_or_replacement(std::string_view s);

// A relative path as a URI reference (RFC 3986): unreserved characters and '/' kept, every
// other byte percent-encoded (upper-case hex). glTF's image URIs and the report's links use it,
// so a name with spaces, '#', '%' or non-ASCII bytes resolves to the file on disk.
std::string percent_encode_path(std::string_view path);

// Lower case for comparing names as people write them: ASCII, and in UTF-8 the capitals of
// Latin-1 (À–Þ), Latin Extended-A (Ā–ž, Ÿ), Greek (Α–Ω) and Cyrillic (Ѐ–Я) to their small
// letters ("BRÏCK" and "Brïck" fold alike). Other bytes, and invalid UTF-8, are kept as they
// are. Simple one-to-one mappings only (no ß → ss): a name never grows or shrinks.
std::string fold_case(std::string_view s);

// The candidate closest to `word` (Levenshtein distance, case-insensitive) when it is close
// enough to be a typo of it (at most a third of its letters, at least one), else "": "did you
// mean" in usage errors (commands, options, presets).
std::string nearest(const std::string& word, const std::vector<std::string>& candidates);

// `s` for HTML and XML, in element text and in double- or single-quoted attribute values (the
// report page, JUnit): ill-formed UTF-8 and the C0 controls other than tab, LF and CR (XML 1.0
// §2.2 forbids them even escaped; HTML calls them parse errors) as U+FFFD, and & < > " ' as
// references (&#39;, which HTML 4 and XML both read, for ').
std::string markup_escape(std::string_view raw);

// `s` for a terminal: every control character (C0, DEL, C1 as UTF-8) written as \xNN, so a file
// name holding ESC or BEL cannot clear the screen or retitle the terminal. Printable text and
// valid UTF-8 are unchanged; a newline stays a newline only when `keep_newlines`.
std::string terminal_safe(std::string_view s, bool keep_newlines = false);

// Numbers in messages and reports: `v` with `digits` decimals ("%.*f"), and a share in [0, 1] as
// a percentage with one decimal ("12.3 %"). One spelling for every finding and page.
std::string fixed(double v, int digits);
std::string percent(double share);

}  // namespace mf
