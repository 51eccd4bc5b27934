#version 460
// One material, the scene's lights, optionally image-based lighting. Pipeline variants are
// made with specialization constants: what a material or scene does not call for is compiled
// out (no normal mapping without a normal map, no sampling for a constant role, a loop over the
// given lights only, no environment unless one is given).
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

const bool NEEDS_LUT = HAS_ENV || BRDF_MODEL == kBrdfAccurate;

layout(set = kSetFrame, binding = kBindingBrdfLut) uniform sampler2D brdf_lut;  // (scale, bias) of F0; x: n·v, y: roughness
layout(set = kSetFrame, binding = kBindingEnvSpecular) uniform samplerCube env_specular;  // GGX-prefiltered, mip = roughness
layout(set = kSetFrame, binding = kBindingEnvIrradiance) uniform samplerCube env_irradiance;  // E(n)/π
layout(set = kSetMaterial, binding = kBindingMaterialTextures) uniform sampler2D textures[kMaxTextures];

layout(location = 0) in vec3 v_position;
layout(location = 1) in vec3 v_normal;
layout(location = 2) in vec4 v_tangent;
layout(location = 3) in vec2 v_uv;
// On the mesh within the covered samples (the pixel's centre may lie off it at a silhouette).
layout(location = kVaryingCentroidPosition) centroid in vec3 v_position_centroid;

layout(location = 0) out vec4 out_radiance;

// Texture coordinate of the image: the material's (u, v) has v = 0 at the bottom row, Vulkan's
// t = 0 is the first (top) row.
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

