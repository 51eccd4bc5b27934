// Unity (HDRP Lit, URP Lit): a .meta beside each texture (TextureImporter) and
// <material>/<material>.mat with its own .meta (NativeFormatImporter).
//
// Sources (docs/engines.md): Unity's TextureImporter and Material YAML as real projects commit
// them (fileFormatVersion 2, TextureImporter serializedVersion 12, Material serializedVersion 8,
// m_TexEnvs {fileID: 2800000, guid, type: 3}); the shaders' guids from their packages' .meta
// files (HDRP Lit.shader 6e4ae4064600d784cac1e41a9e6f2e59, URP Lit.shader
// 933532a4fcc9baf4fa0491de14d08ed7); the keywords the shaders' GUIs set (HDRP LitGUI:
// _NORMALMAP, _NORMALMAP_TANGENT_SPACE, _MASKMAP, _EMISSIVE_COLOR_MAP, _HEIGHTMAP; URP LitGUI:
// _NORMALMAP, _METALLICSPECGLOSSMAP, _OCCLUSIONMAP, _EMISSION, _PARALLAXMAP).
//  - sRGBTexture is the slot's colour flag (1 on base colour and emission, 0 on every data map);
//    textureType 1 (Normal map) on the normal; alphaIsTransparency where the texture's A is the
//    opacity; maxTextureSize the texture's own size (Unity's default 2048 would halve a 4K map);
//  - a .meta Unity does not find complete is completed by Unity with its defaults; the fields
//    written are those that decide how the texture is read;
//  - the scalars that multiply the maps are 1 (URP _Smoothness multiplies the map's A; HDRP's
//    remaps run 0..1), the emissive colour is white times the set's emissive_strength.
#include <algorithm>
#include <filesystem>

#include "core/identifier.hpp"
#include "core/version.hpp"
#include "engine/engine.hpp"

