// matforge preview [<manifest.json>] -o <out-dir> [--scene FILE.json] [--size N]
//   [--shape sphere|cube|plane] [--light SPEC]... [--env FILE.hdr|.exr] [--format png|exr]
//   [--contact-sheet FILE.png] [--device auto|gpu|cpu] [--brdf standard|accurate|assignment]
//   [--aa N|msaaN] [--textures fast|exact] [--shading auto|raster|compute] [--allow-outside]
//   [--vk-validation]
// Options -> scene -> materials -> images: every material is loaded, uploaded, rendered and
// written in manifest order; one that fails is reported and the others are still rendered. A
// pipeline: while material i renders (on the device, or lavapipe's threads), materials i+1 and
// i+2 are read and their textures prepared on other threads, and material i-1's image is encoded
// and written on another. Messages come out in manifest order, as one loop would say them.
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <set>

#include "command.hpp"
#include "core/limits.hpp"
#include "core/text.hpp"
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
    bool validation = false, allow_outside = false, ground = false;
};

// A material name as a file name: path separators and characters shells trip on become '_';
// names that meet case-insensitively (A, a) get _2, _3 … so no preview overwrites another.
std::string unique_stem(const std::string& name, std::set<std::string>& taken) {
    std::string s = name;
    for (char& c : s)
        if (c == '/' || c == '\\' || c == ':' || c == '*' || c == '?' || c == '"' || c == '<' || c == '>' || c == '|')
            c = '_';
    if (s.empty() || s == "." || s == "..") s = "material";
    std::string candidate = s;
    for (int n = 2; !taken.insert(ascii_lower(candidate)).second; ++n) candidate = s + "_" + std::to_string(n);
    return candidate;
}

