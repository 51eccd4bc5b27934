// What a preset needs that a set lacks: constants and MISSING_MAP findings (ingest and validate).
#pragma once
#include <nlohmann/json.hpp>
#include <set>
#include <vector>

#include "core/findings.hpp"
#include "pack/preset.hpp"

namespace mf {

// `available`: output roles the set provides (after unpacking). `written_roles`: roles read by
// the outputs that will be written. Fills `constants` (role -> value generated for an output)
// and returns one MISSING_MAP per role the preset lists in missing_severity.
std::vector<Finding> missing_map_findings(const Preset& preset, const std::set<Role>& available,
                                          const std::set<Role>& written_roles, nlohmann::json& constants);

// The roles read by the outputs a set with `available` roles gets.
std::set<Role> written_roles(const Preset& preset, const std::set<Role>& available);

}  // namespace mf
