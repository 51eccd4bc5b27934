// Option groups shared by subcommands.
#pragma once
#include <CLI/CLI.hpp>
#include <cstdlib>
#include <filesystem>
#include <optional>
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

// The ingest cache's folder: `given` (--cache), else $MATFORGE_CACHE (one shared by runs,
// shards, machines), else $XDG_CACHE_HOME/matforge, else ~/.cache/matforge (where ccache and
// pip keep theirs: outside the output folder, which holds only what the manifest lists).
// nullopt when none can be named (no HOME).
inline std::optional<std::filesystem::path> cache_folder(const std::string& given) {
    if (!given.empty()) return std::filesystem::path(given);
    auto env = [](const char* name) -> std::string {
        const char* v = std::getenv(name);
        return v ? v : "";
    };
    if (const std::string c = env("MATFORGE_CACHE"); !c.empty()) return std::filesystem::path(c);
    if (const std::string x = env("XDG_CACHE_HOME"); !x.empty()) return std::filesystem::path(x) / "matforge";
    if (const std::string h = env("HOME"); !h.empty()) return std::filesystem::path(h) / ".cache" / "matforge";
    return std::nullopt;
}

inline validate::FailOn fail_on_of(const std::string& name) {
    return validate::fail_on_from_name(name).value_or(validate::FailOn::error);
}

}  // namespace mf::cli
