// The preview's BRDF, one small function per term. The CPU reference in
// tests/render/reference.cpp is an independent double-precision implementation of the same.
#ifndef MF_BRDF_GLSL
#define MF_BRDF_GLSL

const float PI = 3.14159265358979323846;

// Smallest perceptual roughness. A point light reflected by a perfect mirror is a Dirac peak;
// 0.045 (Filament's floor for fp32) gives α² ≈ 4.1e-6 and a finite peak
// D = 1/(πα²) ≈ 7.7e4, well inside fp32 (the assignment's 1e-6 floor on α² gives 3.2e5, which
// overflows half floats: erratum 7).
const float MIN_ROUGHNESS = 0.045;
// N·V floor: a normal map can tilt n away from the viewer; the BRDF's 1/(N·V) must stay finite.
const float MIN_NOV = 1e-4;

// GGX / Trowbridge-Reitz normal distribution.
// Walter et al. 2007, "Microfacet Models for Refraction through Rough Surfaces", eq. 33:
// D = α² / (π ((n·h)²(α² − 1) + 1)²), written as (α / ((n·h)²α² + |n×h|²))² / π:
// 1 − (n·h)² = |n×h|² (Lagrange's identity) keeps its precision where n·h → 1, which is where
// a smooth surface's highlight is (Filament, "Physically Based Rendering in Filament", 4.4.1).
float D_GGX(float NoH, vec3 n_cross_h, float alpha) {
    float a = NoH * alpha;
    float k = alpha / (dot(n_cross_h, n_cross_h) + a * a);
    return k * k * (1.0 / PI);
}

// Fresnel reflectance, Schlick's approximation.
// Schlick 1994, "An Inexpensive BRDF Model for Physically-based Rendering", eq. 15.
// F0 is a color: metals tint their reflection (erratum 1 of the assignment).
vec3 F_Schlick(vec3 f0, float VoH) {
    float m = 1.0 - VoH;
    float m2 = m * m;
    return f0 + (1.0 - f0) * (m2 * m2 * m);
}

// Schlick-GGX masking-shadowing for punctual lights, as the visibility term
// V = G / (4 (n·l)(n·v)). G1(x) = x / (x (1 − k) + k) (Schlick 1994, eq. 19; denominator
// "+ k", erratum 3) with k = (r + 1)² / 8 (Karis 2013, "Real Shading in Unreal Engine 4",
// p. 3: the remap for analytic lights only; image-based lighting uses k = α/2, erratum 8).
// The numerators n·l and n·v cancel against the denominator and are left out of both.
float V_SchlickGGX_k(float NoV, float NoL, float k) {
    return 0.25 / ((NoL * (1.0 - k) + k) * (NoV * (1.0 - k) + k));
}
float V_SchlickGGX(float NoV, float NoL, float roughness) {
    return V_SchlickGGX_k(NoV, NoL, (roughness + 1.0) * (roughness + 1.0) / 8.0);
}

// Height-correlated Smith masking-shadowing for GGX, as V = G / (4 (n·l)(n·v)).
// Heitz 2014, "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs", eq. 99.
float V_SmithGGXCorrelated(float NoV, float NoL, float alpha) {
    float a2 = alpha * alpha;
    float lv = NoL * sqrt(NoV * NoV * (1.0 - a2) + a2);
    float ll = NoV * sqrt(NoL * NoL * (1.0 - a2) + a2);
    return 0.5 / (lv + ll);
}

// Lambert diffuse: albedo / π. The 1/π is what makes a white surface under irradiance E
// reflect radiance E/π; the assignment leaves it out (erratum 6; Brdf::Assignment restores that).
float Fd_Lambert() {
    return 1.0 / PI;
}

// Half vector normalize(v + l) (erratum 4: not (v + l)/2). For v = −l it has no direction
// (erratum 5); any unit vector gives finite terms there, and n·l ≤ 0 or n·v ≤ 0 then anyway.
vec3 half_vector(vec3 v, vec3 l, vec3 n) {
    vec3 h = v + l;
    float len2 = dot(h, h);
    return len2 > 1e-12 ? h * inversesqrt(len2) : n;
}

// Multiple-scattering energy compensation for the specular lobe. Single-scattering GGX loses
// the energy 1 − E(μ) of light bouncing between microfacets (Kulla & Conty 2017, "Revisiting
// Physically Based Shading at Imageworks"); scaling the lobe by 1 + F0 (1/E − 1) returns it
// (Fdez-Agüera 2019, "A Multiple-Scattering Microfacet Model for Real-Time Image-based
// Lighting", and Turquin 2019 for the punctual form). E(μ, α) = directional albedo of the lobe
// with F = 1, from the BRDF lookup table.
vec3 energy_compensation(vec3 f0, float E) {
    return 1.0 + f0 * (1.0 / max(E, 1e-4) - 1.0);
}

#endif
