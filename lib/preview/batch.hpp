// `matforge preview`'s batch: the materials of a manifest (or a scene file's own) rendered, each
// loaded, uploaded, rendered and written; one that fails is reported and the others are still
// rendered. A pipeline at the device's pace (issue 49):
//  - workers (one per hardware thread, BatchOptions::jobs) read materials in manifest order and
//    prepare their textures, as far ahead as a memory budget allows (the bytes of prepared
//    textures and rendered images held, not a count: 1K materials run far ahead, 8K ones alone);
//  - lanes (renderers of one device, each on its own thread with its own command pool, targets
//    and readback; the queue is shared under a lock) upload and draw, so that one material's
//    submit-and-wait overlaps the next one's: on a GPU the host, not the device, was the limit
//    (docs/bench/README.md, A library on the H200); one lane on lavapipe, whose rasterizer
//    already runs on every core;
//  - the same workers encode and write the images (first, before reading more) and free the
//    drawn materials' device objects.
// Messages come out in job order, as one loop would say them. The command (options, exit codes)
// is tools/matforge/cmd_preview.cpp.
#pragma once
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <future>
#include <memory>
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

// A device being made on its own thread while the caller does the rest of its start: on the H100
// the NVIDIA driver takes 0.16 s to make one, and `matforge preview` spent 0.05 s (100 materials)
// to 0.2 s (400) before its batch, mostly parsing the manifest's JSON (docs/bench/README.md).
// render_batch takes the device from it (once) instead of making one from
// BatchOptions::context; a failure to make one (render::NoDeviceError) is thrown there, as it
// would have been. Unused, it is destroyed once made.
struct DeviceAhead {
    std::future<std::unique_ptr<render::Context>> made;
};
std::shared_ptr<DeviceAhead> start_device(const render::ContextOptions& options);

struct BatchOptions {
    render::ContextOptions context;
    // When set: the batch's device, made from the options start_device was given (the same
    // `context`, so that the contexts agree); else the batch makes one from `context`.
    std::shared_ptr<DeviceAhead> device_ahead;
    std::filesystem::path out;   // the folder of <stem>.<format>
    std::string format = "png";  // "png" (8-bit sRGB) | "exr" (linear float)
    bool contact_sheet = false;  // keep each image's 8-bit pixels as a SheetTile
    bool progress = false;       // a line per image written, and the device's line first
    unsigned jobs = 0;           // workers reading and writing; 0: one per hardware thread
    unsigned lanes = 0;          // renderers fed at once; 0: by the device (lanes_for)
    // Bytes of prepared textures and rendered images held at once; a material larger than the
    // whole is still rendered, alone.
    uint64_t memory_budget = uint64_t{1} << 30;
};

// The lanes a batch uses on `device` when BatchOptions::lanes is 0: one on a CPU device, else one
// per four hardware threads, 1..4 (the H200 host: 4; measured in docs/bench/README.md).
unsigned lanes_for(const render::DeviceInfo& device);

// Where a batch's time went (`preview --timings`), in seconds. Wall clock from the batch's start
// to each point; thread time summed over the workers or the lanes that spent it.
struct BatchTimes {
    double device = 0.0;     // the device made (render::Context): materials are prepared from here
    double renderers = 0.0;  // every lane's renderer made (pipelines, the scene's load-time passes)
    double first = 0.0;      // the first material's outcome said (its image written)
    double total = 0.0;
    double teardown = 0.0;  // after `total`: the workers joined, the renderers and the device destroyed
    unsigned lanes = 0, workers = 0;
    double read = 0.0;       // workers: files decoded, textures converted (render::prepare)
    double read_wait = 0.0;  // of `read`: waiting for the device, or for the renderers to warm a variant
    double upload = 0.0;     // lanes: staging copies and their submission
    double draw = 0.0;       // lanes: render and read back
    double write = 0.0;      // workers: images encoded and written
    render::Renderer::HostTimes lanes_host;  // upload and draw by part, summed over the lanes
};

struct BatchResult {
    size_t rendered = 0, failed = 0;
    std::vector<SheetTile> tiles;  // with contact_sheet: the rendered materials', in job order
    BatchTimes times;
    // The most bytes held at once, as BatchOptions::memory_budget counts them: at most the budget,
    // but for the two materials read before any size is known and a lone one larger than it.
    uint64_t held_most = 0;
};

// Renders `jobs` with `sf`'s scene; every message goes to `say`, in job order. A material that
// cannot be read, uploaded, drawn or written counts as failed, with a line naming it.
// Throws render::NoDeviceError when no device can be made, and render::Error (or another
// std::exception) when the renderer itself fails: then no later material is rendered.
BatchResult render_batch(const SceneFile& sf, const std::vector<Job>& jobs, const BatchOptions& opt,
                         const std::function<void(const std::string&)>& say);

}  // namespace mf::preview
