// matforge_material.hlsli: what a Direct3D 11 engine includes to shade the `d3d11` preset's
// materials (written once per output folder by `matforge ingest --preset d3d11`).
//
// The textures, as the preset writes them (DDS with the DX10 header and full mip chains; load
// each with DirectXTK's CreateDDSTextureFromFile):
//   Albedo        BC1 (BC3 with opacity in A), *_SRGB: bind an sRGB view, the sampler returns linear
//   NormalMap     BC5 (X, Y), DirectX convention (green down); Z is rebuilt here
//   RoughnessMap  BC4, perceptual roughness in .r (linear)
//   MetalnessMap  BC4, metalness in .r (linear; a 4x4 constant when the set has none)
//
// The BRDF is the corrected Cook-Torrance of matforge's docs/shading.md (the preview's
// kBrdfStandard, lib/render/shaders/brdf.glsl), one function per term, each citing its source.
// Checked here by glslang's HLSL front end (compiled to SPIR-V) and by running these functions on
// the GPU against the same CPU oracle as the GLSL ones (tests/render/brdf_grid_test.cpp); no
// D3D compiler (fxc, dxc) runs on the machines that test it.
#ifndef MATFORGE_MATERIAL_HLSLI
#define MATFORGE_MATERIAL_HLSLI

static const float MF_PI = 3.14159265358979323846;
// Smallest perceptual roughness: a finite highlight peak D = 1/(pi a^2) ~ 7.7e4 (Filament's floor).
static const float MF_MIN_ROUGHNESS = 0.045;
// N.V floor: a normal map can tilt n away from the viewer; V has 1/(N.V) in it.
static const float MF_MIN_NOV = 1e-4;

// ---- Sampling the preset's textures

// Tangent-space normal from the BC5 NormalMap (X, Y in [0, 1]); DirectX maps store +Y down, so
// green is negated to get the frame's +Y (toward +v). Z = sqrt(1 - x^2 - y^2), clamped where
// block compression pushed x^2 + y^2 past 1.
float3 mf_normal_ts(float2 xy01) {
    float2 xy = xy01 * 2.0 - 1.0;
    xy.y = -xy.y;
    return float3(xy, sqrt(saturate(1.0 - dot(xy, xy))));
}

// The tangent-space normal to world space in the frame (T, B, N); a zero vector keeps N.
float3 mf_normal_ws(float3 n_ts, float3 T, float3 B, float3 N) {
    float3 n = n_ts.x * T + n_ts.y * B + n_ts.z * N;
    float len2 = dot(n, n);
    return len2 > 1e-30 ? n * rsqrt(len2) : N;
}

struct MfSurface {
    float3 albedo;     // linear (the sRGB view decoded it)
    float opacity;     // Albedo.a (1 for BC1)
    float3 n;          // world-space unit normal
    float roughness;   // perceptual, clamped to [MF_MIN_ROUGHNESS, 1]
    float metalness;   // [0, 1]
};

// Samples the four textures at uv (one sampler: trilinear or anisotropic, wrap).
MfSurface mf_sample(Texture2D albedo_map, Texture2D normal_map, Texture2D roughness_map, Texture2D metalness_map,
                    SamplerState s, float2 uv, float3 T, float3 B, float3 N) {
    MfSurface o;
    float4 a = albedo_map.Sample(s, uv);
    o.albedo = a.rgb;
    o.opacity = a.a;
    o.n = mf_normal_ws(mf_normal_ts(normal_map.Sample(s, uv).rg), T, B, N);
    o.roughness = clamp(roughness_map.Sample(s, uv).r, MF_MIN_ROUGHNESS, 1.0);
    o.metalness = saturate(metalness_map.Sample(s, uv).r);
    return o;
}

// ---- The BRDF terms (docs/shading.md)

// GGX / Trowbridge-Reitz distribution. Walter et al. 2007, "Microfacet Models for Refraction
// through Rough Surfaces", eq. 33, written as (a / ((n.h)^2 a^2 + |n x h|^2))^2 / pi, which keeps
// its precision where n.h -> 1 (Filament, "Physically Based Rendering in Filament", 4.4.1).
float mf_D_GGX(float NoH, float3 n_cross_h, float alpha) {
    float a = NoH * alpha;
    float k = alpha / (dot(n_cross_h, n_cross_h) + a * a);
    return k * k * (1.0 / MF_PI);
}

// Fresnel, Schlick 1994, "An Inexpensive BRDF Model for Physically-based Rendering", eq. 15;
// F0 is a colour (metals tint their reflection).
float3 mf_F_Schlick(float3 f0, float VoH) {
    float m = 1.0 - VoH;
    float m2 = m * m;
    return f0 + (1.0 - f0) * (m2 * m2 * m);
}

// Schlick-GGX masking-shadowing as the visibility V = G / (4 (n.l)(n.v)), G1(x) = x / (x (1 - k) + k)
// (Schlick 1994, eq. 19) with k = (r + 1)^2 / 8 for punctual lights (Karis 2013, "Real Shading in
// Unreal Engine 4", p. 3); n.l and n.v cancel against the denominator.
float mf_V_SchlickGGX(float NoV, float NoL, float roughness) {
    float k = (roughness + 1.0) * (roughness + 1.0) / 8.0;
    return 0.25 / ((NoL * (1.0 - k) + k) * (NoV * (1.0 - k) + k));
}

// Lambert diffuse, albedo / pi: a white surface under irradiance E reflects E / pi.
float mf_Fd_Lambert() {
    return 1.0 / MF_PI;
}

// One punctual light's reflected radiance (f_d + f_s) E (n.l) at a surface: n, v, l unit, E the
// light's irradiance at normal incidence (colour x intensity; / d^2 for a point light).
// f0 = lerp(0.04, albedo, metalness), diffuse colour albedo (1 - metalness) (Karis 2013, p. 9);
// the diffuse lobe weighted by (1 - F) so the two lobes never exceed the incoming light.
float3 mf_brdf_light(MfSurface s, float3 v, float3 l, float3 E) {
    float3 n = s.n;
    float NoL = dot(n, l);
    if (!(NoL > 0.0)) return float3(0.0, 0.0, 0.0);  // also rejects NaN
    NoL = min(NoL, 1.0);
    float NoV = clamp(dot(n, v), MF_MIN_NOV, 1.0);
    float roughness = clamp(s.roughness, MF_MIN_ROUGHNESS, 1.0);
    float metalness = saturate(s.metalness);
    float3 albedo = saturate(s.albedo);
    float3 f0 = lerp(float3(0.04, 0.04, 0.04), albedo, metalness);
    float alpha = roughness * roughness;
    // h = normalize(v + l); v = -l has no mirror configuration: no specular, diffuse weight 1 - F0.
    float3 hv = v + l;
    float hlen2 = dot(hv, hv);
    bool has_h = hlen2 > 1e-30;
    float3 h = has_h ? hv * rsqrt(hlen2) : n;
    float NoH = saturate(dot(n, h));
    float VoH = has_h ? saturate(dot(v, h)) : 1.0;
    float3 F = mf_F_Schlick(f0, VoH);
    float3 specular = has_h ? (mf_D_GGX(NoH, cross(n, h), alpha) * mf_V_SchlickGGX(NoV, NoL, roughness)) * F
                            : float3(0.0, 0.0, 0.0);
    float3 diffuse = (1.0 - F) * (albedo * (1.0 - metalness)) * mf_Fd_Lambert();
    return (diffuse + specular) * E * NoL;
}

#endif  // MATFORGE_MATERIAL_HLSLI
