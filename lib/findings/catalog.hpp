// The finding catalog: every code any stage raises, with its default severity, a title, the
// stage that raises it and its anchor in docs/rules.md — decided here once. A finding is made
// with finding(), which takes its severity from here; the rules configuration
// (findings/rules.hpp: a preset's "validate" block, --rules FILE) then changes severities,
// switches codes off and suppresses them. tests/findings/catalog_test.cpp ties every code constant
// (findings/findings.hpp), this catalog and docs/interface.md's "Finding codes" table together.
#pragma once
#include <string_view>
#include <vector>

#include "findings/findings.hpp"

namespace mf {

struct CodeInfo {
    std::string_view code;
    Severity severity;       // default severity
    std::string_view title;  // one line: SARIF shortDescription, JUnit text, rules.html
    // What raises it (docs/interface.md "Finding codes", column "raised by"): "finding sets"
    // (lib/sets), "discovery" (lib/material: names to roles), "decoding" (reading a map),
    // "rules" (lib/validate), "planning" (lib/plan: routes, sizes, conversions),
    // "encoding" (lib/texture), "writing" (ingest's outputs); two joined by ", ".
    std::string_view stage;
    std::string_view anchor;  // section of docs/rules.md (rules.html's row id)
};

// Every code, in a fixed order: the rules' codes first, in the order findings are sorted by.
const std::vector<CodeInfo>& finding_catalog();
const CodeInfo* find_code(std::string_view code);

// A finding of `code` at its catalog severity: the one way to make one. A code not in the
// catalog throws std::logic_error (a reader could not describe it).
Finding finding(std::string_view code, std::string role, std::string file, std::string message, Figures figures = {});

}  // namespace mf
