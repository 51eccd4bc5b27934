// The shading of one surface point, shared by both paths so that they cannot drift: shade.frag
// (raster: the hit from the mesh, or the analytic sphere) and shade.comp (compute: the hit by
// analytic ray intersection). Everything after the hit is here: material lookup, normal mapping,
// lights, image-based lighting, the BRDF, opacity over the background.
//
// Pipeline variants are made with specialization constants: what a material or scene does not
// call for is compiled out (no normal mapping without a normal map, no sampling for a constant
// role, a loop over the given lights only, no environment unless one is given).
#ifndef MF_SHADING_GLSL
#define MF_SHADING_GLSL

#include "common.glsl"
#include "brdf.glsl"

// Ids in interface.h (kSpec*); the renderer fills them by name (gpu::ShadeSpecialization).
layout(constant_id = kSpecNumDirectional) const int NUM_DIRECTIONAL = 1;
layout(constant_id = kSpecNumPoint) const int NUM_POINT = 0;
layout(constant_id = kSpecBrdfModel) const int BRDF_MODEL = kBrdfStandard;  // a kBrdf* value
layout(constant_id = kSpecAnalyticSphere) const bool ANALYTIC_SPHERE = true;
layout(constant_id = kSpecHasEnv) const bool HAS_ENV = false;
layout(constant_id = kSpecAlbedoTex) const int ALBEDO_TEX = -1;  // texture slot, or −1: constant
layout(constant_id = kSpecEmissiveTex) const int EMISSIVE_TEX = -1;
layout(constant_id = kSpecNormalTex) const int NORMAL_TEX = -1;
layout(constant_id = kSpecNormalGreenDown) const bool NORMAL_GREEN_DOWN = false;  // DirectX normal map
layout(constant_id = kSpecNormalZFromXy) const bool NORMAL_Z_FROM_XY = false;  // X, Y stored only (BC5)
layout(constant_id = kSpecGround) const bool GROUND = false;  // the ground plane: its own constant material
layout(constant_id = kSpecFillOnly) const bool FILL_ONLY = false;  // benchmarks: the fill-rate floor
layout(constant_id = kSpecMsaa) const bool MSAA = false;  // multisampled: shaded once a pixel
layout(constant_id = kSpecRoughnessTex) const int ROUGHNESS_TEX = -1;
layout(constant_id = kSpecRoughnessChannel) const int ROUGHNESS_CH = 0;
layout(constant_id = kSpecRoughnessInvert) const bool ROUGHNESS_INVERT = false;  // smoothness
layout(constant_id = kSpecMetalnessTex) const int METALNESS_TEX = -1;
layout(constant_id = kSpecMetalnessChannel) const int METALNESS_CH = 0;
layout(constant_id = kSpecMetalnessInvert) const bool METALNESS_INVERT = false;
layout(constant_id = kSpecOcclusionTex) const int OCCLUSION_TEX = -1;
layout(constant_id = kSpecOcclusionChannel) const int OCCLUSION_CH = 0;
layout(constant_id = kSpecOcclusionInvert) const bool OCCLUSION_INVERT = false;
layout(constant_id = kSpecOpacityTex) const int OPACITY_TEX = -1;
layout(constant_id = kSpecOpacityChannel) const int OPACITY_CH = 0;
layout(constant_id = kSpecOpacityInvert) const bool OPACITY_INVERT = false;
layout(constant_id = kSpecAlphaMode) const int ALPHA_MODE = kAlphaBlend;  // a kAlpha* value
layout(constant_id = kSpecDoubleSided) const bool DOUBLE_SIDED = false;

const bool NEEDS_LUT = HAS_ENV || BRDF_MODEL == kBrdfAccurate;

layout(set = kSetFrame, binding = kBindingBrdfLut) uniform sampler2D brdf_lut;  // brdf_lut.glsl: x √(n·v), y roughness
layout(set = kSetFrame, binding = kBindingEnvSpecular) uniform samplerCube env_specular;  // GGX-prefiltered, mip = roughness
layout(set = kSetFrame, binding = kBindingEnvIrradiance) uniform samplerCube env_irradiance;  // E(n)/π
layout(set = kSetMaterial, binding = kBindingMaterialTextures) uniform sampler2D textures[kMaxTextures];

