// The material files of a preset's `material_file`: per set after its outputs (glTF, MaterialX
// and USD for gltf; lib/engine's for godot, unity-hdrp, unity-urp, unreal), the folder's own
// (d3d11's include) and the run's library (library.gltf, .usda, .mtlx) after every set. Written
// through `Write` (the run's output folder: atomic, journaled), recorded in the manifest
// (materials[].material_files, library).
#pragma once
#include <filesystem>
#include <functional>
#include <span>
#include <string>

#include "core/files.hpp"
#include "manifest/manifest.hpp"
#include "manifest/spool.hpp"
#include "pack/pack.hpp"
#include "preset/preset.hpp"

namespace mf {

// Writes `rel` (relative to the output folder) atomically; false + `error`.
using WriteFile = std::function<bool(const std::string& rel, std::span<const unsigned char> bytes, std::string& error)>;
// The same for a file made as it is written (core/files.hpp ByteProducer).
using WriteStream = std::function<bool(const std::string& rel, const ByteProducer& produce, std::string& error)>;

// How the engine uses the opacity of `m`'s outputs (m.alpha_mode, m.alpha_cutoff): from the
// applied opacity plane (texture::classify_opacity; the preset's alpha_cutoff for a cut-out),
// nothing when no output carries it.
void decide_alpha(const Preset& preset, const Planes& planes, manifest::Material& m);

// The set's material files for `m` (its outputs written, alpha decided): gltf, a
// <material>/<material>.gltf + .bin (alpha mode from m.alpha_mode), .mtlx and .usda; an engine's
// (lib/engine). Added to m.material_files, or an OUTPUT_WRITE_FAILED finding (status partial)
// naming the file; MATERIAL_FILE_SKIPPED when the run's normals are not the engine's convention.
void write_material_files(const Preset& preset, const WriteFile& write, manifest::Material& m);

// The files a folder gets once whatever its sets (d3d11: matforge_material.hlsli), every shard
// alike, recorded in `library`.
bool write_folder_files(const Preset& preset, const WriteFile& write, std::vector<manifest::MaterialFile>& library,
                        std::string& error);

// The run's files at the folder's root, appended to `library`: ATTRIBUTION.md, every material's
// source and licence (manifest/attribution.hpp), always; library.gltf + library.bin,
// library.usda and library.mtlx from the materials of `spool` (sorted) that have a .gltf (read
// back from `out_dir` and the spool), when one has.
bool write_library(const manifest::MaterialSpool& spool, const std::filesystem::path& out_dir, const WriteFile& write,
                   const WriteStream& write_stream, std::vector<manifest::MaterialFile>& library, std::string& error);

}  // namespace mf