struct Job {
    std::string name, stem;
    // `samples`: the device's block formats (DDS/KTX2 outputs go up as written where it takes them).
    std::function<std::optional<render::Material>(const preview::BlockSupport& samples, std::vector<std::string>& notes,
                                                  std::string& error)>
        load;
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
std::optional<std::vector<Job>> build_jobs(const PreviewArgs& a, const preview::SceneFile& sf) {
    std::vector<Job> jobs;
    std::set<std::string> stems;
    if (!a.manifest.empty()) {
        std::string error;
        auto m = manifest::read_manifest(a.manifest, error);
        if (!m) {
            say("preview", error);
            return std::nullopt;
        }
        const std::filesystem::path dir = std::filesystem::path(a.manifest).parent_path();
        const preview::MaterialOptions mo{a.allow_outside, {}};
        for (manifest::Material& mm : m->materials) {
            const std::string stem = unique_stem(mm.name, stems);
            jobs.push_back({mm.name, stem,
                            [mm = std::move(mm), dir, mo, &sf](const preview::BlockSupport& samples,
                                                               std::vector<std::string>& notes,
                                                               std::string& err) -> std::optional<render::Material> {
                                preview::MaterialOptions o = mo;
                                o.samples = samples;
                                auto mat = preview::load_material(mm, dir, o, notes, err);
                                if (mat && sf.material && !preview::apply_scene_material(*sf.material, *mat, err))
                                    return std::nullopt;
                                if (mat) preview::place_textures(sf, *mat);
                                return mat;
                            }});
        }
        if (jobs.empty()) say("preview", "note: " + a.manifest + " lists no materials");
        return jobs;
    }
    if (!sf.material) {
        say("preview", a.scene + ": without a manifest the scene must hold a \"material\"");
        return std::nullopt;
    }
    const std::string name = std::filesystem::path(a.scene).stem().string();
    jobs.push_back({name, unique_stem(name, stems),
                    [name, &sf](const preview::BlockSupport&, std::vector<std::string>&,
                                std::string& err) -> std::optional<render::Material> {
                        render::Material m;
                        m.name = name;
                        if (!preview::apply_scene_material(*sf.material, m, err)) return std::nullopt;
                        preview::place_textures(sf, m);
                        return m;
                    }});
    return jobs;
}

ExitCode run_preview(const PreviewArgs& a) {
    if (a.manifest.empty() && a.scene.empty())
        return fail("preview", "nothing to render: give a manifest.json, or a --scene file that holds a material");
    const auto sf = build_scene(a);
    if (!sf) return ExitCode::usage;
    const auto jobs = build_jobs(a, *sf);
    if (!jobs) return ExitCode::usage;
    // Progress on a terminal, quiet otherwise (scripts read the exit code and the files).
    const bool quiet = !::isatty(STDERR_FILENO);
    const render::Scene& scene = sf->scene;

    render::ContextOptions co;
    co.device = *render::parse_device_kind(a.device);  // CLI11 checked the name
    co.validation = a.validation;
    if (a.validation) co.log = std::make_shared<render::MessageLog>();
    ExitCode status = ExitCode::ok;
    const auto started = std::chrono::steady_clock::now();
    size_t rendered = 0, failed = 0;
    std::vector<preview::SheetTile> tiles;
    std::error_code ec;
    std::filesystem::create_directories(a.out, ec);

    // What one material comes to: its messages in the order one loop would say them, whether it
    // failed, and its 8-bit image for the contact sheet.
    struct Outcome {
        std::vector<std::string> lines;
        bool failed = false;
        std::vector<uint8_t> rgba8;
    };
    // The reading half, on a worker thread: files decoded, textures converted and their mips made
    // (render::Renderer::prepare makes no Vulkan call that needs the renderer's thread).
    struct Loaded {
        std::optional<render::PreparedMaterial> prepared;
        std::vector<std::string> notes;
        std::string error;
    };
    try {
        // The first material is read while the device starts and the scene's load-time passes
        // run (the studio environment's prefiltering): the reading waits for the renderer only
        // where it needs it, to know a GPU texture file's formats and to prepare the textures.
        std::optional<render::Context> context;
        std::optional<render::Renderer> renderer;
        std::promise<void> made_early;
        const std::shared_future<void> ready = made_early.get_future().share();
        auto load = [&renderer, &ready, &jobs](size_t i) {
            Loaded l;
            try {
                auto m = (*jobs)[i].load(
                    [&](uint32_t f) {
                        ready.get();
                        return renderer->samples(f);
                    },
                    l.notes, l.error);
                if (m) {
                    ready.get();
                    l.prepared = renderer->prepare(*m);
                }
            } catch (const std::exception& e) {  // this material's textures (or the renderer); the others go on
                l.error = e.what();
            }
            return l;
        };
        std::deque<std::future<Loaded>> loading;
        size_t launched = 0;
        if (!jobs->empty()) loading.push_back(std::async(std::launch::async, load, launched++));
        // Destroyed before `loading` (which waits for the readers): unset, it wakes them.
        std::promise<void> made = std::move(made_early);
        try {
            context.emplace(co);
            if (!quiet)
                say("preview", context->info().name + (context->info().cpu ? " (CPU)" : "") + ", " +
                                   std::to_string(scene.width) + "x" + std::to_string(scene.height) + ", " +
                                   std::to_string(jobs->size()) + " material(s)");
            renderer.emplace(*context, scene);
            made.set_value();
        } catch (...) {
            made.set_exception(std::current_exception());
            throw;
        }
        for (const std::string& n : renderer->take_notes()) say("preview", "note: " + n);
        auto done = [](Outcome o) {
            std::promise<Outcome> p;
            p.set_value(std::move(o));
            return p.get_future();
        };
        // Outcomes in manifest order, said as they complete; at most `keep` left in flight (the
        // last material's image may still be being written while the next one renders).
        std::deque<std::future<Outcome>> pending;
        size_t reported = 0;
        auto flush = [&](size_t keep) {
            while (pending.size() > keep) {
                Outcome o = pending.front().get();
                pending.pop_front();
                const Job& job = (*jobs)[reported++];
                for (const std::string& line : o.lines) say("preview", line);
                ++(o.failed ? failed : rendered);
                if (o.failed) status = ExitCode::findings;
                else if (!a.contact_sheet.empty())
                    tiles.push_back({job.name, scene.width, scene.height, std::move(o.rgba8)});
            }
        };
        // Reading runs ahead, so that it has work while the device renders (on lavapipe, whose
        // passes are not all multithreaded, it fills idle cores): two materials ahead, one where
        // the last material's textures took more than 128 MB (4K maps), none past 512 MB (8K:
        // each in memory alone, as without the pipeline). The first is read alone, to know.
        for (size_t i = 0; i < jobs->size(); ++i) {
            if (launched == i) loading.push_back(std::async(std::launch::async, load, launched++));
            const Job& job = (*jobs)[i];
            Loaded l = loading.front().get();
            loading.pop_front();
            const size_t bytes = l.prepared ? l.prepared->bytes() : 0;
            const size_t ahead = bytes > (size_t{512} << 20) ? 0 : bytes > (size_t{128} << 20) ? 1 : 2;
            for (; launched < jobs->size() && launched <= i + ahead; ++launched)
                loading.push_back(std::async(std::launch::async, load, launched));
            Outcome o;
            for (const std::string& n : l.notes) o.lines.push_back("note: " + n);
            if (!l.prepared) {
                o.lines.push_back(job.name + ": " + l.error);
                o.failed = true;
                pending.push_back(done(std::move(o)));
                flush(1);
                continue;
            }
            try {
                const render::GpuMaterial gm = renderer->upload(std::move(*l.prepared));
                for (const std::string& n : renderer->take_notes()) o.lines.push_back(job.name + ": note: " + n);
                std::vector<uint8_t> rgba8;
                std::vector<float> rgba32f;
                if (a.format == "png" || !a.contact_sheet.empty()) rgba8 = renderer->render(gm, sf->output).rgba8;
                if (a.format != "png") {
                    render::OutputOptions lin;
                    lin.format = render::PixelFormat::rgba32f;
                    rgba32f = renderer->render(gm, lin).rgba32f;
                }
                // Encoded and written on a thread of its own while the next material renders.
                const std::filesystem::path out = std::filesystem::path(a.out) / (job.stem + "." + a.format);
                const std::string progress = "[" + std::to_string(i + 1) + "/" + std::to_string(jobs->size()) + "] ";
                pending.push_back(std::async(std::launch::async, [&a, &scene, &job, out, progress, quiet,
                                                                  o = std::move(o), rgba8 = std::move(rgba8),
                                                                  rgba32f = std::move(rgba32f)]() mutable {
                    std::string error;
                    bool written = false;
                    try {
                        written = a.format == "png"
                                      ? preview::write_png(out, scene.width, scene.height, rgba8, error)
                                      : preview::write_exr(out, scene.width, scene.height, rgba32f, error);
                    } catch (const std::exception& e) {
                        error = e.what();
                    }
                    if (!written) {
                        o.lines.push_back(job.name + ": " + error);
                        o.failed = true;
                    } else if (!quiet) {
                        o.lines.push_back(progress + out.string());
                    }
                    o.rgba8 = std::move(rgba8);
                    return std::move(o);
                }));
            } catch (const render::NoDeviceError&) {
                throw;
            } catch (const std::exception& e) {  // this material's upload or draw failed; the others go on
                o.lines.push_back(job.name + ": " + e.what());
                o.failed = true;
                pending.push_back(done(std::move(o)));
            }
            flush(1);
        }
        flush(0);
    } catch (const render::NoDeviceError& e) {
        return fail("preview", e.what());
    } catch (const std::exception& e) {
        return fail("preview", e.what(), ExitCode::findings);
    }
    if (co.log) {
        for (const std::string& msg : co.log->messages()) say("preview", "vulkan validation: " + msg);
        if (co.log->count() > 0) status = ExitCode::findings;
    }
    if (!a.contact_sheet.empty() && !tiles.empty()) {
        uint32_t w = 0, h = 0;
        std::vector<uint8_t> sheet;
        preview::compose_contact_sheet(tiles, w, h, sheet);
        const std::filesystem::path file(a.contact_sheet);
        if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path(), ec);
        std::string error;
        if (!preview::write_png(file, w, h, sheet, error)) return fail("preview", error, ExitCode::findings);
        if (!quiet) say("preview", "contact sheet: " + file.string());
    }
    // One line on success too, as ingest and report say theirs (scripts may ignore it).
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    say("preview", std::to_string(rendered) + " rendered" +
                       (failed ? ", " + std::to_string(failed) + " failed" : std::string()) + " in " + fixed(secs, 1) +
                       " s: " + a.out + (a.contact_sheet.empty() ? "" : ", " + a.contact_sheet));
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
         sub.add_flag("--vk-validation", a->validation,
                      "run with the Khronos validation layer and report its messages (diagnostics; slow)");
         return [a] { return run_preview(*a); };
     },
     "render the materials of a manifest with a physically based BRDF, headless (PNG or EXR)"}};

}  // namespace
}  // namespace mf::cli
