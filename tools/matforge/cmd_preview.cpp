// matforge preview [<manifest.json>] -o <out-dir> [--scene FILE.json] [--size N]
//   [--shape sphere|cube|plane] [--light SPEC]... [--env FILE.hdr|.exr] [--format png|exr]
//   [--contact-sheet FILE.png] [--device auto|gpu|cpu] [--brdf standard|accurate|assignment]
//   [--aa N|msaaN] [--textures fast|exact] [--shading auto|raster|compute] [--allow-outside]
//   [-j N] [--lanes N] [--timings] [--vk-validation]
// Options -> scene -> materials -> images: the options become a scene (build_scene), the
// manifest's materials (or the scene's own) jobs, and lib/preview's batch renders them
// (preview/batch.hpp: the pipeline, messages in manifest order); this file maps the outcome to
// the exit code and writes the contact sheet.
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <functional>
#include <memory>
#include <optional>

#include "base/limits.hpp"
#include "base/stopwatch.hpp"
#include "command.hpp"
#include "core/text.hpp"
#include "preview/batch.hpp"
#include "preview/preview.hpp"

namespace mf::cli {
namespace {

struct PreviewArgs {
    std::string manifest, out, scene, shape, env, contact_sheet, brdf, tonemap;
    uint32_t size = 0;
    std::optional<float> exposure, distance;
    std::string aa, textures, shading;
    std::vector<float> orbit, uv_scale, uv_offset;
    std::string uv_aspect;
    std::vector<std::string> lights;
    std::string format = "png", device = "auto";
    bool validation = false, allow_outside = false, ground = false, timings = false;
    unsigned jobs = 0, lanes = 0;
};

// The scene with the command line's overrides applied; nullopt after printing a usage error.
std::optional<preview::SceneFile> build_scene(const PreviewArgs& a) {
    std::string error;
    // No --scene (or "lookdev"): the look-dev studio; "reference": the exact reference scene;
    // else a scene file, which starts from the reference.
    std::optional<preview::SceneFile> sf = a.scene.empty() || a.scene == "lookdev" ? preview::default_scene()
                                           : a.scene == "reference"                ? preview::reference_scene()
                                                                    : preview::read_scene_file(a.scene, error);
    if (!sf) {
        say("preview", error);
        return std::nullopt;
    }
    render::Scene& scene = sf->scene;
    if (a.size) scene.width = scene.height = a.size;
    if (!a.aa.empty()) {  // CLI11 checked it: N (supersampling) or msaaN
        const bool msaa = a.aa.rfind("msaa", 0) == 0;
        const auto n = static_cast<uint32_t>(std::stoul(msaa ? a.aa.substr(4) : a.aa));
        scene.supersample = msaa ? 1 : n;
        scene.msaa = msaa ? n : 1;
    }
    if (!a.textures.empty()) scene.fast_textures = a.textures == "fast";
    if (!a.shading.empty()) scene.shading = *render::parse_shading(a.shading);  // CLI11 checked it
    if (a.ground) scene.ground.enabled = true;
    if (!a.shape.empty()) {
        scene.shape.type = *preview::parse_shape(a.shape);  // CLI11 checked the name
        if (!sf->shape_size_given) scene.shape.size = preview::default_shape_size(scene.shape.type);
    }
    if (!a.orbit.empty() || a.distance) {
        std::optional<std::array<float, 2>> az_el;
        if (!a.orbit.empty()) az_el = std::array<float, 2>{a.orbit[0], a.orbit[1]};
        const auto cam = preview::orbit_camera(scene.camera, az_el, a.distance, error);
        if (!cam) {
            say("preview", "--orbit/--distance: " + error);
            return std::nullopt;
        }
        scene.camera = *cam;
    }
    if (!a.uv_scale.empty()) sf->uv_scale = {a.uv_scale[0], a.uv_scale.size() > 1 ? a.uv_scale[1] : a.uv_scale[0]};
    if (!a.uv_offset.empty()) sf->uv_offset = {a.uv_offset[0], a.uv_offset[1]};
    if (!a.uv_aspect.empty()) sf->keep_aspect = a.uv_aspect == "keep";
    if (!a.lights.empty()) {
        if (a.lights.size() > render::kMaxLights) {
            say("preview", "at most " + std::to_string(render::kMaxLights) + " lights");
            return std::nullopt;
        }
        scene.lights.clear();
        for (const std::string& spec : a.lights) {
            const auto light = preview::parse_light_spec(spec, error);
            if (!light) {
                say("preview", "--light: " + error);
                return std::nullopt;
            }
            scene.lights.push_back(*light);
        }
    }
    if (!a.brdf.empty()) scene.brdf = *render::parse_brdf(a.brdf);  // CLI11 checked the name
    if (!a.tonemap.empty()) sf->output.tonemap = *render::parse_tonemap(a.tonemap);
    if (a.exposure) sf->output.exposure = *a.exposure;
    if (!a.env.empty()) sf->environment = a.env;
    if (sf->environment) {
        auto env = preview::read_environment(*sf->environment, sf->environment_intensity, error);
        if (!env) {
            say("preview", "environment: " + error);
            return std::nullopt;
        }
        scene.environment = std::make_shared<render::Environment>(std::move(*env));
    }
    return sf;
}

// The materials to render: the manifest's, or the scene file's own. nullopt after a usage error.
std::optional<std::vector<preview::Job>> build_jobs(const PreviewArgs& a, const preview::SceneFile& sf) {
    std::string error;
    auto jobs = a.manifest.empty() ? preview::scene_jobs(a.scene, sf, error)
                                   : preview::manifest_jobs(a.manifest, sf, a.allow_outside, error);
    if (!jobs) say("preview", error);
    else if (!a.manifest.empty() && jobs->empty()) say("preview", "note: " + a.manifest + " lists no materials");
    return jobs;
}

ExitCode run_preview(const PreviewArgs& a) {
    if (a.manifest.empty() && a.scene.empty())
        return fail("preview", "nothing to render: give a manifest.json, or a --scene file that holds a material");
    preview::BatchOptions opt;
    opt.context.device = *render::parse_device_kind(a.device);  // CLI11 checked the name
    opt.context.validation = a.validation;
    if (a.validation) opt.context.log = std::make_shared<render::MessageLog>();
    // The device is made while the scene is built and the manifest read (a usage error found
    // there still comes first; the device is then dropped).
    opt.device_ahead = preview::start_device(opt.context);
    const auto sf = build_scene(a);
    if (!sf) return ExitCode::usage;
    const auto jobs = build_jobs(a, *sf);
    if (!jobs) return ExitCode::usage;
    opt.out = a.out;
    opt.format = a.format;
    opt.contact_sheet = !a.contact_sheet.empty();
    opt.jobs = a.jobs;
    opt.lanes = a.lanes;
    // Progress on a terminal, quiet otherwise (scripts read the exit code and the files).
    opt.progress = ::isatty(STDERR_FILENO);
    std::error_code ec;
    std::filesystem::create_directories(a.out, ec);
    const auto started = std::chrono::steady_clock::now();
    // The libraries, the scene, the manifest: read from /proc only when asked for.
    const double before_batch = a.timings ? seconds_since_process_start() : -1.0;
    preview::BatchResult r;
    try {
        r = preview::render_batch(*sf, *jobs, opt, [](const std::string& line) { say("preview", line); });
    } catch (const render::NoDeviceError& e) {
        return fail("preview", e.what());
    } catch (const std::exception& e) {
        return fail("preview", e.what(), ExitCode::findings);
    }
    ExitCode status = r.failed ? ExitCode::findings : ExitCode::ok;
    if (const auto& log = opt.context.log) {
        for (const std::string& msg : log->messages()) say("preview", "vulkan validation: " + msg);
        if (log->count() > 0) status = ExitCode::findings;
    }
    if (opt.contact_sheet && !r.tiles.empty()) {
        uint32_t w = 0, h = 0;
        std::vector<uint8_t> sheet;
        preview::compose_contact_sheet(r.tiles, w, h, sheet);
        const std::filesystem::path file(a.contact_sheet);
        if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path(), ec);
        std::string error;
        if (!preview::write_png(file, w, h, sheet, error)) return fail("preview", error, ExitCode::findings);
        if (opt.progress) say("preview", "contact sheet: " + file.string());
    }
    // One line on success too, as ingest and report say theirs (scripts may ignore it).
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    say("preview", std::to_string(r.rendered) + " rendered" +
                       (r.failed ? ", " + std::to_string(r.failed) + " failed" : std::string()) + " in " +
                       fixed(secs, 1) + " s: " + a.out + (a.contact_sheet.empty() ? "" : ", " + a.contact_sheet));
    if (a.timings) {
        const preview::BatchTimes& t = r.times;
        say("preview", "timings: device made " + fixed(t.device, 3) + " s, " + std::to_string(t.lanes) +
                           " renderer(s) " + fixed(t.renderers, 3) + " s, first image " + fixed(t.first, 3) +
                           " s, all " + fixed(t.total, 3) + " s (wall, from the start)");
        if (before_batch >= 0.0)
            say("preview", "timings: the process: " + fixed(before_batch, 2) +
                               " s before the start (its libraries, the scene, the manifest; to the kernel's tick), " +
                               fixed(t.teardown, 3) + " s after all (the renderers and the device destroyed)");
        say("preview", "timings: read " + fixed(t.read, 3) + " s (" + fixed(t.read_wait, 3) +
                           " s of it waiting for the device or the renderers) and write " + fixed(t.write, 3) +
                           " s on " + std::to_string(t.workers) + " worker(s), upload " + fixed(t.upload, 3) +
                           " s and draw " + fixed(t.draw, 3) + " s on the lane(s) (thread time, summed)");
        const render::Renderer::HostTimes& h = t.lanes_host;
        say("preview", "timings: renderers made in " + fixed(h.made, 3) + " s (load-time uploads and passes " +
                           fixed(h.made_load, 3) + " s, then waiting for the shading choice " +
                           fixed(h.made_shading, 3) + " s; thread time, summed)");
        say("preview", "timings: upload: pipelines " + fixed(h.pipelines, 3) + " s, images " + fixed(h.images, 3) +
                           " s, staging copies " + fixed(h.staging, 3) + " s, submission and the rest " +
                           fixed(h.upload_rest, 3) + " s (waiting for the lane's previous upload " +
                           fixed(h.upload_retire, 3) + " s, submitting " + fixed(h.upload_submit, 3) +
                           " s; on the device " + fixed(h.upload_device, 3) + " s); draw: submitted and waited for " +
                           fixed(h.draw_wait, 3) + " s (on the device " + fixed(h.draw_device, 3) + " s), read back " +
                           fixed(h.readback, 3) + " s");
        say("preview", "timings: held at most " + fixed(static_cast<double>(r.held_most) / (1 << 20), 1) +
                           " MiB of prepared textures and images at once (the budget: " +
                           fixed(static_cast<double>(opt.memory_budget) / (1 << 20), 0) + " MiB)");
    }
    return status;
}

const Register register_preview{
    {"preview", 30,
     [](CLI::App& sub) -> std::function<ExitCode()> {
         auto a = std::make_shared<PreviewArgs>();
         sub.add_option("manifest", a->manifest,
                        "manifest.json written by `matforge ingest` (optional with a --scene that holds a material)");
         sub.add_option("-o,--out", a->out,
                        "output folder: <material name>.png|.exr (with no manifest: <scene name>.png)")
             ->required();
         sub.add_option(
             "--scene", a->scene,
             "lookdev (the default: a studio environment generated by matforge, one key light, mid-grey background, "
             "PBR Neutral tone mapping) | reference (one white key light on a sphere, black background, no tone "
             "mapping: exact against the CPU reference) | a scene file (JSON: camera, shape, lights, background, "
             "environment, material, output; unset keys as in reference)");
         sub.add_option(
                "--tonemap", a->tonemap,
                "neutral (Khronos PBR Neutral) | aces (ACES fitted) | none (clip at 1); applied once before the "
                "sRGB curve; default: the scene's (lookdev: neutral, reference and scene files: none)")
             ->check(CLI::IsMember({"neutral", "aces", "none"}));
         sub.add_option("--exposure", a->exposure,
                        "radiance scale before tone mapping, 0..1000 (default: the scene's, 1)")
             ->check(CLI::Range(0.0, 1000.0));
         sub.add_flag("--ground", a->ground,
                      "a ground plane under the shape (grey, rough) with a soft contact shadow from the key light; "
                      "simulated only when asked (default: the scene's, none)");
         sub.add_option("--aa", a->aa,
                        "anti-aliasing: N (1..4) shades N×N samples a pixel and averages them in linear light (cost "
                        "N²; texture and specular detail too); msaa2|msaa4|msaa8 multisamples the silhouettes and "
                        "shades once a pixel; default: the scene's (lookdev msaa4, reference and scene files 1)")
             ->check(CLI::IsMember({"1", "2", "3", "4", "msaa2", "msaa4", "msaa8"}));
         sub.add_option("--textures", a->textures,
                        "fast (8-bit textures go up as read and their mips are made on the device) | exact (mips "
                        "averaged on the CPU in linear light, renormalized normals; on lavapipe 8-bit texels "
                        "filtered in float); default: the scene's (lookdev fast, reference and scene files exact)")
             ->check(CLI::IsMember({"fast", "exact"}));
         sub.add_option("--shading", a->shading,
                        "where pixels are shaded: raster (the mesh rasterized: every shape, --ground) | compute (one "
                        "compute pass casting each pixel's rays at the analytic sphere, cube or plane: faster where "
                        "raster units are few, as on datacenter GPUs; the shaderball and --ground fall back to "
                        "raster with a note) | auto (both timed once on the device, compute when at least 1.5x "
                        "faster); default: the scene's (lookdev auto, reference and scene files raster)")
             ->check(CLI::IsMember({"auto", "raster", "compute"}));
         sub.add_option("--size", a->size,
                        "image width and height in pixels, 1.." + std::to_string(kMaxImageSide) +
                            " (default: the scene's, else 512)")
             ->check(CLI::Range(1, kMaxImageSide));
         sub.add_option("--shape", a->shape,
                        "sphere | cube | plane | shaderball (a sphere girdled by a tilted ring: convex, concave and "
                        "saddle parts); default: the scene's, else sphere")
             ->check(CLI::IsMember({"sphere", "cube", "plane", "shaderball"}));
         sub.add_option("--orbit", a->orbit,
                        "AZ,EL: the camera on its orbit around the target, degrees (azimuth toward +X, elevation "
                        "above the horizon), at --distance or the scene's distance; default: the scene's camera")
             ->expected(2)
             ->delimiter(',')
             ->check(CLI::Range(-360.0, 360.0));
         sub.add_option("--distance", a->distance,
                        "camera distance to the target in metres, 0.1..1000 (default: the scene's, 4)")
             ->check(CLI::Range(0.1, 1000.0));
         sub.add_option("--uv-scale", a->uv_scale, "U[,V]: texture tiling, 0.001..1000 (default 1)")
             ->expected(1, 2)
             ->delimiter(',')
             ->check(CLI::Range(0.001, 1000.0));
         sub.add_option("--uv-offset", a->uv_offset, "U,V: texture offset (default 0,0)")
             ->expected(2)
             ->delimiter(',')
             ->check(CLI::Range(-1000.0, 1000.0));
         sub.add_option("--uv-aspect", a->uv_aspect,
                        "keep (a texture's texels stay square on the shape: a square map goes twice around the "
                        "sphere, a 2:1 map once) | stretch (the map once around, whatever its shape); default: "
                        "lookdev keep, else the scene's (stretch)")
             ->check(CLI::IsMember({"keep", "stretch"}));
         sub.add_option(
                "--light", a->lights,
                "light, repeatable; replaces the scene's lights: dir:X,Y,Z[:INTENSITY[:R,G,B]] (direction of travel; default intensity 3) "
                "or point:X,Y,Z[:INTENSITY[:R,G,B]] (default intensity 10, E = I/d²)")
             ->allow_extra_args(false);
         sub.add_option("--env", a->env,
                        "equirectangular environment (.hdr, .exr; linear) for image-based lighting (default: none)");
         sub.add_option("--format", a->format, "png (8-bit, sRGB-encoded) | exr (linear float radiance); default png")
             ->check(CLI::IsMember({"png", "exr"}));
         sub.add_option("--contact-sheet", a->contact_sheet, "also write every material on one labeled PNG");
         sub.add_option("--device", a->device, "auto (a GPU if any, else lavapipe) | gpu | cpu; default auto")
             ->check(CLI::IsMember({"auto", "gpu", "cpu"}));
         sub.add_option(
                "--brdf", a->brdf,
                "standard (GGX, Schlick Fresnel, Schlick-GGX, Lambert) | accurate (height-correlated Smith, "
                "multiple-scattering compensation) | assignment (un-normalized Lambert: diffuse without 1/π, π× too "
                "strong against the specular); default: the scene's, else standard")
             ->check(CLI::IsMember({"standard", "accurate", "assignment"}));
         sub.add_flag("--allow-outside", a->allow_outside,
                      "read manifest textures that lie outside the manifest's folder");
         sub.add_option("-j,--jobs", a->jobs,
                        "threads reading materials and writing images, 0..1024; 0 = one per hardware thread "
                        "(default 0)")
             ->check(CLI::Range(0u, 1024u));
         sub.add_option("--lanes", a->lanes,
                        "materials uploaded and drawn at once, 0..16; 0 = by the device: 1 on a CPU device, "
                        "else one per 4 hardware threads up to 4 (default 0)")
             ->check(CLI::Range(0u, 16u));
         sub.add_flag("--timings", a->timings,
                      "say where the time went: when the device and the renderers were made and the first and last "
                      "images written, and the threads' time reading, uploading, drawing and writing");
         sub.add_flag("--vk-validation", a->validation,
                      "run with the Khronos validation layer and report its messages (diagnostics; slow)");
         return [a] { return run_preview(*a); };
     },
     "render the materials of a manifest with a physically based BRDF, headless (PNG or EXR)"}};

}  // namespace
}  // namespace mf::cli
