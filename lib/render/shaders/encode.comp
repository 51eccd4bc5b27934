#version 460
// The one place the output is encoded: linear radiance × exposure → transfer curve → 8 bits,
// rounded to nearest.
#include "interface.h"

layout(local_size_x = kTile, local_size_y = kTile) in;

layout(set = 0, binding = kBindingEncodeRadiance, rgba32f) uniform readonly image2D radiance;
layout(set = 0, binding = kBindingEncodePixels, std430) writeonly buffer Pixels { uint rgba8[]; } pixels;
layout(push_constant) uniform EncodePush {
    EncodeParams params;
};

// IEC 61966-2-1 encoding, the exact piecewise curve (not pow(x, 1/2.2)), for x ≥ 0: the caller
// clamps negatives to 0 first. The C++ oracle (lib/color/srgb.hpp) mirrors negatives instead;
// both give code 0, since quantize() clamps to [0, 1]. NaN ends as code 0 (quantize).
float srgb_encode(float x) {
    return x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1.0 / 2.4) - 0.055;
}

uint quantize(float x) {
    // NaN fails every comparison: map it to 0 rather than to an undefined conversion.
    x = x > 0.0 ? min(x, 1.0) : 0.0;
    return uint(x * 255.0 + 0.5);
}

void main() {
    uvec2 xy = gl_GlobalInvocationID.xy;
    if (xy.x >= params.size.x || xy.y >= params.size.y) return;
    vec3 c = imageLoad(radiance, ivec2(xy)).rgb * params.exposure;
    if (params.srgb != 0u) c = vec3(srgb_encode(max(c.r, 0.0)), srgb_encode(max(c.g, 0.0)), srgb_encode(max(c.b, 0.0)));
    pixels.rgba8[xy.y * params.size.x + xy.x] =
        quantize(c.r) | (quantize(c.g) << 8) | (quantize(c.b) << 16) | (255u << 24);
}
