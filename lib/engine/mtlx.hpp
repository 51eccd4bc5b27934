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
//    texture's channels through `extract` nodes (index 0-3 = R, G, B, A) of a vector3 or
//    vector4 image (data: no colour space, an sRGB base colour's alpha too), the normal map through
//    a `normalmap` node (MaterialX's tangent space is +Y, the gltf preset's convention);
//  - `colorspace="srgb_texture"` on the colour maps' file inputs only (base color, emissive);
//    data maps carry none (raw);
//  - the material's credit line (manifest/attribution.hpp material_credit) as the
//    surfacematerial's `doc` (MaterialX 1.39 gives every element `doc` for human text: a
//    description, a UI's tooltip; it has no licence field), none where the licence is unknown;
//  - file paths relative to the document's folder; names valid MaterialX identifiers;
//  - text deterministic (outputs in the manifest's order): same entry, same bytes.
#pragma once
#include <functional>
#include <string>

#include "core/files.hpp"

#include "engine/gltf.hpp"
#include "manifest/manifest.hpp"

namespace mf::mtlx {

// The document of `m` written at `mtlx_file` (relative to the manifest's folder), with its
// alpha mode and cutoff (m.alpha_mode; gltf_pbr's alpha_mode: 0 opaque, 1 mask, 2 blend).
std::string material_mtlx(const manifest::Material& m, const std::string& mtlx_file);

// library.mtlx at the manifest's folder: every material `materials` visits, in its order, as the
// elements its own document holds (file paths relative to the library), in one document, so a
// MaterialX host opens every material of a run from one file. Element names derive from the
// material's identifier, made unique in the visiting order ("a-b" and "a_b": a_b, a_b_2), image
// nodes prefixed with it. Written piece by piece to `sink` (one material's text held at a time).
using MaterialVisitor = std::function<bool(const manifest::Material&)>;
bool library_mtlx(const std::function<bool(const MaterialVisitor&)>& materials, const ByteSink& sink,
                  std::string& error);

}  // namespace mf::mtlx
