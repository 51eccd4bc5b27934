// The text files: the sidecars vendors ship beside the maps (clutter a discoverer must skip)
// and the README.md describing the generated sets.
#pragma once

#include <string>
#include <vector>

#include "sets.hpp"

namespace gen {

std::string text_content(const SetDef& set, Text kind);

// README.md of the output folder: what each generated set is and exercises, file by file.
std::string readme(const std::vector<SetDef>& sets);

}  // namespace gen
