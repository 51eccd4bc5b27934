// The material files of a preset's `material_file` (glTF): per set after its outputs, and the
// run's library.gltf after every set. Written through `Write` (the run's output folder: atomic,
// journaled), recorded in the manifest (materials[].material_files, library).
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

// <material>/<material>.gltf + .bin for `m` (its outputs written): alpha mode from the opacity
// plane (cutout: MASK at the preset's alpha_cutoff; translucent: BLEND). Adds them to
// m.material_files, or an OUTPUT_WRITE_FAILED finding (status partial) naming the file.
void write_material_files(const Preset& preset, const Planes& planes, const WriteFile& write, manifest::Material& m);

// library.gltf + library.bin at the folder's root from the materials' .gltf files (read back
// from `out_dir`; `materials` in the manifest's order, their gltf "" when they have none),
// recorded in `library`. Nothing when no material has a .gltf.
bool write_library(const std::vector<manifest::MaterialSpool::Entry>& materials, const std::filesystem::path& out_dir,
                   const WriteFile& write, const WriteStream& write_stream,
                   std::vector<manifest::MaterialFile>& library, std::string& error);

}  // namespace mf