// Exact hit on the sphere of the primary ray through this pixel's centre. The mesh (three.js
// UV sphere) decides coverage; position, normal, (u, v) and tangent frame come from the sphere
// itself, so shading has no faceting and matches an analytic reference. Returns false when the
// ray misses (only possible at the silhouette, in the last bits of precision).
//
// Multisampled, the shader runs once for all covered samples of a pixel, whose centre may lie
// outside the sphere at the silhouette: the ray goes through the centroid of the covered samples
// on the mesh instead, which lies within the sphere (the mesh's triangles are chords of it), so
// it always hits.
bool sphere_hit(out vec3 p) {
    vec3 o = frame.camera_position.xyz;
    vec3 d;
    if (MSAA) {
        d = normalize(v_position_centroid - o);
    } else {
        vec2 ndc = gl_FragCoord.xy * frame.viewport.zw * 2.0 - 1.0;  // y grows downward
        d = normalize(frame.ray_forward.xyz + ndc.x * frame.ray_right.xyz - ndc.y * frame.ray_up.xyz);
    }
    float r = frame.shape.x;
    // Ray Tracing Gems ch. 7 (Haines et al. 2019): the discriminant from the distance of the
    // centre to the ray, and the near root from c / q, avoid both cancellations.
    float b = dot(o, d);
    vec3 f = o - b * d;
    float disc = r * r - dot(f, f);
    if (disc < 0.0) return false;
    float q = -b + sign(-b) * sqrt(disc);
    float c = dot(o, o) - r * r;
    float t = c / q;
    p = o + t * d;
    return true;
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

void main() {
    if (FILL_ONLY) {
        out_radiance = vec4(frame.albedo.rgb, 1.0);
        return;
    }
    // Gradients of the mesh's (u, v): continuous across the seam at u = 0|1, unlike the
    // analytic u, so the sampler picks the right mip everywhere.
    vec2 st = vec2(v_uv.x, 1.0 - v_uv.y);
    vec2 st_dx = dFdx(st), st_dy = dFdy(st);

    vec3 p = v_position;
    vec3 n = normalize(v_normal);
    vec3 t = v_tangent.xyz;
    float bsign = v_tangent.w;
    if (ANALYTIC_SPHERE) {
        vec3 hit;
        if (sphere_hit(hit)) {
            p = hit;
            n = normalize(hit);
            // (u, v) of three.js's sphere: x = −cos 2πu sin πt, y = cos πt, z = sin 2πu sin πt,
            // v = 1 − t. The tangent ∂p/∂u ∝ (z, 0, −x) is undefined at the poles: keep the
            // mesh's there.
            float u = atan(n.z, -n.x) * (0.5 / PI);
            u = u < 0.0 ? u + 1.0 : u;
            // atan2 rather than acos(n.y): GPUs' acos is a coarse approximation (1e-4 here
            // moves a normal-mapped highlight visibly against the reference).
            float tt = atan(length(n.xz), n.y) / PI;
            st = vec2(u, tt);
            vec2 xz = vec2(n.z, -n.x);
            if (dot(xz, xz) > 1e-12) t = vec3(xz.x, 0.0, xz.y);
            bsign = 1.0;
        }
    }
    t = normalize(t - n * dot(n, t));  // Gram-Schmidt: interpolation bends it off the normal
    // Tiling: a positive scale keeps the tangent frame's orientation (texels may repeat, never mirror).
    st = st * frame.uv.xy + frame.uv.zw;
    st_dx *= frame.uv.xy;
    st_dy *= frame.uv.xy;

    if (NORMAL_TEX >= 0) {
        vec3 b = cross(n, t) * bsign;  // toward +v
        vec3 tn = sample_role(NORMAL_TEX, st, st_dx, st_dy).xyz * 2.0 - 1.0;
        // BC5 keeps X and Y (its blue reads 0): the unit vector's Z is the rest of its length.
        if (NORMAL_Z_FROM_XY) tn.z = sqrt(max(1.0 - dot(tn.xy, tn.xy), 0.0));
        if (NORMAL_GREEN_DOWN) tn.y = -tn.y;
        vec3 mapped = t * tn.x + b * tn.y + n * tn.z;
        float len2 = dot(mapped, mapped);
        if (len2 > 1e-12) n = mapped * inversesqrt(len2);  // a zero texel keeps the surface normal
    }

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

    vec3 spec_scale = vec3(1.0);
    vec3 diffuse_weight = vec3(1.0);  // accurate only: 1 − E_spec(n·v), see brdf.glsl
    vec2 dfg = vec2(1.0, 0.0);
    if (NEEDS_LUT) {
        dfg = textureLod(brdf_lut, vec2(NoV, roughness), 0.0).xy;
        if (BRDF_MODEL == kBrdfAccurate) {
            spec_scale = energy_compensation(f0, dfg.x + dfg.y);
            diffuse_weight = accurate_diffuse_weight(f0, dfg.x, dfg.y, spec_scale);
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
        color += brdf_light(BRDF_MODEL, n, v, l, NoV, roughness, f0, diffuse_color, spec_scale, diffuse_weight, E);
    }

    if (HAS_ENV) {
        float occlusion = scalar_role(OCCLUSION_TEX, OCCLUSION_CH, OCCLUSION_INVERT, frame.scalars.z, st, st_dx, st_dy);
        vec3 r = reflect(-v, n);
        vec3 prefiltered = textureLod(env_specular, r, roughness * frame.shape.z).rgb;
        vec3 irradiance = texture(env_irradiance, n).rgb;
        // Split sum (Karis 2013): ∫ f L ≈ prefiltered(r, α) × (F0 · A + B).
        vec3 FssEss = f0 * dfg.x + dfg.y;
        vec3 ibl;
        if (BRDF_MODEL == kBrdfAccurate) {
            // Fdez-Agüera 2019, eqs. 11-16: multiple scattering for the split sum.
            float Ess = dfg.x + dfg.y;
            float Ems = 1.0 - Ess;
            vec3 Favg = f0 + (1.0 - f0) / 21.0;
            vec3 Fms = FssEss * Favg / (1.0 - Ems * Favg);
            vec3 kd = diffuse_color * (1.0 - FssEss - Fms * Ems);
            ibl = FssEss * prefiltered + (Fms * Ems + kd) * irradiance;
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
    out_radiance = vec4(mix(frame.background.rgb, color, clamp(opacity, 0.0, 1.0)), 1.0);
}
