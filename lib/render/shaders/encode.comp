#version 460
// The one place the output is made: the N×N samples of a pixel averaged (Scene::supersample),
// then either kept as linear floats or encoded: × exposure → tone mapping (none, PBR Neutral or
// ACES; render::Tonemap) → transfer curve → 8 bits, rounded to nearest.
#include "interface.h"
#include "output.glsl"  // output_color: exposure, tone mapping, transfer curve

layout(local_size_x = kTile, local_size_y = kTile) in;

layout(set = 0, binding = kBindingEncodeRadiance, rgba32f) uniform readonly image2D radiance;
// The output buffer, seen two ways: 4 bytes a pixel (RGBA8), or with params.floats one vec4 a
// pixel (one 16-byte store per invocation: a warp's stores to the host-visible buffer coalesce).
layout(set = 0, binding = kBindingEncodePixels, std430) writeonly buffer Pixels { uint words[]; } pixels;
layout(set = 0, binding = kBindingEncodePixels, std430) writeonly buffer PixelFloats { vec4 texels[]; } floats;
layout(push_constant) uniform EncodePush {
    EncodeParams params;
};

uint quantize(float x) {
    // NaN fails every comparison: map it to 0 rather than to an undefined conversion.
    x = x > 0.0 ? min(x, 1.0) : 0.0;
    return uint(x * 255.0 + 0.5);
}

void main() {
    uvec2 xy = gl_GlobalInvocationID.xy;
    if (xy.x >= params.size.x || xy.y >= params.size.y) return;
    // The pixel's N×N samples, averaged in linear radiance (a box filter over the pixel).
    vec4 sum = vec4(0.0);
    uint n = params.supersample;
    for (uint j = 0u; j < n; ++j)
        for (uint i = 0u; i < n; ++i) sum += imageLoad(radiance, ivec2(xy * n + uvec2(i, j)));
    vec4 px = sum / float(n * n);
    uint index = xy.y * params.size.x + xy.x;
    if (params.floats != 0u) {
        floats.texels[index] = px;
        return;
    }
    vec3 c = output_color(px.rgb, params);
    pixels.words[index] = quantize(c.r) | (quantize(c.g) << 8) | (quantize(c.b) << 16) | (255u << 24);
}
