// Split-sum BRDF table (Karis 2013, "Real Shading in Unreal Engine 4", p. 6-7), over
// x = √(n·v) and y = perceptual roughness (texel centres): the directional albedo of the specular
// lobe as F0 · A + B (channels r, g); channel b holds 1 − E(μ, α), what the lobe loses with F = 1
// (E = A + B), and channel a 1 − E_avg(α) = 2 ∫ (1 − E(μ)) μ dμ, the same in every texel of a row.
// The accurate BRDF's multiple-scattering lobe needs 1 − E at n·v and n·l and 1 − E_avg
// (brdf.glsl). √(n·v), not n·v: E changes fastest at grazing angles, where the texels then are
// (ReferenceTest.ConstantSpheresAccurate's worst gold pixel: 3.0 % from the reference with a table
// linear in n·v, 1.7 % with this one); look it up with brdf_table() (shading.glsl).
#include "brdf.glsl"

// One workgroup per row (kBrdfLutSize texels): E_avg is the row's own quadrature.
layout(local_size_x = kBrdfLutSize, local_size_y = 1) in;
shared float row_energy[kBrdfLutSize];  // (1 − E) x³ of each texel
layout(constant_id = kSpecLutCorrelated) const bool CORRELATED = false;  // accurate BRDF: Heitz's height-correlated Smith
layout(constant_id = kSpecLutSamples) const uint SAMPLES = 1024;
layout(set = 0, binding = kBindingLut, LUT_FORMAT) uniform writeonly image2D lut;

// Hammersley point set: low discrepancy, the same every run.
vec2 hammersley(uint i) {
    return vec2(float(i) / float(SAMPLES), float(bitfieldReverse(i)) * 2.3283064365386963e-10);
}

// Half vectors drawn from the distribution of normals visible from v, around n = +Z.
// Heitz 2018, "Sampling the GGX Distribution of Visible Normals", listing 1:
// pdf(h) = G1(v) max(v·h, 0) D(h) / (n·v). With pdf(l) = pdf(h) / (4 v·h), the estimator of the
// lobe's albedo is G2(v, l) / G1(v): bounded by 1, so the table converges at grazing angles
// too, where sampling D alone leaves errors of several per mille after a thousand samples.
vec3 sample_vndf(vec3 v, float alpha, vec2 xi) {
    vec3 vh = normalize(vec3(alpha * v.xy, v.z));
    float len2 = dot(vh.xy, vh.xy);
    vec3 t1 = len2 > 0.0 ? vec3(-vh.y, vh.x, 0.0) * inversesqrt(len2) : vec3(1.0, 0.0, 0.0);
    vec3 t2 = cross(vh, t1);
    float r = sqrt(xi.x);
    float phi = 2.0 * PI * xi.y;
    float p1 = r * cos(phi);
    float p2 = r * sin(phi);
    float s = 0.5 * (1.0 + vh.z);
    p2 = (1.0 - s) * sqrt(1.0 - p1 * p1) + s * p2;
    vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
    return normalize(vec3(alpha * nh.xy, max(0.0, nh.z)));
}

// Smith masking of v for GGX: G1 = 2 (n·v) / ((n·v) + sqrt(α² + (1 − α²)(n·v)²)) (Heitz 2014).
float G1_Smith(float NoV, float alpha) {
    float a2 = alpha * alpha;
    return 2.0 * NoV / (NoV + sqrt(a2 + (1.0 - a2) * NoV * NoV));
}

void main() {
    ivec2 size = imageSize(lut);  // kBrdfLutSize square (ibl.cpp)
    ivec2 xy = ivec2(gl_GlobalInvocationID.xy);
    float x = (float(xy.x) + 0.5) / float(size.x);
    float NoV = x * x;
    float roughness = max((float(xy.y) + 0.5) / float(size.y), MIN_ROUGHNESS);
    float alpha = roughness * roughness;
    vec3 v = vec3(sqrt(1.0 - NoV * NoV), 0.0, NoV);
    float g1 = G1_Smith(NoV, alpha);
    float a = 0.0, b = 0.0, lost = 0.0;
    for (uint i = 0u; i < SAMPLES; ++i) {
        vec3 h = sample_vndf(v, alpha, hammersley(i));
        float VoH = dot(v, h);
        vec3 l = 2.0 * VoH * h - v;
        float NoL = l.z;
        if (NoL <= 0.0 || VoH <= 0.0) {
            lost += 1.0;  // the sample's light leaves below the horizon: all of it lost
            continue;
        }
        // Image-based lighting takes k = α/2 in Schlick-GGX, not the (r + 1)²/8 of punctual
        // lights (Karis 2013, p. 3: that remap is for analytic lights only).
        float vis = CORRELATED ? V_SmithGGXCorrelated(NoV, NoL, alpha) : V_SchlickGGX_k(NoV, NoL, alpha * 0.5);
        // f (n·l) / pdf(l) = G2 / G1(v) × F, with G2 = 4 V (n·l)(n·v).
        float g = 4.0 * vis * NoL * NoV / g1;
        float fc = pow(1.0 - VoH, 5.0);
        a += (1.0 - fc) * g;
        b += fc * g;
        lost += 1.0 - g;
    }
    a /= float(SAMPLES);
    b /= float(SAMPLES);
    lost /= float(SAMPLES);
    // 1 − E_avg = 2 ∫ (1 − E) μ dμ = 4 ∫ (1 − E(x²)) x³ dx, by the midpoint rule over the row's
    // texel centres. Every invocation sums the row in the same order, so all write the same value.
    row_energy[xy.x] = lost * x * x * x;
    barrier();
    float sum = 0.0;
    for (uint i = 0u; i < kBrdfLutSize; ++i) sum += row_energy[i];
    imageStore(lut, xy, vec4(a, b, lost, 4.0 * sum / float(size.x)));
}