namespace mf::engine {
namespace {

namespace fs = std::filesystem;

bool hdrp(const EngineMaterial& e) { return e.kind == MaterialFileKind::unity_hdrp; }

// HDRP's material version (its AssetVersion MonoBehaviour, version 13, as HDRP 14 and later
// save a Lit material beside it): without it HDRP's material post-processor takes the material
// for version 0 and runs every upgrade on import, rewriting the .mat (its manifest hash goes
// stale), one of which copies _Metallic into _MetallicRemapMax.
constexpr const char* kHdrpAssetVersion =
    "--- !u!114 &7421316734529413221\nMonoBehaviour:\n  m_ObjectHideFlags: 11\n"
    "  m_CorrespondingSourceObject: {fileID: 0}\n  m_PrefabInstance: {fileID: 0}\n  m_PrefabAsset: {fileID: 0}\n"
    "  m_GameObject: {fileID: 0}\n  m_Enabled: 1\n  m_EditorHideFlags: 0\n"
    "  m_Script: {fileID: 11500000, guid: da692e001514ec24dbc4cca1949ff7e8, type: 3}\n  m_Name: \n"
    "  m_EditorClassIdentifier: \n  version: 13\n  hdPluginSubTargetMaterialVersions:\n    m_Keys: []\n"
    "    m_Values: \n";

// A YAML scalar: plain when it is letters, digits, '_', '-', '.' and inner spaces (as Unity writes
// names), else double-quoted (string_literal: a YAML double-quoted scalar reads its escapes).
std::string yaml_scalar(const std::string& s) {
    const bool plain = !s.empty() && s.front() != ' ' && s.back() != ' ' && s.front() != '-' &&
                       std::all_of(s.begin(), s.end(), [](char c) {
                           return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                                  c == '_' || c == '-' || c == '.' || c == ' ';
                       });
    return plain ? s : string_literal(s);
}

// The next power of two at or above the texture's larger side, within Unity's 32..16384.
int max_texture_size(const manifest::Output& o) {
    int n = 32;
    while (n < std::max(o.width, o.height) && n < 16384) n *= 2;
    return n;
}

bool holds_opacity(const manifest::Output& o) {
    return std::any_of(o.channels.begin(), o.channels.end(), [](const Channel& c) {
        return c.key == "A" && c.kind == Channel::Kind::role && c.role == Role::opacity;
    });
}

// Whether the texture's A channel holds anything (opacity, smoothness, a constant): Unity keeps
// A only with alphaUsage 1 (From Input); 0 (None) drops it, and HDRP's mask map or URP's
// metallic map would then read smoothness 1 everywhere (what Unity's own samples' mask maps say).
bool has_alpha(const manifest::Output& o) {
    return std::any_of(o.channels.begin(), o.channels.end(), [](const Channel& c) { return c.key == "A"; });
}

std::string texture_meta(const std::string& guid, const manifest::Output& o, const EngineSlot& slot,
                         const manifest::Material& m) {
    const bool normal = slot.reads_role(Role::normal), alpha = holds_opacity(o);
    const std::string size = std::to_string(max_texture_size(o));
    using manifest::AlphaMode;
    const bool cutout = alpha && m.alpha_mode && *m.alpha_mode == AlphaMode::mask;
    return "fileFormatVersion: 2\nguid: " + guid +
           "\nTextureImporter:\n  internalIDToNameTable: []\n  externalObjects: {}\n  serializedVersion: 12\n"
           "  mipmaps:\n    mipMapMode: 0\n    enableMipMap: 1\n    sRGBTexture: " +
           (slot.srgb ? "1" : "0") +
           "\n    linearTexture: 0\n    fadeOut: 0\n    borderMipMap: 0\n    mipMapsPreserveCoverage: " +
           (cutout ? "1" : "0") + "\n    alphaTestReferenceValue: " + scene_number(cutout ? m.alpha_cutoff : 0.5f) +
           "\n    mipMapFadeDistanceStart: 1\n    mipMapFadeDistanceEnd: 3\n"
           "  bumpmap:\n    convertToNormalMap: 0\n    externalNormalMap: 0\n    heightScale: 0.25\n"
           "    normalMapFilter: 0\n    flipGreenChannel: 0\n"
           "  isReadable: 0\n  streamingMipmaps: 0\n  streamingMipmapsPriority: 0\n  grayScaleToAlpha: 0\n"
           "  generateCubemap: 6\n  cubemapConvolution: 0\n  seamlessCubemap: 0\n  textureFormat: 1\n"
           "  maxTextureSize: " +
           size +
           "\n  textureSettings:\n    serializedVersion: 2\n    filterMode: 1\n    aniso: 1\n    mipBias: 0\n"
           "    wrapU: 0\n    wrapV: 0\n    wrapW: 0\n  nPOTScale: 1\n  lightmap: 0\n  compressionQuality: 50\n"
           "  spriteMode: 0\n  alignment: 0\n  alphaUsage: " +
           (has_alpha(o) ? "1" : "0") + "\n  alphaIsTransparency: " + (alpha ? "1" : "0") +
           "\n  textureType: " + (normal ? "1" : "0") +
           "\n  textureShape: 1\n  singleChannelComponent: 0\n  maxTextureSizeSet: 0\n  compressionQualitySet: 0\n"
           "  textureFormatSet: 0\n  ignorePngGamma: 0\n  applyGammaDecoding: 0\n  platformSettings:\n"
           "  - serializedVersion: 3\n    buildTarget: DefaultTexturePlatform\n    maxTextureSize: " +
           size +
           "\n    resizeAlgorithm: 0\n    textureFormat: -1\n    textureCompression: 1\n    compressionQuality: 50\n"
           "    crunchedCompression: 0\n    allowsAlphaSplitting: 0\n    overridden: 0\n"
           "  userData: " +
           std::string(kGenerator) + " " + std::string(slot.slot) + "\n  assetBundleName: \n  assetBundleVariant: \n";
}

struct Props {
    std::vector<std::string> keywords;
    std::string tex, floats, colors;
    void texture(std::string_view name, const std::string& guid) {
        tex += "    - " + std::string(name) + ":\n        m_Texture: " +
               (guid.empty() ? "{fileID: 0}" : "{fileID: 2800000, guid: " + guid + ", type: 3}") +
               "\n        m_Scale: {x: 1, y: 1}\n        m_Offset: {x: 0, y: 0}\n";
    }
    void number(std::string_view name, float v) {
        floats += "    - " + std::string(name) + ": " + scene_number(v) + "\n";
    }
    void color(std::string_view name, float v, float a = 1.f) {
        const std::string x = scene_number(v);
        colors += "    - " + std::string(name) + ": {r: " + x + ", g: " + x + ", b: " + x + ", a: " + scene_number(a) +
                  "}\n";
    }
};

std::string material(const EngineMaterial& e, const manifest::Material& m, const std::vector<Bound>& bound,
                     const std::string& guid_prefix) {
    Props p;
    // Every slot, in the table's order: its texture (or none), and the keywords a texture turns on.
    bool emits = false;
    for (const EngineSlot& s : e.slots) {
        const manifest::Output* o = texture_of(bound, s.slot);
        p.texture(s.slot, o ? guid_of(guid_prefix + std::string(s.slot)) : "");
        if (!o) continue;
        emits = emits || s.reads_role(Role::emissive);
        for (size_t at = 0; at < s.enable.size();) {
            const size_t end = std::min(s.enable.find(' ', at), s.enable.size());
            p.keywords.emplace_back(s.enable.substr(at, end - at));
            at = end + 1;
        }
    }
    using manifest::AlphaMode;
    const bool cutout = m.alpha_mode && *m.alpha_mode == AlphaMode::mask;
    const bool blend = m.alpha_mode && *m.alpha_mode == AlphaMode::blend;
    const float emissive = m.emissive_strength;
    std::string shader, queue = cutout ? "2450" : blend ? "3000" : "-1";
    if (hdrp(e)) {
        shader = "6e4ae4064600d784cac1e41a9e6f2e59";
        p.number("_AlphaCutoff", m.alpha_cutoff);
        p.number("_AlphaCutoffEnable", cutout ? 1.f : 0.f);
        p.number("_AORemapMax", 1.f);
        p.number("_AORemapMin", 0.f);
        p.number("_DoubleSidedEnable", manifest::double_sided(m.alpha_mode) ? 1.f : 0.f);
        p.number("_EmissiveIntensity", emits ? emissive : 1.f);
        p.number("_Metallic", 1.f);
        p.number("_MetallicRemapMax", 1.f);
        p.number("_MetallicRemapMin", 0.f);
        p.number("_NormalScale", 1.f);
        p.number("_Smoothness", 1.f);
        p.number("_SmoothnessRemapMax", 1.f);
        p.number("_SmoothnessRemapMin", 0.f);
        p.number("_SurfaceType", blend ? 1.f : 0.f);
        p.color("_BaseColor", 1.f);
        p.color("_EmissiveColor", emits ? emissive : 0.f);
        p.color("_EmissiveColorLDR", emits ? 1.f : 0.f);
        if (cutout) p.keywords.emplace_back("_ALPHATEST_ON");
        if (manifest::double_sided(m.alpha_mode)) p.keywords.emplace_back("_DOUBLESIDED_ON");
        if (blend) p.keywords.emplace_back("_SURFACE_TYPE_TRANSPARENT");
    } else {
        shader = "933532a4fcc9baf4fa0491de14d08ed7";
        p.number("_AlphaClip", cutout ? 1.f : 0.f);
        p.number("_BumpScale", 1.f);
        p.number("_Cull", manifest::double_sided(m.alpha_mode) ? 0.f : 2.f);  // 0: off (both sides), 2: back
        p.number("_Cutoff", m.alpha_cutoff);
        p.number("_GlossMapScale", 1.f);
        p.number("_Metallic", 1.f);
        p.number("_OcclusionStrength", 1.f);
        p.number("_Parallax", 0.005f);
        p.number("_Smoothness", 1.f);
        p.number("_SmoothnessTextureChannel", 0.f);
        p.number("_Surface", blend ? 1.f : 0.f);
        p.number("_WorkflowMode", 1.f);
        p.number("_ZWrite", blend ? 0.f : 1.f);
        p.color("_BaseColor", 1.f);
        p.color("_EmissionColor", emits ? emissive : 0.f);
        if (cutout) p.keywords.emplace_back("_ALPHATEST_ON");
        if (blend) p.keywords.emplace_back("_SURFACE_TYPE_TRANSPARENT");
    }
    std::sort(p.keywords.begin(), p.keywords.end());
    std::string kw;
    for (const auto& k : p.keywords) kw += "\n  - " + k;
    return "%YAML 1.1\n%TAG !u! tag:unity3d.com,2011:\n--- !u!21 &2100000\nMaterial:\n  serializedVersion: 8\n"
           "  m_ObjectHideFlags: 0\n  m_CorrespondingSourceObject: {fileID: 0}\n  m_PrefabInstance: {fileID: 0}\n"
           "  m_PrefabAsset: {fileID: 0}\n  m_Name: " +
           yaml_scalar(m.name) + "\n  m_Shader: {fileID: 4800000, guid: " + shader +
           ", type: 3}\n  m_Parent: {fileID: 0}\n" +
           "  m_ModifiedSerializedProperties: 0\n  m_ValidKeywords:" + (kw.empty() ? " []" : kw) +
           "\n  m_InvalidKeywords: []\n  m_LightmapFlags: 4\n  m_EnableInstancingVariants: 0\n  m_DoubleSidedGI: 0\n"
           "  m_CustomRenderQueue: " +
           queue + "\n  stringTagMap:" +
           (blend    ? "\n    RenderType: Transparent"
            : cutout ? "\n    RenderType: TransparentCutout"
                     : " {}") +
           "\n  disabledShaderPasses: []\n  m_LockedProperties: \n  m_SavedProperties:\n    serializedVersion: 3\n"
           "    m_TexEnvs:\n" +
           p.tex + "    m_Ints: []\n    m_Floats:\n" + p.floats + "    m_Colors:\n" + p.colors +
           "  m_BuildTextureStacks: []\n  m_AllowLocking: 1\n" + (hdrp(e) ? std::string(kHdrpAssetVersion) : "");
}

}  // namespace

std::vector<File> unity_files(const EngineMaterial& e, const manifest::Material& m, const std::vector<Bound>& bound) {
    // Guids from the material's name and the slot: the same in every run, distinct per material.
    const std::string prefix = m.name + "/" + std::string(word(e.kind)) + "/";
    std::vector<File> files;
    files.reserve(bound.size() + 2);
    for (const Bound& b : bound)
        files.push_back({b.output->file + ".meta", "meta",
                         texture_meta(guid_of(prefix + std::string(b.slot->slot)), *b.output, *b.slot, m)});
    const std::string mat = m.name + "/" + m.name + ".mat";
    files.push_back({mat, "mat", material(e, m, bound, prefix)});
    files.push_back({mat + ".meta", "meta",
                     "fileFormatVersion: 2\nguid: " + guid_of(prefix + "material") +
                         "\nNativeFormatImporter:\n  externalObjects: {}\n  mainObjectFileID: 2100000\n"
                         "  userData: \n  assetBundleName: \n  assetBundleVariant: \n"});
    return files;
}

}  // namespace mf::engine
