// Direct3D 11: matforge_material.hlsli (this folder), embedded at build time and written as it
// is once per output folder (engine.hpp folder_files).
#include "engine/engine.hpp"

namespace mf::engine {
namespace {
#include "matforge_material_hlsli.inc"  // kMaterialHlsli
}  // namespace

File hlsl_include() { return {"matforge_material.hlsli", "hlsli", kMaterialHlsli}; }

}  // namespace mf::engine
