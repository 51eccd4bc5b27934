#version 460
// Diffuse environment: E(n)/π, the cosine-weighted average radiance over the hemisphere of n
// (what a white Lambertian surface reflects). Cosine-weighted samples with filtered importance
// sampling as in prefilter.comp.
#include "ibl_common.glsl"

layout(set = 0, binding = kBindingIblSource) uniform samplerCube src;
layout(set = 0, binding = kBindingIblTarget, rgba16f) uniform writeonly image2DArray dst;

void main() {
    uvec3 id = gl_GlobalInvocationID;
    if (id.x >= params.size || id.y >= params.size) return;
    vec3 n = cube_direction(id.xy, id.z, params.size);
    vec3 t, b;
    basis(n, t, b);
    float texel_solid_angle = 4.0 * PI / (6.0 * params.src_size * params.src_size);
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < params.samples; ++i) {
        vec2 xi = hammersley(i, params.samples);
        // Malley's method: uniform on the disk, projected up: pdf = cos θ / π.
        float r = sqrt(xi.x);
        float phi = 2.0 * PI * xi.y;
        float cos_t = sqrt(max(0.0, 1.0 - xi.x));
        vec3 l = t * (r * cos(phi)) + b * (r * sin(phi)) + n * cos_t;
        float pdf = max(cos_t, 1e-4) / PI;
        float lod = max(0.5 * log2(1.0 / (float(params.samples) * pdf) / texel_solid_angle) + 1.0, 0.0);
        sum += textureLod(src, l, lod).rgb;
    }
    // With pdf = cos/π the estimator of (1/π)∫ L cos dω is the plain mean of L.
    imageStore(dst, ivec3(id), vec4(sum / float(params.samples), 1.0));
}
