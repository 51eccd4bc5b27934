// The verdict of a run over its findings: `--fail-on`, the counts by severity, and whether the
// run fails (the exit code that says so is the CLI's, tools/matforge/command.hpp). The reports
// that show the findings are lib/report's (report/formats.hpp).
#pragma once
#include <optional>
#include <string_view>
#include <vector>

#include "findings/findings.hpp"
#include "manifest/manifest.hpp"

namespace mf::validate {

// `--fail-on`: the lowest severity that fails the run ("never": findings never fail it).
enum class FailOn { info, warning, error, never };
std::optional<FailOn> fail_on_from_name(std::string_view name);  // "error"|"warning"|"info"|"never"
std::string_view fail_on_name(FailOn f);
bool fails(Severity s, FailOn f);

struct Summary {
    int error = 0, warning = 0, info = 0;
    int failures = 0;    // inputs that could not be processed
    int incomplete = 0;  // materials with a map not read or an output not written
};

// The counts of a run's materials and failures.
Summary summarize(const manifest::Manifest& m);
// Counts one material's findings into `s` (summarize's step, for other kinds of results).
void add_material(Summary& s, const std::vector<Finding>& findings);

// The run's verdict: it fails when an input could not be processed or a material is incomplete
// (whatever --fail-on says, even never), or when a finding is at or above `fail_on`.
bool run_fails(const Summary& s, FailOn fail_on);

}  // namespace mf::validate
