#include "preset/engine_slots.hpp"

#include <array>
#include <map>

namespace mf {
namespace {

using R = Role;

// Godot 4 ORMMaterial3D (docs: "Standard Material 3D and ORM Material 3D"): albedo_texture
// sampled as colour (source_color) with alpha; orm_texture R occlusion, G roughness, B metallic;
// normal_texture (+Y); emission_texture (colour); heightmap_texture (R, white = high).
constexpr EngineSlot kGodot[] = {
    {"albedo_texture", R::albedo, false, "RGB", true},     {"albedo_texture", R::opacity, false, "A", true},
    {"orm_texture", R::occlusion, false, "R", false},      {"orm_texture", R::roughness, false, "G", false},
    {"orm_texture", R::metalness, false, "B", false},      {"normal_texture", R::normal, false, "RGB", false},
    {"emission_texture", R::emissive, false, "RGB", true}, {"heightmap_texture", R::height, false, "R", false},
};
// Unity HDRP Lit (HDRP docs, "Lit shader", "Mask Map"): _BaseColorMap RGB + alpha; _MaskMap R
// metallic, G ambient occlusion, B detail mask, A smoothness; _NormalMap (+Y, OpenGL);
// _HeightMap R; _EmissiveColorMap colour.
constexpr EngineSlot kHdrp[] = {
    {"_BaseColorMap", R::albedo, false, "RGB", true}, {"_BaseColorMap", R::opacity, false, "A", true},
    {"_MaskMap", R::metalness, false, "R", false},    {"_MaskMap", R::occlusion, false, "G", false},
    {"_MaskMap", R::roughness, true, "A", false},     {"_NormalMap", R::normal, false, "RGB", false},
    {"_HeightMap", R::height, false, "R", false},     {"_EmissiveColorMap", R::emissive, false, "RGB", true},
};
// Unity URP Lit (URP docs, "Lit Shader"): _BaseMap RGB + alpha; _MetallicGlossMap R metallic,
// A smoothness (_SmoothnessTextureChannel 0); _BumpMap; _OcclusionMap and _ParallaxMap are read
// from G by URP's shaders, the same as R in the grey one-channel files written for them;
// _EmissionMap colour.
constexpr EngineSlot kUrp[] = {
    {"_BaseMap", R::albedo, false, "RGB", true},
    {"_BaseMap", R::opacity, false, "A", true},
    {"_MetallicGlossMap", R::metalness, false, "R", false},
    {"_MetallicGlossMap", R::roughness, true, "A", false},
    {"_BumpMap", R::normal, false, "RGB", false},
    {"_OcclusionMap", R::occlusion, false, "R", false},
    {"_ParallaxMap", R::height, false, "R", false},
    {"_EmissionMap", R::emissive, false, "RGB", true},
};
// Unreal Engine (the import script's material instance, engine/unreal.cpp): BaseColor (sRGB,
// opacity in A), ORM packed R occlusion, G roughness, B metallic (TC_MASKS, no sRGB), Normal
// (TC_NORMALMAP, DirectX -Y), Emissive (sRGB), Height (R).
constexpr EngineSlot kUnreal[] = {
    {"BaseColor", R::albedo, false, "RGB", true},  {"BaseColor", R::opacity, false, "A", true},
    {"ORM", R::occlusion, false, "R", false},      {"ORM", R::roughness, false, "G", false},
    {"ORM", R::metalness, false, "B", false},      {"Normal", R::normal, false, "RGB", false},
    {"Emissive", R::emissive, false, "RGB", true}, {"Height", R::height, false, "R", false},
};
// Direct3D 11 (matforge_material.hlsli, engine/hlsl.cpp): Texture2D Albedo (sRGB view, opacity
// in A), NormalMap (BC5 X, Y; Z rebuilt), RoughnessMap and MetalnessMap (.r).
constexpr EngineSlot kD3d11[] = {
    {"Albedo", R::albedo, false, "RGB", true},         {"Albedo", R::opacity, false, "A", true},
    {"NormalMap", R::normal, false, "RGB", false},     {"RoughnessMap", R::roughness, false, "R", false},
    {"MetalnessMap", R::metalness, false, "R", false},
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

bool holds(const Channel& c, const EngineSlot& s) {
    return c.role == s.role &&
           ((c.kind == Channel::Kind::role && !s.smoothness) || (c.kind == Channel::Kind::smoothness && s.smoothness));
}

}  // namespace

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
        for (const EngineSlot& s : e.slots) {
            for (const ChannelSpec& c : o.channels) {
                if (!holds(c, s)) continue;
                const std::string what = "'" + o.suffix + "' holds " + std::string(role_name(s.role)) +
                                         (s.smoothness ? " (as smoothness)" : "") + " in " + c.key + "; ";
                if (s.slot != slot->slot) {
                    error = where + what + "the engine reads it from " + std::string(s.slot) + ", not " +
                            std::string(slot->slot);
                    return false;
                }
                if (c.key != s.key || o.srgb != s.srgb) {
                    error = where + what + std::string(s.slot) + " reads it from " + std::string(s.key) +
                            (s.srgb ? " as sRGB" : " as linear data");
                    return false;
                }
            }
        }
    }
    return true;
}

}  // namespace mf
