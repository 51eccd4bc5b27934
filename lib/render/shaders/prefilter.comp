#version 460
// Split-sum prefiltered environment, one mip per roughness (Karis 2013, "Real Shading in
// Unreal Engine 4", p. 4-6: n = v = r). GGX importance sampling reads the source at a mip
// chosen from each sample's solid angle ("filtered importance sampling", Křivánek & Colbert
// 2008, "Real-time Shading with Filtered Importance Sampling"), so a few hundred samples show no
// noise. Weighted by n·l as Karis does.
#include "ibl_common.glsl"

layout(set = 0, binding = kBindingIblSource) uniform samplerCube src;
layout(set = 0, binding = kBindingIblTarget, rgba16f) uniform writeonly image2DArray dst;

void main() {
    uvec3 id = gl_GlobalInvocationID;
    if (id.x >= params.size || id.y >= params.size) return;
    vec3 n = cube_direction(id.xy, id.z, params.size);
    float roughness = max(params.roughness, MIN_ROUGHNESS);
    float alpha = roughness * roughness;
    if (params.roughness == 0.0) {  // a mirror: the environment itself
        imageStore(dst, ivec3(id), vec4(textureLod(src, n, 0.0).rgb, 1.0));
        return;
    }
    vec3 t, b;
    basis(n, t, b);
    float texel_solid_angle = 4.0 * PI / (6.0 * params.src_size * params.src_size);
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (uint i = 0u; i < params.samples; ++i) {
        vec2 xi = hammersley(i, params.samples);
        // GGX half vector (Walter et al. 2007, eqs. 35-36) around n.
        float phi = 2.0 * PI * xi.y;
        float cos_h = sqrt((1.0 - xi.x) / (1.0 + (alpha * alpha - 1.0) * xi.x));
        float sin_h = sqrt(max(0.0, 1.0 - cos_h * cos_h));
        vec3 h = t * (sin_h * cos(phi)) + b * (sin_h * sin(phi)) + n * cos_h;
        vec3 l = 2.0 * cos_h * h - n;  // v = n, so v·h = n·h = cos_h
        float NoL = dot(n, l);
        if (NoL <= 0.0) continue;
        // pdf(l) = D (n·h) / (4 v·h) = D / 4 with v = n.
        float pdf = D_GGX(cos_h, cross(n, h), alpha) * 0.25;
        float sample_solid_angle = 1.0 / (float(params.samples) * pdf + 1e-6);
        float lod = max(0.5 * log2(sample_solid_angle / texel_solid_angle) + 1.0, 0.0);
        sum += textureLod(src, l, lod).rgb * NoL;
        weight += NoL;
    }
    imageStore(dst, ivec3(id), vec4(sum / max(weight, 1e-6), 1.0));
}
