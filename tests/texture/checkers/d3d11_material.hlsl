// A Direct3D 11 pixel shader as an engine writes it around matforge_material.hlsli (the d3d11
// preset's include): the four textures of the preset's layout, one light. Compiled by the tests
// with glslang's HLSL front end (glslangValidator -D) to SPIR-V: the include's functions must
// compile as HLSL with every intrinsic they use.
#include "matforge_material.hlsli"

Texture2D Albedo : register(t0);
Texture2D NormalMap : register(t1);
Texture2D RoughnessMap : register(t2);
Texture2D MetalnessMap : register(t3);
SamplerState Trilinear : register(s0);

cbuffer Frame : register(b0) {
    float3 eye;
    float3 light_dir;
    float3 light_irradiance;
};

struct PSIn {
    float4 pos : SV_Position;
    float3 world : POSITION;
    float2 uv : TEXCOORD0;
    float3 T : TANGENT;
    float3 B : BINORMAL;
    float3 N : NORMAL;
};

float4 main(PSIn i) : SV_Target {
    MfSurface s = mf_sample(Albedo, NormalMap, RoughnessMap, MetalnessMap, Trilinear, i.uv, normalize(i.T),
                            normalize(i.B), normalize(i.N));
    float3 v = normalize(eye - i.world);
    return float4(mf_brdf_light(s, v, normalize(light_dir), light_irradiance), s.opacity);
}
