// ATTRIBUTION.md: every material of an output folder with its source and licence, as its
// manifest entry's `provenance` says (material/provenance.hpp), for shipping beside the
// textures. Written by ingest (and merge) into the output folder with the library files
// (process/material_file.hpp write_library), listed in the manifest's `library`.
#pragma once
#include <functional>
#include <optional>
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

// What a vendor's own licence forbids, as ATTRIBUTION.md's licence column and the credit say it.
inline constexpr std::string_view kVendorLicenceTerms = "the vendor's licence: no redistribution of the files";

// A material's credit, for the material files an engine or DCC opens (glTF `asset.copyright`,
// the USD layer's `customLayerData`, the MaterialX material's `doc`): the facts of its
// ATTRIBUTION.md row, from its provenance, each one line of valid UTF-8. nullopt when the
// licence is unknown: a file without a known licence claims none.
struct Credit {
    // Who to credit: the attribution where the licence asks for one (the holder, the licence
    // and its address), else the vendor's name; "" when neither is known.
    std::string author;
    // The licence: "<name> (<SPDX id>, <url>)", a vendor's own licence with its terms after it.
    std::string licence;
    // Where the material comes from: "<vendor> asset <id> (<asset page>)", as far as known; "".
    std::string source;
    std::string url;  // the asset's page, where the vendor's URL scheme makes it certain; ""
    // All of it in one line: the source, then the attribution where the licence asks for one,
    // else "licensed under " and the licence.
    std::string line;
};
std::optional<Credit> material_credit(const Provenance& p);

}  // namespace mf::manifest
