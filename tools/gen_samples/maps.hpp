// From a bake to the pixels of one map file: which maps exist, how each texel is stored
// (colour curve, normal encoding, channel packing), and the vendor-style preview render.
#pragma once

#include <vector>

#include "bake.hpp"

namespace gen {

enum class Map {
    albedo,
    normal_gl,
    normal_dx,
    roughness,
    gloss,
    metalness,
    occlusion,
    height,
    opacity,
    emissive,
    arm,
    ort,
    metal_rough,
    specular,
    preview
};
enum class Enc { png8, png16, jpg, exr_half };

// Pixel values in their final encoding, [0,1].
struct Pixels {
    int w = 0, h = 0, c = 0;
    std::vector<float> v;
};

int channels_of(Map m);
bool is_color(Map m);  // sRGB-encoded colour (tagged so), not data

// The whole map `m` of a bake, as stored.
Pixels extract(const Baked& b, Map m);

// Vendor-style preview: the material on a lit sphere over a dark background (clutter that a
// discoverer must not mistake for a map).
Pixels render_preview(const Baked& b, int size);

}  // namespace gen
