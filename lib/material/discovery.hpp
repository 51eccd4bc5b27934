// Discovery: from file names (and, when present, a set's glTF or Megascans JSON sidecar) to
// roles. Pure functions over names, header facts and sidecar text, so every rule is testable
// without images or a file system.
//
// Conventions of this module (implementation by job: tokens.cpp the tokenizer, families.cpp the
// rule tables, classify.cpp clutter and role tags, choose.cpp ranking and discover_set,
// group.cpp group_files, sidecar.cpp glTF / Megascans JSON):
//  - Tokens: a name's stem splits on '_' '-' '.' ' ', on the UTF-8 en dash, em dash, middle dot
//    and no-break space, and on lower→upper camel-case boundaries ("baseColor" and "base_color"
//    give "base","color"; "NormalGL" gives "normal","gl"). Matching is case-insensitive unless a
//    family's rule asks for a case (ambientCG "_Color", Textures.com "_COL").
//  - Tags: a resolution tag (1k…64k, 2048px, 4096x4096, a bare power of two 256…16384) or a
//    format tag (png jpg jpeg exr tif tiff tga hdr bmp webp psd dds 8bit 16bit 32bit 8b 16b 32b)
//    is ignored for the role and the material name but kept as a hint (resolution_hint, bit
//    depth). A piece of a camel-case word is never a tag ("TgaRle" is a name, not tga + "Rle").
//    A bare 16 or 32 is a bit-depth tag only after the role tag ("Rock_Height_16"); before it, it
//    belongs to the material's name ("Metal_16_Color" is the material "Metal_16", apart from
//    "Metal_32_Color"). Any other number ("001", "059", "600") is a word: part of the name when
//    it stands before the role tag.
//  - Role tag: the match ending nearest the end of the name; on a tie the longer match wins, then
//    a family rule over the generic one ("metal_plate_diff_1k": diff, not metal). Short tags
//    count only where a word would not stand: game pipelines' two-letter tags (BC NM NO RO MT
//    EM OP) and Unreal's letters ("T_Rock_D", with the T prefix) only as the last word; "Lights"
//    only glued to the name ("LampLights"). A capitalised tag may carry a lower-case variant
//    letter ("Rock_DISPa" is DISP).
//  - Clutter (never a map, reported as UNRECOGNIZED_FILE info with its kind): previews,
//    thumbnails, swatches, icons, renders ("Material_1639": a 3dtextures.me preview), ID and other
//    masks with no PBR role ("_mask", "_IdMap"), all-black placeholders ("_black"), and Megascans
//    billboard maps (a plant's far-LOD impostor, "Billboard" anywhere in the name). The set's
//    own preview among them is its `preview` instead (SetDiscovery::preview).
//  - Licence and readme files (provenance.hpp is_licence_file_name) are no maps and not reported:
//    they are read for the set's provenance.
//  - Sidecars (optional): a role a glTF material or a Megascans JSON states for a file beats the
//    name's; the Megascans JSON beats a glTF. Where the name agrees on the role, what else it
//    states is kept (opacity in A, a GL/DX tag the sidecar leaves open). Billboard names stay
//    clutter whatever a sidecar says.
#pragma once
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "findings/findings.hpp"
#include "material/roles.hpp"

