// Engine material files (a preset's `material_file`: godot, unity-hdrp, unity-urp, unreal,
// d3d11): the files an engine or its editor opens as they are, beside the textures, so that no
// import setting is clicked by hand (sRGB off on data maps, normal maps imported as normal maps,
// every map in its slot). Built from the manifest entry and the preset's slot table
// (preset/engine_slots.hpp), so a reader of the manifest could rebuild them.
//
// Conventions of this module (decided once here):
//  - a texture's slot is the one slot_of() gives the channels its manifest entry lists; whether the engine samples it
//    as colour is the slot's (the preset check made it the output's color_space);
//  - paths are relative to the file that names them (Godot resolves a relative ext_resource path
//    against the .tres; Unity binds by guid; the Unreal script by its own folder);
//  - ids are stable: the same material and slot give the same Unity guid in every run
//    (guid_of), so a re-ingest keeps every reference in a user's project;
//  - text is deterministic (outputs in the manifest's order): same entry, same bytes.
#pragma once
#include <string>
#include <vector>

#include "manifest/manifest.hpp"
#include "preset/engine_slots.hpp"
#include "preset/preset.hpp"

namespace mf::engine {

struct File {
    std::string file;    // relative to the manifest's folder
    std::string format;  // the manifest's material_files format: "tres", "import", "meta", "mat", "py", "hlsli"
    std::string text;
};

// A written texture and the slot that reads it.
struct Bound {
    const manifest::Output* output = nullptr;
    const EngineSlot* slot = nullptr;
};
// The outputs of `m` with their slots (manifest order), each bound by the channels its entry
// lists (slot_of); an output no slot reads is left out.
std::vector<Bound> bind(const EngineMaterial& e, const manifest::Material& m);
// The bound texture read by `slot`, or nullptr.
const manifest::Output* texture_of(const std::vector<Bound>& bound, std::string_view slot);

// The material files of `m` for the preset's engine, in the order they are to be written
// (textures' import settings before the material that names them): nothing for d3d11 (its
// include is per folder).
std::vector<File> material_files(const EngineMaterial& e, const manifest::Material& m);

// The files written once per output folder, whatever its sets: d3d11's matforge_material.hlsli,
// Unreal's import_all.py.
std::vector<File> folder_files(const EngineMaterial& e);

// One writer per engine (godot.cpp, unity.cpp, unreal.cpp, hlsl.cpp); each iterates its engine's
// slot table (preset/engine_slots.hpp) and names no slot itself.
std::vector<File> godot_files(const EngineMaterial& e, const manifest::Material& m, const std::vector<Bound>& bound);
std::vector<File> unity_files(const EngineMaterial& e, const manifest::Material& m, const std::vector<Bound>& bound);
std::vector<File> unreal_files(const EngineMaterial& e, const manifest::Material& m, const std::vector<Bound>& bound);
File unreal_import_all();  // import_all.py: runs every material's script under the folder
File hlsl_include();

// How a person opens a material file of `format` (the manifest's material_files format), one
// line: matforge report shows it beside each file.
std::string_view how_to_open(std::string_view format);

// `s` as a double-quoted string literal with JSON's escapes (\", \\, \n, \uXXXX for other
// control characters; bytes that are not UTF-8 become U+FFFD): what Godot's text resources,
// YAML's double-quoted scalars and Python all read back as `s`. A name is any bytes: never raw.
std::string string_literal(const std::string& s);

// A Unity asset guid (32 lowercase hex digits) derived from `what` (sha256): stable across runs.
std::string guid_of(const std::string& what);

}  // namespace mf::engine
