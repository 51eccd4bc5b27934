// The preview's BRDF, one small function per term. Its CPU twin, written from the papers'
// formulas in double precision, is tests/stability/brdf_reference.hpp (the oracle of the tests).
#ifndef MF_BRDF_GLSL
#define MF_BRDF_GLSL

#include "interface.h"  // kBrdfStandard, kBrdfAccurate, kBrdfUnnormalizedDiffuse

// Arithmetic type of the terms: fp32 (the preview), or binary16 where the includer enables
// GL_EXT_shader_explicit_arithmetic_types_float16 and defines MF_BRDF_FP16 (the accuracy harness,
// brdf_grid_f16.comp). Literals are written mf_float(…) because that extension converts float16_t
// to float implicitly but not the other way; in fp32 mf_float(x) is x.
#ifdef MF_BRDF_FP16
#define mf_float float16_t
#define mf_vec3 f16vec3
#else
#define mf_float float
#define mf_vec3 vec3
#endif

const float PI = 3.14159265358979323846;

// Smallest perceptual roughness. A point light reflected by a perfect mirror is a Dirac peak;
// 0.045 (Filament's floor for fp32) gives α² ≈ 4.1e-6 and a finite peak
// D = 1/(πα²) ≈ 7.7e4, well inside fp32 (a floor of 1e-6 on α² instead gives 3.2e5, which
// overflows half floats, whose maximum is 65504).
const float MIN_ROUGHNESS = 0.045;
// N·V floor: a normal map can tilt n away from the viewer; the BRDF's 1/(N·V) must stay finite.
const float MIN_NOV = 1e-4;

// GGX / Trowbridge-Reitz normal distribution.
// Walter et al. 2007, "Microfacet Models for Refraction through Rough Surfaces", eq. 33:
// D = α² / (π ((n·h)²(α² − 1) + 1)²), written as (α / ((n·h)²α² + |n×h|²))² / π:
// 1 − (n·h)² = |n×h|² (Lagrange's identity) keeps its precision where n·h → 1, which is where
// a smooth surface's highlight is (Filament, "Physically Based Rendering in Filament", 4.4.1).
mf_float D_GGX(mf_float NoH, mf_vec3 n_cross_h, mf_float alpha) {
    mf_float a = NoH * alpha;
    mf_float k = alpha / (dot(n_cross_h, n_cross_h) + a * a);
    return k * k * mf_float(1.0 / PI);
}

// Fresnel reflectance, Schlick's approximation.
// Schlick 1994, "An Inexpensive BRDF Model for Physically-based Rendering", eq. 15.
// F0 is a color, not a scalar: metals tint their reflection.
mf_vec3 F_Schlick(mf_vec3 f0, mf_float VoH) {
    mf_float m = mf_float(1.0) - VoH;
    mf_float m2 = m * m;
    return f0 + (mf_float(1.0) - f0) * (m2 * m2 * m);
}

// Schlick-GGX masking-shadowing for punctual lights, as the visibility term
// V = G / (4 (n·l)(n·v)). G1(x) = x / (x (1 − k) + k) (Schlick 1994, eq. 19: the denominator
// adds k, so G1(1) = 1) with k = (r + 1)² / 8 (Karis 2013, "Real Shading in Unreal Engine 4",
// p. 3: the remap for analytic lights only; image-based lighting uses k = α/2, brdf_lut.glsl).
// The numerators n·l and n·v cancel against the denominator and are left out of both.
mf_float V_SchlickGGX_k(mf_float NoV, mf_float NoL, mf_float k) {
    return mf_float(0.25) / ((NoL * (mf_float(1.0) - k) + k) * (NoV * (mf_float(1.0) - k) + k));
}
mf_float V_SchlickGGX(mf_float NoV, mf_float NoL, mf_float roughness) {
    return V_SchlickGGX_k(NoV, NoL, (roughness + mf_float(1.0)) * (roughness + mf_float(1.0)) / mf_float(8.0));
}

