// manifest.json (version 1): what `ingest` wrote, typed. Ingest builds a Manifest and writes it
// with to_json(); preview (and every later reader) reads it back with manifest_from_json().
// The schema is docs/manifest.schema.json; docs/interface.md describes every field.
//
// Conventions of this module (decided once here):
//  - paths are kept as the manifest writes them: Material::source and Output::file relative to
//    the manifest's folder, Input::file relative to the source; resolving them is the reader's;
//  - JSON objects are written with sorted keys and the numbers as the types below give them,
//    so the same manifest is the same bytes (core/json: json_text);
//  - reading never throws: every member is type-checked, an unknown role, channel key or
//    status is an error naming the material and the member (a typo must not become a default).
#pragma once
#include <functional>
#include <map>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "findings/findings.hpp"
#include "material/channel.hpp"
#include "material/provenance.hpp"
#include "material/roles.hpp"

namespace mf::manifest {

inline constexpr int kVersion = 1;

// How an input normal map's green convention was decided.
struct NormalFacts {
    NormalConvention convention = NormalConvention::unknown;
    std::string source;                // "name" | "content" | "" (undecided)
    std::optional<double> confidence;  // with source "content"
    std::string method;                // with source "content": the test that decided ("height+curl", "curl")
};

struct Input {
    Role role = Role::albedo;  // input role (orm, gloss, … included)
    std::string file;          // relative to the material's source
    std::string family, rule;  // the naming rule that matched
    int width = 0, height = 0, channels = 0, bit_depth = 0;
    bool is_float = false;
    std::string color_space;            // "sRGB" | "linear" (float color) | "data"
    std::optional<NormalFacts> normal;  // normal inputs only
    // A height map stored as depth (white = deep), read inverted (HEIGHT_STORED_AS_DEPTH).
    bool stored_as_depth = false;
    // Read and judged, but not applied: an opacity map that would hide the whole surface
    // (OPACITY_ALL_TRANSPARENT); the material is written opaque and judged as such.
    bool unused = false;
};

// One entry of Output::channels: what a channel (or the RGB triple) holds.
using Channel = mf::Channel;

// One mip level of a block-compressed output: its size and the error of the decoded level
// against the level it encodes (PSNR over the stored channels; angles for normals).
struct LevelError {
    int width = 0, height = 0;
    std::optional<double> psnr_db;                        // color and data; 100 = identical
    std::optional<double> mean_angle_deg, max_angle_deg;  // normals
    // An alpha-tested cut-out's share of the level's texels its alpha test at the material's
    // cutoff keeps (each level's alpha scaled to keep level 0's: texture::make_mips).
    std::optional<double> coverage;
};

struct Output {
    std::string file;   // relative to the manifest's folder
    bool srgb = false;  // "color_space": "sRGB" (color channels encoded) or "linear"
    std::vector<Channel> channels;
    std::optional<NormalConvention> normal_convention;  // textures holding a normal
    // A normal texture whose green channel was flipped: the input's convention (the output's is
    // normal_convention). Absent: written in the convention it was read in, or no map (flat).
    std::optional<NormalConvention> normal_converted_from;
    int width = 0, height = 0, bit_depth = 0;
    std::string format, sha256;
    // Block-compressed outputs (format dds | ktx2) only:
    std::string block_format;             // "bc1", "bc5", "astc-6x6", ...
    std::string gpu_format;               // the container's format name (DXGI_FORMAT_BC1_UNORM_SRGB, VK_FORMAT_...)
    std::string supercompression;         // "zstd" when the KTX2 levels are supercompressed
    bool normal_z_reconstructed = false;  // a normal stored as X, Y only (BC5): Z = sqrt(1 - x² - y²)
    // Texels never shown (under the alpha test, or alpha 0 in a blend) whose colour was filled from
    // the nearest shown ones before the mips and blocks (texture::dilate_under_alpha).
    std::optional<int64_t> dilated_texels;
    std::vector<LevelError> levels;  // every mip level, largest first
};

// A file describing the material for an engine or viewer (the glTF of a set and its buffer).
struct MaterialFile {
    std::string file;    // relative to the manifest's folder
    std::string format;  // "gltf" | "bin"
    std::string sha256;
};

// A value ingest generated for a role the set has no map of (scalar, or RGB for a color).
struct Constant {
    Role role = Role::metalness;
    std::vector<float> value;  // 1 or 3 numbers
};

enum class Status { ok, partial };  // partial: some map could not be read or written

// How an engine uses the opacity an output carries (texture::classify_opacity of the applied
// opacity map): opaque (every texel 1), mask (cut-out at Material::alpha_cutoff, the preset's),
// blend (translucent). Every material file of the set says the same (glTF alphaMode, MaterialX
// alpha_mode, Godot transparency, Unity _ALPHATEST_ON / _SURFACE_TYPE_TRANSPARENT, ...).
enum class AlphaMode { opaque, mask, blend };
std::string_view alpha_mode_name(AlphaMode a);  // "opaque" | "mask" | "blend"
// Whether a material is seen from both sides: a cut-out or translucent sheet shows its far side
// (glTF doubleSided, Godot cull_mode, Unity _DoubleSidedEnable, the preview's far side).
bool double_sided(std::optional<AlphaMode> a);

struct Material {
    std::string name;
    std::string source;                  // relative to the manifest's folder
    std::optional<std::string> archive;  // the .zip holding the set
    std::string convention;              // naming family
    // Where the set comes from and under what licence (material/provenance.hpp); absent when
    // nothing is known (its LICENCE_UNKNOWN finding says why) and in older manifests.
    std::optional<Provenance> provenance;
    // The set's action key (process/work.hpp action_key: its files' contents and everything that
    // decides its outputs), "" when a file could not be read: `plan --changed-since` compares it.
    std::string key;
    Status status = Status::ok;
    std::vector<Input> inputs;                 // in role order
    std::vector<Constant> constants;           // in role order
    std::vector<Output> outputs;               // in preset order
    std::vector<MaterialFile> material_files;  // preset material_file (glTF + buffer)
    std::vector<Finding> findings;
    // > 1 when the emissive map holds radiance above 1 (an EXR) and the preset writes it to an
    // integer file: the outputs hold emissive / emissive_strength (the brightest texel at 1, hue
    // kept), the engine multiplies back (glTF: KHR_materials_emissive_strength). 1: as stored.
    float emissive_strength = 1.f;
    // Only when an output carries the set's opacity (preset order: the first such channel).
    std::optional<AlphaMode> alpha_mode;
    float alpha_cutoff = 0.5f;  // with alpha_mode mask
};

struct Manifest {
    int manifest_version = kVersion;
    std::string generator;
    std::string preset;
    NormalConvention normal_convention = NormalConvention::gl;
    std::vector<Material> materials;     // sorted by name
    std::vector<InputFailure> failures;  // sorted by source
    std::vector<MaterialFile> library;   // library.gltf + library.bin (preset material_file gltf)
    // The validation thresholds the run applied, by the names a rules file gives them
    // ({CODE: {name: value}}, rules::threshold_table): a later reader judges as the run did
    // (the report's albedo overlay counts what the findings count). Empty in older manifests.
    std::map<std::string, std::map<std::string, double>> thresholds;
    // Only in the manifest of one shard (`ingest --shard I/N`): which part of which run it is.
    // `context` is the digest of everything but the inputs that decides the outputs (preset
    // content, rules, OpenColorIO config, versions): shards of one run have the same. `merge`
    // checks the parts against it and writes no `shard`.
    // `plan` is the digest of the library's split (process/work.hpp plan_digest): shards of one
    // run over one unchanged library have the same. `sets`: how many sets this shard was given.
    struct Shard {
        int index = 0, count = 1;
        std::string context;
        std::string plan;
        int sets = 0;
    };
    std::optional<Shard> shard;
};

std::string_view status_name(Status s);  // "ok" | "partial"

nlohmann::json to_json(const Input& in);
nlohmann::json to_json(const std::vector<Input>& inputs);        // {role: input, ...}
nlohmann::json to_json(const std::vector<Constant>& constants);  // {role: number or [r, g, b], ...}
nlohmann::json to_json(const Output& out);
nlohmann::json to_json(const Provenance& p);
nlohmann::json to_json(const Material& m);
nlohmann::json to_json(const Manifest& m);
// The manifest file's text: the bytes of core's json_text(to_json(m)), made one material at a
// time so that writing a library of 10,000 sets holds its text, not a JSON tree of it (about
// six times the text's size).
std::string manifest_text(const Manifest& m);

// nullopt + `error` (naming the material and member) when `j` is not a manifest this version
// reads. Members a later version may add are ignored; members of the wrong type are errors.
std::optional<Manifest> manifest_from_json(const nlohmann::json& j, std::string& error);
// Reads and parses a manifest file (the error names the file).
std::optional<Manifest> read_manifest(const std::string& path, std::string& error);
// The same without holding the materials (a manifest of 100,000 sets is hundreds of MB as a JSON
// tree): each element of "materials" is checked and handed to `each` as soon as it is parsed, then
// dropped; the manifest returned has every other member and no materials. `each` returns false
// + `error` to stop. Peak memory: one material's tree.
std::optional<Manifest> read_manifest(const std::string& path,
                                      const std::function<bool(Material&&, std::string& error)>& each,
                                      std::string& error);
// One element of "materials" (`at` names it in the error).
std::optional<Material> material_from_json(const nlohmann::json& j, const std::string& at, std::string& error);

// The manifest of one run from the manifests of its shards (`matforge ingest --shard I/N`), all
// but its materials (manifest/spool.hpp's merge_shards brings those): failures merged in the
// order one unsharded run writes them (by source; a failure every shard reports is kept once).
// nullopt + `error` naming the inputs when they do not make one run: different manifest
// versions, generators, presets, normal conventions or contexts, a part that is not a shard, a
// shard missing or given twice. `names[i]` names parts[i] in messages.
std::optional<Manifest> merge_heads(const std::vector<Manifest>& parts, const std::vector<std::string>& names,
                                    std::string& error);

// Findings of every material by severity: [info, warning, error].
std::array<size_t, 3> count_findings(const Manifest& m);

}  // namespace mf::manifest
