#include "preset/engine_slots.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <set>

namespace mf {
namespace {

using R = Role;

// Each table lists an engine's slots in the order its material file names them (the writers
// follow it), with the roles each reads.

// glTF 2.0 (the specification's section 3.9, Materials): baseColorTexture (sRGB RGB, A alpha),
// metallicRoughnessTexture (linear, G roughness, B metalness; metallicFactor and roughnessFactor
// default to 1, so both are written), normalTexture (+Y), occlusionTexture (R, linear; a set
// without an occlusion map names none: the engine's default is no occlusion), emissiveTexture
// (sRGB RGB). One texture may serve several slots: the ORM serves occlusion and
// metallicRoughness.
constexpr SlotRead kGltfBase[] = {{.role = R::albedo, .key = "RGB", .required = true},
                                  {.role = R::opacity, .key = "A"}};
constexpr SlotRead kGltfMr[] = {{.role = R::roughness, .key = "G", .required = true},
                                {.role = R::metalness, .key = "B", .required = true}};
constexpr SlotRead kNormalRgb[] = {{.role = R::normal, .key = "RGB"}};
constexpr SlotRead kOcclusionR[] = {{.role = R::occlusion, .key = "R"}};
constexpr SlotRead kEmissiveRgb[] = {{.role = R::emissive, .key = "RGB"}};
constexpr EngineSlot kGltf[] = {
    {.slot = "baseColorTexture", .srgb = true, .reads = kGltfBase, .group = "pbrMetallicRoughness"},
    {.slot = "metallicRoughnessTexture", .reads = kGltfMr, .group = "pbrMetallicRoughness"},
    {.slot = "occlusionTexture", .reads = kOcclusionR, .map_only = true},
    {.slot = "normalTexture", .reads = kNormalRgb},
    {.slot = "emissiveTexture", .srgb = true, .reads = kEmissiveRgb},
};
// Godot 4 ORMMaterial3D (docs: "Standard Material 3D and ORM Material 3D"): albedo_texture
// sampled as colour (source_color) with alpha; orm_texture R occlusion, G roughness, B metallic
// (read with ao_enabled); normal_texture (+Y); emission_texture (colour); heightmap_texture
// (R, white = high). A slot other than albedo's and the ORM's is read only with its *_enabled.
constexpr SlotRead kAlbedoRgbA[] = {{.role = R::albedo, .key = "RGB"}, {.role = R::opacity, .key = "A"}};
constexpr SlotRead kOrm[] = {{.role = R::occlusion, .key = "R"},
                             {.role = R::roughness, .key = "G"},
                             {.role = R::metalness, .key = "B"}};
constexpr SlotRead kHeightR[] = {{.role = R::height, .key = "R"}};
constexpr EngineSlot kGodot[] = {
    {.slot = "albedo_texture", .srgb = true, .reads = kAlbedoRgbA},
    {.slot = "orm_texture", .reads = kOrm, .enable = "ao_enabled", .enable_after = true},
    {.slot = "normal_texture", .reads = kNormalRgb, .enable = "normal_enabled"},
    {.slot = "emission_texture", .srgb = true, .reads = kEmissiveRgb, .enable = "emission_enabled"},
    {.slot = "heightmap_texture", .reads = kHeightR, .enable = "heightmap_enabled"},
};
// Unity HDRP Lit (HDRP docs, "Lit shader", "Mask Map"): _BaseColorMap RGB + alpha; _MaskMap R
// metallic, G ambient occlusion, B detail mask, A smoothness; _NormalMap (+Y, OpenGL);
// _HeightMap R; _EmissiveColorMap colour. Each map turns on its shader keyword.
constexpr SlotRead kHdrpMask[] = {{.role = R::metalness, .key = "R"},
                                  {.role = R::occlusion, .key = "G"},
                                  {.role = R::roughness, .smoothness = true, .key = "A"}};
constexpr EngineSlot kHdrp[] = {
    {.slot = "_BaseColorMap", .srgb = true, .reads = kAlbedoRgbA},
    {.slot = "_NormalMap", .reads = kNormalRgb, .enable = "_NORMALMAP _NORMALMAP_TANGENT_SPACE"},
    {.slot = "_MaskMap", .reads = kHdrpMask, .enable = "_MASKMAP"},
    {.slot = "_HeightMap", .reads = kHeightR, .enable = "_HEIGHTMAP"},
    {.slot = "_EmissiveColorMap", .srgb = true, .reads = kEmissiveRgb, .enable = "_EMISSIVE_COLOR_MAP"},
};
// Unity URP Lit (URP docs, "Lit Shader"): _BaseMap RGB + alpha; _MetallicGlossMap R metallic,
// A smoothness (_SmoothnessTextureChannel 0); _BumpMap; _OcclusionMap and _ParallaxMap are read
// from G by URP's shaders, the same as R in the grey one-channel files written for them;
// _EmissionMap colour. Each map turns on its shader keyword.
constexpr SlotRead kUrpMetallic[] = {{.role = R::metalness, .key = "R"},
                                     {.role = R::roughness, .smoothness = true, .key = "A"}};
constexpr EngineSlot kUrp[] = {
    {.slot = "_BaseMap", .srgb = true, .reads = kAlbedoRgbA},
    {.slot = "_BumpMap", .reads = kNormalRgb, .enable = "_NORMALMAP"},
    {.slot = "_MetallicGlossMap", .reads = kUrpMetallic, .enable = "_METALLICSPECGLOSSMAP"},
    {.slot = "_OcclusionMap", .reads = kOcclusionR, .enable = "_OCCLUSIONMAP"},
    {.slot = "_ParallaxMap", .reads = kHeightR, .enable = "_PARALLAXMAP"},
    {.slot = "_EmissionMap", .srgb = true, .reads = kEmissiveRgb, .enable = "_EMISSION"},
};
// Unreal Engine (the import script's material instance of a parent it makes, engine/unreal.cpp):
// BaseColor (sRGB; RGB to Base Color, A to Opacity and Opacity Mask), ORM packed R occlusion,
// G roughness, B metallic (TC_MASKS, no sRGB), Normal (TC_NORMALMAP, DirectX -Y), Emissive
// (sRGB, times the EmissiveStrength scalar), Height (R, TC_GRAYSCALE; imported, not a parameter
// of the parent). Where a set has no normal or emissive map, the instance reads the engine's flat
// normal and black.
constexpr SlotRead kUnrealBase[] = {{.role = R::albedo, .key = "RGB", .input = "MP_BASE_COLOR"},
                                    {.role = R::opacity, .key = "A", .input = "MP_OPACITY_MASK MP_OPACITY"}};
constexpr SlotRead kUnrealOrm[] = {{.role = R::occlusion, .key = "R", .input = "MP_AMBIENT_OCCLUSION"},
                                   {.role = R::roughness, .key = "G", .input = "MP_ROUGHNESS"},
                                   {.role = R::metalness, .key = "B", .input = "MP_METALLIC"}};
constexpr SlotRead kUnrealNormal[] = {{.role = R::normal, .key = "RGB", .input = "MP_NORMAL"}};
constexpr SlotRead kUnrealEmissive[] = {{.role = R::emissive, .key = "RGB", .input = "MP_EMISSIVE_COLOR"}};
constexpr EngineSlot kUnreal[] = {
    {.slot = "BaseColor",
     .srgb = true,
     .reads = kUnrealBase,
     .compression = "TC_DEFAULT",
     .sampler = "SAMPLERTYPE_COLOR"},
    {.slot = "ORM", .reads = kUnrealOrm, .compression = "TC_MASKS", .sampler = "SAMPLERTYPE_MASKS"},
    {.slot = "Normal",
     .reads = kUnrealNormal,
     .compression = "TC_NORMALMAP",
     .fallback = "/Engine/EngineMaterials/FlatNormal",
     .sampler = "SAMPLERTYPE_NORMAL"},
    {.slot = "Emissive",
     .srgb = true,
     .reads = kUnrealEmissive,
     .compression = "TC_DEFAULT",
     .fallback = "/Engine/EngineResources/Black",
     .sampler = "SAMPLERTYPE_COLOR"},
    {.slot = "Height", .reads = kHeightR, .compression = "TC_GRAYSCALE"},
};
// Direct3D 11 (matforge_material.hlsli, engine/hlsl.cpp): Texture2D Albedo (sRGB view, opacity
// in A), NormalMap (BC5 X, Y; Z rebuilt), RoughnessMap and MetalnessMap (.r).
constexpr SlotRead kRoughnessR[] = {{.role = R::roughness, .key = "R"}};
constexpr SlotRead kMetalnessR[] = {{.role = R::metalness, .key = "R"}};
constexpr EngineSlot kD3d11[] = {
    {.slot = "Albedo", .srgb = true, .reads = kAlbedoRgbA},
    {.slot = "NormalMap", .reads = kNormalRgb},
    {.slot = "RoughnessMap", .reads = kRoughnessR},
    {.slot = "MetalnessMap", .reads = kMetalnessR},
};

constexpr FileFormat kPng[] = {FileFormat::png};  // glTF core: PNG or JPEG
constexpr FileFormat kPngExr[] = {FileFormat::png, FileFormat::exr};
constexpr FileFormat kUnityFormats[] = {FileFormat::png, FileFormat::exr, FileFormat::tif, FileFormat::tga};
constexpr FileFormat kDds[] = {FileFormat::dds};

constexpr std::array<EngineMaterial, 6> kEngines{{
    {.kind = MaterialFileKind::gltf,
     .engine = "glTF 2.0 metallic-roughness",
     .normal = NormalConvention::gl,
     .formats = kPng,
     .slots = kGltf,
     .shared_textures = true,
     .other_outputs = true},
    {.kind = MaterialFileKind::godot,
     .engine = "Godot 4 ORMMaterial3D",
     .normal = NormalConvention::gl,
     .formats = kPngExr,
     .slots = kGodot},
    {.kind = MaterialFileKind::unity_hdrp,
     .engine = "Unity HDRP Lit",
     .normal = NormalConvention::gl,
     .formats = kUnityFormats,
     .slots = kHdrp},
    {.kind = MaterialFileKind::unity_urp,
     .engine = "Unity URP Lit",
     .normal = NormalConvention::gl,
     .formats = kUnityFormats,
     .slots = kUrp},
    {.kind = MaterialFileKind::unreal,
     .engine = "Unreal Engine material instance",
     .normal = NormalConvention::dx,
     .formats = kUnityFormats,
     .slots = kUnreal},
    {.kind = MaterialFileKind::d3d11,
     .engine = "Direct3D 11 (matforge_material.hlsli)",
     .normal = NormalConvention::dx,
     .formats = kDds,
     .slots = kD3d11},
}};

bool holds(const Channel& c, const SlotRead& r) {
    return c.role == r.role &&
           ((c.kind == Channel::Kind::role && !r.smoothness) || (c.kind == Channel::Kind::smoothness && r.smoothness));
}
bool holds(const Channel& c, const EngineSlot& s) {
    return std::any_of(s.reads.begin(), s.reads.end(), [&](const SlotRead& r) { return holds(c, r); });
}

}  // namespace

bool EngineSlot::reads_role(Role r) const {
    return std::any_of(reads.begin(), reads.end(), [r](const SlotRead& x) { return x.role == r; });
}

bool EngineSlot::binds(const std::vector<Channel>& written, bool srgb_) const {
    if (srgb_ != srgb || reads.empty()) return false;
    for (size_t i = 0; i < reads.size(); ++i) {
        if (i > 0 && !reads[i].required) continue;
        const SlotRead& r = reads[i];
        if (std::none_of(written.begin(), written.end(),
                         [&](const Channel& c) { return c.key == r.key && holds(c, r); }))
            return false;
    }
    return true;
}

const EngineMaterial* engine_material(MaterialFileKind kind) {
    for (const auto& e : kEngines)
        if (e.kind == kind) return &e;
    return nullptr;
}

template <class C>
const EngineSlot* slot_reading(const EngineMaterial& e, const std::vector<C>& channels) {
    for (const EngineSlot& s : e.slots)
        for (const Channel& c : channels)
            if (holds(c, s)) return &s;
    return nullptr;
}

const EngineSlot* slot_of(const EngineMaterial& e, const OutputSpec& o) { return slot_reading(e, o.channels); }
const EngineSlot* slot_of(const EngineMaterial& e, const std::vector<Channel>& written) {
    return slot_reading(e, written);
}

bool check_engine_layout(const Preset& p, const EngineMaterial& e, std::string& error) {
    const std::string where = "material_file " + std::string(word(e.kind)) + " (" + std::string(e.engine) + "): ";
    if (p.normal_convention != e.normal) {
        error = where + "its normal slot reads " + std::string(convention_name(e.normal)) +
                " normals; this preset's normal_convention is " + std::string(convention_name(p.normal_convention));
        return false;
    }
    bool format_ok = false;
    std::string formats;
    for (FileFormat f : e.formats) {
        format_ok = format_ok || f == p.format;
        formats += (formats.empty() ? "" : ", ") + std::string(word(f));
    }
    if (!format_ok) {
        error = where + "it imports " + formats + "; this preset writes " + std::string(word(p.format));
        return false;
    }
    std::map<std::string_view, std::string> reader;    // slot -> the output it reads
    std::set<std::pair<std::string_view, Role>> held;  // (slot, role) some output holds where the slot reads it
    for (const OutputSpec& o : p.outputs) {
        const EngineSlot* slot = slot_of(e, o);
        if (!slot && e.other_outputs) continue;
        if (!slot) {
            error = where + "no slot reads the output '" + o.suffix + "'";
            return false;
        }
        for (const EngineSlot& s : e.slots)
            for (const SlotRead& r : s.reads)
                for (const ChannelSpec& c : o.channels) {
                    if (!holds(c, r)) continue;
                    const std::string what = "'" + o.suffix + "' holds " + std::string(role_name(r.role)) +
                                             (r.smoothness ? " (as smoothness)" : "") + " in " + c.key + "; ";
                    if (s.slot != slot->slot && !e.shared_textures) {
                        error = where + what + "the engine reads it from " + std::string(s.slot) + ", not " +
                                std::string(slot->slot);
                        return false;
                    }
                    if (c.key != r.key || o.srgb != s.srgb) {
                        error = where + what + std::string(s.slot) + " reads it from " + std::string(r.key) +
                                (s.srgb ? " as sRGB" : " as linear data");
                        return false;
                    }
                    held.emplace(s.slot, r.role);
                    if (const auto [it, fresh] = reader.emplace(s.slot, o.suffix); !fresh && it->second != o.suffix) {
                        error = where + std::string(s.slot) + " reads one texture; '" + it->second + "' and '" +
                                o.suffix + "' both go there";
                        return false;
                    }
                }
    }
    // What the material needs: each required role in its slot's channel (an output holding it
    // elsewhere was refused above).
    for (const EngineSlot& s : e.slots)
        for (const SlotRead& r : s.reads)
            if (r.required && !held.count({s.slot, r.role})) {
                std::string reads;
                for (const SlotRead& x : s.reads)
                    if (x.required)
                        reads += (reads.empty() ? "" : ", ") + std::string(role_name(x.role)) + " in " +
                                 std::string(x.key);
                error = where + std::string(s.slot) + " needs an output with " + reads +
                        (s.srgb ? " (sRGB)" : " (linear)") + "; this preset has none";
                return false;
            }
    return true;
}

}  // namespace mf
