// glTF 2.0 material files: a set's textures as a pbrMetallicRoughness material on a UV sphere
// (<material>/<material>.gltf + .bin), and library.gltf with every material of a run on its own
// node of a grid. Built from the manifest entry (which output holds which role), so a reader of
// the manifest could rebuild them.
//
// Conventions of this module (decided once here):
//  - the mesh is a UV sphere of radius 0.5 m (64 segments, 32 rings) with normals, tangents
//    (w = +1: the bitangent cross(N, T) points to the image's top, glTF's +Y normal-map
//    convention) and texture coordinates, counter-clockwise front faces, no degenerate
//    triangles at the poles. A sphere, not a plane: it shows the material under every angle of
//    light and view at once (the roughness and metalness response, the normal map's relief on
//    both flanks), as matforge's own preview does; tangents are written so no viewer has to
//    generate them (MikkTSpace on the poles' fan is where viewers disagree);
//  - URIs are relative to the .gltf file and percent-encoded (RFC 3986, '/' kept);
//  - texture slots follow glTF 2.0 section 3.9: base color (sRGB RGB, A = alpha),
//    metallicRoughness (G roughness, B metalness), occlusion (R), normal (+Y), emissive (sRGB,
//    emissiveFactor 1); factors left at their defaults of 1 (the textures carry the values);
//  - `asset.copyright` (glTF 2.0: "a copyright message suitable for display to credit the
//    content creator") is the material's credit line (manifest/attribution.hpp material_credit),
//    absent where its licence is unknown; library.gltf carries the materials' one credit when
//    they share it, else a pointer to ATTRIBUTION.md;
//  - JSON text is deterministic (sorted keys, 2-space indent): same inputs, same bytes.
#pragma once
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/files.hpp"
#include "manifest/manifest.hpp"

namespace mf::gltf {

struct Files {
    std::string gltf;          // JSON text
    std::vector<uint8_t> bin;  // the mesh buffer
};

// The mesh buffer (positions, normals, tangents, texture coordinates, 16-bit indices) shared by
// every file: the same bytes for each material.
const std::vector<uint8_t>& sphere_buffer();

// The .gltf of `m` written at `gltf_file` (relative to the manifest's folder), referencing its
// buffer as `bin_uri` beside it: alphaMode and alphaCutoff from m.alpha_mode (MASK, BLEND; none
// when opaque), KHR_materials_emissive_strength when m.emissive_strength > 1. False + `error`
// when the outputs do not fit glTF's slots.
bool material_gltf(const manifest::Material& m, const std::string& gltf_file, const std::string& bin_uri, Files& out,
                   std::string& error);

// library.gltf at the root of `out_dir` (its buffer `library.bin`, sphere_buffer()): each item's
// material, read back from its .gltf, on a node of a square grid, 1.25 m apart, named after the
// material, in the items' order (the manifest's: by name). The .gltf files are read now (false +
// `error` naming the file); the text is made by the producer returned, as it is written, from
// temporary files in `out_dir` (a library of 100,000 materials is never held in memory).
struct LibraryItem {
    std::string name;
    std::string gltf_file;  // relative to out_dir
};
std::optional<ByteProducer> library_gltf(const std::vector<LibraryItem>& items, const std::filesystem::path& out_dir,
                                         std::string& error);

// A relative path as a URI reference (RFC 3986 percent-encoding, '/' kept).
std::string uri_of(const std::string& relative_path);

// What feeds a material input of role `role`, as the MaterialX and USD files bind it (the glTF
// has fixed slots, material_gltf): the first texture channel holding the role (in the
// manifest's order of outputs and channels), or else the constant the manifest records for it
// (a generated map's value, RGB for 3 numbers).
struct RoleSource {
    const manifest::Output* output = nullptr;  // the texture, or nullptr
    const Channel* channel = nullptr;          // its channel ("RGB", "R", ... "A")
    std::optional<std::array<float, 3>> constant;
};
RoleSource role_source(const manifest::Material& m, Role role);

// The surface inputs the MaterialX and USD files bind, in the order both list them: the role
// each reads, whether its map is colour (sRGB), and its name and type in MaterialX's gltf_pbr and
// in USD's UsdPreviewSurface. One table for both writers (mtlx.cpp, usd.cpp).
struct SurfaceInput {
    struct Name {
        const char* input;
        const char* type;
    };
    Role role;
    bool color;
    Name mtlx, usd;
};
inline constexpr SurfaceInput kSurfaceInputs[] = {
    {Role::albedo, true, {"base_color", "color3"}, {"diffuseColor", "color3f"}},
    {Role::opacity, false, {"alpha", "float"}, {"opacity", "float"}},
    {Role::metalness, false, {"metallic", "float"}, {"metallic", "float"}},
    {Role::roughness, false, {"roughness", "float"}, {"roughness", "float"}},
    {Role::occlusion, false, {"occlusion", "float"}, {"occlusion", "float"}},
    {Role::normal, false, {"normal", "vector3"}, {"normal", "normal3f"}},
    {Role::emissive, true, {"emissive", "color3"}, {"emissiveColor", "color3f"}},
};

}  // namespace mf::gltf
