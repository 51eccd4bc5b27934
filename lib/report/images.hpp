// The report's pictures: thumbnails of maps and false-colour overlays of the albedo's range and
// of non-binary metalness. Every result is an RGB float image of display values (sRGB-encoded,
// [0, 1]) ready for encode_image as an 8-bit PNG.
//
// Conventions of this module (decided once here):
//  - thumbnails are box-filtered (each output pixel the mean of the source pixels it covers),
//    color maps in linear light (averaging encoded values darkens fine detail), data maps as
//    stored; never enlarged (the page scales small maps up with nearest-neighbour CSS);
//  - overlays are computed on the albedo's full grid, pixel by pixel, then reduced like a
//    thumbnail: a red or blue speck is a real share of pixels, not an artefact of averaging;
//  - other maps are sampled on the albedo's grid by nearest neighbour (a 2x2 constant map or a
//    smaller mask fits any size), as the validation rules do.
#pragma once
#include <cstddef>

#include "image/image.hpp"

namespace mf::report {

// An RGB thumbnail of `src` no larger than max_size on its long side. One channel is shown as
// grey, two as (R, G, 0); a fourth channel is ignored. `srgb`: channels 0–2 are sRGB-encoded
// color (averaged in linear light, re-encoded). Values are clamped to [0, 1].
Image thumbnail(const Image& src, int max_size, bool srgb);
// Channel `channel` of `src` as a grey RGB thumbnail (as stored, clamped to [0, 1]).
Image channel_thumbnail(const Image& src, int channel, int max_size);

// One scalar read from a map's channel, or a constant where the material has no map.
struct Scalar {
    const Image* image = nullptr;  // nullptr: `constant` everywhere
    int channel = 0;
    bool invert = false;  // stored as 1 - value (smoothness)
    float constant = 0.f;
    // The value at pixel (x, y) of a grid of w x h (nearest neighbour onto this map's grid).
    float at(int x, int y, int w, int h) const;
};

// The bounds of the albedo overlay, as sRGB-encoded luminance 0–255 (IEC 61966-2-1 curve over
// Rec. 709 relative luminance of the linear color). Defaults: the ranges of Unity's Material
// Validator ("Validate Albedo": 50–243 sRGB for non-metals, 186–255 for metals).
struct AlbedoBounds {
    double dielectric_min = 50, dielectric_max = 243;
    double metal_min = 186, metal_max = 255;
    // Pixel classes (as the validation rules: lib/validate/rules.hpp Thresholds): metalness at
    // or below dielectric_metalness is dielectric, at or above metal_metalness metal; blends
    // between are in neither class and not judged.
    double dielectric_metalness = 0.1, metal_metalness = 0.9;
    double opacity_visible = 0.5;  // glTF 2.0 alphaCutoff default: pixels below are not judged
};

struct AlbedoStats {
    size_t pixels = 0, visible = 0;
    size_t dielectric = 0, dielectric_dark = 0, dielectric_bright = 0;
    size_t metal = 0, metal_dark = 0, metal_bright = 0;
    size_t blend = 0;  // visible, metalness strictly between the classes
};

// Overlay colours (display values), named so the page's legend says the same.
inline constexpr float kTooDark[3] = {0.86f, 0.12f, 0.12f};     // red
inline constexpr float kTooBright[3] = {0.16f, 0.32f, 0.92f};   // blue
inline constexpr float kBlend[3] = {0.85f, 0.65f, 0.15f};       // amber, scaled by luminance
inline constexpr float kBetween[3] = {0.90f, 0.10f, 0.80f};     // magenta: metalness strictly between the classes
inline constexpr float kNearBinary[3] = {0.98f, 0.70f, 0.55f};  // peach: within a class but not exactly 0 or 1

// The albedo's false-colour overlay at its full size: red = darker than its class allows, blue =
// brighter, grey (its luminance) = in range, amber = a blend (not judged), checkerboard = not
// visible (opacity below the cutoff). `albedo_srgb`: channels 0–2 are sRGB-encoded (else linear).
Image albedo_overlay(const Image& albedo, bool albedo_srgb, const Scalar& metalness, const Scalar& opacity,
                     const AlbedoBounds& bounds, AlbedoStats& stats);

struct MetalnessStats {
    size_t pixels = 0, zero = 0, one = 0;
    size_t near_binary = 0;  // within a class (≤ dielectric / ≥ metal bound) but not exactly 0 or 1
    size_t between = 0;      // strictly between the classes: what METALNESS_NOT_BINARY counts
};

// Metalness that is neither 0 nor 1, at the map's full size: black = 0, white = 1 (within half an
// 8-bit code), peach = near 0 or 1, magenta = between `dielectric` and `metal` (the rule's band).
Image metalness_overlay(const Scalar& metalness, int width, int height, double dielectric, double metal,
                        MetalnessStats& stats);

}  // namespace mf::report
