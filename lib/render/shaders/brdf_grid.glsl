// Accuracy harness of the preview's BRDF (brdf.glsl, the same functions shade.frag calls): not
// part of the preview, run by render/brdf_harness.hpp for tests/render/brdf_grid_test.cpp and
// bench/brdf_bench.cpp. Included by brdf_grid.comp (fp32) and brdf_grid_f16.comp (the BRDF's
// arithmetic in binary16; inputs, normalization and the sphere's geometry stay fp32).
//
// MODE kGridModeInputs: one arbitrary input per invocation (n, v, l, albedo, roughness, metalness,
// intensity), each shaded with the three models. The preview only ever passes unit vectors; the
// harness takes anything and applies the CPU reference's conventions (tests/stability/
// brdf_reference.hpp): n or l without a direction → 0, v without one → n, intensity not positive
// and finite → 0, roughness clamped to [MIN_ROUGHNESS, 1], metalness and albedo to [0, 1].
// MODE kGridModeSphere: the accuracy benchmark's scene (bench/accuracy/knobs_brdf.cpp): an
// orthographic unit sphere, one directional light, roughness bands, metal on the right half,
// with 1/4/8 samples per pixel at the D3D11 standard multisample positions.
//
// The accurate model's multiple-scattering lobe and diffuse weight need the split-sum terms
// (A, B) and the loss 1 − E at (n·v, roughness), 1 − E at (n·l, roughness) and 1 − E_avg(roughness),
// which the preview samples from its BRDF lookup table; here they are a 32 × 32 table of texel
// centres uniform in n·v (kBindingGridEnergy, (A, B, 1 − E, 1 − E_avg) each) read bilinearly, the
// same table and interpolation as the CPU reference's EnergyTable, so the two evaluations differ
// by arithmetic only.
#include "brdf.glsl"  // includes interface.h: GridInput, GridPush

layout(local_size_x = kGridGroup) in;
layout(constant_id = kSpecGridMode) const int MODE = kGridModeInputs;

layout(std430, set = 0, binding = kBindingGridInputs) readonly buffer Inputs { GridInput inputs[]; };
layout(std430, set = 0, binding = kBindingGridOutputs) writeonly buffer Outputs { vec4 outputs[]; };
layout(std430, set = 0, binding = kBindingGridEnergy) readonly buffer Energy { vec4 dfg_table[]; };  // [roughness][n·v]

layout(push_constant) uniform GridPushBlock {
    GridPush pc;
};

const int kEnergyN = kEnergyTableSize;

vec4 dfg_lookup(float NoV, float r) {
    float x = clamp(NoV * float(kEnergyN) - 0.5, 0.0, float(kEnergyN - 1));
    float y = clamp(r * float(kEnergyN) - 0.5, 0.0, float(kEnergyN - 1));
    int x0 = min(int(x), kEnergyN - 2), y0 = min(int(y), kEnergyN - 2);
    float fx = x - float(x0), fy = y - float(y0);
    int i = y0 * kEnergyN + x0;
    return ((1.0 - fy) * ((1.0 - fx) * dfg_table[i] + fx * dfg_table[i + 1]) +
            fy * ((1.0 - fx) * dfg_table[i + kEnergyN] + fx * dfg_table[i + kEnergyN + 1]));
}

bool to_unit(inout vec3 a) {
    float len2 = dot(a, a);
    if (!(len2 > 1e-30) || isinf(len2)) return false;
    a *= 1.0 / sqrt(len2);
    return true;
}

