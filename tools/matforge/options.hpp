// Option groups shared by subcommands.
#pragma once
#include <CLI/CLI.hpp>
#include <string>

#include "validate/report.hpp"

namespace mf::cli {

inline void add_fail_on(CLI::App& sub, std::string& fail_on) {
    sub.add_option("--fail-on", fail_on,
                   "exit 1 when a finding has at least this severity (never: findings never fail the run; "
                   "an input or output that could not be read or written still does)")
        ->check(CLI::IsMember({"error", "warning", "info", "never"}))
        ->default_val("error")
        ->capture_default_str();
}

inline validate::FailOn fail_on_of(const std::string& name) {
    return validate::fail_on_from_name(name).value_or(validate::FailOn::error);
}

}  // namespace mf::cli
