// Discovery: from file names to roles. Pure functions over names (and optional header facts),
// so every family's table is testable without images.
//
// Conventions of this module:
//  - Names are matched case-insensitively after splitting the stem on '_', '-', '.', ' ' and
//    on lower→upper camel-case boundaries (so "baseColor" and "base_color" both give the
//    tokens "base","color"; "NormalGL" gives "normal","gl").
//  - Resolution tags (1k 2k 4k 8k 16k, 512 1024 2048 4096 8192, 2048px, …) and format tags
//    (png jpg jpeg exr tif tiff tga 8bit 16bit 16 32 hdr …) are ignored for the role but kept
//    as hints (resolution_hint).
//  - The role tag is the match ending nearest the end of the name; on a tie the longer match
//    wins, then a family rule over the generic one ("metal_plate_diff_1k": diff, not metal).
#pragma once
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/findings.hpp"
#include "material/roles.hpp"

namespace mf {

// Naming conventions a set can follow (shared/spec/interface.md "convention").
// "ambientcg" "polyhaven" "texturescom" "megascans" "substance" "gltf" "generic"
struct NameMatch {
    Role role = Role::albedo;
    std::string family;  // the convention whose rule matched
    std::string rule;    // human-readable rule id, e.g. "ambientcg:_NormalGL"
    NormalConvention normal = NormalConvention::unknown;  // what the name says, if anything
};

// True for extensions OpenImageIO reads that matforge treats as maps
// (png jpg jpeg tga tif tiff exr hdr webp bmp dds psd).
bool is_image_file(std::string_view filename);

// Previews, thumbnails, ID masks, renders, swatches: images that are never maps.
bool is_clutter(std::string_view filename);

// The role a file name states, or nullopt (clutter, non-image, no role tag).
std::optional<NameMatch> classify_name(std::string_view filename);

// The material name part of a file name: the tokens before the role tag, with resolution and
// format tags removed, joined by '_' in their original case ("Bricks059_1K-PNG_Color.png" →
// "Bricks059"). Empty when the name is only a role tag ("albedo.png").
std::string material_stem(std::string_view filename);

// Pixel size a name claims ("_2K" → 2048, "_1024" → 1024), 0 when none.
int resolution_hint(std::string_view filename);

// Header facts used to rank candidates; all zero when unknown.
struct HeaderInfo {
    int width = 0, height = 0, channels = 0, bit_depth = 0;
    bool is_float = false;
};

struct Candidate {
    std::string file;  // path relative to the set's root, '/'-separated
    NameMatch match;
    HeaderInfo header;
};

// The map chosen for one input role.
struct RoleChoice {
    Role role;
    Candidate chosen;
    std::vector<Candidate> rejected;  // other candidates for the same role, best first
};

// Where an output role's values come from.
struct RoleSource {
    Role role;          // output role (albedo … opacity) or translucency
    std::string file;   // chosen input file
    Role from;          // the input role of that file (e.g. orm, gloss, roughness)
    int channel = -1;   // -1: the whole map; 0/1/2: the R/G/B channel of a packed input
    bool invert = false;  // gloss → roughness
};

// Where an output role may come from, best first: a dedicated map, then packed inputs (orm,
// metallic_roughness, ort), then gloss (inverted) for roughness. discover_set applies it to the
// chosen files; ingest applies it again over the files that actually decoded.
struct Provider {
    Role from = Role::albedo;
    int channel = -1;  // -1: the whole map; 0/1/2: R/G/B of a packed input
    bool invert = false;
};
std::vector<Provider> providers_of(Role out);

struct ChoicePolicy {
    NormalConvention preferred_normal = NormalConvention::gl;  // the preset's convention
    int max_size = 0;  // preset size limit; 0 = none
};

struct SetDiscovery {
    std::string convention;            // the family most maps follow ("generic" when mixed/none)
    std::vector<RoleChoice> choices;   // one per input role present, in Role order
    std::vector<RoleSource> sources;   // one per output role that has a source, in Role order
    std::vector<Finding> findings;     // AMBIGUOUS_MAP, UNRECOGNIZED_FILE (info)
};

// Classify the files of one set, choose one file per input role deterministically, and resolve
// which file feeds each output role. Ranking: for normals, the policy's convention first, then
// any known convention, then unknown; then the largest size within max_size (from the header,
// else the name's hint); then lossless over lossy (exr tif png tga bmp webp jpg); then higher
// bit depth; then byte-wise name order. A dedicated map beats a packed one for the same role;
// roughness beats gloss. Every choice among several candidates gets one AMBIGUOUS_MAP (info)
// per role naming all candidates, the chosen one and why. `header` may return nullopt.
SetDiscovery discover_set(const std::vector<std::string>& files,
                          const std::function<std::optional<HeaderInfo>(const std::string&)>& header,
                          const ChoicePolicy& policy);

// Split one folder's files into material groups by material_stem (case-insensitive). Files
// with no stem, clutter and unrecognized files join the group whose stem is the longest prefix
// of their own name, else the first group. Groups are returned sorted by stem; `name` is the
// stem in its first-seen original case, or `fallback_name` for the empty stem.
struct FileGroup {
    std::string name;
    std::vector<std::string> files;
};
std::vector<FileGroup> group_files(const std::vector<std::string>& files,
                                   const std::string& fallback_name);

}  // namespace mf
