// accuracy_bench: what accuracy costs in time. Every knob's variants are measured once for
// error (against a double-precision reference) and timed with Google Benchmark; the results go
// to docs/accuracy/results.md, results.csv and error_vs_time.png.
//
//   accuracy_bench [--quick] [--out DIR] [--only KNOB-SUBSTRING] [Google Benchmark flags]
//
// --quick: small inputs and short timings (CI smoke, seconds), written to the build folder
// unless --out is given. A full run (4K resampling, 8K statistics) takes a few minutes on 2 cores.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <thread>

#include "harness.hpp"
#include "image/image.hpp"
#include "plot.hpp"

namespace fs = std::filesystem;
using mf::bench::Variant;

namespace {

// CPU seconds per call, by benchmark name.
class Collector : public benchmark::ConsoleReporter {
public:
    std::map<std::string, double> seconds;
    void ReportRuns(const std::vector<Run>& runs) override {
        for (const Run& r : runs)
            if (!r.error_occurred && r.iterations > 0)
                seconds[r.run_name.function_name] = r.cpu_accumulated_time / static_cast<double>(r.iterations);
        ConsoleReporter::ReportRuns(runs);
    }
};

std::string cpu_model() {
    std::ifstream f("/proc/cpuinfo");
    std::string line;
    while (std::getline(f, line))
        if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
    return "unknown CPU";
}

std::string fmt(double v, int sig = 3) {
    if (std::isnan(v)) return "–";
    if (v == 0) return "0";
    char buf[32];
    if (std::abs(v) >= 1e5 || std::abs(v) < 1e-3) std::snprintf(buf, sizeof buf, "%.*e", sig - 1, v);
    else std::snprintf(buf, sizeof buf, "%.*g", sig, v);
    return buf;
}

// The time column in the knob's unit: ns per pixel, or ms per named map (4K, 8K, 1K) scaled
// from the measured size when --quick used a smaller one.
double time_in_unit(const Variant& v) {
    if (std::isnan(v.time_s)) return v.time_s;
    if (v.unit == "ns/px") return v.time_s * 1e9 / v.pixels;
    return v.time_s * 1e3 * (v.map_pixels / v.pixels);
}
std::string unit_label(const Variant& v) { return v.unit == "ns/px" ? "ns/px" : "ms per " + v.map_name + " map"; }
double ms_per_mpx(const Variant& v) { return v.time_s * 1e3 / (v.pixels / 1e6); }

std::string csv_escape(const std::string& s) {
    std::string out = "\"";
    for (char ch : s) out += ch == '"' ? std::string("\"\"") : std::string(1, ch);
    return out + "\"";
}

const char* knob_intro(const std::string& knob) {
    if (knob.rfind("transfer: decode", 0) == 0)
        return "Input: 1 M RGB pixels of random 8-bit sRGB codes. Reference: IEC 61966-2-1 in double. "
               "Code error: how far (in 8-bit code units) the exact re-encoding of the output lands from the input code.";
    if (knob.rfind("transfer: encode", 0) == 0)
        return "Input: 1 M RGB pixels of linear values spread evenly in encoded space. Reference: IEC 61966-2-1 in double. "
               "Code error: |output − exact| × 255 (continuous); the note counts 8-bit codes that differ after rounding.";
    if (knob.rfind("resample", 0) == 0)
        return "Input: a 4096² 8-bit sRGB albedo (1-px lines and checkers, a zone plate, colour edges, noise). "
               "Reference: separable Lanczos-3 in linear light in double precision (kernel widened by the reduction ratio). "
               "Errors in 8-bit sRGB codes of the output, 4-px border excluded. Single-threaded OpenImageIO resize.";
    if (knob.rfind("quantize", 0) == 0)
        return "A 1024² texture-like map written and read back. Albedo: sRGB in PNG, linear in EXR; code error in 8-bit sRGB codes, "
               "other error in linear light. Roughness: linear data; errors in data units (× 255 for codes). Time: encode_image per 1K map.";
    if (knob.rfind("normal", 0) == 0)
        return "A 1024² bumpy normal map, roughness 0.25, standard BRDF (double), light and viewer ±24° so the flat highlight is at n = +Z. "
               "Truth: full-resolution shading averaged over each level-3 texel's 8×8 footprint. Error of the level-3 preview in display codes "
               "(sRGB of radiance) and radiance. All stored at 8 bits. Time: building the whole mip chain of a 1K map. "
               "Toksvig's roughness is on by default in the presets with mips (the preset field `toksvig` defaults to `mips`; "
               "lib/texture's make_mips widens the roughness from the normal map's 8-bit codes).";
    if (knob.rfind("BRDF", 0) == 0)
        return "A 128² sphere, one directional light (intensity 3), roughness bands (0.045 through the highlight, 0.2, 0.5, 1), metal on the right. "
               "Reference: accurate model, double, 256 samples per pixel. Samples: D3D11 standard MSAA positions. "
               "CPU evaluation of tests/stability/brdf_reference.hpp; the shader's own numbers: \"GPU (shader) BRDF\" below.";
    if (knob.rfind("validation", 0) == 0)
        return "A synthetic 8192² 8-bit albedo (noisy bricks, 2-px bright mortar every 16 px, a dark corner). Figures of the luminance "
               "(in sRGB codes): mean, 5th and 95th percentile; shares below code 30 and above 240 (% points). Error: against every pixel. "
               "The 5th percentile sits at the gap between the dark corner (5 % of pixels) and the bricks, so a sample that moves it "
               "by a few pixels' worth jumps it by ~55 codes: percentiles at a gap need every pixel or a wide tolerance.";
    if (knob.rfind("block encoders", 0) == 0)
        return "Poly Haven's brown_planks_09 albedo (tests/data/corpus/real, 1K JPEG; --quick: its middle 256²) as 8-bit sRGB RGB codes, "
               "encoded by texture::encode_level (sRGB formats, one thread) and decoded back by decode_level. Error: the decoded "
               "codes against the source's over R, G, B; the note gives the PSNR over the three channels and the bytes per texel. "
               "Time: encode_level alone. BC1 fast/normal: stb_dxt, thorough: libsquish's cluster fit; BC7: matforge's own "
               "encoder (lib/texture/bc7.hpp); ASTC: Arm's astcenc (fast/medium/thorough presets).";
    if (knob.rfind("cut-out mips", 0) == 0)
        return "ambientCG's Net004A (colour + opacity as A, 1K; --quick: the middle 256², so its 16×16 level is 16× smaller, "
               "not 64×). Error: the alpha test's coverage (alpha ≥ 0.5) of the 16×16 mip level minus level 0's, in % points "
               "(both columns; the note gives the worst level down to 16×16). Alpha averaged as data thins the strands away; "
               "alpha_tested (texture::make_mips) keeps the coverage; \"then BC7\" is that chain encoded and decoded as the GPU "
               "samples it, without the re-encoding the ingest's encode_output does where the decoded coverage strays "
               "(keep_decoded_coverage). Time: make_mips of the whole chain (+ BC7 of every level) per 1K map.";
    if (knob.rfind("cut-out edges", 0) == 0)
        return "Net004A as above. The hidden texels (A < 128) with a shown 8-neighbour: the code distance of their BC7-decoded "
               "(normal effort) colour from the mean of their shown neighbours in linear light (source codes), per channel, "
               "as tests/texture/gpu_presets_test.cpp measures the ingested outputs. Without the fill, whatever colour the "
               "source left in the holes is what bilinear lookups, mips and the block fit mix into the net's edges. "
               "Time: dilate_under_alpha (alpha in channel 3, shown from code 128: the presets' cutoff 0.5) per 1K map.";
    return "";
}

}  // namespace

