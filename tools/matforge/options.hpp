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
// shards, machines), else `.<out>.matforge-cache` beside the output folder `out`: on the same
// file system (blobs are hard links to the outputs, no second copy), outside the output folder
// (which holds only what the manifest lists), and hidden, so a walk of an input folder that
// holds the output skips it. nullopt when `out` is empty (the cache command without --cache).
inline std::optional<std::filesystem::path> cache_folder(const std::string& given,
                                                         const std::filesystem::path& out = {}) {
    if (!given.empty()) return std::filesystem::path(given);
    if (const char* c = std::getenv("MATFORGE_CACHE"); c && *c) return std::filesystem::path(c);
    if (out.empty()) return std::nullopt;
    std::filesystem::path o = std::filesystem::absolute(out).lexically_normal();
    if (!o.has_filename()) o = o.parent_path();  // "out/" names the folder out
    return o.parent_path() / ("." + o.filename().string() + ".matforge-cache");
}

inline validate::FailOn fail_on_of(const std::string& name) {
    return validate::fail_on_from_name(name).value_or(validate::FailOn::error);
}

}  // namespace mf::cli