// n, v, l unit (fp32); the rest as the preview prepares it in shade.frag.
vec3 shade_one(int model, vec3 n, vec3 v, vec3 l, vec3 albedo, float roughness, float metalness, float E) {
    roughness = clamp(roughness, MIN_ROUGHNESS, 1.0);
    metalness = clamp(metalness, 0.0, 1.0);
    albedo = clamp(albedo, 0.0, 1.0);
    vec3 f0 = mix(vec3(0.04), albedo, metalness);
    vec3 diffuse_color = albedo * (1.0 - metalness);
    float NoV = clamp(dot(n, v), MIN_NOV, 1.0);
    // The accurate model's per-pixel terms (shade.frag computes them once per pixel), in the
    // BRDF's arithmetic type; the table reads stay fp32.
    vec3 ms_v = vec3(0.0), diffuse_weight = vec3(1.0);
    float lost_l = 0.0;
    if (model == kBrdfAccurate) {
        vec4 dfg = dfg_lookup(NoV, roughness);
        mf_vec3 F_ms = multiscatter_fresnel(mf_vec3(f0), mf_float(dfg.w));
        ms_v = vec3(multiscatter_lobe(F_ms, mf_float(dfg.z), mf_float(dfg.w)));
        diffuse_weight = vec3(accurate_diffuse_weight(mf_vec3(f0), mf_float(dfg.x), mf_float(dfg.y), mf_float(dfg.z), F_ms));
        lost_l = dfg_lookup(clamp(dot(n, l), 0.0, 1.0), roughness).z;
    }
    return vec3(brdf_light(model, mf_vec3(n), mf_vec3(v), mf_vec3(l), mf_float(NoV), mf_float(roughness),
                           mf_vec3(f0), mf_vec3(diffuse_color), mf_vec3(ms_v), mf_float(lost_l), mf_vec3(diffuse_weight),
                           mf_vec3(E)));
}

// D3D11 standard multisample positions, in 1/16 pixel.
const ivec2 kPattern4[4] = ivec2[](ivec2(-2, -6), ivec2(6, -2), ivec2(-6, 2), ivec2(2, 6));
const ivec2 kPattern8[8] = ivec2[](ivec2(1, -3), ivec2(-1, 3), ivec2(5, 1), ivec2(-3, -5),
                                   ivec2(-5, 5), ivec2(-7, -1), ivec2(3, 7), ivec2(7, -7));

// knobs_brdf.cpp's scene: sx, sy in [−1.1, 1.1], y up; bands of roughness (0.5 above, 0.045
// through the highlight, 0.2 below it, 1 in the lower half), metal on the right.
vec3 sphere_sample(float sx, float sy) {
    float r2 = sx * sx + sy * sy;
    if (r2 > 1.0) return vec3(0.0);
    float rough = sy > 0.45 ? 0.5 : sy > 0.2 ? 0.045 : sy > 0.0 ? 0.2 : 1.0;
    vec3 n = vec3(sx, sy, sqrt(1.0 - r2));
    to_unit(n);
    vec3 l = normalize(vec3(0.0, 0.6, 0.8));
    return shade_one(pc.model, n, vec3(0.0, 0.0, 1.0), l, vec3(0.9, 0.6, 0.3), rough, sx > 0.0 ? 1.0 : 0.0, 3.0);
}

void main() {
    uint i = gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x + gl_GlobalInvocationID.x;
    if (i >= pc.count) return;
    if (MODE == kGridModeInputs) {
        GridInput g = inputs[i];
        vec3 n = g.n.xyz, v = g.v.xyz, l = g.l.xyz;
        float E = g.l.w;
        bool lit = E > 0.0 && !isinf(E) && to_unit(n) && to_unit(l);
        if (!to_unit(v)) v = n;
        for (int m = 0; m < 3; ++m)
            outputs[3 * i + uint(m)] = vec4(lit ? shade_one(m, n, v, l, g.albedo.rgb, g.n.w, g.v.w, E) : vec3(0.0), 0.0);
    } else {
        uint x = i % pc.width, y = i / pc.width;
        float size = float(pc.width);
        vec3 acc = vec3(0.0);
        for (uint s = 0u; s < pc.spp; ++s) {
            vec2 o = pc.spp == 1u ? vec2(0.0) : vec2(pc.spp == 4u ? kPattern4[s] : kPattern8[s]);
            float px = float(x) + 0.5 + o.x / 16.0, py = float(y) + 0.5 + o.y / 16.0;
            acc += sphere_sample((px / size * 2.0 - 1.0) * 1.1, (1.0 - py / size * 2.0) * 1.1);
        }
        outputs[i] = vec4(acc / float(pc.spp), 1.0);
    }
}
