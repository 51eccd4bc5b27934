// Internal pieces of the renderer core shared between its source files.
#pragma once
#include <cstdint>
#include <vector>

#include "render/vk.hpp"

namespace mf::render::detail {

// ---- geometry.cpp

struct Vertex {
    float position[3];
    float normal[3];
    float tangent[4];  // xyz: ∂p/∂u direction; w: sign of the bitangent (toward +v)
    float uv[2];       // v = 0 at the image's bottom row
};
struct Mesh {
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;  // counter-clockwise seen from outside
};

// three.js SphereGeometry(radius, width_segments, height_segments): same vertices, (u, v),
// pole offsets and triangle list.
Mesh make_sphere(float radius, uint32_t width_segments = 128, uint32_t height_segments = 64);
// A cube of the given edge, turned (35° about Y, then 25° about X) so that three faces show.
Mesh make_cube(float edge);
// A square of the given side in the XY plane, facing +Z.
Mesh make_plane(float side);
Mesh make_shape(const Shape& shape);

// ---- textures.cpp

// How a texture's mips are averaged: color in linear light (sRGB decoded, averaged, encoded),
// normals as renormalized vectors, data as plain averages.
enum class MipKind { Color, Normal, Data };

struct TextureLevel {
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> bytes;  // tightly packed texels of the upload format
};
struct PreparedTexture {
    VkFormat format = VK_FORMAT_UNDEFINED;
    std::vector<TextureLevel> levels;  // level 0 first, down to 1×1
};

// Converts to a 4-channel upload format the device can filter linearly and builds the mips.
PreparedTexture prepare_texture(const Device& d, const Texture& t, MipKind kind);

uint16_t float_to_half(float f);  // round to nearest even; overflow → infinity

// Exact IEC 61966-2-1 curves.
double srgb_to_linear(double c);
double linear_to_srgb(double l);

}  // namespace mf::render::detail
