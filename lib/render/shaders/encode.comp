#version 460
// The one place the output is made: the N×N samples of a pixel averaged (Scene::supersample),
// then either kept as linear floats or encoded: × exposure → tone mapping (none, PBR Neutral or
// ACES; render::Tonemap) → transfer curve → 8 bits, rounded to nearest.
#include "interface.h"

layout(local_size_x = kTile, local_size_y = kTile) in;

layout(set = 0, binding = kBindingEncodeRadiance, rgba32f) uniform readonly image2D radiance;
// The output buffer, seen two ways: 4 bytes a pixel (RGBA8), or with params.floats one vec4 a
// pixel (one 16-byte store per invocation: a warp's stores to the host-visible buffer coalesce).
layout(set = 0, binding = kBindingEncodePixels, std430) writeonly buffer Pixels { uint words[]; } pixels;
layout(set = 0, binding = kBindingEncodePixels, std430) writeonly buffer PixelFloats { vec4 texels[]; } floats;
layout(push_constant) uniform EncodePush {
    EncodeParams params;
};

// IEC 61966-2-1 encoding, the exact piecewise curve (not pow(x, 1/2.2)), for x ≥ 0: the caller
// clamps negatives to 0 first. The C++ oracle (lib/base/srgb.hpp) mirrors negatives instead;
// both give code 0, since quantize() clamps to [0, 1]. NaN ends as code 0 (quantize).
float srgb_encode(float x) {
    return x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1.0 / 2.4) - 0.055;
}

// Khronos PBR Neutral tone mapping (Khronos 3D Commerce, "PBR Neutral Specification", 2024),
// from its formulas: a small toe offset removes near-black colour shifts, values whose largest
// channel stays below 0.76 pass unchanged (a base color up to 0.8 under unit light reads true),
// the rest compress toward 1 along a hyperbola and desaturate toward white by 0.15 of the
// compression. tests/render/tonemap_test.cpp holds the C++ oracle.
vec3 tonemap_neutral(vec3 c) {
    const float start = 0.8 - 0.04;
    const float desaturation = 0.15;
    float x = min(c.r, min(c.g, c.b));
    float offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
    c -= offset;
    float peak = max(c.r, max(c.g, c.b));
    if (peak < start) return c;
    const float d = 1.0 - start;
    float new_peak = 1.0 - d * d / (peak + d - start);
    c *= new_peak / peak;
    float g = 1.0 - 1.0 / (desaturation * (peak - new_peak) + 1.0);
    return mix(c, vec3(new_peak), g);
}

// ACES: the reference rendering transform and the sRGB output transform as fitted by Stephen
// Hill (2016): Rec.709 to the RRT's working space, a rational fit of RRT + ODT, back to
// Rec.709. Column-major GLSL matrices (each vec3 below is a column).
vec3 tonemap_aces(vec3 c) {
    const mat3 to_rrt = mat3(0.59719, 0.07600, 0.02840, 0.35458, 0.90834, 0.13383, 0.04823, 0.01566, 0.83777);
    const mat3 from_odt = mat3(1.60475, -0.10208, -0.00327, -0.53108, 1.10813, -0.07276, -0.07367, -0.00605, 1.07602);
    vec3 v = to_rrt * c;
    v = (v * (v + 0.0245786) - 0.000090537) / (v * (0.983729 * v + 0.4329510) + 0.238081);
    return clamp(from_odt * v, 0.0, 1.0);
}

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
    vec3 c = px.rgb * params.exposure;
    if (params.tonemap == kTonemapNeutral) c = tonemap_neutral(max(c, vec3(0.0)));
    else if (params.tonemap == kTonemapAces) c = tonemap_aces(max(c, vec3(0.0)));
    if (params.srgb != 0u) c = vec3(srgb_encode(max(c.r, 0.0)), srgb_encode(max(c.g, 0.0)), srgb_encode(max(c.b, 0.0)));
    pixels.words[index] = quantize(c.r) | (quantize(c.g) << 8) | (quantize(c.b) << 16) | (255u << 24);
}
