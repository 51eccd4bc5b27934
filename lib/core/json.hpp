// JSON helpers shared by the parsers (presets, rules, manifests, scenes) and the writers.
#pragma once
#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/files.hpp"

namespace mf {

// JSON text for files we write (manifest, reports): 2-space indent, trailing newline. File and
// folder names are bytes, not necessarily UTF-8; invalid sequences become U+FFFD instead of
// throwing, so one odd name never costs the whole report.
std::string json_text(const nlohmann::json& j);
// json_text(head) where head's top-level `key` is an empty array, with that array holding
// `count` elements made by element(i), each dumped alone: the same bytes as json_text of the whole
// tree, without ever holding the tree (a JSON tree is several times its text; a manifest or
// report of 10,000 sets would hold hundreds of MB).
std::string json_text_with_array(const nlohmann::json& head, const std::string& key, size_t count,
                                 const std::function<nlohmann::json(size_t)>& element);

// The streamed form, for documents too large to hold as text either (core/spool keeps the
// elements): one element of a top-level array as json_text writes it inside the document (each
// line indented 4 spaces, no comma, no final newline) ...
std::string array_element_text(const nlohmann::json& element);
// ... and a top-level array of `count` such texts, element(i, sink) handing the i-th to `sink`.
struct StreamedArray {
    std::string key;
    size_t count = 0;
    std::function<bool(size_t i, const ByteSink& sink)> element;
};
// The bytes json_text would write for `head` with each arrays[k].key (an empty top-level array of
// `head`) holding its elements, handed to `sink` in order. False when an element or the sink
// failed (the caller's element function says why).
bool write_json_text(const nlohmann::json& head, const std::vector<StreamedArray>& arrays, const ByteSink& sink);

// JSON numbers arrive as 64-bit integers or doubles, whatever a file says; narrowing one outside
// the target's range is undefined behaviour (the preset fuzzer found `"preset_version": 1e100`).
// These check the value in its JSON type first.
//   json_int:   an integer (not 2.5, not 1e100) within [lo, hi]
//   json_float: a finite number within [lo, hi], narrowed to float
std::optional<int> json_int(const nlohmann::json& v, int lo, int hi);
std::optional<float> json_float(const nlohmann::json& v, double lo, double hi);

// Every JSON document matforge reads (presets, rules, scene files, manifests, sidecars) is
// parsed here. Nesting deeper than kMaxJsonDepth is refused before a DOM is built: a document
// 100,000 levels deep would exhaust the stack of any code that walks the tree recursively, and
// no document of ours nests past a dozen levels. nullopt + `error` naming `what` (a file name)
// and the problem (not JSON, at which byte; too deep).
inline constexpr int kMaxJsonDepth = 256;
std::optional<nlohmann::json> parse_json(std::string_view text, const std::string& what, std::string& error);
// read_file (a regular file only, never a FIFO or device) + parse_json.
std::optional<nlohmann::json> read_json_file(const std::filesystem::path& file, std::string& error);
// read_json_file for documents whose top-level array `key` is too large to hold as a tree (a
// manifest of 100,000 sets): each element of it is handed to `each` as soon as it is parsed, then
// dropped; the document is returned with that array empty. `each` returns false + `error` to
// stop. Peak memory: one element's tree and the rest of the document.
std::optional<nlohmann::json> read_json_file(
    const std::filesystem::path& file, const std::string& key,
    const std::function<bool(nlohmann::json& element, std::string& error)>& each, std::string& error);

}  // namespace mf
