// The texture slots of each engine material a preset's `material_file` names (gltf, godot,
// unity-hdrp, unity-urp, unreal, d3d11): which role the engine reads from which channel of
// which slot's texture, whether it samples that texture as sRGB, and what a writer does with a
// slot the set has a texture for (the property or keywords that turn it on, Unreal's import
// settings and fallback). The preset check (check_engine_layout, at load) and the writers
// (lib/engine) read these tables alone: a slot's name is typed once, here, and a preset whose
// layout an engine's slots cannot read is refused before any set is ingested.
#pragma once
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "material/roles.hpp"
#include "preset/preset.hpp"

namespace mf {

// One role an engine reads from a texture slot.
struct SlotRead {
    Role role{};
    bool smoothness = false;   // stored as 1 - roughness (role roughness)
    std::string_view key{};    // the channel it reads it from: "RGB", "R", "G", "B", "A"
    bool required = false;     // the material needs it (glTF: albedo, roughness, metalness)
    std::string_view input{};  // Unreal: the parent material's inputs it feeds (MP_*, space-separated)
};

// One texture slot of an engine's material, with everything a writer needs of it: the writers
// (lib/engine) iterate these rows and never name a slot.
struct EngineSlot {
    std::string_view slot{};  // the engine's name of the texture ("albedo_texture", "_MaskMap", ...)
    bool srgb = false;        // the engine samples the texture as sRGB colour
    std::span<const SlotRead> reads{};
    // When the set has this slot's texture: Godot, the property set to true ("normal_enabled");
    // Unity, the shader keywords turned on (space-separated).
    std::string_view enable{};
    bool enable_after = false;       // Godot: the property follows the texture's line (ao_enabled)
    std::string_view compression{};  // Unreal: the import's TextureCompressionSettings
    std::string_view fallback{};     // Unreal: the engine's own texture where the set has none
    std::string_view sampler{};      // Unreal: the parent's sampler (SAMPLERTYPE_*); empty: not a parameter of it
    std::string_view group{};        // glTF: the object holding the slot ("pbrMetallicRoughness"), else the material
    bool map_only = false;           // glTF: named only where the set has a map of its role (occlusion: else 1)
    bool reads_role(Role r) const;   // one of `reads` is `r`
    // Whether the texture of `written` (a manifest entry's channels, in `srgb` or not) is read by
    // this slot: it holds the slot's first read and every required one, in their channels, and
    // is sampled as the slot samples.
    bool binds(const std::vector<Channel>& written, bool srgb) const;
};

struct EngineMaterial {
    MaterialFileKind kind;
    std::string_view engine;              // "Godot 4 ORMMaterial3D", ...
    NormalConvention normal;              // the tangent-space convention its normal slot reads
    std::span<const FileFormat> formats;  // the texture files it imports
    std::span<const EngineSlot> slots;    // in the order the material file lists them
    // One texture may serve several slots (glTF: one ORM texture serves occlusionTexture and
    // metallicRoughnessTexture); else each texture has one slot.
    bool shared_textures = false;
    // Outputs no slot reads are written beside the material (glTF: a height map for other tools);
    // else the preset is refused.
    bool other_outputs = false;
};

// nullptr for none.
const EngineMaterial* engine_material(MaterialFileKind kind);

// The slot reading output `o` of a preset (the first slot one of whose roles `o` holds), or
// nullptr when none does; the same of an output written, by the channels its manifest entry
// lists (what the material files bind: a reader of the manifest binds the same).
const EngineSlot* slot_of(const EngineMaterial& e, const OutputSpec& o);
const EngineSlot* slot_of(const EngineMaterial& e, const std::vector<Channel>& written);

// Whether `p`'s outputs fit `e`: its normal convention and format, each output read by a slot,
// each role in the channel and colour encoding the slot reads it from, a slot's roles in one
// output. False + `error` naming the output and the slot.
bool check_engine_layout(const Preset& p, const EngineMaterial& e, std::string& error);

}  // namespace mf
