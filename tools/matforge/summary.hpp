// What a batch tells its user on the terminal: each set's state in the progress line and the
// sets that need attention, by name (ingest; validate's text report does the same).
#pragma once
#include <string>

#include "command.hpp"
#include "manifest/manifest.hpp"
#include "process/ingest.hpp"
#include "validate/verdict.hpp"

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

// validate::summarize's counts, for an ingest run.
inline validate::Summary summarize(const IngestResult& r) {
    validate::Summary s;
    for (const auto& m : r.materials) {
        s.error += m.findings.error;
        s.warning += m.findings.warning;
        s.info += m.findings.info;
        s.incomplete += m.findings.incomplete;
    }
    s.failures = static_cast<int>(r.manifest.failures.size());
    return s;
}

// "sets with errors: A, B" and "sets with warnings: C" (at most 20 names each, by name).
inline void print_attention(std::string_view command, const IngestResult& r) {
    for (const Severity level : {Severity::error, Severity::warning}) {
        std::string names;
        size_t n = 0;
        for (const auto& m : r.materials) {
            const Severity worst = m.findings.error > 0     ? Severity::error
                                   : m.findings.warning > 0 ? Severity::warning
                                                            : Severity::info;
            if (worst != level) continue;
            if (n++ < 20) names += (names.empty() ? "" : ", ") + m.name;
        }
        if (n == 0) continue;
        if (n > 20) names += ", … (" + std::to_string(n - 20) + " more)";
        say(command, std::string("sets with ") + (level == Severity::error ? "errors" : "warnings") + ": " + names);
    }
}

}  // namespace mf::cli
