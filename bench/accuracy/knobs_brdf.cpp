// The preview's BRDF on the CPU: the standard, the accurate and the un-normalized-Lambert model
// (--brdf assignment: diffuse without 1/π, π times too strong against the specular), fp32 vs
// fp16 (emulated: every intermediate rounded to binary16), 1/4/8 samples per pixel, against a
// 256-sample double-precision render of the accurate model. A sphere under one directional light
// with bands of roughness (0.045 through the highlight) and a metal/dielectric split.
//
// These are CPU timings of brdf_reference.hpp, not of the shader: the shader's own numbers on the
// same scene (lavapipe and the GPU machine) come from bench/brdf_bench (docs/bench/brdf_*.txt).
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

#include "base/srgb.hpp"
#include "brdf_reference.hpp"
#include "harness.hpp"

namespace mf::bench {
namespace {

using cpubrdf::Model;
using cpubrdf::V3;

// D3D11 standard multisample positions (in 1/16 pixel), the GPU's own patterns.
const std::vector<std::array<int, 2>> kPattern1 = {{0, 0}};
const std::vector<std::array<int, 2>> kPattern4 = {{-2, -6}, {6, -2}, {-6, 2}, {2, 6}};
const std::vector<std::array<int, 2>> kPattern8 = {{1, -3}, {-1, 3},  {5, 1}, {-3, -5},
                                                   {-5, 5}, {-7, -1}, {3, 7}, {7, -7}};

struct SceneSample {
    bool hit;
    double n[3];
    double roughness, metalness;
};

// Roughness in horizontal bands: 0.5 above, 0.045 (the floor) through the highlight at
// y ≈ 0.32, 0.2 below it, 1 in the lower half. Metal on the right half.
SceneSample sample_scene(double sx, double sy) {  // sx, sy in [-1.1, 1.1], y up
    const double r2 = sx * sx + sy * sy;
    if (r2 > 1.0) return {false, {0, 0, 0}, 0, 0};
    const double rough = sy > 0.45 ? 0.5 : sy > 0.2 ? 0.045 : sy > 0.0 ? 0.2 : 1.0;
    return {true, {sx, sy, std::sqrt(1.0 - r2)}, rough, sx > 0.0 ? 1.0 : 0.0};
}

template <class T, class P>
double radiance(const SceneSample& s, Model m) {
    if (!s.hit) return 0.0;
    const V3<double> l{0.0, 0.6, 0.8};  // highlight (n = h) at (0, 0.32)
    cpubrdf::Inputs<T> in{{static_cast<T>(s.n[0]), static_cast<T>(s.n[1]), static_cast<T>(s.n[2])},
                          {T(0), T(0), T(1)},
                          {static_cast<T>(l.x), static_cast<T>(l.y), static_cast<T>(l.z)},
                          {T(0.9f), T(0.6f), T(0.3f)},
                          static_cast<T>(s.roughness),
                          static_cast<T>(s.metalness),
                          T(3)};  // the renderer's default light intensity
    const auto c = cpubrdf::shade<T, P>(in, m);
    return static_cast<double>(c[1]);  // green: one channel is enough for the error figures
}

template <class T, class P>
std::vector<double> render(int size, Model m, const std::vector<std::array<int, 2>>& pattern) {
    std::vector<double> img(static_cast<size_t>(size) * size);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            double acc = 0;
            for (const auto& o : pattern) {
                const double px = x + 0.5 + o[0] / 16.0, py = y + 0.5 + o[1] / 16.0;
                acc += radiance<T, P>(sample_scene((px / size * 2 - 1) * 1.1, (1 - py / size * 2) * 1.1), m);
            }
            img[static_cast<size_t>(y) * size + x] = acc / static_cast<double>(pattern.size());
        }
    return img;
}

}  // namespace

std::vector<Variant> brdf_variants(const Config& c) {
    const int size = c.quick ? 32 : 128;
    // Reference: accurate model, double, 16 × 16 stratified samples per pixel.
    std::vector<std::array<int, 2>> grid;
    for (int j = 0; j < 16; ++j)
        for (int i = 0; i < 16; ++i) grid.push_back({2 * i - 15, 2 * j - 15});  // 1/16-px units, centred
    // Offsets in 1/32 px: a regular 16 × 16 grid over the pixel.
    std::vector<double> ref(static_cast<size_t>(size) * size);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            double acc = 0;
            for (const auto& g : grid) {
                const double px = x + 0.5 + g[0] / 32.0, py = y + 0.5 + g[1] / 32.0;
                acc += radiance<double, cpubrdf::Exact>(sample_scene((px / size * 2 - 1) * 1.1,
                                                                     (1 - py / size * 2) * 1.1),
                                                        Model::accurate);
            }
            ref[static_cast<size_t>(y) * size + x] = acc / static_cast<double>(grid.size());
        }

    std::vector<Variant> out;
    struct Kind {
        const char* knob;
        const char* name;
        Model model;
        bool half;
    };
    const Kind kinds[] = {{"BRDF: accurate fp32 (CPU)", "accurate, fp32", Model::accurate, false},
                          {"BRDF: accurate fp16 (CPU emul.)", "accurate, fp16 (emulated)", Model::accurate, true},
                          {"BRDF: standard fp32 (CPU)", "standard (GGX, Schlick F, Schlick-GGX k = (r+1)^2/8), fp32",
                           Model::standard, false},
                          {"BRDF: Lambert x pi fp32 (CPU)",
                           "--brdf assignment: Lambert without 1/pi (diffuse pi x too strong vs specular), fp32",
                           Model::unnormalized_diffuse, false}};
    for (const Kind& k : kinds) {
        for (int spp : {1, 4, 8}) {
            const auto& pattern = spp == 1 ? kPattern1 : spp == 4 ? kPattern4 : kPattern8;
            auto run = [size, model = k.model, half = k.half, &pattern] {
                return half ? render<float, cpubrdf::Binary16>(size, model, pattern)
                            : render<float, cpubrdf::Exact>(size, model, pattern);
            };
            const std::vector<double> img = run();
            double max_c = 0, sum_c = 0, max_l = 0, sum_l = 0;
            size_t nonfinite = 0;
            for (size_t i = 0; i < img.size(); ++i) {
                if (!std::isfinite(img[i])) ++nonfinite;
                const double e = std::isfinite(img[i]) ? std::abs(display_code(img[i]) - display_code(ref[i])) : 255.0;
                const double el = std::isfinite(img[i]) ? std::abs(img[i] - ref[i]) : 1e30;
                max_c = std::max(max_c, e), sum_c += e;
                max_l = std::max(max_l, el), sum_l += std::min(el, 1e6);
            }
            Variant v;
            v.knob = k.knob;
            v.name = std::string(k.name) + ", " + std::to_string(spp) + " spp";
            v.tag = std::to_string(spp) + " SPP";
            v.max_codes = max_c, v.mean_codes = sum_c / static_cast<double>(img.size());
            v.max_linear = max_l, v.mean_linear = sum_l / static_cast<double>(img.size());
            v.linear_unit = "radiance";
            if (nonfinite)
                v.note = std::to_string(nonfinite) +
                         " non-finite pixels (fp16 overflow: D past the half-float maximum)";
            v.work = [run] { (void)run(); };
            v.pixels = static_cast<double>(size) * size;
            v.unit = "ns/px";
            out.push_back(std::move(v));
        }
    }
    return out;
}

}  // namespace mf::bench
