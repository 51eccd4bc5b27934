// The `matforge preview` command: options → scene → materials → images.
#include <chrono>
#include <cstdio>
#include <functional>
#include <ostream>

#include "preview/preview.hpp"

namespace mf::preview {

namespace {

// A material name as a file name: path separators and characters shells trip on become '_'.
std::string file_stem(const std::string& name) {
    std::string s = name;
    for (char& c : s)
        if (c == '/' || c == '\\' || c == ':' || c == '*' || c == '?' || c == '"' || c == '<' || c == '>' || c == '|')
            c = '_';
    if (s.empty() || s == "." || s == "..") s = "material";
    return s;
}

struct Job {
    std::string name;
    std::function<render::Material(std::vector<std::string>& notes)> load;
};

}  // namespace

int run(const Options& o, std::ostream& log) {
    try {
        if (!o.manifest && !o.scene)
            throw UsageError("nothing to render: give a manifest.json, or a --scene file that holds a material");
        if (o.format != "png" && o.format != "exr") throw UsageError("--format must be png or exr");
        const auto device = render::parse_device_kind(o.device);
        if (!device) throw UsageError("--device must be auto, gpu or cpu");

        SceneFile sf = o.scene ? read_scene_file(*o.scene) : default_scene();
        render::Scene& scene = sf.scene;
        if (o.size) {
            if (*o.size < 1 || *o.size > 16384) throw UsageError("--size must be in 1..16384");
            scene.width = scene.height = *o.size;
        }
        if (o.shape) {
            if (*o.shape == "sphere") scene.shape.type = render::ShapeType::Sphere;
            else if (*o.shape == "cube") scene.shape.type = render::ShapeType::Cube;
            else if (*o.shape == "plane") scene.shape.type = render::ShapeType::Plane;
            else throw UsageError("--shape must be sphere, cube or plane");
            if (!sf.shape_size_given) scene.shape.size = default_shape_size(scene.shape.type);
        }
        if (!o.lights.empty()) {
            if (o.lights.size() > render::kMaxLights)
                throw UsageError("at most " + std::to_string(render::kMaxLights) + " lights");
            scene.lights.clear();
            for (const std::string& spec : o.lights) {
                std::string error;
                const auto light = parse_light_spec(spec, error);
                if (!light) throw UsageError("--light: " + error);
                scene.lights.push_back(*light);
            }
        }
        if (o.brdf) {
            const auto brdf = render::parse_brdf(*o.brdf);
            if (!brdf) throw UsageError("--brdf must be standard, accurate or assignment");
            scene.brdf = *brdf;
        }
        if (o.env) sf.environment = *o.env;
        if (sf.environment) {
            try {
                scene.environment = std::make_shared<render::Environment>(
                    read_environment(*sf.environment, sf.environment_intensity));
            } catch (const std::exception& e) {
                throw UsageError(std::string("environment: ") + e.what());
            }
        }

        std::vector<Job> jobs;
        if (o.manifest) {
            const Manifest manifest = read_manifest(*o.manifest);
            for (const ManifestMaterial& mm : manifest.materials)
                jobs.push_back({mm.name, [mm, &sf](std::vector<std::string>& notes) {
                                    render::Material m = load_manifest_material(mm, notes);
                                    if (sf.material) apply_scene_material(*sf.material, m);
                                    return m;
                                }});
            if (jobs.empty()) log << "note: " << o.manifest->string() << " lists no materials\n";
        } else {
            if (!sf.material) throw UsageError(o.scene->string() + ": without a manifest the scene must hold a \"material\"");
            const std::string name = o.scene->stem().string();
            jobs.push_back({name, [name, &sf](std::vector<std::string>&) {
                                render::Material m;
                                m.name = name;
                                apply_scene_material(*sf.material, m);
                                return m;
                            }});
        }

        render::ContextOptions co;
        co.device = *device;
        co.validation = o.validation;
        if (o.validation) co.log = std::make_shared<render::MessageLog>();
        int status = 0;
        std::vector<SheetTile> tiles;
        {
            render::Context context(co);
            if (!o.quiet)
                log << "preview: " << context.info().name << (context.info().cpu ? " (CPU)" : "") << ", "
                    << scene.width << "x" << scene.height << ", " << jobs.size() << " material(s)\n";
            render::Renderer renderer(context, scene);
            std::filesystem::create_directories(o.out_dir);
            for (size_t i = 0; i < jobs.size(); ++i) {
                const Job& job = jobs[i];
                try {
                    std::vector<std::string> notes;
                    const render::Material m = job.load(notes);
                    for (const std::string& n : notes) log << "note: " << n << "\n";
                    const render::GpuMaterial gm = renderer.upload(m);
                    const std::filesystem::path out = o.out_dir / (file_stem(job.name) + "." + o.format);
                    std::vector<uint8_t> rgba8;
                    if (o.format == "png" || o.contact_sheet) {
                        render::Frame f = renderer.render(gm, sf.output);
                        rgba8 = std::move(f.rgba8);
                    }
                    if (o.format == "png") {
                        write_png(out, scene.width, scene.height, rgba8);
                    } else {
                        render::OutputOptions lin;
                        lin.format = render::PixelFormat::Rgba32F;
                        const render::Frame f = renderer.render(gm, lin);
                        write_exr(out, scene.width, scene.height, f.rgba32f);
                    }
                    if (o.contact_sheet) tiles.push_back({job.name, scene.width, scene.height, std::move(rgba8)});
                    if (!o.quiet) log << "[" << i + 1 << "/" << jobs.size() << "] " << out.string() << "\n";
                } catch (const render::NoDeviceError&) {
                    throw;
                } catch (const std::exception& e) {
                    log << "error: " << job.name << ": " << e.what() << "\n";
                    status = 1;
                }
            }
        }
        if (co.log) {
            for (const std::string& m : co.log->messages()) log << "vulkan validation: " << m << "\n";
            if (co.log->count() > 0) status = 1;
        }
        if (o.contact_sheet && !tiles.empty()) {
            uint32_t w = 0, h = 0;
            std::vector<uint8_t> sheet;
            compose_contact_sheet(tiles, w, h, sheet);
            if (o.contact_sheet->has_parent_path()) std::filesystem::create_directories(o.contact_sheet->parent_path());
            write_png(*o.contact_sheet, w, h, sheet);
            if (!o.quiet) log << "contact sheet: " << o.contact_sheet->string() << "\n";
        }
        return status;
    } catch (const UsageError& e) {
        log << "error: " << e.what() << "\n";
        return 2;
    } catch (const render::NoDeviceError& e) {
        log << "error: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        log << "error: " << e.what() << "\n";
        return 1;
    }
}

}  // namespace mf::preview
