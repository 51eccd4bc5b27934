// Option groups shared by subcommands.
#pragma once
#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "core/findings.hpp"

namespace mf::cli {

inline void add_fail_on(CLI::App& sub, std::string& fail_on) {
    sub.add_option("--fail-on", fail_on,
                   "exit 1 when a finding has at least this severity (never: only failed inputs)")
        ->check(CLI::IsMember({"error", "warning", "info", "never"}))
        ->default_val("error")
        ->capture_default_str();
}

// Exit code for a batch: 1 when findings reach --fail-on or some inputs failed.
inline int findings_exit(std::optional<Severity> worst, const std::string& fail_on, bool any_failure) {
    if (any_failure) return 1;
    if (fail_on == "never" || !worst) return 0;
    const auto threshold = severity_from_name(fail_on);
    return threshold && *worst >= *threshold ? 1 : 0;
}

}  // namespace mf::cli
