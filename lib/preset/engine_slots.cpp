#include "preset/engine_slots.hpp"

#include <algorithm>
#include <array>
#include <map>

namespace mf {
namespace {

using R = Role;

// Each table lists an engine's slots in the order its material file names them (the writers
// follow it), with the roles each reads.

// Godot 4 ORMMaterial3D (docs: "Standard Material 3D and ORM Material 3D"): albedo_texture
// sampled as colour (source_color) with alpha; orm_texture R occlusion, G roughness, B metallic
// (read with ao_enabled); normal_texture (+Y); emission_texture (colour); heightmap_texture
// (R, white = high). A slot other than albedo's and the ORM's is read only with its *_enabled.
constexpr SlotRead kAlbedoRgbA[] = {{R::albedo, false, "RGB"}, {R::opacity, false, "A"}};
constexpr SlotRead kOrm[] = {{R::occlusion, false, "R"}, {R::roughness, false, "G"}, {R::metalness, false, "B"}};
constexpr SlotRead kNormalRgb[] = {{R::normal, false, "RGB"}};
constexpr SlotRead kEmissiveRgb[] = {{R::emissive, false, "RGB"}};
constexpr SlotRead kHeightR[] = {{R::height, false, "R"}};
constexpr EngineSlot kGodot[] = {
    {"albedo_texture", true, kAlbedoRgbA, "", false, "", ""},
    {"orm_texture", false, kOrm, "ao_enabled", true, "", ""},
    {"normal_texture", false, kNormalRgb, "normal_enabled", false, "", ""},
    {"emission_texture", true, kEmissiveRgb, "emission_enabled", false, "", ""},
    {"heightmap_texture", false, kHeightR, "heightmap_enabled", false, "", ""},
};
// Unity HDRP Lit (HDRP docs, "Lit shader", "Mask Map"): _BaseColorMap RGB + alpha; _MaskMap R
// metallic, G ambient occlusion, B detail mask, A smoothness; _NormalMap (+Y, OpenGL);
// _HeightMap R; _EmissiveColorMap colour. Each map turns on its shader keyword.
constexpr SlotRead kHdrpMask[] = {{R::metalness, false, "R"}, {R::occlusion, false, "G"}, {R::roughness, true, "A"}};
constexpr EngineSlot kHdrp[] = {
    {"_BaseColorMap", true, kAlbedoRgbA, "", false, "", ""},
    {"_NormalMap", false, kNormalRgb, "_NORMALMAP _NORMALMAP_TANGENT_SPACE", false, "", ""},
    {"_MaskMap", false, kHdrpMask, "_MASKMAP", false, "", ""},
    {"_HeightMap", false, kHeightR, "_HEIGHTMAP", false, "", ""},
    {"_EmissiveColorMap", true, kEmissiveRgb, "_EMISSIVE_COLOR_MAP", false, "", ""},
};
// Unity URP Lit (URP docs, "Lit Shader"): _BaseMap RGB + alpha; _MetallicGlossMap R metallic,
// A smoothness (_SmoothnessTextureChannel 0); _BumpMap; _OcclusionMap and _ParallaxMap are read
// from G by URP's shaders, the same as R in the grey one-channel files written for them;
// _EmissionMap colour. Each map turns on its shader keyword.
constexpr SlotRead kUrpMetallic[] = {{R::metalness, false, "R"}, {R::roughness, true, "A"}};
constexpr SlotRead kOcclusionR[] = {{R::occlusion, false, "R"}};
constexpr EngineSlot kUrp[] = {
    {"_BaseMap", true, kAlbedoRgbA, "", false, "", ""},
    {"_BumpMap", false, kNormalRgb, "_NORMALMAP", false, "", ""},
    {"_MetallicGlossMap", false, kUrpMetallic, "_METALLICSPECGLOSSMAP", false, "", ""},
    {"_OcclusionMap", false, kOcclusionR, "_OCCLUSIONMAP", false, "", ""},
    {"_ParallaxMap", false, kHeightR, "_PARALLAXMAP", false, "", ""},
    {"_EmissionMap", true, kEmissiveRgb, "_EMISSION", false, "", ""},
};
// Unreal Engine (the import script's material instance, engine/unreal.cpp): BaseColor (sRGB,
// opacity in A), ORM packed R occlusion, G roughness, B metallic (TC_MASKS, no sRGB), Normal
// (TC_NORMALMAP, DirectX -Y), Emissive (sRGB), Height (R, TC_GRAYSCALE). Where a set has no
// normal or emissive map, the instance reads the engine's flat normal and black.
constexpr EngineSlot kUnreal[] = {
    {"BaseColor", true, kAlbedoRgbA, "", false, "TC_DEFAULT", ""},
    {"ORM", false, kOrm, "", false, "TC_MASKS", ""},
    {"Normal", false, kNormalRgb, "", false, "TC_NORMALMAP", "/Engine/EngineMaterials/FlatNormal"},
    {"Emissive", true, kEmissiveRgb, "", false, "TC_DEFAULT", "/Engine/EngineResources/Black"},
    {"Height", false, kHeightR, "", false, "TC_GRAYSCALE", ""},
};
// Direct3D 11 (matforge_material.hlsli, engine/hlsl.cpp): Texture2D Albedo (sRGB view, opacity
// in A), NormalMap (BC5 X, Y; Z rebuilt), RoughnessMap and MetalnessMap (.r).
constexpr SlotRead kRoughnessR[] = {{R::roughness, false, "R"}};
constexpr SlotRead kMetalnessR[] = {{R::metalness, false, "R"}};
constexpr EngineSlot kD3d11[] = {
    {"Albedo", true, kAlbedoRgbA, "", false, "", ""},
    {"NormalMap", false, kNormalRgb, "", false, "", ""},
    {"RoughnessMap", false, kRoughnessR, "", false, "", ""},
    {"MetalnessMap", false, kMetalnessR, "", false, "", ""},
};

constexpr FileFormat kPngExr[] = {FileFormat::png, FileFormat::exr};
constexpr FileFormat kUnityFormats[] = {FileFormat::png, FileFormat::exr, FileFormat::tif, FileFormat::tga};
constexpr FileFormat kDds[] = {FileFormat::dds};

constexpr std::array<EngineMaterial, 5> kEngines{{
    {MaterialFileKind::godot, "Godot 4 ORMMaterial3D", NormalConvention::gl, kPngExr, kGodot},
    {MaterialFileKind::unity_hdrp, "Unity HDRP Lit", NormalConvention::gl, kUnityFormats, kHdrp},
    {MaterialFileKind::unity_urp, "Unity URP Lit", NormalConvention::gl, kUnityFormats, kUrp},
    {MaterialFileKind::unreal, "Unreal Engine material instance", NormalConvention::dx, kUnityFormats, kUnreal},
    {MaterialFileKind::d3d11, "Direct3D 11 (matforge_material.hlsli)", NormalConvention::dx, kDds, kD3d11},
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
    std::map<std::string_view, std::string> reader;  // slot -> the output it reads
    for (const OutputSpec& o : p.outputs) {
        const EngineSlot* slot = slot_of(e, o);
        if (!slot) {
            error = where + "no slot reads the output '" + o.suffix + "'";
            return false;
        }
        if (const auto [it, fresh] = reader.emplace(slot->slot, o.suffix); !fresh) {
            error = where + std::string(slot->slot) + " reads one texture; '" + it->second + "' and '" + o.suffix +
                    "' both go there";
            return false;
        }
        for (const EngineSlot& s : e.slots)
            for (const SlotRead& r : s.reads)
                for (const ChannelSpec& c : o.channels) {
                    if (!holds(c, r)) continue;
                    const std::string what = "'" + o.suffix + "' holds " + std::string(role_name(r.role)) +
                                             (r.smoothness ? " (as smoothness)" : "") + " in " + c.key + "; ";
                    if (s.slot != slot->slot) {
                        error = where + what + "the engine reads it from " + std::string(s.slot) + ", not " +
                                std::string(slot->slot);
                        return false;
                    }
                    if (c.key != r.key || o.srgb != s.srgb) {
                        error = where + what + std::string(s.slot) + " reads it from " + std::string(r.key) +
                                (s.srgb ? " as sRGB" : " as linear data");
                        return false;
                    }
                }
    }
    return true;
}

}  // namespace mf
