// Internal pieces of the renderer core shared between its source files.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "render/vk.hpp"

namespace mf::render::detail {

// ---- renderer.cpp

int32_t brdf_model_id(Brdf b);  // the shaders' value of a model (a kBrdf* of shaders/interface.h)

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
// That turn, object to world (rows), also given to shade.comp, which intersects the cube.
using Rotation = std::array<std::array<double, 3>, 3>;
Rotation cube_rotation();
// A square of the given side in the XY plane, facing +Z.
Mesh make_plane(float side);
// A torus around +Y in the XZ plane: u along the ring, v around the tube.
Mesh make_torus(float major, float minor, uint32_t major_segments, uint32_t minor_segments);
Mesh make_shaderball(float size);
Mesh make_shape(const Shape& shape);

// ---- textures.cpp

// How a texture's mips are averaged: color in linear light (sRGB decoded, averaged, encoded),
// normals as renormalized vectors, data as plain averages.
enum class MipKind { color, normal, data };

struct TextureLevel {
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> bytes;  // tightly packed texels of the upload format
};
struct PreparedTexture {
    VkFormat format = VK_FORMAT_UNDEFINED;
    std::vector<TextureLevel> levels;  // level 0 first, down to 1×1 (or level 0 alone: see mips)
    // Levels of the image; more than levels.size() when the device makes the rest from the last
    // one given (Scene::fast_textures: level 0 given, the chain down to 1×1 blitted).
    uint32_t mips = 0;
    // Channels (bit c: channel c) stored as their complement, 1 − x (the fast path's `invert`).
    uint32_t inverted = 0;
    std::string note;  // set when the texture was reduced to fit the device (said to the user)
};

// Fits `t` within the device's maxImageDimension2D (a larger image crashes drivers: lavapipe
// segfaults past 16384): a mip chain starts at its first level that fits; a single 32-bit float
// level (an environment) is halved by 2x2 box averages until it fits. Sets t.note when it changed
// anything; throws Error naming the size and the limit when it cannot.
void fit_to_device(const Device& d, PreparedTexture& t, const std::string& what);

// Converts to a 4-channel upload format the device can filter linearly and builds the mips. With
// `fast` (Scene::fast_textures), an 8-bit texture whose format the device blits gets level 0 only
// (the bytes the CPU chain would start with; color in 8-bit sRGB also where precise textures
// would promote it) and PreparedTexture::mips for the device to fill; the channels in `invert`
// (bit c: channel c) are then stored as their complement (PreparedTexture::inverted says whether
// that was done).
PreparedTexture prepare_texture(const Device& d, const Texture& t, MipKind kind, bool fast = false,
                                uint32_t invert = 0);
// Blit source and destination with a linear filter: what making mips on the device needs.
inline constexpr VkFormatFeatureFlags kBlitMipFeatures = VK_FORMAT_FEATURE_BLIT_SRC_BIT |
                                                         VK_FORMAT_FEATURE_BLIT_DST_BIT |
                                                         VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;

// A block-compressed format Texture::block_format may name: its UNORM and sRGB VkFormats (the
// sRGB one VK_FORMAT_UNDEFINED where none exists) and block size. nullptr for any other value.
struct BlockFormatDesc {
    VkFormat unorm, srgb;
    uint32_t block_width, block_height, block_bytes;
};
const BlockFormatDesc* block_format_desc(uint32_t vk_format);
// Sampled, linearly filtered and a transfer destination: what a material texture needs.
inline constexpr VkFormatFeatureFlags kSampledTextureFeatures = VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT |
                                                                VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT |
                                                                VK_FORMAT_FEATURE_TRANSFER_DST_BIT;

uint16_t float_to_half(float f);  // round to nearest even; overflow → infinity

// ---- specialization constants by name

// The map entry of one 4-byte constant (int32 or VkBool32): the shader's id (a kSpec* of
// shaders/interface.h) and offsetof(its field) in the C++ struct of values. Tables of these
// replace positional filling, so adding a constant cannot shift the others.
constexpr VkSpecializationMapEntry spec_entry(int id, size_t offset) {
    return {static_cast<uint32_t>(id), static_cast<uint32_t>(offset), 4};
}
// No id and no field mapped twice.
template <size_t N>
constexpr bool spec_entries_distinct(const VkSpecializationMapEntry (&e)[N]) {
    for (size_t i = 0; i < N; ++i)
        for (size_t j = i + 1; j < N; ++j)
            if (e[i].constantID == e[j].constantID || e[i].offset == e[j].offset) return false;
    return true;
}
// `values` is the struct the entries' offsets index; every field must have an entry.
template <class Values, size_t N>
VkSpecializationInfo spec_info(const VkSpecializationMapEntry (&entries)[N], const Values& values) {
    static_assert(N * 4 == sizeof(Values), "a field without a map entry");
    return {static_cast<uint32_t>(N), entries, sizeof(Values), &values};
}
template <class Values, size_t N>
VkSpecializationInfo spec_info(const std::array<VkSpecializationMapEntry, N>& entries, const Values& values) {
    static_assert(N * 4 == sizeof(Values), "a field without a map entry");
    return {static_cast<uint32_t>(N), entries.data(), sizeof(Values), &values};
}

// A row of a constant table that others read too (shade.frag's, for the report's WebGL2 view,
// export.cpp): the id, the field, and whether the shader declares it bool (VkBool32 in the struct).
struct SpecField {
    int id;
    size_t offset;
    bool boolean;
};
template <size_t N>
constexpr std::array<VkSpecializationMapEntry, N> spec_entries(const SpecField (&fields)[N]) {
    std::array<VkSpecializationMapEntry, N> e{};
    for (size_t i = 0; i < N; ++i) e[i] = spec_entry(fields[i].id, fields[i].offset);
    return e;
}
template <size_t N>
constexpr bool spec_entries_distinct(const std::array<VkSpecializationMapEntry, N>& e) {
    for (size_t i = 0; i < N; ++i)
        for (size_t j = i + 1; j < N; ++j)
            if (e[i].constantID == e[j].constantID || e[i].offset == e[j].offset) return false;
    return true;
}

}  // namespace mf::render::detail
