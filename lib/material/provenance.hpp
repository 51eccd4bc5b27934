// Where a material comes from and under what licence: the vendor and its asset id, the licence
// and how it was known, the credit a licence asks for, and the asset's page where the vendor's
// URL scheme makes it certain. The one owner of the vendor and licence tables (docs/provenance.md
// cites the public page behind each fact). Pure over names and texts: plan/plan.cpp reads the
// set's licence files and sidecars and hands their text here.
//
// How the licence is known, first that applies:
//  1. a licence or readme file in the download (is_licence_file_name) naming one licence;
//  2. a sidecar member stating one (glTF asset.extras.license or asset.copyright, a Megascans
//     JSON's "license");
//  3. the vendor, when the set's names (or its Megascans JSON) are certainly that vendor's and
//     the vendor publishes every asset under one licence (vendor_table).
// Files naming several licences leave it unknown: which covers the maps is not said.
#pragma once
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "material/discovery.hpp"

namespace mf {

// A licence matforge can name.
struct LicenceInfo {
    std::string_view spdx;  // SPDX id; empty for a vendor's own licence and "CC BY" without a version
    std::string_view name;  // readable
    std::string_view url;   // its text
    bool attribution;       // its terms ask for credit (the CC BY family; MIT's notice)
    // A vendor's own royalty-free licence: use in your own work, no redistribution of the files.
    bool vendor_licence;
};
// Every licence matforge names: CC0 1.0; CC BY, BY-SA, BY-NC, BY-ND, BY-NC-SA, BY-NC-ND 3.0
// and 4.0; CC BY with no version stated; MIT; the vendors' own (Poliigon, Fab).
const std::vector<LicenceInfo>& licence_table();
const LicenceInfo* licence_by_spdx(std::string_view spdx);  // any case; nullptr when unknown

// A licence a text names, and where it first does (byte offset).
struct LicenceMention {
    const LicenceInfo* licence = nullptr;
    size_t at = 0;
};
// Every licence `text` names, each once, in order of first mention: an SPDX-License-Identifier;
// "CC0", "CC-0", "CC Zero", "Creative Commons Zero", creativecommons.org/publicdomain/zero/1.0;
// "CC BY[-SA][-NC][-ND] <version>", "Creative Commons Attribution[-ShareAlike]… <version>" and
// creativecommons.org/licenses/by[-sa…]/<version> for 3.0 and 4.0 ("CC BY" alone: the
// version-less entry); "MIT License". A licence's text without its name is not recognised.
std::vector<LicenceMention> licences_named(std::string_view text);

// A licence or readme file a download may carry: LICENSE*, LICENCE*, COPYING*, README*,
// CREDITS*, ATTRIBUTION* (any case) with no extension or .txt / .md. Read for the set's
// provenance, never a map (discover_set does not report them).
bool is_licence_file_name(std::string_view filename);
// How much of such a file is read: a licence says so in its first lines.
inline constexpr size_t kLicenceFileMaxBytes = size_t{64} << 10;

// A vendor matforge recognises and what it publishes its assets under.
struct VendorInfo {
    std::string_view id;          // the manifest's provenance.vendor
    std::string_view name;        // as the vendor writes it
    std::string_view licence;     // licence_table's spdx, or the name of the vendor's own
    std::string_view url_prefix;  // the asset page is url_prefix + asset id; "" where no scheme is certain
    std::string_view naming;      // how its downloads are named (the evidence's words)
};
// ambientcg, polyhaven, 3dtextures, poliigon, megascans.
const std::vector<VendorInfo>& vendor_table();

struct Provenance {
    struct Evidence {
        std::string how;     // "vendor" | "file" | "sidecar"
        std::string file;    // the map whose name showed the vendor, the licence file, the sidecar
        std::string field;   // sidecar: the member that states it
        std::string detail;  // one sentence
        bool operator==(const Evidence&) const = default;
    };
    struct Licence {
        std::string spdx;  // empty for a vendor's own licence
        std::string name, url;
        bool attribution_required = false;
        bool vendor_licence = false;
        Evidence evidence;
        bool operator==(const Licence&) const = default;
    };
    std::string vendor;         // vendor_table's id; "" when no vendor is certain
    std::string vendor_name;    // its name
    std::string asset_id;       // the vendor's id of the asset, where the names or a sidecar carry it
    std::string asset_id_from;  // "name" | "sidecar"
    std::optional<Licence> licence;
    std::string attribution;  // the credit to give, only where the licence asks for it
    std::string url;          // the asset's page, only where the vendor's URL scheme makes it certain
    bool empty() const { return vendor.empty() && asset_id.empty() && !licence; }
    bool operator==(const Provenance&) const = default;
};

// A text file of the set, as plan read it (at most kLicenceFileMaxBytes).
struct SetText {
    std::string file;   // relative to the set's root, as in discover_set's files
    std::string text;   // empty when it could not be read
    std::string error;  // why not
};

struct ProvenanceInput {
    const std::vector<std::string>& files;  // the set's files, as given to discover_set
    const SetDiscovery& discovery;
    const std::vector<SidecarRoles>& sidecars;
    const std::vector<SetText>& licence_files;  // the set's is_licence_file_name files, read
    bool shared_folder = false;                 // ChoicePolicy::shared_folder
};

struct ProvenanceResult {
    Provenance provenance;
    // Without a licence: why none was found (LICENCE_UNKNOWN's message), the file it is about
    // ("" none) and the figures behind it.
    std::string unknown;
    std::string unknown_file;
    Figures figures;
};
ProvenanceResult find_provenance(const ProvenanceInput& in);

}  // namespace mf
