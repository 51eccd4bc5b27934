// Reports of `matforge validate`: text for people, JSON (docs/validate-report.md), JUnit XML
// for CI dashboards, SARIF 2.1.0 for code-scanning tools; plus the exit code.
//
// Conventions: every writer is a pure function of the Report (byte-identical output for the
// same input: no timestamps, materials and findings in the order given, rules in catalog
// order); JSON and SARIF end with a newline.
#pragma once
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/findings.hpp"
#include "core/version.hpp"
#include "manifest/manifest.hpp"

namespace mf::validate {

// `--fail-on`: the lowest severity that fails the run ("never": findings never fail it).
enum class FailOn { info, warning, error, never };
std::optional<FailOn> fail_on_from_name(std::string_view name);  // "error"|"warning"|"info"|"never"
std::string_view fail_on_name(FailOn f);
bool fails(Severity s, FailOn f);

struct MaterialReport {
    std::string name;
    std::string source;              // as given / relative to the report's folder
    std::vector<Finding> findings;   // Finding::file is relative to `source`
    std::vector<std::string> rules;  // codes evaluated (JUnit passes); empty: the validate rules
    // What was decided, not only what is wrong: the naming family, each chosen file's role and
    // the rule that matched (with the normal map's convention verdict), and the constants
    // ingest generates for missing roles.
    std::string convention;
    std::vector<manifest::Input> inputs;
    std::vector<manifest::Constant> constants;
};

using mf::InputFailure;  // an input that could not be processed at all

struct Report {
    std::string tool_version{kVersion};
    std::vector<MaterialReport> materials;
    std::vector<InputFailure> failures;
};

struct Summary {
    int error = 0, warning = 0, info = 0;
    int failures = 0;    // inputs that could not be processed
    int incomplete = 0;  // materials with a map not read or an output not written
};

Summary summarize(const Report& r);
// Counts one material's findings into `s` (summarize's step, for other kinds of results).
void add_material(Summary& s, const std::vector<Finding>& findings);

// The run's verdict: it fails when an input could not be processed or a material is incomplete
// (whatever --fail-on says, even never), or when a finding is at or above `fail_on`. The exit
// code that says so is the CLI's (tools/matforge/command.hpp).
bool run_fails(const Summary& s, FailOn fail_on);

nlohmann::json report_json(const Report& r);  // {"report_version": 1, ...}
std::string write_json(const Report& r);
std::string write_text(const Report& r, FailOn fail_on);
std::string write_junit(const Report& r, FailOn fail_on);
std::string write_sarif(const Report& r);

}  // namespace mf::validate
