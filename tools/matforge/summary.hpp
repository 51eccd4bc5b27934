// What a batch tells its user on the terminal: each set's state in the progress line and the
// sets that need attention, by name (ingest; validate's text report does the same).
#pragma once
#include <string>

#include "command.hpp"
#include "manifest/manifest.hpp"
#include "process/ingest.hpp"
#include "validate/report.hpp"

namespace mf::cli {

// "failed", "partial", "errors", "warnings" or "ok": a set with findings to act on never says ok.
inline std::string set_status(const MaterialResult& r) {
    if (r.failure) return "failed";
    if (r.entry.status == manifest::Status::partial) return "partial";
    const auto w = worst(r.entry.findings);
    if (w == Severity::error) return "errors";
    if (w == Severity::warning) return "warnings";
    return "ok";
}

// validate::summarize's counts, for a manifest.
inline validate::Summary summarize(const manifest::Manifest& m) {
    validate::Summary s;
    for (const auto& mat : m.materials) validate::add_material(s, mat.findings);
    s.failures = static_cast<int>(m.failures.size());
    return s;
}

// "sets with errors: A, B" and "sets with warnings: C" (at most 20 names each).
inline void print_attention(std::string_view command, const manifest::Manifest& m) {
    for (const Severity level : {Severity::error, Severity::warning}) {
        std::string names;
        size_t n = 0;
        for (const auto& mat : m.materials) {
            if (worst(mat.findings) != level) continue;
            if (n++ < 20) names += (names.empty() ? "" : ", ") + mat.name;
        }
        if (n == 0) continue;
        if (n > 20) names += ", … (" + std::to_string(n - 20) + " more)";
        say(command, std::string("sets with ") + (level == Severity::error ? "errors" : "warnings") + ": " + names);
    }
}

}  // namespace mf::cli
