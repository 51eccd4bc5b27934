// The report's pictures: thumbnails of maps and false-colour overlays of the albedo's range and
// of non-binary metalness. Every result is an RGB float image of display values (sRGB-encoded,
// [0, 1]) ready for encode_image as an 8-bit PNG.
//
// Conventions of this module (decided once here):
//  - thumbnails are box-filtered (each output pixel the mean of the source pixels it covers),
//    color maps in linear light (averaging encoded values darkens fine detail), data maps as
//    stored; never enlarged (the page scales small maps up with nearest-neighbour CSS);
//  - of the whole decoded picture: no JPEG decoded at 1/2..1/8 scale (libjpeg's DCT scaling
//    averages encoded YCbCr, not linear light: on the corpus's 1K colour maps the thumbnails
//    moved by up to 27 codes at 1/4, 18 at 1/2 then boxed, for a decode only 16-45 % shorter);
//  - overlays are computed on the albedo's full grid, pixel by pixel, and reduced like a
//    thumbnail as each row is made: a red or blue speck is a real share of pixels, not an
//    artefact of averaging, and no full-size picture is held;
//  - other maps are sampled on the albedo's grid by nearest neighbour (a 2x2 constant map or a
//    smaller mask fits any size), as the validation rules do.
#pragma once
#include <cstddef>

#include "findings/rules.hpp"
#include "image/image.hpp"
#include "validate/albedo_class.hpp"

namespace mf::report {

// Pictures are read as floats (Image) or, for 8-bit files, as their codes (Image8: a quarter of
// the memory; code k read as unorm8_values()[k], the float read_image gives it, so both give the
// same thumbnail, bit for bit: the codes' box sums are exact integer sums, images.cpp).

// An RGB thumbnail of `src` no larger than max_size on its long side. One channel is shown as
// grey, two as (R, G, 0); a fourth channel is ignored. `srgb`: channels 0–2 are sRGB-encoded
// color (averaged in linear light, re-encoded). Values are clamped to [0, 1].
Image thumbnail(const Image& src, int max_size, bool srgb);
Image thumbnail(const Image8& src, int max_size, bool srgb);
// Channel `channel` of `src` as a grey RGB thumbnail (as stored, clamped to [0, 1]).
Image channel_thumbnail(const Image& src, int channel, int max_size);
Image channel_thumbnail(const Image8& src, int channel, int max_size);

// One scalar read from a map's channel, or a constant where the material has no map.
struct Scalar {
    const Image* image = nullptr;   // a float map, or
    const Image8* codes = nullptr;  // an 8-bit map's codes; neither: `constant` everywhere
    int channel = 0;
    bool invert = false;  // stored as 1 - value (smoothness)
    float constant = 0.f;
    // The value at pixel (x, y) of a grid of w x h (nearest neighbour onto this map's grid).
    float at(int x, int y, int w, int h) const;
};

// What the albedo overlay counted: the rules' own weighted sums (validate/albedo_class.hpp), so
// a share of the visible surface here is the finding's surface_share on the same pixels.
struct AlbedoStats {
    size_t pixels = 0;  // every pixel, visible or not (visible: counts.visible)
    validate::AlbedoCounts counts;
};

// Overlay colours (display values), named so the page's legend says the same.
inline constexpr float kTooDark[3] = {0.86f, 0.12f, 0.12f};     // red
inline constexpr float kTooBright[3] = {0.16f, 0.32f, 0.92f};   // blue
inline constexpr float kBetween[3] = {0.90f, 0.10f, 0.80f};     // magenta: metalness strictly between the classes
inline constexpr float kNearBinary[3] = {0.98f, 0.70f, 0.55f};  // peach: within a class but not exactly 0 or 1

// The albedo's false-colour overlay, reduced as a thumbnail to at most `max_size` on its long
// side while it is made (0: its full size; never held at full size otherwise): each pixel
// classed as the rules class it (validate/albedo_class.hpp, under `t`): red = darker than its
// class allows, blue = brighter, grey (its luminance) = in range; a pixel of metalness between
// the classes mixes them by the weight of it that breaks a bound (half red: half of it too dark);
// checkerboard = not visible (opacity below t.opacity_visible). `albedo_srgb`: channels 0–2 are
// sRGB-encoded (else linear).
Image albedo_overlay(const Image& albedo, bool albedo_srgb, const Scalar& metalness, const Scalar& opacity,
                     const rules::Thresholds& t, AlbedoStats& stats, int max_size = 0);
Image albedo_overlay(const Image8& albedo, bool albedo_srgb, const Scalar& metalness, const Scalar& opacity,
                     const rules::Thresholds& t, AlbedoStats& stats, int max_size = 0);

struct MetalnessStats {
    size_t pixels = 0, zero = 0, one = 0;
    size_t near_binary = 0;  // within a class (≤ dielectric / ≥ metal bound) but not exactly 0 or 1
    size_t between = 0;      // strictly between the classes: what METALNESS_NOT_BINARY counts
};

// Metalness that is neither 0 nor 1, reduced as albedo_overlay is (0: the map's full size): black = 0, white = 1
// (within half an 8-bit code), peach = near 0 or 1, magenta = between t.dielectric_max and t.metal_min
// (METALNESS_NOT_BINARY's band).
Image metalness_overlay(const Scalar& metalness, int width, int height, const rules::Thresholds& t,
                        MetalnessStats& stats, int max_size = 0);

}  // namespace mf::report
