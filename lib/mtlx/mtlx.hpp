// MaterialX documents of a set's written textures (<material>/<material>.mtlx), beside the
// glTF: the same material for MaterialX hosts (Houdini, Maya, Blender, Omniverse, USD).
//
// Conventions of this module (decided once here):
//  - the shader is `gltf_pbr` (MaterialX's standard bxdf library, ND_gltf_pbr_surfaceshader):
//    the same model and the same inputs as the .gltf beside it (base color + alpha, metallic,
//    roughness, occlusion, normal, emissive + strength, alpha mode and cutoff), so every map the
//    preset writes has an input (standard_surface has no occlusion; open_pbr_surface none
//    either), and a MaterialX host renders what a glTF viewer renders;
//  - one `image` node per (file, type) read, named after the file ("img_<stem>"); a packed
//    texture's channels through `extract` nodes (index 0-3 = R, G, B, A), the normal map through
//    a `normalmap` node (MaterialX's tangent space is +Y, the gltf preset's convention);
//  - `colorspace="srgb_texture"` on the colour maps' file inputs only (base color, emissive);
//    data maps carry none (raw);
//  - file paths relative to the document's folder; names valid MaterialX identifiers;
//  - text deterministic (outputs in the manifest's order): same entry, same bytes.
#pragma once
#include <string>

#include "gltf/gltf.hpp"
#include "manifest/manifest.hpp"

namespace mf::mtlx {

// The document of `m` written at `mtlx_file` (relative to the manifest's folder), with the
// glTF's alpha mode and cutoff (gltf_pbr's alpha_mode: 0 opaque, 1 mask, 2 blend).
std::string material_mtlx(const manifest::Material& m, const std::string& mtlx_file, const gltf::MaterialOptions& opt);

}  // namespace mf::mtlx
