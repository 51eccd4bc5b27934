// Decoding inputs into canonical role planes, and packing planes into a preset's outputs.
//
// Canonical planes (the one internal convention, decided here):
//  - albedo, emissive: 3 channels, linear Rec.709 light, or still sRGB-encoded while no step
//    needs linear values (`encoding`), so an 8-bit sRGB map copied at its size stays exact;
//  - normal: 3 channels, unit vectors in the OpenGL (+Y) tangent convention, components in [-1,1];
//  - every other role: 1 channel of data in [0,1] (values outside are kept and clamped on output).
#pragma once
#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "color/color.hpp"
#include "image/image.hpp"
#include "material/roles.hpp"
#include "preset/preset.hpp"

namespace mf {

struct RolePlane {
    RolePlane() = default;
    RolePlane(Image img, ColorEncoding enc) : image(std::move(img)), encoding(enc) {}

    Image image;
    ColorEncoding encoding = ColorEncoding::linear;  // only albedo/emissive may be srgb
    // Or, while no step needs floats, the 8-bit codes the plane came from (then `image` is
    // empty): scalar roles and sRGB albedo/emissive as the values above (code k = unorm8 k),
    // normals as stored, encoded in `codes_convention` (2 to 4 channels). An output made of codes
    // planes only is packed in 8 bits straight from them (pack_output8).
    Image8 codes;
    NormalConvention codes_convention = NormalConvention::gl;

    bool is_codes() const { return !codes.empty(); }
    int width() const { return is_codes() ? codes.width : image.width; }
    int height() const { return is_codes() ? codes.height : image.height; }
};
using Planes = std::map<Role, RolePlane>;

// One channel of `src` as a 1-channel image.
Image extract_channel(const Image& src, int channel);
Image8 extract_channel(const Image8& src, int channel);
// 3-channel color from grey (replicated), grey+alpha, RGB or RGBA (alpha dropped).
Image to_rgb(const Image& src);
Image8 to_rgb(const Image8& src);
// v -> 1 - v in place (gloss/smoothness <-> roughness); codes: k -> 255 - k.
void invert(Image& img);
void invert(Image8& codes);

// The plane of `role` in floats (codes decoded; normal codes to unit GL vectors), and in place.
Image plane_floats(Role role, const RolePlane& plane);
void make_floats(Role role, RolePlane& plane);

// Decodes an encoded normal map (c in [0,1], 2 to 4 channels; with 2 channels Z is rebuilt) to
// unit GL vectors. Zero-length or non-finite texels become (0,0,1). `from` unknown is treated as
// gl. Returns the share of texels whose stored length was far from 1 (|len-1| > 0.2) or Z < 0.
double decode_normal(const Image& encoded, NormalConvention from, Image& out);
// Rescales the 3-channel vectors of `n` to unit length; zero or non-finite ones become (0,0,1).
void renormalize(Image& n);
// Unit GL vectors `n` -> encoded colors in `to` (renormalizing first: resampling shortens vectors).
Image encode_normal(const Image& n, NormalConvention to);

// Resamples to w x h with a Lanczos-3 filter (OpenImageIO). Callers resample color in linear
// light and renormalize normals afterwards.
Image resample(const Image& src, int w, int h);

// Brings a plane to w x h: color goes to linear first; normals are renormalized. A codes plane
// already at w x h stays codes.
void fit_plane(Role role, RolePlane& plane, int w, int h, const ColorContext& color);

// The size of an output: the largest of its map-backed roles, scaled so neither side exceeds
// max_size (0 = no limit); constant_size² when no role has a map.
struct Size {
    int width = 0, height = 0;
    bool operator==(const Size&) const = default;
};
Size output_size(const OutputSpec& o, const Planes& planes, const Preset& preset);

// Whether the output is written at all (always, or a role of it has a map).
bool output_needed(const OutputSpec& o, const Planes& planes);

// The channels actually written (optional channels dropped when their role has no map).
std::vector<ChannelSpec> effective_channels(const OutputSpec& o, const Planes& planes);

// Everything packing an output reads besides its planes' pixels, as a value: pack_spec takes it
// from the output, the planes present and the preset, and pack_output and pack_output8 read
// nothing else. So two outputs of equal specs over equal planes (same_plane for each of `roles`)
// pack equal images, whatever their names and presets, and may share one encoding
// (process/share.hpp). The ColorContext is the caller's to compare.
struct PackSpec {
    struct Written {
        Channel channel;  // as written: optional channels of missing roles are dropped
        // A role without a plane: its default in linear values (albedo's three; a scalar's in
        // [0], before a smoothness channel's inversion; a normal's flat 0.5, 0.5, 1); zeros when
        // the role has a plane.
        std::array<float, 3> missing{};
        bool operator==(const Written&) const = default;
    };
    Size size;
    bool srgb = false;  // the output's color channels are sRGB-encoded
    int bit_depth = 8;
    FileFormat format = FileFormat::png;
    std::optional<NormalConvention> normal_to;  // the convention a normal channel is written in
    std::vector<Written> channels;
    std::vector<Role> roles;  // the roles whose planes it reads, in channel order
    bool operator==(const PackSpec&) const = default;
};
PackSpec pack_spec(const OutputSpec& o, const Planes& planes, const Preset& preset, Size size);

// Packs `planes` into one output image in its file encoding ([0,1], sRGB where the output's
// color roles are sRGB). Planes must already be at `spec.size` (fit_plane).
Image pack_output(const PackSpec& spec, const Planes& planes, const ColorContext& color);
// The same output as 8-bit codes made straight from codes planes, with no float image: what
// quantizing pack_output's result gives, code for code (tests/pack check every code). nullopt
// when the output is not 8-bit integer (16-bit, EXR), a plane it reads is float, or a color
// plane's encoding is not the output's (then use pack_output).
std::optional<Image8> pack_output8(const PackSpec& spec, const Planes& planes, const ColorContext& color);
// The same, the spec taken from `o` (pack_spec).
Image pack_output(const OutputSpec& o, const Planes& planes, const Preset& preset, Size size,
                  const ColorContext& color);
std::optional<Image8> pack_output8(const OutputSpec& o, const Planes& planes, const Preset& preset, Size size,
                                   const ColorContext& color);

// Whether two planes hold the same samples in the same form.
bool same_plane(const RolePlane& a, const RolePlane& b);

}  // namespace mf
