// A run's findings as reports for people and CI, written from the manifest's materials — the
// same writers for `matforge validate` (its Manifest, outputs empty) and `matforge ingest`
// (the manifest it wrote): text for people, JSON (docs/validate-report.md), JUnit XML for CI
// dashboards, SARIF 2.1.0 for code-scanning tools. The HTML page is report/report.hpp's.
//
// Conventions (decided once here):
//  - every writer is a pure function of the manifest (byte-identical output for the same input:
//    no timestamps, materials and findings in the order given, rules in catalog order); JSON and
//    SARIF end with a newline;
//  - a finding's file is shown as the material's source joined with Finding::file, as the paths
//    stand in the manifest given (a caller rebases the sources to where the reader stands:
//    rebase_sources);
//  - a report states what the manifest records (the normal map's verdict, the constants) and
//    never infers a fact from whether a finding is present.
#pragma once
#include <filesystem>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "manifest/manifest.hpp"
#include "validate/verdict.hpp"

namespace mf::report {

// The findings report formats, by their `--report` names.
enum class Format { text, json, junit, sarif };
std::optional<Format> format_from_name(std::string_view name);  // "text" | "json" | "junit" | "sarif"

nlohmann::json report_json(const manifest::Manifest& r);  // {"report_version": 1, ...}
std::string write_json(const manifest::Manifest& r);
std::string write_text(const manifest::Manifest& r, validate::FailOn fail_on);
// What a terminal shows of a run (issue 45: 287 lines for 10 warnings hid them): each material
// with an error or warning and those findings, the inputs that failed, how many materials and
// info findings are left out, and the verdict line write_text ends with. Never empty.
std::string write_terminal_summary(const manifest::Manifest& r, validate::FailOn fail_on);
std::string write_junit(const manifest::Manifest& r, validate::FailOn fail_on);
std::string write_sarif(const manifest::Manifest& r);
// One of the above by format (text as written: the caller makes it terminal-safe).
std::string write_findings(const manifest::Manifest& m, Format format, validate::FailOn fail_on);

// The manifest's material sources (relative to `manifest_dir`) as paths from where the reader
// stands: manifest_dir / source, lexically normal (relative when manifest_dir is); the
// failures' sources too.
void rebase_sources(manifest::Manifest& m, const std::filesystem::path& manifest_dir);

}  // namespace mf::report