int main(int argc, char** argv) {
    mf::bench::Config cfg;
    cfg.ocio_config = std::string(MATFORGE_SOURCE_DIR) + "/ocio/config.ocio";
    std::string out_dir, only;
    std::vector<char*> rest{argv[0]};
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--quick") cfg.quick = true;
        else if (a == "--out" && i + 1 < argc) out_dir = argv[++i];
        else if (a == "--only" && i + 1 < argc) only = argv[++i];
        else rest.push_back(argv[i]);
    }
    if (out_dir.empty())
        out_dir = cfg.quick ? std::string(MATFORGE_BINARY_DIR) + "/accuracy-quick"
                            : std::string(MATFORGE_SOURCE_DIR) + "/docs/accuracy";
    int bargc = static_cast<int>(rest.size());
    benchmark::Initialize(&bargc, rest.data());

    const auto t0 = std::chrono::steady_clock::now();
    std::vector<Variant> variants;
    using Maker = std::vector<Variant> (*)(const mf::bench::Config&);
    const std::pair<const char*, Maker> makers[] = {{"transfer", mf::bench::transfer_variants},
                                                    {"resample", mf::bench::resample_variants},
                                                    {"quantize", mf::bench::quantize_variants},
                                                    {"normal", mf::bench::normal_variants},
                                                    {"brdf", mf::bench::brdf_variants},
                                                    {"validation", mf::bench::stats_variants},
                                                    {"encoders", mf::bench::encoder_variants},
                                                    {"cut-out mips", mf::bench::cutout_mip_variants},
                                                    {"cut-out edges", mf::bench::cutout_edge_variants}};
    try {
        for (const auto& [name, make] : makers) {
            if (!only.empty() && std::string(name).find(only) == std::string::npos) continue;
            std::cerr << "accuracy: " << name << "…\n";
            for (auto& v : make(cfg)) variants.push_back(std::move(v));
        }
    } catch (const std::exception& e) {
        std::cerr << "accuracy_bench: " << e.what() << "\n";
        return 1;
    }

    for (size_t i = 0; i < variants.size(); ++i) {
        Variant& v = variants[i];
        if (!v.work) continue;
        auto* b = benchmark::RegisterBenchmark((v.knob + " | " + v.name).c_str(), [&v](benchmark::State& st) {
            for (auto _ : st) v.work();
        });
        // Process CPU time (all threads: OpenEXR compresses on its own pool): robust against the
        // other jobs of a shared 2-core build machine, which inflate wall time.
        b->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();
        if (v.iterations > 0) b->Iterations(v.iterations);
        else b->MinTime(cfg.quick ? 0.01 : 0.25);
    }
    Collector collector;
    benchmark::RunSpecifiedBenchmarks(&collector);
    benchmark::Shutdown();
    for (Variant& v : variants) {
        auto it = collector.seconds.find(v.knob + " | " + v.name);
        v.time_s = it == collector.seconds.end() ? std::nan("") : it->second;
    }
    const double total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    fs::create_directories(out_dir);
    // CSV
    {
        std::ofstream csv(fs::path(out_dir) / "results.csv");
        csv << "knob,variant,max_err_codes8,mean_err_codes8,max_err_other,mean_err_other,other_unit,time,time_unit,ms_per_megapixel,note\n";
        for (const Variant& v : variants)
            csv << csv_escape(v.knob) << "," << csv_escape(v.name) << "," << fmt(v.max_codes, 6) << ","
                << fmt(v.mean_codes, 6) << "," << fmt(v.max_linear, 6) << "," << fmt(v.mean_linear, 6) << ","
                << csv_escape(v.linear_unit) << "," << fmt(time_in_unit(v), 6) << "," << csv_escape(unit_label(v))
                << "," << fmt(ms_per_mpx(v), 6) << "," << csv_escape(v.note) << "\n";
    }
    // Markdown
    {
        std::ofstream md(fs::path(out_dir) / "results.md");
        md << "# Accuracy vs time\n\n"
           << "Generated by `bench/accuracy` (`accuracy_bench" << (cfg.quick ? " --quick" : "")
           << "`); do not edit by hand. "
           << "Regenerate: `cmake -S . -B build -G Ninja && ninja -C build accuracy_bench && build/bench-accuracy/accuracy_bench` "
           << "(writes this file, [results.csv](results.csv) and [error_vs_time.png](error_vs_time.png)).\n\n"
           << "Machine: " << cpu_model() << ", " << std::thread::hardware_concurrency()
           << " hardware threads; timings are process CPU time per call (Google Benchmark 1.7, `MeasureProcessCPUTime`; our code runs single-threaded, OpenEXR compresses on its own threads). "
           << "Whole run: " << fmt(total_s, 3) << " s"
           << (cfg.quick ? " (quick mode: small inputs, times scaled to the named map size)" : "") << ".\n\n"
           << "Errors are against a double-precision reference named per knob. **codes** = 8-bit code units of the encoded "
           << "(sRGB or data) value, the unit a texture file or a display has; the other column's unit is given per row.\n\n"
           << "![error vs time](error_vs_time.png)\n\n";
        // The preview's shader on the same scene (bench/brdf_bench, Vulkan): numbers in docs/bench/,
        // summarized here by hand after a run (this generator has no GPU).
        auto gpu_brdf = [&md] {
            md << "\n### GPU (shader) BRDF\n\n"
               << "The same scene shaded by the preview's own BRDF code (`lib/render/shaders/brdf.glsl` through the compute "
               << "harness `brdf_grid.comp`, `render/brdf_harness.hpp`): `bench/brdf_bench` at 2048² (GPU time, timestamp "
               << "queries) and 256² (error, green channel, against the accurate model in double with 16×16 samples per pixel). "
               << "Lavapipe: [docs/bench/brdf_lavapipe.txt](../bench/brdf_lavapipe.txt) ([csv](../bench/brdf_lavapipe.csv)), "
               << "2026-12-03, the accurate model with its multiple-scattering lobe (`brdf_bench --device cpu --reps 5`, "
               << "Intel Xeon, 2 cores: accurate fp32 mean error 0.252 / 0.065 / 0.029 codes at 1 / 4 / 8 spp). "
               << "NVIDIA H200: [docs/bench/brdf_h200.txt](../bench/brdf_h200.txt) ([csv](../bench/brdf_h200.csv)), the same "
               << "day: standard 0.047 ms and accurate 0.051 ms at 1 spp for 2048² (the lobe's second table read; 0.129 "
               << "against 0.238 ms at 8 spp, the harness reading its table from a storage buffer); fp16 saves nothing there "
               << "and gave non-finite pixels at 4 and 8 spp "
               << "(D past the half-float maximum near the roughness floor: [docs/shading.md](../shading.md)), which is why the preview shades in fp32.\n";
        };
        std::string knob;
        for (const Variant& v : variants) {
            if (v.knob != knob) {
                if (knob.rfind("BRDF", 0) == 0 && v.knob.rfind("BRDF", 0) != 0) gpu_brdf();
                knob = v.knob;
                md << "\n## " << knob << "\n\n"
                   << knob_intro(knob) << "\n\n"
                   << "| variant | max err (codes) | mean err (codes) | max err (other) | mean err (other) | time | note |\n"
                   << "| --- | ---: | ---: | ---: | ---: | ---: | --- |\n";
            }
            md << "| " << v.name << " | " << fmt(v.max_codes) << " | " << fmt(v.mean_codes) << " | "
               << fmt(v.max_linear) << " " << v.linear_unit << " | " << fmt(v.mean_linear) << " | "
               << fmt(time_in_unit(v)) << " " << unit_label(v) << " | " << v.note << " |\n";
        }
        if (knob.rfind("BRDF", 0) == 0) gpu_brdf();
    }
    // Plot: x = ms per megapixel, y = mean error in 8-bit codes, one curve per knob.
    {
        std::vector<mf::bench::PlotSeries> series;
        std::map<std::string, size_t> index;
        for (const Variant& v : variants) {
            const double x = ms_per_mpx(v);
            // Untimed rows, and rows with no error in codes (a coverage in % points).
            if (!(x > 0) || !std::isfinite(v.mean_codes)) continue;
            if (!index.count(v.knob)) index[v.knob] = series.size(), series.push_back({v.knob, {}});
            series[index[v.knob]].points.push_back({x, v.mean_codes, v.tag});
        }
        for (auto& s : series)
            std::sort(s.points.begin(), s.points.end(), [](const auto& a, const auto& b) { return a.x < b.x; });
        mf::bench::PlotSpec spec;
        spec.title = "MATFORGE: MEAN ERROR VS TIME" + std::string(cfg.quick ? " (QUICK)" : "");
        spec.x_label = "TIME, MS PER MEGAPIXEL (1 CORE)";
        spec.y_label = "MEAN ERR, 8-BIT CODES";
        spec.y_floor = 1e-6;
        const mf::Image img = mf::bench::draw_plot(spec, series);
        std::vector<unsigned char> bytes;
        std::string err;
        if (!mf::encode_image(img, {mf::FileFormat::png, 8}, bytes, err)) {
            std::cerr << "accuracy_bench: plot: " << err << "\n";
            return 1;
        }
        std::ofstream(fs::path(out_dir) / "error_vs_time.png", std::ios::binary)
            .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    }
    std::cerr << "accuracy: wrote " << out_dir << "/results.{md,csv} and error_vs_time.png in " << fmt(total_s, 3)
              << " s\n";
    return 0;
}