// Height-correlated Smith masking-shadowing for GGX, as V = G / (4 (n·l)(n·v)).
// Heitz 2014, "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs", eq. 99.
mf_float V_SmithGGXCorrelated(mf_float NoV, mf_float NoL, mf_float alpha) {
    mf_float a2 = alpha * alpha;
    mf_float lv = NoL * sqrt(NoV * NoV * (mf_float(1.0) - a2) + a2);
    mf_float ll = NoV * sqrt(NoL * NoL * (mf_float(1.0) - a2) + a2);
    return mf_float(0.5) / (lv + ll);
}

// Lambert diffuse: albedo / π. The 1/π is what makes a white surface under irradiance E
// reflect radiance E/π, conserving energy; kBrdfUnnormalizedDiffuse leaves it out (diffuse π
// times too strong against the specular lobe), for comparison with engines that do.
mf_float Fd_Lambert() {
    return mf_float(1.0 / PI);
}


// Multiple scattering of the specular lobe, as a lobe of its own (Kulla & Conty 2017,
// "Revisiting Physically Based Shading at Imageworks", slides 18-21). Single-scattering GGX
// loses the energy 1 − E(μ) of light that bounces between microfacets; E(μ, α) = A + B is the
// lobe's directional albedo with F = 1, E_avg(α) = 2 ∫ E(μ) μ dμ its cosine-weighted average.
// The lobe
//   f_ms(v, l) = F_ms (1 − E(n·v)) (1 − E(n·l)) / (π (1 − E_avg))
// reflects exactly 1 − E(n·v) for F = 1 (the white furnace stays at 1) and, unlike scaling the
// single-scattering lobe by 1 + F0 (1/E − 1) (Turquin 2019, this model's form before), spreads
// the returned energy as broadly as the random walk does (docs/accuracy/pathtracer.md).
// The tables hold the losses 1 − E and 1 − E_avg themselves (channels b, a of the BRDF table),
// accumulated as such: on smooth surfaces E is within 1e-5 of 1, and 1 − E formed from an fp32 E
// keeps two significant digits (it moved the radiance by 1e-3 relative).
// F_ms: the lobe's Fresnel, every bounce's F replaced by Schlick's hemispherical average
// F_avg = F0 + (1 − F0)/21 and the bounces summed: F_avg² E_avg / (1 − F_avg (1 − E_avg)).
mf_vec3 multiscatter_fresnel(mf_vec3 f0, mf_float lost_avg) {
    mf_vec3 F_avg = f0 + (mf_float(1.0) - f0) * mf_float(1.0 / 21.0);
    return F_avg * F_avg * (mf_float(1.0) - lost_avg) / (mf_float(1.0) - F_avg * lost_avg);
}

// The per-pixel factor of f_ms: F_ms (1 − E(n·v)) / (π (1 − E_avg)); brdf_light() multiplies it by
// 1 − E(n·l). 1 − E_avg is floored at 1e-4, which only roughness below 0.1 reaches: there
// 1 − E(n·v) is as small, and the floor takes less than 1e-4 of the light away while keeping the
// quotient finite (also in binary16, whose smallest normal number is 6.1e-5).
mf_vec3 multiscatter_lobe(mf_vec3 F_ms, mf_float lost_v, mf_float lost_avg) {
    return F_ms * (lost_v * mf_float(1.0 / PI) / max(lost_avg, mf_float(1e-4)));
}

// The accurate model's weight of the diffuse lobe: one minus the directional albedo of the whole
// specular lobe toward the viewer, 1 − E_spec(n·v), E_spec = F0 A + B + F_ms (1 − E) (single
// scattering with Schlick's F, Karis 2013, plus f_ms's albedo). This is albedo scaling (Kulla &
// Conty 2017; as Blender 4's Principled BSDF and OpenPBR): the diffuse lobe gets exactly the
// energy the specular lobe does not reflect, so a white dielectric under uniform light reflects
// 1 at every n·v, where the per-light weight 1 − F(v·h) loses 2 % on rough surfaces and adds up
// to 40 % at grazing views on smooth ones (docs/accuracy/pathtracer.md). The environment's
// diffuse in shading.glsl has the same weight, so lights and environment share one diffuse
// weighting. It depends on n·v only (not reciprocal): one value per pixel.
mf_vec3 accurate_diffuse_weight(mf_vec3 f0, mf_float A, mf_float B, mf_float lost_v, mf_vec3 F_ms) {
    return mf_float(1.0) - (f0 * A + B) - F_ms * lost_v;
}