namespace mf {

// Naming conventions a set can follow (docs/interface.md "Words": convention).
// "ambientcg" "polyhaven" "texturescom" "megascans" "substance" "gltf" "unreal" "generic"
struct NameMatch {
    Role role = Role::albedo;
    std::string family;                                   // the convention whose rule matched
    std::string rule;                                     // human-readable rule id, e.g. "ambientcg:_NormalGL"
    NormalConvention normal = NormalConvention::unknown;  // what the name says, if anything
    // The map's alpha channel is opacity: Megascans "_B-O" (base color + opacity), a glTF
    // baseColorTexture of a material with alphaMode MASK or BLEND.
    bool opacity_in_alpha = false;
    // Output roles this map must not feed although its role holds them: a glTF
    // metallicRoughnessTexture whose material has metallicFactor 0 (metalness; roughnessFactor 0:
    // roughness), an emissiveTexture whose emissiveFactor is 0 (emissive). Sorted, in Role order.
    std::vector<Role> unused;
    std::string sidecar;  // the sidecar file that stated the role; empty when the name did
    // A normal map's space as its name states it ("_nm_tangent", "_normal_os"): an object-space
    // map is never the material's (tangent-space) normal map.
    NormalSpace space = NormalSpace::unknown;
    // The convention the set's engine family implies where the name states none (Unity: gl,
    // Unreal: dx); used only when the pixels do not decide (validate's convention verdict).
    NormalConvention engine_normal = NormalConvention::unknown;
};

// True for extensions OpenImageIO reads that matforge treats as maps
// (png jpg jpeg tga tif tiff exr hdr webp bmp dds psd).
bool is_image_file(std::string_view filename);

// Previews, thumbnails, ID masks, renders, swatches, placeholders, billboards: images that are
// never maps of the material.
bool is_clutter(std::string_view filename);

// The role a file name states, or nullopt (clutter, non-image, no role tag).
std::optional<NameMatch> classify_name(std::string_view filename);

// Whether every image of `files` (one folder's, or one set's) that names a role is a billboard
// map ("<id>_Billboard_Albedo"): such a folder is the billboard's own material, and its maps are
// maps. Beside the asset's own maps, billboard maps are clutter (a plant's far-LOD impostor).
bool billboards_only(const std::vector<std::string>& files);

// classify_name, with billboard maps read as maps when `billboards_are_maps`.
std::optional<NameMatch> classify_name(std::string_view filename, bool billboards_are_maps);

// The material name part of a file name: the tokens before the role tag, with resolution and
// format tags removed, joined by '_' in their original case ("Bricks059_1K-PNG_Color.png" →
// "Bricks059"). Empty when the name is only a role tag ("albedo.png").
std::string material_stem(std::string_view filename);

// Pixel size a name claims ("_2K" → 2048, "_1024" → 1024), 0 when none.
int resolution_hint(std::string_view filename);

// ---------------------------------------------------------------------------------------------
// Sidecars: roles a set's own material description states.
//
// Which files: every `*.gltf` and `*.glb` of the set, every `*.json` (a Megascans asset file is
// "<id>.json" beside its maps) and every `*.mtlx` (ambientCG ships one with each download);
// is_sidecar_name() says which names to read. Read at most
// kSidecarMaxBytes of each (a .glb's JSON chunk comes first, so its first bytes are enough; a
// larger .gltf or .json is skipped: the names decide). Pass the file's path relative to the
// set's root, '/'-separated, the same spelling as in the `files` given to discover_set: map URIs
// are resolved against the sidecar's folder.

inline constexpr size_t kSidecarMaxBytes = size_t{8} << 20;

bool is_sidecar_name(std::string_view filename);  // .gltf .glb .json .mtlx

enum class SidecarKind { none, gltf, megascans, materialx };

struct SidecarMap {
    std::string file;  // relative to the set's root, '/'-separated, "." and ".." resolved
    NameMatch match;   // family "gltf" or "megascans", rule e.g. "gltf:materials[0].normalTexture"
};

// What a sidecar states of the asset's origin, for its provenance (material/provenance.hpp):
// empty where it says nothing. glTF: `asset.copyright` and the `asset.extras` a store writes
// (Sketchfab's "license", "author", "title", "source"); Megascans: "id", "name", a "license" or
// "licence" member if any, and "previews" (the vendor's preview images, resolved like maps).
struct SidecarFacts {
    std::string asset_id, title, author, copyright, source_url;
    std::string licence;        // the text of the member that states a licence
    std::string licence_field;  // that member's path ("asset.extras.license", "license")
    std::vector<std::string> previews;
    bool operator==(const SidecarFacts&) const = default;
};

struct SidecarRoles {
    std::string source;  // the sidecar's path as given
    SidecarKind kind = SidecarKind::none;
    std::vector<SidecarMap> maps;  // one per file, in the sidecar's order (first role wins)
    std::string error;             // why nothing could be read; empty when the text was read
    SidecarFacts facts;
};

// glTF 2.0 (.gltf JSON, or .glb: its JSON chunk): for every material, baseColorTexture → albedo
// (opacity in A when alphaMode is MASK or BLEND), normalTexture → normal with glTF's +Y
// convention (gl), metallicRoughnessTexture → metallic_roughness (orm when the material's
// occlusionTexture is the same image), occlusionTexture → occlusion, emissiveTexture → emissive;
// factors of 0 mark the role unused (NameMatch::unused). Images given as data: URIs or absolute
// URLs name no file of the set and are skipped; URIs are percent-decoded.
// Megascans (.json): "maps": [{"type", "uri"}] (surfaces, decals, 3D plants) and "components":
// [{"type", "uris": [{"resolutions": [{"formats": [{"uri"}]}]}]}] (3D assets, atlases); the types
// albedo/diffuse, normal, roughness, gloss, specular, displacement/bump (height), ao (occlusion),
// cavity, opacity, translucency and metalness have roles; others (fuzz, thickness, curvature,
// brush, mask, transmission) are skipped.
// MaterialX (.mtlx, read with libxml2): every surface shader's texture inputs (standard_surface,
// gltf_pbr, open_pbr_surface, UsdPreviewSurface) and a displacement shader's, followed through
// nodes (normalmap, extract, swizzle, convert, nodegraph outputs) to their image nodes' "file";
// a normal map reached through a `normalmap` node is gl (MaterialX's tangent space is +Y up). A
// file reached for two roles (a packed map split by extract nodes) is left to its name. The
// family stays empty: a MaterialX document is no naming convention, so where the name agrees on
// the role the name's family counts for the set's convention.
// Never throws; content that is not one of these gives kind none and an error.
SidecarRoles sidecar_roles(std::string_view filename, std::string_view content);

// ---------------------------------------------------------------------------------------------
// Choosing one map per role

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

// Which chosen file feeds each output role is routing's business (material/routing.hpp:
// route_roles over the maps that could be read), decided there for ingest and validate alike.

struct ChoicePolicy {
    NormalConvention preferred_normal = NormalConvention::gl;  // the preset's convention
    int max_size = 0;                                          // preset size limit; 0 = none
    // The set shares its folder with other sets (a flat folder split by name, sets.hpp): a
    // preview image that names no material ("Material_1586.jpg") is then no set's preview.
    bool shared_folder = false;
};

struct SetDiscovery {
    std::string convention;           // the family most maps follow ("generic" when mixed/none)
    std::vector<RoleChoice> choices;  // one per input role present, in Role order
    std::vector<Finding> findings;    // AMBIGUOUS_MAP, UNRECOGNIZED_FILE (info)
    // The vendor's preview image of the material (role preview), when the set has maps: one a
    // Megascans JSON lists, ambientCG's "<id>.png" beside "<id>_<res>-<format>_*" maps, or an
    // image whose name says preview, thumbnail, render, sphere, cube or flat (Poliigon
    // "_Preview1", "_Sphere"; 3dtextures.me's "Material_NNNN") and names the set's material or
    // no material (not in a shared folder). Best first: the sidecar's, then by the word (the id
    // alone, preview, render, sphere, cube, flat, thumbnail), the largest, the name. Never a
    // choice: never read as a map, validated or packed. Other previews stay UNRECOGNIZED_FILE.
    std::optional<Candidate> preview;
};

// Classify the files of one set, choose one file per input role deterministically, and resolve
// which file feeds each output role. Ranking: for normals, the policy's convention first, then
// any known convention, then unknown; then the largest size within max_size (from the header,
// else the name's hint); then lossless over lossy (exr tif png tga bmp jpg webp: a WebP twin of
// a JPEG is a re-encoded copy); then higher bit depth; then byte-wise name order. A dedicated
// map beats a packed one for the same role; roughness beats gloss. Every choice among several
// candidates gets one AMBIGUOUS_MAP (info) per role naming all candidates, the chosen one and
// why. `header` may return nullopt. `sidecars`: sidecar_roles() of the set's sidecar files. A
// file a sidecar names takes the sidecar's role (a Megascans JSON before a glTF, then the order
// given); a sidecar that named at least one file of the set is not reported, one that named none
// is UNRECOGNIZED_FILE.
// `colour(file)`: whether the file's pixels are colour (R, G, B apart), nullopt when unknown;
// asked only of names whose role the pixels decide: Unreal-style "T_<name>_A" and "_D" (a
// colour "_A" is Megascans' albedo, never an opacity mask; a grey "_D" beside it is the
// displacement). Object-space normal maps ("_nm_os", or an untagged "_nm" beside "_nm_tangent")
// never take the normal role: UNRECOGNIZED_FILE (info) says why. A file a sidecar names for a
// role outranks a file of another material name for that role (a stray map of another id).
// `normal(file)`: whether the file's pixels are a tangent-space normal map, asked of maps named
// for a scalar role in a set without a normal map (ROLE_FROM_PIXELS: the pixels win).
using PixelProbe = std::function<std::optional<bool>(const std::string&)>;
SetDiscovery discover_set(const std::vector<std::string>& files,
                          const std::function<std::optional<HeaderInfo>(const std::string&)>& header,
                          const ChoicePolicy& policy, const std::vector<SidecarRoles>& sidecars = {},
                          const PixelProbe& colour = {}, const PixelProbe& normal = {});

// ---------------------------------------------------------------------------------------------
// Grouping a flat folder into materials

// Two or more different spellings of a material name that reduced to one group name.
struct StemMerge {
    std::vector<std::string> spellings;  // the name part as written (tags included), byte order
    std::vector<std::string> files;      // the first file of each spelling
    bool tags_differ = false;            // resolution/format tags differ ("Metal_1K" / "Metal_2K-PNG")
    bool spelling_differs = false;       // letter case or separators differ ("Wood" / "WOOD")
    std::string message;                 // one sentence, ready for a finding
};

// Split one folder's files into material groups by material_stem (case-insensitive, separators
// unified). Files with no stem, clutter and unrecognized files join the group whose stem is the
// longest prefix of their own name, else the first group; a licence or readme file
// (provenance.hpp is_licence_file_name) that names no group joins every group: it speaks for
// the folder. Groups are returned sorted by stem;
// `name` is the stem in its first-seen original case, or `fallback_name` for the empty stem.
// `merge` is set when files spell the group's name differently: the caller decides whether that
// is worth a warning (tags only: one material at several sizes or formats, expected; a spelling
// difference: possibly two materials).
struct FileGroup {
    std::string name;
    std::vector<std::string> files;
    std::optional<StemMerge> merge;
    bool shared = false;  // the folder held other groups too (ChoicePolicy::shared_folder)
};
std::vector<FileGroup> group_files(const std::vector<std::string>& files, const std::string& fallback_name);

}  // namespace mf
