// matforge preview [<manifest.json>] -o <out-dir> [--scene FILE.json] [--size N]
//   [--shape sphere|cube|plane] [--light SPEC]... [--env FILE.hdr|.exr] [--format png|exr]
//   [--contact-sheet FILE.png] [--device auto|gpu|cpu] [--brdf standard|accurate|assignment]
#include <unistd.h>

#include <iostream>
#include <memory>

#include "command.hpp"
#include "preview/preview.hpp"

namespace {

struct PreviewArgs {
    std::string manifest, out, scene, shape, env, contact_sheet, brdf;
    uint32_t size = 0;
    std::vector<std::string> lights;
    std::string format = "png", device = "auto";
    bool validation = false;
};

// Runs at command time, not during static initialization: the registration below holds no reference to
// std::cerr (a global of another translation unit).
int run_preview(const PreviewArgs& a) {
    mf::preview::Options o;
    if (!a.manifest.empty()) o.manifest = a.manifest;
    o.out_dir = a.out;
    if (!a.scene.empty()) o.scene = a.scene;
    if (a.size) o.size = a.size;
    if (!a.shape.empty()) o.shape = a.shape;
    o.lights = a.lights;
    if (!a.env.empty()) o.env = a.env;
    o.format = a.format;
    if (!a.contact_sheet.empty()) o.contact_sheet = a.contact_sheet;
    o.device = a.device;
    if (!a.brdf.empty()) o.brdf = a.brdf;
    o.validation = a.validation;
    // Progress on a terminal, quiet otherwise (scripts read the exit code and the files).
    o.quiet = !isatty(STDERR_FILENO);
    return mf::preview::run(o, std::cerr);
}

const mf::cli::Register reg{{
    "preview", 30,
    [](CLI::App& sub) -> std::function<int()> {
        auto a = std::make_shared<PreviewArgs>();
        sub.add_option("manifest", a->manifest, "manifest.json written by `matforge ingest` (optional with a --scene that holds a material)");
        sub.add_option("-o,--out", a->out, "output folder: <material name>.png|.exr (with no manifest: <scene name>.png)")->required();
        sub.add_option("--scene", a->scene, "scene file (JSON): camera, shape, lights, background, environment, material, output; default: one white key light on a sphere, black background");
        sub.add_option("--size", a->size, "image width and height in pixels, 1..16384 (default: the scene's, else 512)")->check(CLI::Range(1, 16384));
        sub.add_option("--shape", a->shape, "sphere | cube | plane (default: the scene's, else sphere)")->check(CLI::IsMember({"sphere", "cube", "plane"}));
        sub.add_option("--light", a->lights,
                       "light, repeatable; replaces the scene's lights: dir:X,Y,Z[:INTENSITY[:R,G,B]] (direction of travel; default intensity 3) "
                       "or point:X,Y,Z[:INTENSITY[:R,G,B]] (default intensity 10, E = I/d²)")
            ->allow_extra_args(false);
        sub.add_option("--env", a->env, "equirectangular environment (.hdr, .exr; linear) for image-based lighting (default: none)");
        sub.add_option("--format", a->format, "png (8-bit, sRGB-encoded) | exr (linear float radiance); default png")->check(CLI::IsMember({"png", "exr"}));
        sub.add_option("--contact-sheet", a->contact_sheet, "also write every material on one labeled PNG");
        sub.add_option("--device", a->device, "auto (a GPU if any, else lavapipe) | gpu | cpu; default auto")->check(CLI::IsMember({"auto", "gpu", "cpu"}));
        sub.add_option("--brdf", a->brdf,
                       "standard (the mission's BRDF, errata fixed) | accurate (height-correlated Smith, multiple-scattering compensation) "
                       "| assignment (diffuse without 1/π, as the course's engine); default: the scene's, else standard")
            ->check(CLI::IsMember({"standard", "accurate", "assignment"}));
        sub.add_flag("--vk-validation", a->validation, "run with the Khronos validation layer and report its messages (diagnostics; slow)");
        return [a] { return run_preview(*a); };
    },
    "render the materials of a manifest with the full BRDF, headless (PNG or EXR)"}};

}  // namespace
