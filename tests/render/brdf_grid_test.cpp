// The preview's BRDF evaluated by the shader itself (shaders/brdf_grid.glsl, which calls the
// functions of shaders/brdf.glsl that shade.frag calls) on lavapipe: a grid of more than 10⁶ hard
// inputs against the CPU reference in double precision (tests/stability/brdf_reference.hpp), and
// the white-furnace check integrated from the shader's own values. The CPU side of the same
// checks is tests/stability/brdf_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "../stability/brdf_reference.hpp"
#include "render/brdf_harness.hpp"
#include "vulkan_fixture.hpp"

#include "brdf_grid_hlsl.inc"  // kBrdfGridHlsl: brdf_grid.hlsl compiled by glslangValidator -D

namespace {

using namespace mf::cpubrdf;
using mf::render::BrdfHarness;
using mf::render::BrdfInput;

// (A, B, 1 − E, 1 − E_avg)(n·v, roughness) at the 32 × 32 texel centres of the reference's table: the shader reads
// the same numbers (see brdf_grid.glsl), so the accurate model's comparison is of arithmetic only.
std::vector<float> energy_table() { return EnergyTable::get().texels(); }

// 1 / |v̂ + l̂| (capped): how strongly rounding moves the half vector.
double condition(V3<double> v, V3<double> l) {
    const double lv = std::sqrt(dot(v, v)), ll = std::sqrt(dot(l, l));
    if (lv == 0.0 || ll == 0.0) return 1.0;
    const V3<double> h{v.x / lv + l.x / ll, v.y / lv + l.y / ll, v.z / lv + l.z / ll};
    return std::min(1e3, 1.0 / std::max(std::sqrt(dot(h, h)), 1e-3));
}

class BrdfShaderGrid : public mf::test::VulkanTest {};

// More than 10⁶ hard inputs: normals unit, tilted, zero and unnormalized; every pair of the hard
// directions as v and l; roughness 0 to 1 around the floor; black, white, coloured and half
// metals and dielectrics; intensities 0 to 10⁶.
std::vector<BrdfInput> hard_inputs() {
    const auto dirs = hard_directions();
    const std::vector<V3<float>> normals = {{0.f, 0.f, 1.f},
                                            {0.6f, 0.f, 0.8f},
                                            {0.f, 0.f, 0.f},
                                            {0.f, 0.f, 5.f}};  // unit, tilted, zero, unnormalized
    // Roughness 0 and 1, below and at the floor (0.045), and between.
    const std::vector<float> roughness = {0.f, 1e-4f, 0.045f, 0.1f, 0.3f, 0.6f, 1.f};
    // F0 = 0 (black metal), F0 = 1 (white metal), colored metal, dielectrics (F0 = 0.04) white,
    // black, and a half-metal.
    struct Mat {
        std::array<float, 3> albedo;
        float metalness;
    };
    const std::vector<Mat> materials = {{{0.f, 0.f, 0.f}, 1.f}, {{1.f, 1.f, 1.f}, 1.f}, {{1.f, 0.5f, 0.f}, 1.f},
                                        {{1.f, 1.f, 1.f}, 0.f}, {{0.f, 0.f, 0.f}, 0.f}, {{0.8f, 0.5f, 0.2f}, 0.5f}};
    const std::vector<float> intensities = {0.f, 1.f, 1e3f, 1e6f};

    std::vector<BrdfInput> in;
    in.reserve(normals.size() * dirs.size() * dirs.size() * roughness.size() * materials.size() * intensities.size());
    for (const auto& n : normals)
        for (const auto& v : dirs)
            for (const auto& l : dirs)
                for (float r : roughness)
                    for (const auto& m : materials)
                        for (float e : intensities)
                            in.push_back({{n.x, n.y, n.z, r},
                                          {v.x, v.y, v.z, m.metalness},
                                          {l.x, l.y, l.z, e},
                                          {m.albedo[0], m.albedo[1], m.albedo[2], 0.f}});
    return in;
}

// The shader's radiance `out` (model m of input i at 3 i + m) of `in` against the double
// evaluation, for the models `models` (0 standard, 1 accurate, 2 unnormalized diffuse), within
// the stated bound; `what` names the shader in the printed summary.
void expect_agrees_with_double(const char* what, const std::vector<BrdfInput>& in,
                               const std::vector<std::array<float, 3>>& out, std::initializer_list<size_t> models,
                               double ms) {
    ASSERT_EQ(out.size(), in.size() * 3);
    const Model kModels[] = {Model::standard, Model::accurate, Model::unnormalized_diffuse};
    size_t nonfinite = 0, disagree = 0, lit = 0, zero_mismatch = 0;
    double worst_ratio = 0.0, worst_rel[3] = {0, 0, 0}, worst_abs_unlit = 0.0;
    for (size_t i = 0; i < in.size(); ++i) {
        const BrdfInput& g = in[i];
        const V3<double> v{g.v[0], g.v[1], g.v[2]}, l{g.l[0], g.l[1], g.l[2]};
        const Inputs<double> d{
            {g.n[0], g.n[1], g.n[2]}, v, l, {g.albedo[0], g.albedo[1], g.albedo[2]}, g.n[3], g.v[3], g.l[3]};
        const double e = g.l[3];
        const double cond = condition(v, l);
        for (const size_t m : models) {
            const auto rd = shade(d, kModels[m]);
            const auto& rg = out[3 * i + m];
            for (size_t c = 0; c < 3; ++c) {
                const double gpu = rg[c];
                if (!std::isfinite(rg[c]) || rg[c] < 0.f) ++nonfinite;
                if (rd[c] > 0.0) ++lit;
                if (rd[c] == 0.0 && gpu != 0.0) worst_abs_unlit = std::max(worst_abs_unlit, gpu / std::max(e, 1.0));
                // Stated bound, derived for fp32 (ε = 2⁻²⁴ ≈ 6e-8):
                //  - relative 2e-4: ~40 operations of ≤ 3 ulp each (Vulkan's precision table for
                //    division, sqrt and inversesqrt) give ~1e-5; the rest is D near its peak.
                //    D = (α / (|n×h|² + (n·h α)²))² / π (Walter et al. 2007, eq. 33, Lagrange form)
                //    squares the relative error of the denominator, whose |n×h|² carries an
                //    absolute error of ~2|n×h| ε: relative 2ε/α ≈ 6e-5 at α = 0.045², doubled by the
                //    square, plus N·H, V·H and F (Schlick 1994: (1 − V·H)⁵ amplifies V·H's error
                //    five-fold where V·H → 0);
                //  - 1e-6·cond²: rounding the normalized v and l moves h by ~ε/|v̂ + l̂| = ε·cond, and
                //    a narrow lobe turns that into a relative change of D of ~(ε·cond/α)²·… — the CPU
                //    suite found the same widening for v ≈ −l (cond ≤ 1e3 by the grid's 1e-7 cosines);
                //  - absolute 1e-5 of the intensity: where N·L or N·V are ~1e-7 a few ulps of the
                //    dot products are all of the value (and N·L's sign may round either way).
                const double err = std::abs(gpu - rd[c]);
                const double bound = (2e-4 + 1e-6 * cond * cond) * rd[c] + 1e-5 * e;
                if (err > bound && ++disagree <= 5)
                    std::printf("  outside: model %zu n (%g %g %g) v (%g %g %g) l (%g %g %g) r %g metal %g E %g: "
                                "shader %.9g double %.9g\n",
                                m, g.n[0], g.n[1], g.n[2], g.v[0], g.v[1], g.v[2], g.l[0], g.l[1], g.l[2], g.n[3],
                                g.v[3], g.l[3], gpu, rd[c]);
                if (bound > 0.0) worst_ratio = std::max(worst_ratio, err / bound);
                else if (err > 0.0) ++zero_mismatch;
                if (cond < 4.0 && rd[c] > 1e-3 * e && e > 0.0) worst_rel[m] = std::max(worst_rel[m], err / rd[c]);
            }
        }
    }
    std::printf("%s: %zu inputs x %zu models in %.1f ms (lavapipe), lit channels %zu; worst error / bound "
                "%.3g; worst relative error (well-conditioned, value > 1e-3 E): standard %.3g, accurate %.3g, "
                "unnormalized diffuse %.3g; worst GPU value where double is 0: %.3g E\n",
                what, in.size(), models.size(), ms, lit, worst_ratio, worst_rel[0], worst_rel[1], worst_rel[2],
                worst_abs_unlit);
    EXPECT_GE(in.size(), size_t{1000000});
    EXPECT_EQ(nonfinite, 0u) << "NaN, Inf or negative radiance from the shader";
    EXPECT_EQ(disagree, 0u) << "shader outside the stated bound of the double evaluation";
    EXPECT_EQ(zero_mismatch, 0u) << "the shader lit a configuration with zero intensity";
    EXPECT_GT(lit, in.size() * models.size() / 20) << "the grid must exercise lit configurations";
    for (double w : worst_rel) EXPECT_LT(w, 2e-5);
}

TEST_F(BrdfShaderGrid, MillionHardInputsFiniteAndAgreeWithDouble) {
    BrdfHarness harness(context(), energy_table());
    const auto in = hard_inputs();
    double ms = 0.0;
    const auto out = harness.evaluate(in, mf::render::BrdfPrecision::fp32, &ms);
    expect_agrees_with_double("shader grid", in, out, {0, 1, 2}, ms);
}

// The d3d11 preset's HLSL include (lib/engine/matforge_material.hlsli: mf_brdf_light, the
// standard model) compiled by glslang's HLSL front end (brdf_grid.hlsl, at build time) and run on
// the same inputs: the same oracle, the same bound as the GLSL.
TEST_F(BrdfShaderGrid, HlslIncludeAgreesWithDoubleAsTheGlslDoes) {
    BrdfHarness harness(context(), energy_table());
    const auto in = hard_inputs();
    double ms = 0.0;
    const auto out = harness.evaluate_spirv(kBrdfGridHlsl, sizeof kBrdfGridHlsl, in, &ms);
    expect_agrees_with_double("HLSL grid (standard model)", in, out, {0}, ms);
    // The models the HLSL does not have stay untouched.
    size_t written = 0;
    for (size_t i = 0; i < in.size(); ++i) written += out[3 * i + 1] != std::array<float, 3>{0.f, 0.f, 0.f};
    EXPECT_EQ(written, 0u);
}

// White furnace (F0 = 1, so F = 1: a white metal under unit irradiance): the specular lobe's
// directional albedo E(v) = ∫ f(v, l) (n·l) dω_l, integrated from the shader's own values. l is
// parameterized by the half vector h, dω_l = 4 (v·h) dω_h (Walter et al. 2007, eq. 14), and h by
// GGX's inverse CDF, tan² θ_h = α² u / (1 − u) (Walter et al. 2007, eq. 35), so the quadrature
// points concentrate where D does and the midpoint rule in (u, φ) resolves even the floor
// roughness 0.045, whose lobe is a milliradian wide. The accurate model's multiple-scattering
// lobe is as broad as a diffuse one, which that grid samples poorly at low roughness: its part is
// taken out of the grid's sum as the CPU evaluates it from the same table (ms_radiance) and
// integrated over cos θ_l instead (a control variate; BrdfShaderGrid.MillionHardInputs… checks
// the shader's lobe against the CPU's).
namespace {
// f_ms (n·l) for unit irradiance, with EnergyTable's (1 − E, 1 − E_avg): the oracle's
// multiscatter_lobe() times 1 − E(μ_l) and μ_l.
double ms_radiance(double f0, double mu_v, double mu_l, double r) {
    if (!(mu_l > 0.0)) return 0.0;
    const auto t = EnergyTable::get().lookup_dfg(mu_v, r);
    const double lost_l = EnergyTable::get().lookup_dfg(std::min(mu_l, 1.0), r)[2];
    return multiscatter_lobe(multiscatter_fresnel(f0, t[3]), t[2], t[3]) * lost_l * mu_l;
}
// ∫ ms_radiance dω_l over the hemisphere (it depends on cos θ_l only).
double ms_albedo(double f0, double mu_v, double r) {
    constexpr int kSteps = 2000;
    double sum = 0.0;
    for (int i = 0; i < kSteps; ++i) sum += ms_radiance(f0, mu_v, (i + 0.5) / kSteps, r);
    return sum * 2.0 * std::numbers::pi / kSteps;
}
}  // namespace

TEST_F(BrdfShaderGrid, WhiteFurnaceFromTheShader) {
    BrdfHarness harness(context(), energy_table());
    const int nu = 512, nphi = 128;
    double worst_std = 0.0, worst_dev = 0.0, worst_acc_hi = 0.0, worst_acc_lo = 2.0, worst_acc_edge = 0.0;
    double worst_diel = 0.0, worst_diel_edge = 0.0;
    for (double r : {0.0, 0.045, 0.1, 0.3, 0.5, 0.8, 1.0})
        for (double mu : {1.0, 0.9, 0.7, 0.3, 0.1, 0.03, 0.01, 1e-4}) {
            const double rr = std::max(r, kMinRoughness), alpha = rr * rr;
            const double sv = std::sqrt(1.0 - mu * mu);
            std::vector<BrdfInput> in;
            std::vector<double> w;
            for (int i = 0; i < nu; ++i) {
                const double u = (i + 0.5) / nu;
                const double s = std::sqrt(u / (1.0 - u));
                const double th = std::atan(alpha * s);
                const double dth_du = alpha / (1.0 + alpha * alpha * s * s) * 0.5 /
                                      (std::sqrt(u) * std::pow(1.0 - u, 1.5));
                for (int j = 0; j < nphi; ++j) {
                    const double phi = 2.0 * std::numbers::pi * (j + 0.5) / nphi;
                    const double hx = std::sin(th) * std::cos(phi), hy = std::sin(th) * std::sin(phi),
                                 hz = std::cos(th);
                    const double voh = sv * hx + mu * hz;
                    if (voh <= 0.0) continue;  // h seen from behind: not a reflection toward v
                    const double lx = 2 * voh * hx - sv, ly = 2 * voh * hy, lz = 2 * voh * hz - mu;
                    in.push_back({{0.f, 0.f, 1.f, static_cast<float>(r)},
                                  {static_cast<float>(sv), 0.f, static_cast<float>(mu), 1.f},
                                  {static_cast<float>(lx), static_cast<float>(ly), static_cast<float>(lz), 1.f},
                                  {1.f, 1.f, 1.f, 0.f}});
                    w.push_back(4.0 * voh * std::sin(th) * dth_du * (1.0 / nu) * (2.0 * std::numbers::pi / nphi));
                }
            }
            // The accurate white dielectric (albedo 1, metalness 0, F0 = 0.04): its specular lobe
            // is a black dielectric's (no diffuse) on the same half-vector grid; its diffuse lobe,
            // white minus black, on a grid uniform in (cos θ_l, φ), where the midpoint rule
            // integrates Lambert's cos θ_l exactly.
            const size_t n_spec = in.size();
            for (size_t k = 0; k < n_spec; ++k) {
                BrdfInput b = in[k];
                b.v[3] = 0.f;
                b.albedo = {0.f, 0.f, 0.f, 0.f};
                in.push_back(b);
            }
            const int nt = 64, np = 16;
            for (int i = 0; i < nt; ++i)
                for (int j = 0; j < np; ++j) {
                    const double ct = (i + 0.5) / nt, st = std::sqrt(1.0 - ct * ct);
                    const double phi = 2.0 * std::numbers::pi * (j + 0.5) / np;
                    for (float a : {1.f, 0.f})
                        in.push_back({{0.f, 0.f, 1.f, static_cast<float>(r)},
                                      {static_cast<float>(sv), 0.f, static_cast<float>(mu), 0.f},
                                      {static_cast<float>(st * std::cos(phi)), static_cast<float>(st * std::sin(phi)),
                                       static_cast<float>(ct), 1.f},
                                      {a, a, a, 0.f}});
                }
            const auto out = harness.evaluate(in);
            const double NoV = std::max(mu, 1e-4);
            double e_diel = ms_albedo(0.04, NoV, rr);
            for (size_t k = 0; k < n_spec; ++k)
                e_diel += w[k] * (out[3 * (n_spec + k) + 1][0] - ms_radiance(0.04, NoV, in[k].l[2], rr));
            for (size_t k = 2 * n_spec; k < in.size(); k += 2)
                e_diel += (out[3 * k + 1][0] - out[3 * (k + 1) + 1][0]) * (2.0 * std::numbers::pi / (nt * np));
            double e_std = 0.0, e_acc = ms_albedo(1.0, NoV, rr);
            for (size_t k = 0; k < n_spec; ++k) {
                e_std += w[k] * out[3 * k + 0][0];  // standard: f (n·l) with E = 1
                // accurate: single and multiple scattering
                e_acc += w[k] * (out[3 * k + 1][0] - ms_radiance(1.0, NoV, in[k].l[2], rr));
            }
            const double cpu = specular_albedo(Model::standard, mu, r);
            worst_std = std::max(worst_std, e_std);
            worst_dev = std::max(worst_dev, std::abs(e_std - cpu));
            // Energy conservation of single scattering; 1e-3 covers the quadrature (the CPU
            // reference, itself converged to < 6e-4, agrees within the next bound).
            EXPECT_LE(e_std, 1.0 + 1e-3) << "roughness " << r << " N·V " << mu;
            EXPECT_NEAR(e_std, cpu, 2e-3) << "roughness " << r << " N·V " << mu;
            // Kulla & Conty 2017: the compensated lobe of a white metal reflects everything.
            // Between the 32 × 32 table's first and last texel centres (n·v in [1/64, 63/64]) its
            // bilinear error leaves it within [0.95, 1.02] (the CPU suite's bound). Outside, the
            // lookup clamps to the edge texel: E(1/64) stands for E(1e-4), which is smaller, and
            // the compensation over-shoots (measured up to 1.085 at roughness 0.1, n·v = 1e-4).
            const bool interior = mu >= 1.0 / 64 && mu <= 63.0 / 64;
            (interior ? worst_acc_hi : worst_acc_edge) = std::max(interior ? worst_acc_hi : worst_acc_edge, e_acc);
            if (interior) worst_acc_lo = std::min(worst_acc_lo, e_acc);
            EXPECT_LE(e_acc, interior ? 1.02 : 1.1) << "roughness " << r << " N·V " << mu;
            EXPECT_GE(e_acc, interior ? 0.95 : 0.9) << "roughness " << r << " N·V " << mu;
            // The white dielectric reflects all it receives (its diffuse weight is 1 − E_spec(n·v)),
            // up to the 32 × 32 table's bilinear error in (A, B): measured |albedo − 1| ≤ 1e-3 at
            // n·v ≥ 0.1, 0.017 at n·v = 0.03 (roughness 0.1, where B changes fastest), 0.066 past
            // the first texel centre (roughness 0.1, n·v = 1e-4; the lookup clamps, as above).
            (interior ? worst_diel : worst_diel_edge) = std::max(interior ? worst_diel : worst_diel_edge,
                                                                 std::abs(e_diel - 1.0));
            EXPECT_NEAR(e_diel, 1.0, mu >= 0.1 ? 2e-3 : interior ? 0.02 : 0.08) << "roughness " << r << " N·V " << mu;
        }
    std::printf("shader furnace: standard max E %.6f, max |E - CPU quadrature| %.3g; accurate (compensated) "
                "E in [%.4f, %.4f] inside the table, max %.4f at its edges; accurate white dielectric: max "
                "|albedo - 1| %.4f inside the table, %.4f at its edges\n",
                worst_std, worst_dev, worst_acc_lo, worst_acc_hi, worst_acc_edge, worst_diel, worst_diel_edge);
}

}  // namespace
