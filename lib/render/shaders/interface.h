// The renderer's GPU interface, declared once for C++ and GLSL: uniform and push-constant
// layouts, array sizes, descriptor set and binding numbers, vertex input locations and the ids
// of the specialization constants. Shaders `#include "interface.h"`; C++ includes
// "render/shaders/interface.h" and finds everything in mf::render::gpu.
//
// The GLSL types used in the structs are aliased to plain arrays in C++ (vec4 → float[4], mat4
// → float[16], column-major like GLSL's), so a struct has the same bytes on both sides when
// every member sits at its natural std140 / std430 offset: only vec4, mat4 and 4-byte scalars
// (an uvec2 first) are used, and the C++ section checks the sizes.
#ifndef MF_RENDER_INTERFACE_H
#define MF_RENDER_INTERFACE_H

#ifdef __cplusplus
#include <array>
#include <compare>
#include <cstdint>

namespace mf::render::gpu {

using uint = uint32_t;
using uvec2 = uint32_t[2];
using vec4 = float[4];
using mat4 = float[16];

#define MF_CONST inline constexpr
#else
#define MF_CONST const
#endif

// ---- array sizes

MF_CONST int kMaxLights = 16;
MF_CONST int kMaxTextures = 8;   // material textures, one descriptor array
MF_CONST uint kTile = 8u;        // 2D compute passes run in kTile × kTile workgroups
MF_CONST uint kGridGroup = 64u;  // brdf_grid.glsl's 1D workgroup
MF_CONST int kEnergyTableSize = 32;  // brdf_grid.glsl's E(n·v, roughness) table side
// brdf_lut.glsl's table side (√(n·v) across, roughness down). One workgroup computes one row, so
// that the row's 1 − E_avg(roughness) goes into the table with it: at most 128 invocations (the
// least maxComputeWorkGroupInvocations Vulkan allows).
MF_CONST uint kBrdfLutSize = 128u;

// ---- descriptor sets and bindings

// The shading pipeline: set 0 per frame, set 1 per material.
MF_CONST int kSetFrame = 0;
MF_CONST int kBindingFrameData = 0;       // uniform FrameData
MF_CONST int kBindingBrdfLut = 1;         // sampler2D: (scale, bias) of F0; x: n·v, y: roughness
MF_CONST int kBindingEnvSpecular = 2;     // samplerCube: GGX-prefiltered, mip = roughness
MF_CONST int kBindingEnvIrradiance = 3;   // samplerCube: E(n)/π
MF_CONST int kSetMaterial = 1;
MF_CONST int kBindingMaterialTextures = 0;  // sampler2D[kMaxTextures]; a role's slot indexes it
// shade.comp only: the radiance target as a storage image, in encode.comp's set (bound again as
// set 2, binding kBindingEncodeRadiance), so the compute path needs no descriptors of its own.
MF_CONST int kSetShadeTarget = 2;

// encode.comp
MF_CONST int kBindingEncodeRadiance = 0;  // rgba32f storage image
MF_CONST int kBindingEncodePixels = 1;    // storage buffer of packed RGBA8

// The environment passes (env_to_cube, cube_downsample, prefilter, irradiance).
MF_CONST int kBindingIblSource = 0;  // sampled
MF_CONST int kBindingIblTarget = 1;  // rgba16f storage image, all six faces of one mip

// brdf_lut.glsl
MF_CONST int kBindingLut = 0;

// brdf_grid.glsl
MF_CONST int kBindingGridInputs = 0;
MF_CONST int kBindingGridOutputs = 1;
MF_CONST int kBindingGridEnergy = 2;

// ---- vertex inputs of shade.vert (interleaved, one binding)

MF_CONST int kLocationPosition = 0;
MF_CONST int kLocationNormal = 1;
MF_CONST int kLocationTangent = 2;  // xyz: ∂p/∂u; w: sign of the bitangent (toward +v)
MF_CONST int kLocationUv = 3;
// shade.vert → shade.frag: the position again, interpolated at the centroid of the covered samples
MF_CONST int kVaryingCentroidPosition = 4;

// ---- BRDF models (the values of the BRDF_MODEL and model constants)

MF_CONST int kBrdfStandard = 0;
MF_CONST int kBrdfAccurate = 1;
// Standard with Lambert's diffuse lacking its 1/π: π times too strong against the specular lobe,
// for comparison with engines that leave the 1/π out.
MF_CONST int kBrdfUnnormalizedDiffuse = 2;

// encode.comp's tone mappers (EncodeParams::tonemap; render::Tonemap in the same order).
MF_CONST int kTonemapNone = 0;     // radiance clipped at 1: exact, for reference scenes
MF_CONST int kTonemapNeutral = 1;  // Khronos PBR Neutral
MF_CONST int kTonemapAces = 2;     // ACES RRT + sRGB ODT, Hill's fit

// ---- specialization constant ids

// shade.frag: what a material and scene call for; the rest is compiled out.
MF_CONST int kSpecNumDirectional = 0;
MF_CONST int kSpecNumPoint = 1;
MF_CONST int kSpecBrdfModel = 2;
MF_CONST int kSpecAnalyticSphere = 3;
MF_CONST int kSpecHasEnv = 4;
MF_CONST int kSpecAlbedoTex = 5;  // *_TEX: a slot of the material's textures, or −1: constant
MF_CONST int kSpecEmissiveTex = 6;
MF_CONST int kSpecNormalTex = 7;
MF_CONST int kSpecNormalGreenDown = 8;
MF_CONST int kSpecRoughnessTex = 9;
MF_CONST int kSpecRoughnessChannel = 10;
MF_CONST int kSpecRoughnessInvert = 11;
MF_CONST int kSpecMetalnessTex = 12;
MF_CONST int kSpecMetalnessChannel = 13;
MF_CONST int kSpecMetalnessInvert = 14;
MF_CONST int kSpecOcclusionTex = 15;
MF_CONST int kSpecOcclusionChannel = 16;
MF_CONST int kSpecOcclusionInvert = 17;
MF_CONST int kSpecOpacityTex = 18;
MF_CONST int kSpecOpacityChannel = 19;
MF_CONST int kSpecOpacityInvert = 20;
MF_CONST int kSpecNormalZFromXy = 21;  // a two-channel normal map (BC5): Z rebuilt from X and Y
MF_CONST int kSpecGround = 22;         // this draw is the ground plane (Scene::ground), not the shape
MF_CONST int kSpecFillOnly = 23;       // write a constant and return: the fill-rate floor (Scene::fill_only)
MF_CONST int kSpecMsaa = 24;           // multisampled (Scene::msaa): the sphere's ray through the centroid
MF_CONST int kSpecShape = 25;          // shade.comp: the kShape* intersected by the primary rays
MF_CONST int kSpecSamples = 26;        // shade.comp: rays a pixel at the standard msaa positions (1, 2, 4, 8)
MF_CONST int kSpecAlphaMode = 27;      // a kAlpha* value: how opacity applies (render::AlphaMode)
MF_CONST int kSpecDoubleSided = 28;    // the far side shaded too, its normal reversed (glTF doubleSided)

// Shapes shade.comp intersects analytically (render::ShapeType in the same order).
MF_CONST int kAlphaBlend = 0;  // render::AlphaMode, as it is
MF_CONST int kAlphaMask = 1;
MF_CONST int kAlphaOpaque = 2;

MF_CONST int kShapeSphere = 0;
MF_CONST int kShapeCube = 1;
MF_CONST int kShapePlane = 2;

// brdf_lut.glsl
MF_CONST int kSpecLutCorrelated = 0;
MF_CONST int kSpecLutSamples = 1;

// brdf_grid.glsl
MF_CONST int kSpecGridMode = 0;
MF_CONST int kGridModeInputs = 0;  // one arbitrary input per invocation
MF_CONST int kGridModeSphere = 1;  // the accuracy benchmark's sphere

// ---- uniform and push-constant layouts

struct LightData {
    vec4 position;    // xyz: unit vector toward a directional light, or a point light's position
    vec4 irradiance;  // rgb: color × intensity (E at 1 m for a point light)
};

// Per frame, std140. Directional lights come first in `lights`, then point lights.
struct FrameData {
    mat4 view_proj;
    vec4 camera_position;
    vec4 ray_right;    // camera right × tan(yfov/2) × aspect: primary ray through a pixel
    vec4 ray_up;       // camera up × tan(yfov/2)
    vec4 ray_forward;  // unit view direction
    vec4 viewport;     // width, height, 1/width, 1/height
    vec4 background;   // rgb, linear
    vec4 albedo;       // rgb: constant albedo (linear) where the role has no texture
    vec4 emissive;     // rgb: constant emitted radiance; w: the emissive texture's strength
    vec4 scalars;      // constant roughness, metalness, occlusion, opacity
    vec4 shape;        // x: sphere radius; y: environment intensity; z: last prefiltered mip
    vec4 uv;           // xy: scale, zw: offset of the texture coordinates (tiling)
    vec4 ground;       // x: height of the ground plane; y: its albedo (grey); z: its roughness; w: tan of the key light's angular radius
    vec4 occluder;     // xyz: centre, w: radius of the shape's bounding sphere (the ground's shadow)
    vec4 alpha;        // x: the cutoff of a mask (kAlphaMask): opaque at or above, dropped below
    mat4 shape_rotation;  // the cube's turn, object to world (shade.comp intersects it in object space)
    LightData lights[kMaxLights];
};

// encode.comp's push constants.
struct EncodeParams {
    uvec2 size;
    float exposure;
    uint srgb;         // 1: IEC 61966-2-1 sRGB curve; 0: linear
    uint tonemap;      // kTonemap*: applied to the exposed radiance, before the transfer curve
    uint supersample;  // N: the radiance image holds N×N samples a pixel, averaged here
    uint floats;       // 1: write the averaged linear radiance as 4 floats a pixel (no encoding)
};

// The environment passes' push constants.
struct IblParams {
    uint size;        // destination face size in texels
    float roughness;  // prefilter: perceptual roughness of this mip
    uint samples;     // prefilter / irradiance: sample count
    float src_size;   // face size of the source cube's mip 0
};

// brdf_grid.glsl: one input (std430) and the push constants.
struct GridInput {
    vec4 n;       // w: roughness
    vec4 v;       // w: metalness
    vec4 l;       // w: intensity (irradiance at normal incidence)
    vec4 albedo;  // rgb
};
struct GridPush {
    uint count;  // inputs mode: inputs; sphere mode: pixels (width × height)
    uint width;  // sphere: image side
    uint spp;    // sphere: 1, 4 or 8
    int model;   // sphere: kBrdfStandard, kBrdfAccurate or kBrdfUnnormalizedDiffuse
};

// ---- export.comp (render/export.cpp): a sampled image read back as floats, one mip at a time

MF_CONST int kBindingExportSource = 0;  // sampler2DArray: a 2D image (1 layer) or a cube (6 layers)
MF_CONST int kBindingExportTexels = 1;  // storage buffer of vec4: layer by layer, rows top to bottom

struct ExportParams {
    uint width;   // of the mip read
    uint height;
    uint layers;
    uint mip;
};

#ifdef __cplusplus
static_assert(sizeof(LightData) == 32);
static_assert(sizeof(FrameData) == 2 * 64 + 14 * 16 + kMaxLights * sizeof(LightData), "std140 layout");
static_assert(sizeof(EncodeParams) == 28 && sizeof(IblParams) == 16 && sizeof(GridPush) == 16);
static_assert(sizeof(GridInput) == 64);
static_assert(sizeof(ExportParams) == 16);

// ---- specialization constant values (C++ only): one 4-byte field per constant (int32, or
// uint32 holding a VkBool32), mapped to its id by name where the pipeline is made, so adding a
// constant cannot shift the others.

// shade.frag; also the key of the renderer's pipeline cache.
struct ShadeSpecialization {
    int32_t num_directional = 0;
    int32_t num_point = 0;
    int32_t brdf_model = kBrdfStandard;
    uint32_t analytic_sphere = 0;
    uint32_t has_env = 0;
    int32_t albedo_tex = -1;
    int32_t emissive_tex = -1;
    int32_t normal_tex = -1;
    uint32_t normal_green_down = 0;
    int32_t roughness_tex = -1;
    int32_t roughness_channel = 0;
    uint32_t roughness_invert = 0;
    int32_t metalness_tex = -1;
    int32_t metalness_channel = 0;
    uint32_t metalness_invert = 0;
    int32_t occlusion_tex = -1;
    int32_t occlusion_channel = 0;
    uint32_t occlusion_invert = 0;
    int32_t opacity_tex = -1;
    int32_t opacity_channel = 0;
    uint32_t opacity_invert = 0;
    uint32_t normal_z_from_xy = 0;
    uint32_t ground = 0;
    uint32_t fill_only = 0;
    uint32_t msaa = 0;
    int32_t shape = kShapeSphere;
    int32_t samples = 1;
    int32_t alpha_mode = kAlphaBlend;
    uint32_t double_sided = 0;

    // The texture slots the variant samples (−1 where a role is a constant).
    std::array<int32_t, 7> texture_slots() const {
        return {albedo_tex, emissive_tex, normal_tex, roughness_tex, metalness_tex, occlusion_tex, opacity_tex};
    }
    friend auto operator<=>(const ShadeSpecialization&, const ShadeSpecialization&) = default;
};

// brdf_lut.glsl
struct LutSpecialization {
    uint32_t correlated = 0;  // VkBool32: the accurate BRDF's height-correlated Smith
    uint32_t samples = 0;
};

// brdf_grid.glsl
struct GridSpecialization {
    int32_t mode = kGridModeInputs;
};

}  // namespace mf::render::gpu
#endif

#undef MF_CONST
#endif
