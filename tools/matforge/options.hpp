// Option groups shared by subcommands.
#pragma once
#include <CLI/CLI.hpp>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

#include "validate/verdict.hpp"

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
// shards, machines), else the user's cache folder, $XDG_CACHE_HOME/matforge or
// ~/.cache/matforge (the XDG base directory convention): never inside the repository or an
// input tree unless asked. nullopt when none can be named (no $HOME): the run has no cache.
inline std::optional<std::filesystem::path> cache_folder(const std::string& given) {
    if (!given.empty()) return std::filesystem::path(given);
    if (const char* c = std::getenv("MATFORGE_CACHE"); c && *c) return std::filesystem::path(c);
    // The specification: a relative $XDG_CACHE_HOME is invalid and is ignored.
    if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x == '/') return std::filesystem::path(x) / "matforge";
    if (const char* h = std::getenv("HOME"); h && *h == '/') return std::filesystem::path(h) / ".cache" / "matforge";
    return std::nullopt;
}

inline validate::FailOn fail_on_of(const std::string& name) {
    return validate::fail_on_from_name(name).value_or(validate::FailOn::error);
}

}  // namespace mf::cli
