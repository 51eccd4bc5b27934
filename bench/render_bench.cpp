// render_bench: what each effect of the preview costs on the GPU.
//
//   render_bench [--device auto|gpu|cpu] [--sizes 512,2048] [--frames N] [--warmup N]
//                [--csv FILE] [--only NAME[,NAME…]] [--gpu-formats] [--texture-size N]
//                [--library N] [--ahead N] [--shading raster|compute|auto]
//
// For each configuration and size it builds a renderer (load-time passes timed once), uploads
// the material, renders --warmup frames untimed and --frames frames timed, and prints the median
// GPU time of each pass from timestamp queries. Textures and the environment are made in memory:
// no image files, so the program needs nothing but the Vulkan loader and a driver.
//
// --library N: for each textured configuration, N materials previewed one after another as
// `matforge preview` does (textures prepared on other threads ahead, upload and render with the
// 8-bit readback on this one): materials per second, file decoding and PNG writing left out
// (they stay on the host's CPU whatever the device). Printed beside it, per material: the
// device's own time (the frame's timestamped passes), and where this thread's wall time went
// (waiting for a prepared material, upload, render with its submit-and-wait and readback).
// --ahead N: materials being prepared at once (default: the host's hardware threads, 3 to 8;
// 3 was the loop before; what `matforge preview` reads ahead is lib/preview/batch.cpp's).
// Finished materials are freed on another thread (render.hpp's GpuMaterial contract).
//
// --shading: the path every configuration is shaded on (Scene::shading; default raster), so the
// same table can be made on both. The path that ran is printed for each configuration (a scene
// compute does not cover falls back to raster, said in a note) and is a CSV column.
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <deque>
#include <fstream>
#include <future>
#include <map>
#include <memory>
#include <numbers>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "render/render.hpp"

namespace {

using namespace mf::render;

struct Args {
    DeviceKind device = DeviceKind::automatic;
    std::vector<uint32_t> sizes{512, 2048};
    int frames = 0;  // 0: 50 on a GPU, 8 on a CPU device
    int warmup = 3;
    std::string csv;
    std::vector<std::string> only;
    bool gpu_formats = false;  // ContextOptions::precise_cpu_textures off
    uint32_t texture_size = 2048;
    int library = 0;  // --library N: materials previewed in a row per textured configuration
    // --ahead N. 8 was the best on the H200's 16-core host (4: as fast, 16: 5 % slower, the
    // threads contending for memory bandwidth with the upload's copies); at least 3 elsewhere.
    int ahead = std::clamp(static_cast<int>(std::thread::hardware_concurrency()), 3, 8);
    Shading shading = Shading::raster;
};

[[noreturn]] void usage(const char* why) {
    std::fprintf(stderr,
                 "render_bench: %s\n"
                 "usage: render_bench [--device auto|gpu|cpu] [--sizes 512,2048] [--frames N] [--warmup N]\n"
                 "                    [--csv FILE] [--only NAME[,NAME...]] [--gpu-formats]\n"
                 "                    [--texture-size N] [--library N] [--ahead N] [--shading raster|compute|auto]\n",
                 why);
    std::exit(2);
}

std::vector<std::string> split(const std::string& s) {
    std::vector<std::string> out;
    std::stringstream ss(s);
    for (std::string p; std::getline(ss, p, ',');) out.push_back(p);
    return out;
}

Args parse(int argc, char** argv) {
    Args a;
    for (int i = 1; i < argc; ++i) {
        const std::string k = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) usage(("missing value after " + k).c_str());
            return argv[++i];
        };
        if (k == "--device") {
            const auto d = parse_device_kind(value());
            if (!d) usage("--device must be auto, gpu or cpu");
            a.device = *d;
        } else if (k == "--sizes") {
            a.sizes.clear();
            for (const std::string& s : split(value())) {
                const long n = std::strtol(s.c_str(), nullptr, 10);
                if (n < 1 || n > 16384) usage("sizes must be in 1..16384");
                a.sizes.push_back(static_cast<uint32_t>(n));
            }
        } else if (k == "--frames") {
            a.frames = std::atoi(value().c_str());
            if (a.frames < 1) usage("--frames must be positive");
        } else if (k == "--warmup") {
            a.warmup = std::max(0, std::atoi(value().c_str()));
        } else if (k == "--csv") {
            a.csv = value();
        } else if (k == "--only") {
            a.only = split(value());
        } else if (k == "--gpu-formats") {
            a.gpu_formats = true;
        } else if (k == "--texture-size") {
            const long n = std::strtol(value().c_str(), nullptr, 10);
            if (n < 1 || n > 16384) usage("--texture-size must be in 1..16384");
            a.texture_size = static_cast<uint32_t>(n);
        } else if (k == "--library") {
            const long n = std::strtol(value().c_str(), nullptr, 10);
            if (n < 1 || n > 100000) usage("--library must be in 1..100000");
            a.library = static_cast<int>(n);
        } else if (k == "--ahead") {
            const long n = std::strtol(value().c_str(), nullptr, 10);
            if (n < 1 || n > 256) usage("--ahead must be in 1..256");
            a.ahead = static_cast<int>(n);
        } else if (k == "--shading") {
            const auto sh = parse_shading(value());
            if (!sh) usage("--shading must be raster, compute or auto");
            a.shading = *sh;
        } else if (k == "-h" || k == "--help") {
            usage("GPU time per pass of the matforge preview");
        } else {
            usage(("unknown option " + k).c_str());
        }
    }
    return a;
}

