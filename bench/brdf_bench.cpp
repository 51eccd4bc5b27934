// brdf_bench: the preview's BRDF in its own shader — what the model, the shading precision and
// the samples per pixel cost on the GPU and what they buy in accuracy.
//
//   brdf_bench [--device auto|gpu|cpu] [--size 2048] [--ref-size 256] [--reps N] [--csv FILE]
//
// Scene (bench/accuracy/knobs_brdf.cpp's, so the CPU and GPU rows compare): an orthographic unit
// sphere under one directional light (intensity 3, l = (0, 0.6, 0.8)), albedo (0.9, 0.6, 0.3),
// roughness bands (0.5; 0.045 through the highlight; 0.2; 1 in the lower half), metal on the
// right half; 1, 4 or 8 samples per pixel at the D3D11 standard multisample positions (a
// stratified sub-pixel pattern). Shaded by render/brdf_harness.hpp: the functions of
// lib/render/shaders/brdf.glsl that the preview's fragment shader calls, in fp32 or, where the
// device has shaderFloat16, with the BRDF's arithmetic in binary16.
//
// Time: median GPU time (timestamp queries) of shading --size² pixels, after one untimed run.
// Error: at --ref-size², the green channel's display code (exact sRGB of radiance clamped to
// [0, 1], × 255, unrounded) against the accurate model in double precision with 16 × 16
// stratified samples per pixel (CPU, tests/stability/brdf_reference.hpp). A pixel that is not
// finite counts as 255 codes off. Links only the renderer core (Vulkan loaded at run time), so
// the binary runs on a GPU machine with nothing but the C++ runtime and a driver.
//
// Models, by their --brdf names: assignment (standard without Lambert's 1/π: diffuse π times too
// strong against the specular lobe), standard, accurate.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "base/srgb.hpp"
#include "brdf_reference.hpp"
#include "render/brdf_harness.hpp"
#include "render/render.hpp"

namespace {

using namespace mf::render;
namespace cb = mf::cpubrdf;

struct Args {
    DeviceKind device = DeviceKind::automatic;
    uint32_t size = 2048, ref_size = 256;
    int reps = 0;  // 0: 20 on a GPU, 5 on a CPU device
    std::string csv;
};

[[noreturn]] void usage(const char* why) {
    std::fprintf(stderr,
                 "brdf_bench: %s\n"
                 "usage: brdf_bench [--device auto|gpu|cpu] [--size 2048] [--ref-size 256] [--reps N] [--csv FILE]\n",
                 why);
    std::exit(2);
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
        } else if (k == "--size") {
            a.size = static_cast<uint32_t>(std::stoul(value()));
        } else if (k == "--ref-size") {
            a.ref_size = static_cast<uint32_t>(std::stoul(value()));
        } else if (k == "--reps") {
            a.reps = std::stoi(value());
        } else if (k == "--csv") {
            a.csv = value();
        } else {
            usage(("unknown argument " + k).c_str());
        }
    }
    if (a.size == 0 || a.size > 8192 || a.ref_size == 0 || a.ref_size > 8192) usage("sizes must be 1..8192");
    return a;
}

double display_code(double radiance) { return mf::linear_to_srgb(std::clamp(radiance, 0.0, 1.0)) * 255.0; }

// knobs_brdf.cpp's scene in double, green channel of the accurate model.
double reference_radiance(double sx, double sy) {
    const double r2 = sx * sx + sy * sy;
    if (r2 > 1.0) return 0.0;
    const double rough = sy > 0.45 ? 0.5 : sy > 0.2 ? 0.045 : sy > 0.0 ? 0.2 : 1.0;
    const cb::Inputs<double> in{{sx, sy, std::sqrt(1.0 - r2)}, {0, 0, 1}, {0.0, 0.6, 0.8}, {0.9, 0.6, 0.3}, rough,
                                sx > 0.0 ? 1.0 : 0.0,          3.0};
    return cb::shade(in, cb::Model::accurate)[1];
}

std::vector<double> reference_image(uint32_t size) {
    std::vector<double> ref(size_t{size} * size);
    for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x) {
            double acc = 0;
            for (int j = 0; j < 16; ++j)
                for (int i = 0; i < 16; ++i) {  // 16 × 16 stratum centres
                    const double px = x + (i + 0.5) / 16.0, py = y + (j + 0.5) / 16.0;
                    acc += reference_radiance((px / size * 2 - 1) * 1.1, (1 - py / size * 2) * 1.1);
                }
            ref[size_t{y} * size + x] = acc / 256.0;
        }
    return ref;
}

