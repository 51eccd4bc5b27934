// The d3d11 preset's HLSL BRDF (lib/engine/matforge_material.hlsli) in the accuracy harness: the
// inputs mode of brdf_grid.glsl (render/brdf_harness.hpp evaluate_spirv), with the same
// conventions (n or l without a direction, or an intensity not positive and finite: 0; v without
// one: n), writing the standard model at 3 i. Compiled by glslang's HLSL front end at build time
// (tests/render/CMakeLists.txt); tests/render/brdf_grid_test.cpp checks it against the double
// oracle.
#include "matforge_material.hlsli"

struct GridInput {  // render/shaders/interface.h
    float4 n;       // w: roughness
    float4 v;       // w: metalness
    float4 l;       // w: intensity
    float4 albedo;
};
struct GridPush {
    uint count;
    uint width;  // invocations per row of the dispatch
    uint spp;
    int model;
};

[[vk::binding(0, 0)]] StructuredBuffer<GridInput> inputs;
[[vk::binding(1, 0)]] RWStructuredBuffer<float4> outputs;
[[vk::push_constant]] ConstantBuffer<GridPush> pc;

bool to_unit(inout float3 a) {
    float len2 = dot(a, a);
    if (!(len2 > 1e-30) || isinf(len2)) return false;
    a *= 1.0 / sqrt(len2);
    return true;
}

[numthreads(64, 1, 1)]  // kGridGroup
void main(uint3 id : SV_DispatchThreadID) {
    uint i = id.y * pc.width + id.x;
    if (i >= pc.count) return;
    GridInput g = inputs[i];
    float3 n = g.n.xyz, v = g.v.xyz, l = g.l.xyz;
    float E = g.l.w;
    bool lit = E > 0.0 && !isinf(E);
    lit = to_unit(n) && lit;
    lit = to_unit(l) && lit;
    if (!to_unit(v)) v = n;
    MfSurface s;
    s.albedo = g.albedo.rgb;
    s.opacity = 1.0;
    s.n = n;
    s.roughness = g.n.w;
    s.metalness = g.v.w;
    outputs[3 * i] = float4(lit ? mf_brdf_light(s, v, l, float3(E, E, E)) : float3(0.0, 0.0, 0.0), 0.0);
}