// ---- in-memory content

Texture make_texture(uint32_t size, uint32_t channels, bool srgb, uint32_t seed) {
    Texture t;
    t.width = t.height = size;
    t.channels = channels;
    t.srgb = srgb;
    t.data.resize(size_t{size} * size * channels);
    uint32_t x = seed * 2654435761u + 1u;
    for (uint8_t& texel : t.data) {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        texel = static_cast<uint8_t>(96 + (x >> 24) % 64);  // mid-range noise
    }
    return t;
}

Texture make_normal_map(uint32_t size) {
    Texture t;
    t.width = t.height = size;
    t.channels = 3;
    t.data.resize(size_t{size} * size * 3);
    const double k = 2 * std::numbers::pi * 16 / size;
    for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x) {
            const double nx = 0.4 * std::sin(k * x), ny = 0.4 * std::cos(k * y);
            const double l = std::sqrt(nx * nx + ny * ny + 1);
            uint8_t* p = &t.data[(size_t{y} * size + x) * 3];
            p[0] = static_cast<uint8_t>(std::lround((nx / l * 0.5 + 0.5) * 255));
            p[1] = static_cast<uint8_t>(std::lround((ny / l * 0.5 + 0.5) * 255));
            p[2] = static_cast<uint8_t>(std::lround((1 / l * 0.5 + 0.5) * 255));
        }
    return t;
}

std::shared_ptr<Environment> make_environment(uint32_t w, uint32_t h) {
    auto env = std::make_shared<Environment>();
    env->width = w;
    env->height = h;
    env->rgba.resize(size_t{w} * h * 4);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            float* p = &env->rgba[(size_t{y} * w + x) * 4];
            const float sky = y < h / 2 ? 1.0f : 0.2f;
            const bool sun = std::abs(int(x) - int(w / 3)) < 3 && std::abs(int(y) - int(h / 4)) < 3;
            p[0] = sun ? 500.f : 0.6f * sky;
            p[1] = sun ? 480.f : 0.7f * sky;
            p[2] = sun ? 450.f : 1.0f * sky;
            p[3] = 1.f;
        }
    return env;
}

struct Config {
    std::string name, what;
    bool textures = false, normal_map = false, environment = false;
    int point_lights = 0;
    Brdf brdf = Brdf::standard;
    PixelFormat output = PixelFormat::rgba8;
    uint32_t supersample = 1;
    Tonemap tonemap = Tonemap::none;
    ShapeType shape = ShapeType::sphere;
    bool ground = false;
    bool fill_only = false;
    uint32_t msaa = 1;
    bool fast_textures = false;
};