// The BRDF table at (μ, roughness): (A, B) = scale and bias of F0, 1 − E(μ), 1 − E_avg.
vec4 brdf_table(float mu, float roughness) {
    return textureLod(brdf_lut, vec2(sqrt(clamp(mu, 0.0, 1.0)), roughness), 0.0);
}

// A point of the shape as either path finds it. `st` is the material's (u, v) as the image's
// texture coordinate (t = 1 − v: Vulkan's t = 0 is the first, top row), before tiling; st_dx and
// st_dy its change to the next pixel right and down (mip selection: explicit, because a compute
// shader has no implicit derivatives).
struct SurfacePoint {
    vec3 p;        // world position
    vec3 n;        // unit geometric normal
    vec3 t;        // tangent (∂p/∂u), not necessarily orthogonal to n
    float bsign;   // sign of the bitangent (toward +v)
    vec2 st, st_dx, st_dy;
    // The shape's far side, seen through a double-sided material: n, t and bsign are the
    // surface's own (outward), and the shading normal is reversed (glTF 2.0, 3.9.5: "back-face
    // must have its normals reversed before the lighting equation is evaluated").
    bool back;
};

vec4 sample_role(int slot, vec2 st, vec2 dx, vec2 dy) {
    return textureGrad(textures[max(slot, 0)], st, dx, dy);
}

float pick(vec4 t, int ch, bool invert) {
    float x = ch == 0 ? t.r : ch == 1 ? t.g : ch == 2 ? t.b : t.a;
    return invert ? 1.0 - x : x;
}

float scalar_role(int slot, int ch, bool invert, float constant, vec2 st, vec2 dx, vec2 dy) {
    if (slot < 0) return constant;
    return pick(sample_role(slot, st, dx, dy), ch, invert);
}

// Near (or with `far`, far) hit of the ray o + t·d (d unit) on the sphere of radius r at the
// origin, seen from outside; false on a miss. Ray Tracing Gems ch. 7 (Haines et al. 2019): the
// discriminant from the distance of the centre to the ray, and the roots as c / q and q, avoid
// both cancellations.
bool sphere_intersect(vec3 o, vec3 d, float r, bool far, out float t) {
    float b = dot(o, d);
    vec3 f = o - b * d;
    float disc = r * r - dot(f, f);
    t = 0.0;
    if (disc < 0.0) return false;
    float q = -b + sign(-b) * sqrt(disc);
    float c = dot(o, o) - r * r;
    t = far ? q : c / q;
    return true;
}

// (u, v) of three.js's sphere at unit normal n, as st: x = −cos 2πu sin πt, y = cos πt,
// z = sin 2πu sin πt, v = 1 − t.
vec2 sphere_st(vec3 n) {
    float u = atan(n.z, -n.x) * (0.5 / PI);
    u = u < 0.0 ? u + 1.0 : u;
    // atan2 rather than acos(n.y): GPUs' acos is a coarse approximation (1e-4 here moves a
    // normal-mapped highlight visibly against the reference).
    return vec2(u, atan(length(n.xz), n.y) / PI);
}

// The sphere's tangent ∂p/∂u ∝ (z, 0, −x); `pole` where it is undefined (at the poles).
vec3 sphere_tangent(vec3 n, vec3 pole) {
    vec2 xz = vec2(n.z, -n.x);
    return dot(xz, xz) > 1e-12 ? vec3(xz.x, 0.0, xz.y) : pole;
}

// The fraction of the key light (a disc of angular radius atan(frame.ground.w) around direction
// `l`) that the occluding sphere (frame.occluder) leaves visible from `p`: 1 where the ray toward
// the light passes the sphere by more than the disc's spread at that distance, 0 well inside,
// smooth in between (the penumbra widens with the distance to the occluder: a contact shadow is
// sharp at the contact and soft farther out).
float key_light_visibility(vec3 p, vec3 l) {
    vec3 to_centre = frame.occluder.xyz - p;
    float t = dot(to_centre, l);
    if (t <= 0.0) return 1.0;  // the sphere is behind the light's direction
    float miss = length(to_centre - t * l);
    float spread = t * frame.ground.w;
    return smoothstep(frame.occluder.w - spread, frame.occluder.w + spread, miss);
}

