// `matforge preview`'s batch: the materials of a manifest (or a scene file's own) rendered in
// order, each loaded, uploaded, rendered and written; one that fails is reported and the others
// are still rendered. A pipeline: while material i renders (on the device, or lavapipe's
// threads), materials i+1 and i+2 are read and their textures prepared on other threads, and
// material i-1's image is encoded and written on another. Messages come out in job order, as
// one loop would say them. The command (options, exit codes) is tools/matforge/cmd_preview.cpp.
#pragma once
#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "preview/preview.hpp"
#include "render/render.hpp"

namespace mf::preview {

// One material to render: `load` reads it (its notes and error filled; `samples`: the device's
// block formats, so DDS/KTX2 outputs go up as written where it takes them).
struct Job {
    std::string name;  // as messages and the contact sheet name it
    std::string stem;  // the image's file name without extension (unique_stem)
    std::function<std::optional<render::Material>(const BlockSupport& samples, std::vector<std::string>& notes,
                                                  std::string& error)>
        load;
};

// A material name as a file name: path separators and characters shells trip on become '_';
// names that meet case-insensitively (A, a) get _2, _3 … so no preview overwrites another.
std::string unique_stem(const std::string& name, std::set<std::string>& taken);

// The manifest's materials as jobs, each with the scene file's material and texture placement
// applied. nullopt + `error` when the manifest cannot be read.
std::optional<std::vector<Job>> manifest_jobs(const std::filesystem::path& manifest, const SceneFile& sf,
                                              bool allow_outside, std::string& error);
// The scene file's own material as the one job (named after `scene_file`); nullopt + `error`
// when the scene holds none.
std::optional<std::vector<Job>> scene_jobs(const std::filesystem::path& scene_file, const SceneFile& sf,
                                           std::string& error);

struct BatchOptions {
    render::ContextOptions context;
    std::filesystem::path out;   // the folder of <stem>.<format>
    std::string format = "png";  // "png" (8-bit sRGB) | "exr" (linear float)
    bool contact_sheet = false;  // keep each image's 8-bit pixels as a SheetTile
    bool progress = false;       // a line per image written, and the device's line first
};

struct BatchResult {
    size_t rendered = 0, failed = 0;
    std::vector<SheetTile> tiles;  // with contact_sheet: the rendered materials', in job order
};

// Renders `jobs` with `sf`'s scene; every message goes to `say`, in job order. A material that
// cannot be read, uploaded, drawn or written counts as failed, with a line naming it.
// Throws render::NoDeviceError when no device can be made, and render::Error (or another
// std::exception) when the renderer itself fails: then no later material is rendered.
BatchResult render_batch(const SceneFile& sf, const std::vector<Job>& jobs, const BatchOptions& opt,
                         const std::function<void(const std::string&)>& say);

}  // namespace mf::preview
