// JSON helpers shared by the parsers (presets, rules, manifests, scenes) and the writers.
#pragma once
#include <nlohmann/json.hpp>

#include <optional>
#include <string>

namespace mf {

// JSON text for files we write (manifest, reports): 2-space indent, trailing newline. File and
// folder names are bytes, not necessarily UTF-8; invalid sequences become U+FFFD instead of
// throwing, so one odd name never costs the whole report.
std::string json_text(const nlohmann::json& j);

// JSON numbers arrive as 64-bit integers or doubles, whatever a file says; narrowing one outside
// the target's range is undefined behaviour (the preset fuzzer found `"preset_version": 1e100`).
// These check the value in its JSON type first.
//   json_int:   an integer (not 2.5, not 1e100) within [lo, hi]
//   json_float: a finite number within [lo, hi], narrowed to float
std::optional<int> json_int(const nlohmann::json& v, int lo, int hi);
std::optional<float> json_float(const nlohmann::json& v, double lo, double hi);

}  // namespace mf