std::vector<Config> configs() {
    return {
        {"floor", "the fill-rate floor: the sphere's pixels written with a constant, nothing shaded", false, false,
         false, 0, Brdf::standard, PixelFormat::rgba8, 1, Tonemap::none, ShapeType::sphere, false, true},
        {"base", "constant material, 1 directional light, standard BRDF", false, false, false, 0, Brdf::standard,
         PixelFormat::rgba8},
        {"exr", "base, linear float output (resolve to floats instead of encode)", false, false, false, 0,
         Brdf::standard, PixelFormat::rgba32f},
        {"textures", "base + albedo/ORM textures (2048² unless --texture-size, trilinear)", true, false, false, 0,
         Brdf::standard, PixelFormat::rgba8},
        {"normal_map", "textures + normal map", true, true, false, 0, Brdf::standard, PixelFormat::rgba8},
        {"lights8", "base + 7 point lights (8 in all)", false, false, false, 7, Brdf::standard, PixelFormat::rgba8},
        {"accurate", "base, accurate BRDF (correlated Smith + energy compensation)", false, false, false, 0,
         Brdf::accurate, PixelFormat::rgba8},
        {"ibl", "base + environment (split-sum IBL)", false, false, true, 0, Brdf::standard, PixelFormat::rgba8},
        {"full", "textures + normal map + 8 lights + accurate + IBL", true, true, true, 7, Brdf::accurate,
         PixelFormat::rgba8},
        {"tonemap", "base + PBR Neutral tone mapping (in the encode pass)", false, false, false, 0, Brdf::standard,
         PixelFormat::rgba8, 1, Tonemap::neutral},
        {"aa2", "base, 2x2 samples a pixel", false, false, false, 0, Brdf::standard, PixelFormat::rgba8, 2},
        {"aa3", "base, 3x3 samples a pixel (--aa 3)", false, false, false, 0, Brdf::standard, PixelFormat::rgba8, 3},
        {"aa4", "base, 4x4 samples a pixel", false, false, false, 0, Brdf::standard, PixelFormat::rgba8, 4},
        {"shaderball", "base on the shaderball (mesh shading, ring and ball)", false, false, false, 0, Brdf::standard,
         PixelFormat::rgba8, 1, Tonemap::none, ShapeType::shaderball},
        {"ground", "base + ground plane with the key light's soft shadow", false, false, false, 0, Brdf::standard,
         PixelFormat::rgba8, 1, Tonemap::none, ShapeType::sphere, true},
        {"lookdev", "textures + normal map + IBL + 1 light + PBR Neutral + 3x3 samples", true, true, true, 0,
         Brdf::standard, PixelFormat::rgba8, 3, Tonemap::neutral},
        {"lookdev_aa1", "lookdev with one sample a pixel (no anti-aliasing)", true, true, true, 0, Brdf::standard,
         PixelFormat::rgba8, 1, Tonemap::neutral},
        {"msaa4", "base, 4 samples a pixel multisampled (shaded once)", false, false, false, 0, Brdf::standard,
         PixelFormat::rgba8, 1, Tonemap::none, ShapeType::sphere, false, false, 4},
        {"lookdev_msaa", "lookdev with MSAA 4x instead of 3x3 samples, CPU mips", true, true, true, 0, Brdf::standard,
         PixelFormat::rgba8, 1, Tonemap::neutral, ShapeType::sphere, false, false, 4},
        {"lookdev_fast", "lookdev with MSAA 4x and mips made on the device (the default preview)", true, true, true, 0,
         Brdf::standard, PixelFormat::rgba8, 1, Tonemap::neutral, ShapeType::sphere, false, false, 4, true},
        {"mips_device", "textures + normal map, mips made on the device (material load)", true, true, false, 0,
         Brdf::standard, PixelFormat::rgba8, 1, Tonemap::none, ShapeType::sphere, false, false, 1, true},
    };
}

// CPU time of the whole process, all threads (on lavapipe the rendering itself): unlike wall
// time, other programs on a shared machine barely move it.
double process_cpu_ms() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return (static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) * 1e3) +
           (static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec) * 1e-3);
}

double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Row {
    std::string config;
    std::string shading;  // the path that ran: raster or compute
    uint32_t size;
    std::string pass;
    double median_ms, min_ms;
    int samples;
};

}  // namespace

