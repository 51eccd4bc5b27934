// Writing one set: bakes the resolutions it uses, writes its maps, clutter and sidecars into
// its folder, or into a staging folder zipped into its .zip.
#pragma once

#include <filesystem>
#include <string>

#include "sets.hpp"

namespace gen {

// Replaces <out>/<set.root> (a folder or a .zip) with the set's files.
bool generate_set(const std::filesystem::path& out, const SetDef& set, std::string& err);

}  // namespace gen