// The share of the hemisphere above `p` (normal `n`) hidden by the occluding sphere, cosine
// weighted: (R / D)² · cos θ for a sphere of radius R at distance D and angle θ from the normal
// (the exact form-factor of a sphere while it stays above the horizon).
float sphere_occlusion(vec3 p, vec3 n) {
    vec3 d = frame.occluder.xyz - p;
    float D2 = dot(d, d);
    float r = frame.occluder.w;
    return clamp(dot(n, d) * inversesqrt(D2) * r * r / D2, 0.0, 1.0);
}

// Linear radiance leaving `s` toward the camera (rgb) and the share of what lies behind it that
// the surface covers (a): its opacity as ALPHA_MODE applies it (glTF alphaMode: a mask is
// opaque at or above its cutoff and drops the rest; opaque ignores opacity).
vec4 shade_surface(SurfacePoint s) {
    vec3 p = s.p;
    vec3 n = s.n;
    vec3 t = normalize(s.t - n * dot(n, s.t));  // Gram-Schmidt: interpolation bends it off the normal
    // Tiling: a positive scale keeps the tangent frame's orientation (texels may repeat, never mirror).
    vec2 st = s.st * frame.uv.xy + frame.uv.zw;
    vec2 st_dx = s.st_dx * frame.uv.xy;
    vec2 st_dy = s.st_dy * frame.uv.xy;

    if (NORMAL_TEX >= 0) {
        vec3 b = cross(n, t) * s.bsign;  // toward +v
        vec3 tn = sample_role(NORMAL_TEX, st, st_dx, st_dy).xyz * 2.0 - 1.0;
        // BC5 keeps X and Y (its blue reads 0): the unit vector's Z is the rest of its length.
        if (NORMAL_Z_FROM_XY) tn.z = sqrt(max(1.0 - dot(tn.xy, tn.xy), 0.0));
        if (NORMAL_GREEN_DOWN) tn.y = -tn.y;
        vec3 mapped = t * tn.x + b * tn.y + n * tn.z;
        float len2 = dot(mapped, mapped);
        if (len2 > 1e-12) n = mapped * inversesqrt(len2);  // a zero texel keeps the surface normal
    }
    if (s.back) n = -n;  // the tangent frame reversed with it, as three.js's faceDirection does

    vec3 albedo = ALBEDO_TEX >= 0 ? sample_role(ALBEDO_TEX, st, st_dx, st_dy).rgb : frame.albedo.rgb;
    if (GROUND) {  // a grey dielectric, flat (its variant samples no texture)
        albedo = vec3(frame.ground.y);
        n = vec3(0.0, 1.0, 0.0);
    }
    vec3 emitted = EMISSIVE_TEX >= 0 ? sample_role(EMISSIVE_TEX, st, st_dx, st_dy).rgb * frame.emissive.w : frame.emissive.rgb;
    float roughness = scalar_role(ROUGHNESS_TEX, ROUGHNESS_CH, ROUGHNESS_INVERT, frame.scalars.x, st, st_dx, st_dy);
    float metalness = scalar_role(METALNESS_TEX, METALNESS_CH, METALNESS_INVERT, frame.scalars.y, st, st_dx, st_dy);
    float opacity = scalar_role(OPACITY_TEX, OPACITY_CH, OPACITY_INVERT, frame.scalars.w, st, st_dx, st_dy);
    if (GROUND) {
        emitted = vec3(0.0);
        roughness = frame.ground.z;
        metalness = 0.0;
        opacity = 1.0;
    }

    roughness = clamp(roughness, MIN_ROUGHNESS, 1.0);
    metalness = clamp(metalness, 0.0, 1.0);
    // Metalness workflow: F0 = lerp(0.04, albedo, metalness) (Karis 2013, p. 9); metals have no
    // diffuse lobe.
    vec3 f0 = mix(vec3(0.04), albedo, metalness);
    vec3 diffuse_color = albedo * (1.0 - metalness);
    float diffuse_norm = BRDF_MODEL == kBrdfUnnormalizedDiffuse ? 1.0 : Fd_Lambert();

    vec3 v = normalize(frame.camera_position.xyz - p);
    float NoV = clamp(dot(n, v), MIN_NOV, 1.0);

    // Accurate model only (brdf.glsl): the multiple-scattering lobe's per-pixel factor and
    // Fresnel, and the diffuse weight 1 − E_spec(n·v).
    vec3 ms_v = vec3(0.0), F_ms = vec3(0.0);
    vec3 diffuse_weight = vec3(1.0);
    vec4 dfg = vec4(1.0, 0.0, 0.0, 0.0);  // (A, B, 1 − E, 1 − E_avg) at (n·v, roughness)
    if (NEEDS_LUT) {
        dfg = brdf_table(NoV, roughness);
        if (BRDF_MODEL == kBrdfAccurate) {
            F_ms = multiscatter_fresnel(f0, dfg.w);
            ms_v = multiscatter_lobe(F_ms, dfg.z, dfg.w);
            diffuse_weight = accurate_diffuse_weight(f0, dfg.x, dfg.y, dfg.z, F_ms);
        }
    }

    vec3 color = vec3(0.0);
    for (int i = 0; i < NUM_DIRECTIONAL + NUM_POINT; ++i) {
        vec3 l;
        vec3 E = frame.lights[i].irradiance.rgb;
        if (i < NUM_DIRECTIONAL) {
            l = frame.lights[i].position.xyz;
        } else {
            vec3 to_light = frame.lights[i].position.xyz - p;
            float d2 = dot(to_light, to_light);
            if (d2 < 1e-12) continue;  // a light inside the surface has no direction
            l = to_light * inversesqrt(d2);
            E /= d2;
        }
        // The ground's contact shadow: the key light (the first directional one) behind the shape.
        if (GROUND && i == 0 && NUM_DIRECTIONAL > 0) E *= key_light_visibility(p, l);
        // 1 − E(n·l) for the multiple-scattering lobe: one more table fetch per light, accurate only.
        float lost_l = BRDF_MODEL == kBrdfAccurate ? brdf_table(dot(n, l), roughness).z : 0.0;
        color += brdf_light(BRDF_MODEL, n, v, l, NoV, roughness, f0, diffuse_color, ms_v, lost_l, diffuse_weight, E);
    }

    if (HAS_ENV) {
        float occlusion = scalar_role(OCCLUSION_TEX, OCCLUSION_CH, OCCLUSION_INVERT, frame.scalars.z, st, st_dx, st_dy);
        vec3 r = reflect(-v, n);
        vec3 prefiltered = textureLod(env_specular, r, roughness * frame.shape.z).rgb;
        vec3 irradiance = textureLod(env_irradiance, n, 0.0).rgb;  // one level; compute has no implicit lod
        // Split sum (Karis 2013): ∫ f L ≈ prefiltered(r, α) × (F0 · A + B).
        vec3 FssEss = f0 * dfg.x + dfg.y;
        vec3 ibl;
        if (BRDF_MODEL == kBrdfAccurate) {
            // The lights' multiple-scattering lobe under the environment: its albedo
            // F_ms (1 − E(n·v)) times the cosine-weighted radiance (Fdez-Agüera 2019, eq. 16,
            // with Kulla & Conty's F_ms as the lights have it), and the same diffuse weight.
            vec3 ms = F_ms * dfg.z;
            ibl = FssEss * prefiltered + (ms + diffuse_color * diffuse_weight) * irradiance;
        } else {
            // The diffuse lobe keeps what the specular lobe does not reflect. env_irradiance
            // holds E(n)/π, the radiance a white Lambertian surface reflects.
            vec3 kd = diffuse_color * (1.0 - FssEss);
            ibl = FssEss * prefiltered + kd * irradiance * (diffuse_norm * PI);
        }
        if (GROUND) occlusion = 1.0 - sphere_occlusion(p, n);
        color += ibl * occlusion * frame.shape.y;
    }

    color += emitted;
    if (ALPHA_MODE == kAlphaMask) opacity = opacity >= frame.alpha.x ? 1.0 : 0.0;
    if (ALPHA_MODE == kAlphaOpaque) opacity = 1.0;
    return vec4(color, clamp(opacity, 0.0, 1.0));
}

// Linear radiance toward the camera of a single-sided surface, over the background.
vec3 shade_point(SurfacePoint s) {
    vec4 c = shade_surface(s);
    return mix(frame.background.rgb, c.rgb, c.a);
}

#endif