int main(int argc, char** argv) {
    const Args args = parse(argc, argv);
    try {
        ContextOptions co;
        co.device = args.device;
        co.precise_cpu_textures = !args.gpu_formats;
        Context context(co);
        const DeviceInfo& info = context.info();
        if (!info.timestamps) {
            std::fprintf(stderr, "render_bench: %s has no timestamp queries on its graphics queue\n",
                         info.name.c_str());
            return 1;
        }
        const int frames = args.frames ? args.frames : (info.cpu ? 8 : 50);
        std::printf("device: %s (%s), Vulkan %u.%u, %d timed frames after %d warm-up\n", info.name.c_str(),
                    info.driver.c_str(), (info.api_version >> 22) & 0x7f, (info.api_version >> 12) & 0x3ff, frames,
                    args.warmup);

        std::shared_ptr<Environment> env = make_environment(1024, 512);
        Material textured;
        textured.name = "textured";
        const uint32_t ts = args.texture_size;
        textured.textures = {make_texture(ts, 4, true, 1), make_texture(ts, 3, false, 2), make_normal_map(ts)};
        textured.albedo.texture = 0;
        textured.roughness = {1, Channel::G, false, 0.5f};
        textured.metalness = {1, Channel::B, false, 0.f};
        textured.occlusion = {1, Channel::R, false, 1.f};
        Material constant;
        constant.name = "constant";
        constant.albedo.value = {0.8f, 0.5f, 0.3f};
        constant.roughness.value = 0.4f;

        std::vector<Row> rows;
        std::printf("\n%-11s %6s  %-28s %10s %10s\n", "config", "size", "pass", "median ms", "min ms");
        for (const Config& c : configs()) {
            if (!args.only.empty() && std::find(args.only.begin(), args.only.end(), c.name) == args.only.end())
                continue;
            for (uint32_t size : args.sizes) {
                Scene scene;
                scene.width = scene.height = size;
                scene.brdf = c.brdf;
                scene.supersample = c.supersample;
                scene.shape.type = c.shape;
                scene.ground.enabled = c.ground;
                scene.fill_only = c.fill_only;
                scene.msaa = c.msaa;
                scene.fast_textures = c.fast_textures;
                scene.shading = args.shading;
                for (int i = 0; i < c.point_lights; ++i) {
                    Light l;
                    l.type = LightType::point;
                    const double a = 2 * std::numbers::pi * i / std::max(1, c.point_lights);
                    l.position = {float(3 * std::cos(a)), float(1.5 * std::sin(3 * a)), float(2 + std::sin(a))};
                    l.intensity = 8.f;
                    scene.lights.push_back(l);
                }
                if (c.environment) scene.environment = env;
                using Clock = std::chrono::steady_clock;
                const auto ms_since = [](Clock::time_point t0) {
                    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
                };
                auto t0 = Clock::now();
                Renderer renderer(context, scene);
                const double scene_wall = ms_since(t0);
                const char* path = renderer.shading() == Shading::compute ? "compute" : "raster";
                std::printf("%-11s %6u  shading: %s\n", c.name.c_str(), size, path);
                for (const std::string& n : renderer.take_notes())
                    std::printf("%-11s %6u  note: %s\n", c.name.c_str(), size, n.c_str());
                Material m = c.textures ? textured : constant;
                if (c.textures && c.normal_map) m.normal.texture = 2;
                t0 = Clock::now();
                double cpu0 = process_cpu_ms();
                const GpuMaterial gm = renderer.upload(m);
                const double upload_wall = ms_since(t0), upload_cpu = process_cpu_ms() - cpu0;
                auto emit = [&](const std::string& pass, const std::vector<double>& ms) {
                    const Row r{c.name,        path, size, pass, median(ms), *std::min_element(ms.begin(), ms.end()),
                                int(ms.size())};
                    std::printf("%-11s %6u  %-28s %10.3f %10.3f\n", r.config.c_str(), r.size, r.pass.c_str(),
                                r.median_ms, r.min_ms);
                    rows.push_back(r);
                };
                for (const PassTime& p : renderer.load_times())
                    emit("load: " + p.name.substr(0, p.name.find(' ')), {p.ms});
                // Host wall time: what a user waits for, CPU work (mips, pipeline compilation)
                // included; on lavapipe also the only exact split, see docs/bench/README.md.
                emit("load wall: scene (host)", {scene_wall});
                emit("load wall: material (host)", {upload_wall});
                emit("load cpu: material (process)", {upload_cpu});
                if (c.textures) {
                    // Again, the pipeline and the blits' shaders now compiled: what each further
                    // material of a library costs (median of five).
                    std::vector<double> wall, cpu;
                    for (int i = 0; i < 5; ++i) {
                        t0 = Clock::now();
                        cpu0 = process_cpu_ms();
                        renderer.upload(m);
                        wall.push_back(ms_since(t0));
                        cpu.push_back(process_cpu_ms() - cpu0);
                    }
                    emit("load wall: next material", wall);
                    emit("load cpu: next material", cpu);
                }

                OutputOptions out;
                out.format = c.output;
                out.tonemap = c.tonemap;
                std::map<std::string, std::vector<double>> times;
                std::vector<std::string> order;
                for (int f = 0; f < args.warmup + frames; ++f) {
                    t0 = Clock::now();
                    cpu0 = process_cpu_ms();
                    renderer.render(gm, out);
                    const double wall = ms_since(t0), cpu = process_cpu_ms() - cpu0;
                    if (f < args.warmup) continue;
                    times["frame wall (host)"].push_back(wall);
                    times["frame cpu (process)"].push_back(cpu);
                    double total = 0;
                    for (const PassTime& p : renderer.frame_times()) {
                        if (!times.count(p.name)) order.push_back(p.name);
                        times[p.name].push_back(p.ms);
                        total += p.ms;
                    }
                    times["frame (sum)"].push_back(total);
                }
                order.emplace_back("frame (sum)");
                order.emplace_back("frame wall (host)");
                order.emplace_back("frame cpu (process)");
                for (const std::string& p : order) emit(p, times[p]);
                if (args.library && c.textures) {
                    // Four texture sets in turn (each prepared anew, as distinct files would be).
                    std::vector<Material> library(4, m);
                    for (uint32_t k = 1; k < library.size(); ++k)
                        library[k].textures = {make_texture(ts, 4, true, 1 + 2 * k),
                                               make_texture(ts, 3, false, 2 + 2 * k), library[0].textures[2]};
                    std::deque<std::future<PreparedMaterial>> ahead;
                    int launched = 0;
                    auto launch = [&] {
                        const Material& lm = library[size_t(launched++) % library.size()];
                        ahead.push_back(std::async(std::launch::async,
                                                   [&renderer, &lm] { return renderer.prepare(lm); }));
                    };
                    t0 = Clock::now();
                    cpu0 = process_cpu_ms();
                    size_t checksum = 0;
                    std::vector<double> waited, uploaded, rendered, device;
                    std::future<void> freeing;  // the last material's device objects, freed on another thread
                    for (int i = 0; i < args.library; ++i) {
                        while (launched < args.library && launched < i + args.ahead) launch();
                        auto t = Clock::now();
                        PreparedMaterial pm = ahead.front().get();
                        ahead.pop_front();
                        waited.push_back(ms_since(t));
                        t = Clock::now();
                        GpuMaterial lg = renderer.upload(std::move(pm));
                        uploaded.push_back(ms_since(t));
                        t = Clock::now();
                        checksum += renderer.render(lg, out).rgba8.size();
                        rendered.push_back(ms_since(t));
                        if (freeing.valid()) freeing.get();
                        freeing = std::async(std::launch::async,
                                             [g = std::move(lg)]() mutable { GpuMaterial done = std::move(g); });
                        double frame = 0;
                        for (const PassTime& p : renderer.frame_times()) frame += p.ms;
                        device.push_back(frame);
                    }
                    if (freeing.valid()) freeing.get();
                    const double wall = ms_since(t0), cpu = process_cpu_ms() - cpu0;
                    if (checksum != size_t(args.library) * size * size * 4)
                        throw std::runtime_error("library: short frame");
                    emit("library wall per material", {wall / args.library});
                    emit("library cpu per material", {cpu / args.library});
                    emit("library: waiting for prepare", waited);
                    emit("library: upload (host)", uploaded);
                    emit("library: render (host)", rendered);
                    emit("library: frame (device)", device);
                    std::printf("%-11s %6u  library of %d materials (%u² textures, %d prepared at once): %.2f s wall, "
                                "%.1f materials/s, %.2f s CPU; a material: %.3f ms wall, %.3f ms on the device\n",
                                c.name.c_str(), size, args.library, ts, args.ahead, wall / 1e3,
                                args.library * 1e3 / wall, cpu / 1e3, wall / args.library, median(device));
                }
            }
        }
        std::printf("\nvariants:\n");
        for (const Config& c : configs())
            if (args.only.empty() || std::find(args.only.begin(), args.only.end(), c.name) != args.only.end())
                std::printf("  %-11s %s\n", c.name.c_str(), c.what.c_str());

        if (!args.csv.empty()) {
            std::ofstream csv(args.csv);
            if (!csv) {
                std::fprintf(stderr, "render_bench: cannot write %s\n", args.csv.c_str());
                return 1;
            }
            csv << "device,config,shading,size,pass,median_ms,min_ms,samples\n";
            for (const Row& r : rows)
                csv << '"' << info.name << "\"," << r.config << ',' << r.shading << ',' << r.size << ",\"" << r.pass
                    << "\"," << r.median_ms << ',' << r.min_ms << ',' << r.samples << '\n';
        }
        return 0;
    } catch (const NoDeviceError& e) {
        std::fprintf(stderr, "render_bench: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "render_bench: %s\n", e.what());
        return 1;
    }
}
