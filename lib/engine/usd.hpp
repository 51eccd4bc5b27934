// USD text layers of a set's written textures (<material>/<material>.usda), beside the glTF and
// the MaterialX document: a UsdPreviewSurface material any USD host opens (usdview, Omniverse,
// Houdini Solaris, Maya, Blender built with USD). No USD library is packaged in Debian: the text
// is written here, and the tests open it with OpenUSD itself (PyPI usd-core:
// tests/texture/checkers/usd_open.py, Usd.Stage.Open and usdchecker's validators).
//
// Conventions of this module (decided once here):
//  - `def Material "<name>"` is the layer's defaultPrim; under it a `UsdPreviewSurface` shader
//    ("Surface"), one `UsdPrimvarReader_float2` reading the primvar "st" ("TexCoord"), and one
//    `UsdUVTexture` per written texture ("Tex_<stem>"), all connected by absolute paths;
//  - `sourceColorSpace` "sRGB" on the colour maps (base color, emissive), "raw" on data maps;
//  - a packed texture's channels through the reader's `outputs:r/g/b/a`; the normal map through
//    `outputs:rgb` with scale (2, 2, 2, 1) and bias (-1, -1, -1, 0) (UsdPreviewSurface expects a
//    tangent-space normal in [-1, 1]; st's origin is bottom-left, +Y up as the gltf preset
//    writes it); an emissive scaled down to fit [0, 1] gets its strength back as the reader's
//    scale;
//  - the opacity: `opacityThreshold` = the cutoff for a cutout, 0 for a blend;
//  - the material's credit (manifest/attribution.hpp material_credit) in the layer's
//    `customLayerData`, as ambientCG's own USD files carry theirs: `author` (who to credit),
//    `copyright` (the licence), `url` (the asset's page, where certain); none where the licence
//    is unknown. OpenUSD defines no licence field; library.usda holds none (each referenced
//    layer keeps its own);
//  - asset paths relative to the layer; text deterministic.
#pragma once
#include <string>
#include <vector>

#include "core/files.hpp"

#include "engine/gltf.hpp"
#include "manifest/manifest.hpp"

namespace mf::usd {

// The layer of `m` written at `usda_file` (relative to the manifest's folder), with its alpha
// mode and cutoff (m.alpha_mode).
std::string material_usda(const manifest::Material& m, const std::string& usda_file);

// library.usda: a `Scope "Materials"` (the defaultPrim) holding one prim per material that
// references that material's layer (`layer`, relative to the library's folder), so a USD host
// opens every material of a run from one file. Prim names are the materials' identifiers,
// made unique in the items' order ("a-b" and "a_b": a_b, a_b_2). Written piece by piece to `sink`.
struct LibraryItem {
    std::string name;
    std::string layer;
};
bool library_usda(const std::vector<LibraryItem>& items, const ByteSink& sink);

}  // namespace mf::usd