std::vector<float> energy_table() { return cb::EnergyTable::get().texels(); }

struct Row {
    std::string model, precision;
    uint32_t spp = 1;
    double median_ms = 0, min_ms = 0, ns_per_px = 0;
    double max_codes = 0, mean_codes = 0;
    size_t nonfinite = 0;
};

}  // namespace

int main(int argc, char** argv) {
    const Args args = parse(argc, argv);
    try {
        ContextOptions co;
        co.device = args.device;
        Context context(co);
        const DeviceInfo& info = context.info();
        if (!info.timestamps) {
            std::fprintf(stderr, "brdf_bench: %s has no timestamp queries\n", info.name.c_str());
            return 1;
        }
        const int reps = args.reps ? args.reps : (info.cpu ? 5 : 20);
        BrdfHarness harness(context, energy_table());
        std::printf("device: %s (%s); shaderFloat16: %s; %u² px timed (median of %d), error at %u² px\n",
                    info.name.c_str(), info.driver.c_str(), harness.supports_fp16() ? "yes" : "no", args.size, reps,
                    args.ref_size);
        const std::vector<double> ref = reference_image(args.ref_size);

        struct ModelName {
            Brdf brdf;
            const char* name;
        };
        const ModelName models[] = {{Brdf::unnormalized_diffuse, "assignment"},
                                    {Brdf::standard, "standard"},
                                    {Brdf::accurate, "accurate"}};
        std::vector<BrdfPrecision> precisions{BrdfPrecision::fp32};
        if (harness.supports_fp16()) precisions.push_back(BrdfPrecision::fp16);

        std::vector<Row> rows;
        for (const ModelName& m : models)
            for (BrdfPrecision p : precisions)
                for (uint32_t spp : {1u, 4u, 8u}) {
                    Row r;
                    r.model = m.name;
                    r.precision = p == BrdfPrecision::fp16 ? "fp16" : "fp32";
                    r.spp = spp;
                    (void)harness.sphere(args.size, m.brdf, spp, p);  // warm-up (pipeline, caches)
                    std::vector<double> ms;
                    for (int i = 0; i < reps; ++i) ms.push_back(harness.sphere(args.size, m.brdf, spp, p));
                    std::sort(ms.begin(), ms.end());
                    r.median_ms = ms[ms.size() / 2];
                    r.min_ms = ms.front();
                    r.ns_per_px = r.median_ms * 1e6 / (double(args.size) * args.size);
                    std::vector<float> rgb;
                    harness.sphere(args.ref_size, m.brdf, spp, p, &rgb);
                    double sum = 0;
                    for (size_t i = 0; i < ref.size(); ++i) {
                        const double g = rgb[3 * i + 1];
                        double e = 255.0;
                        if (std::isfinite(g)) e = std::abs(display_code(g) - display_code(ref[i]));
                        else ++r.nonfinite;
                        r.max_codes = std::max(r.max_codes, e);
                        sum += e;
                    }
                    r.mean_codes = sum / static_cast<double>(ref.size());
                    rows.push_back(r);
                }

        std::printf("\n%-11s %-5s %4s %12s %10s %10s %15s %16s %10s\n", "model", "prec", "spp", "GPU ms", "min ms",
                    "ns/px", "max err (codes)", "mean err (codes)", "non-finite");
        for (const Row& r : rows)
            std::printf("%-11s %-5s %4u %12.3f %10.3f %10.3f %15.3g %16.3g %10zu\n", r.model.c_str(),
                        r.precision.c_str(), r.spp, r.median_ms, r.min_ms, r.ns_per_px, r.max_codes, r.mean_codes,
                        r.nonfinite);
        if (!args.csv.empty()) {
            std::ofstream csv(args.csv);
            if (!csv) {
                std::fprintf(stderr, "brdf_bench: cannot write %s\n", args.csv.c_str());
                return 1;
            }
            csv << "device,model,precision,spp,size,median_ms,min_ms,ns_per_px,ref_size,max_err_codes,mean_err_codes,"
                   "nonfinite_px\n";
            for (const Row& r : rows)
                csv << '"' << info.name << "\"," << r.model << ',' << r.precision << ',' << r.spp << ',' << args.size
                    << ',' << r.median_ms << ',' << r.min_ms << ',' << r.ns_per_px << ',' << args.ref_size << ','
                    << r.max_codes << ',' << r.mean_codes << ',' << r.nonfinite << '\n';
        }
        return 0;
    } catch (const NoDeviceError& e) {
        std::fprintf(stderr, "brdf_bench: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "brdf_bench: %s\n", e.what());
        return 1;
    }
}
