// What a preset needs that a set lacks: the constants generated for it and the MISSING_MAP
// findings (called once per set, by plan_set).
#pragma once
#include <set>
#include <vector>

#include "findings/findings.hpp"
#include "manifest/manifest.hpp"
#include "preset/preset.hpp"

namespace mf {

// `available`: output roles the set provides (its routes). `written_roles`: roles read by the
// outputs that will be written. Appends to `constants` (in role order) the value generated for
// each missing role an output needs, and returns one MISSING_MAP per missing role the preset
// lists in missing_severity. `generated`: the words say what ingest did ("generated constant
// 0"); false (validate, which writes nothing): what ingest would generate.
std::vector<Finding> missing_map_findings(const Preset& preset, const std::set<Role>& available,
                                          const std::set<Role>& written_roles,
                                          std::vector<manifest::Constant>& constants, bool generated);

// The roles read by the outputs a set with `available` roles gets.
std::set<Role> written_roles(const Preset& preset, const std::set<Role>& available);

}  // namespace mf
