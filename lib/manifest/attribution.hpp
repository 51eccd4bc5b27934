// ATTRIBUTION.md: every material of an output folder with its source and licence, as its
// manifest entry's `provenance` says (material/provenance.hpp), for shipping beside the
// textures. Written by ingest (and merge) into the output folder with the library files
// (process/material_file.hpp write_library), listed in the manifest's `library`.
#pragma once
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "core/files.hpp"
#include "manifest/manifest.hpp"
#include "manifest/spool.hpp"

namespace mf::manifest {

inline constexpr std::string_view kAttributionFile = "ATTRIBUTION.md";

// The file's text, one table row per material in the order `each` visits them (name order), a
// count per licence last. `materials(visit)` calls visit on every material and returns false
// when it could not (then so does this). Deterministic: the same materials give the same bytes.
using MaterialVisitor = std::function<bool(const std::function<bool(const Material&)>& visit)>;
bool attribution_text(const MaterialVisitor& materials, const ByteSink& sink);
// The same for the spooled materials of a run (after sort()), read back one at a time.
bool attribution_text(const MaterialSpool& spool, const ByteSink& sink, std::string& error);
std::string attribution_text(const std::vector<Material>& materials);

}  // namespace mf::manifest