// One punctual light's reflected radiance (f_d + f_s) E (n·l): the body of shade.frag's light
// loop, here so that the preview and the accuracy harness (brdf_grid.comp) run the same code.
// n, v, l unit; NoV = clamp(n·v, MIN_NOV, 1); roughness in [MIN_ROUGHNESS, 1]; f0 = lerp(0.04,
// albedo, metalness) (Karis 2013, p. 9); diffuse_color = albedo (1 − metalness); accurate model
// only (the others ignore them): ms_v = multiscatter_lobe() at this pixel, lost_l = 1 − E(n·l)
// from the table, diffuse_weight = accurate_diffuse_weight() (the other models weight the diffuse lobe by
// 1 − F(v·h)); E the light's irradiance at normal incidence.
mf_vec3 brdf_light(int model, mf_vec3 n, mf_vec3 v, mf_vec3 l, mf_float NoV, mf_float roughness, mf_vec3 f0,
                   mf_vec3 diffuse_color, mf_vec3 ms_v, mf_float lost_l, mf_vec3 diffuse_weight, mf_vec3 E) {
    mf_float NoL = dot(n, l);
    // Also rejects NaN: NaN × 0 = NaN would survive a max(n·l, 0) clamp.
    if (!(NoL > mf_float(0.0))) return mf_vec3(0.0);
    NoL = min(NoL, mf_float(1.0));
    mf_float alpha = roughness * roughness;
    mf_float diffuse_norm = model == kBrdfUnnormalizedDiffuse ? mf_float(1.0) : Fd_Lambert();
    // Half vector normalize(v + l), not (v + l)/2 (which is not unit length). For v = −l it has
    // no direction: there is no mirror configuration, so no specular reflection, and the diffuse
    // lobe keeps its normal-incidence weight 1 − F0 (accurate: 1 − E_spec, as for any l). With
    // n·l > 0 this needs n·v < 0, i.e. a normal map bent away from the viewer; a fallback h = n
    // would put D's peak (~1e5 E with the N·V floor) exactly there. The cut-off is
    // |v + l|² ≤ 1e-30, as the CPU reference: a wider one (1e-12) replaced a well-defined h for
    // nearly opposite v and l at grazing angles (measured by tests/render/brdf_grid_test.cpp:
    // 1.5e4 · E against 2e-6 · E).
    mf_vec3 hv = v + l;
    mf_float hlen2 = dot(hv, hv);
    bool has_h = hlen2 > mf_float(1e-30);
    mf_vec3 h = has_h ? hv * inversesqrt(hlen2) : n;
    mf_float NoH = clamp(dot(n, h), mf_float(0.0), mf_float(1.0));
    mf_float VoH = has_h ? clamp(dot(v, h), mf_float(0.0), mf_float(1.0)) : mf_float(1.0);
    mf_vec3 F = F_Schlick(f0, VoH);
    mf_float D = D_GGX(NoH, cross(n, h), alpha);
    mf_float V = model == kBrdfAccurate ? V_SmithGGXCorrelated(NoV, NoL, alpha)
                                        : V_SchlickGGX(NoV, NoL, roughness);
    // A select, not a product: D at the fallback h may overflow in fp16, and inf × 0 = NaN.
    mf_vec3 specular = has_h ? (D * V) * F : mf_vec3(0.0);
    // The multiple-scattering lobe has no half vector: it is there for v = −l too.
    if (model == kBrdfAccurate) specular += ms_v * lost_l;
    // Energy left to the diffuse lobe: (1 − F)(1 − metalness); accurate: (1 − E_spec(n·v)) ×
    // (1 − metalness).
    mf_vec3 kd = model == kBrdfAccurate ? diffuse_weight : mf_float(1.0) - F;
    mf_vec3 diffuse = kd * diffuse_color * diffuse_norm;
    return (diffuse + specular) * E * NoL;
}

#endif
