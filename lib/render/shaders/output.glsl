// The output transform of a linear radiance, declared once for every pass that makes display
// values: encode.comp (the renderer's frame) and the report's WebGL2 viewer (lib/report/viewer/
// encode.frag, translated to ESSL at build time): × exposure → tone mapping → transfer curve.
#ifndef MF_OUTPUT_GLSL
#define MF_OUTPUT_GLSL

#include "interface.h"  // kTonemap*, EncodeParams

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

// Linear radiance to display values in [0, 1] before quantizing: × exposure, the tone mapper
// `p.tonemap` (a kTonemap*), then the sRGB curve when p.srgb (else linear).
vec3 output_color(vec3 radiance, EncodeParams p) {
    vec3 c = radiance * p.exposure;
    if (p.tonemap == kTonemapNeutral) c = tonemap_neutral(max(c, vec3(0.0)));
    else if (p.tonemap == kTonemapAces) c = tonemap_aces(max(c, vec3(0.0)));
    if (p.srgb != 0u) c = vec3(srgb_encode(max(c.r, 0.0)), srgb_encode(max(c.g, 0.0)), srgb_encode(max(c.b, 0.0)));
    return c;
}

#endif
