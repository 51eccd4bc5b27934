// The BRDF on a grid of more than 10⁶ hard inputs (CPU side): no NaN or Inf, fp32 within a
// stated bound of the double-precision evaluation, and the white-furnace check — the specular
// lobe's directional albedo with F = 1 never exceeds 1.
//
// The same grid through the shader itself (a compute harness on lavapipe) is
// tests/render/brdf_grid_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "brdf_reference.hpp"

namespace {

using namespace mf::cpubrdf;

V3<double> to_d(V3<float> a) { return {a.x, a.y, a.z}; }

// 1 / |v̂ + l̂| (capped): how strongly input rounding moves the half vector.
double condition(V3<double> v, V3<double> l) {
    const double lv = std::sqrt(dot(v, v)), ll = std::sqrt(dot(l, l));
    if (lv == 0.0 || ll == 0.0) return 1.0;
    const V3<double> h{v.x / lv + l.x / ll, v.y / lv + l.y / ll, v.z / lv + l.z / ll};
    return std::min(1e3, 1.0 / std::max(std::sqrt(dot(h, h)), 1e-3));
}

struct Material {
    std::array<float, 3> albedo;
    float metalness;
};

TEST(BrdfGrid, MillionHardInputsFiniteAndFp32AgreesWithDouble) {
    const auto dirs = hard_directions();
    const std::vector<V3<float>> normals = {{0.f, 0.f, 1.f},
                                            {0.6f, 0.f, 0.8f},
                                            {0.f, 0.f, 0.f},
                                            {0.f, 0.f, 5.f}};  // unit, tilted, zero, unnormalized
    const std::vector<float> roughness = {0.f, 1e-4f, 0.045f, 0.1f, 0.3f, 0.6f, 1.f};
    // F0 = 0 (black metal), F0 = 1 (white metal), dielectrics (F0 = 0.04) white, black, colored.
    const std::vector<Material> materials = {{{0.f, 0.f, 0.f}, 1.f},  {{1.f, 1.f, 1.f}, 1.f},
                                             {{1.f, 0.5f, 0.f}, 1.f}, {{1.f, 1.f, 1.f}, 0.f},
                                             {{0.f, 0.f, 0.f}, 0.f},  {{0.8f, 0.5f, 0.2f}, 0.5f}};
    const std::vector<float> intensities = {0.f, 1.f, 1e3f, 1e6f};
    const Model models[] = {Model::standard, Model::accurate, Model::unnormalized_diffuse};

    size_t count = 0, nonfinite = 0, disagree = 0, nonzero = 0;
    double worst_rel = 0.0, worst_ratio = 0.0;
    for (Model model : models) {
        for (const auto& n : normals)
            for (const auto& v : dirs)
                for (const auto& l : dirs)
                    for (float r : roughness)
                        for (const auto& mat : materials)
                            for (float e : intensities) {
                                Inputs<float> f{n, v, l, mat.albedo, r, mat.metalness, e};
                                Inputs<double> d{to_d(n), to_d(v),
                                                 to_d(l), {mat.albedo[0], mat.albedo[1], mat.albedo[2]},
                                                 r,       mat.metalness,
                                                 e};
                                const auto rf = shade(f, model);
                                const auto rd = shade(d, model);
                                ++count;
                                // Conditioning: where v ≈ −l the half vector is a difference of
                                // nearly equal vectors; rounding the inputs to float moves it by
                                // ~ε/|v̂ + l̂| (ε = 6e-8), and a narrow lobe amplifies that.
                                const double cond = condition(to_d(v), to_d(l));
                                for (size_t c = 0; c < 3; ++c) {
                                    if (!std::isfinite(rf[c]) || !std::isfinite(rd[c]) || rf[c] < 0.f || rd[c] < 0.0)
                                        ++nonfinite;
                                    if (rd[c] > 0.0) ++nonzero;
                                    // Stated bound: relative 2e-4 + 1e-6·cond², plus an absolute
                                    // 1e-5 of the intensity where N·L ≈ 0 makes the value tiny.
                                    const double err = std::abs(double{rf[c]} - rd[c]);
                                    const double bound = (2e-4 + 1e-6 * cond * cond) * rd[c] + 1e-5 * e;
                                    if (err > bound) ++disagree;
                                    worst_ratio = std::max(worst_ratio, err / bound);
                                    if (cond < 4.0 && rd[c] > 1e-3 * e && e > 0.f)
                                        worst_rel = std::max(worst_rel, err / rd[c]);
                                }
                            }
    }
    std::printf("inputs %zu, lit channels %zu, worst error / bound %.3g, worst relative error "
                "(well-conditioned) %.3g\n",
                count, nonzero, worst_ratio, worst_rel);
    EXPECT_GE(count, size_t{1000000}) << "inputs (each evaluated in fp32 and fp64, 3 channels)";
    EXPECT_EQ(nonfinite, 0u) << "NaN, Inf or negative radiance";
    EXPECT_EQ(disagree, 0u) << "fp32 outside the stated bound of the double evaluation";
    EXPECT_GT(nonzero, count / 20) << "the grid must exercise lit configurations";
    EXPECT_LT(worst_rel, 2e-5);
}

TEST(BrdfGrid, DefinedValuesAtTheBoundaries) {
    const V3<double> n{0, 0, 1};
    const std::array<double, 3> white{1, 1, 1};
    // Normal incidence on a perfect mirror at the roughness floor: D = 1/(π α²), α = 0.045².
    {
        const auto r = shade(Inputs<double>{n, n, n, white, 0.0, 1.0, 1.0}, Model::standard);
        const double alpha = kMinRoughness * kMinRoughness;
        const double k = (kMinRoughness + 1) * (kMinRoughness + 1) / 8;
        const double expected = 1.0 / (std::numbers::pi * alpha * alpha) * 0.25 / (1.0 * 1.0);
        // V = 0.25 / ((1(1−k)+k)²) = 0.25 at N·L = N·V = 1, independent of k.
        (void)k;
        EXPECT_NEAR(r[0], expected, expected * 1e-12);
        EXPECT_LT(r[0], 65504.0 * 2) << "finite, and the floor keeps it near half-float range";
    }
    // v = −l with N·L > 0 (so N·V < 0: a normal bent away from the viewer): no half vector, no
    // specular; exactly the diffuse lobe at normal-incidence Fresnel, (1 − F0) albedo/π · E · N·L,
    // at every roughness (a fallback h = n gave a ~1e5 · E spike at roughness 0).
    for (double rough : {0.0, 0.5, 1.0}) {
        const V3<double> l{0.6, 0, 0.8}, v{-0.6, 0, -0.8};
        const auto r = shade(Inputs<double>{n, v, l, white, rough, 0.0, 1.0}, Model::standard);
        for (double c : r) EXPECT_NEAR(c, (1.0 - 0.04) / std::numbers::pi * 0.8, 1e-12) << rough;
    }
    // Zero-length l or n: no light. Zero-length v: viewer along n.
    {
        const V3<double> z{0, 0, 0}, l{0, 0.6, 0.8};
        EXPECT_EQ(shade(Inputs<double>{n, n, z, white, 0.5, 0.0, 1.0}, Model::standard)[0], 0.0);
        EXPECT_EQ(shade(Inputs<double>{z, n, l, white, 0.5, 0.0, 1.0}, Model::standard)[0], 0.0);
        EXPECT_EQ(shade(Inputs<double>{n, z, l, white, 0.5, 0.0, 1.0}, Model::standard)[1],
                  shade(Inputs<double>{n, n, l, white, 0.5, 0.0, 1.0}, Model::standard)[1]);
    }
    // N·L exactly 0 gives 0; N·L = 1e-7 gives a tiny positive value, linear in N·L.
    {
        const V3<double> grazing{1, 0, 0}, l7{1, 0, 1e-7};
        EXPECT_EQ(shade(Inputs<double>{n, n, grazing, white, 0.5, 0.0, 1.0}, Model::standard)[0], 0.0);
        const double a = shade(Inputs<double>{n, n, l7, white, 0.5, 0.0, 1.0}, Model::standard)[0];
        EXPECT_GT(a, 0.0);
        EXPECT_LT(a, 1e-6);
    }
    // NaN material inputs take their documented fallbacks, never propagate.
    {
        const double nan = std::numeric_limits<double>::quiet_NaN();
        const auto r = shade(Inputs<double>{n, n, n, {nan, 0.5, 0.5}, nan, nan, 1.0}, Model::standard);
        for (double c : r) EXPECT_TRUE(std::isfinite(c));
        const auto inf = shade(Inputs<double>{n, n, n, white, 0.5, 0.0, std::numeric_limits<double>::infinity()},
                               Model::standard);
        EXPECT_EQ(inf[0], 0.0);
    }
    // Without Lambert's 1/π the diffuse lobe is π times stronger; nothing else differs.
    {
        const V3<double> l{0, 0.6, 0.8};
        const auto s = shade(Inputs<double>{n, n, l, {0.5, 0.5, 0.5}, 1.0, 0.0, 1.0}, Model::standard);
        const auto a = shade(Inputs<double>{n, n, l, {0.5, 0.5, 0.5}, 1.0, 0.0, 1.0}, Model::unnormalized_diffuse);
        const auto spec = shade(Inputs<double>{n, n, l, {0.0, 0.0, 0.0}, 1.0, 0.0, 1.0}, Model::standard);
        EXPECT_NEAR(a[0] - spec[0], (s[0] - spec[0]) * std::numbers::pi, 1e-12);
    }
}

TEST(BrdfGrid, Fp16EmulationOverflowsOnlyWhereDocumented) {
    // D at the roughness floor and N·H = 1 is 7.7e4 > 65504, the half maximum. The
    // emulated fp16 evaluation overflows exactly there; at roughness ≥ 0.1 it stays finite.
    const V3<float> n{0, 0, 1};
    const std::array<float, 3> white{1, 1, 1};
    const auto smooth = shade<float, Binary16>(Inputs<float>{n, n, n, white, 0.f, 1.f, 1.f}, Model::standard);
    EXPECT_TRUE(std::isinf(smooth[0]));
    const auto rough = shade<float, Binary16>(Inputs<float>{n, n, n, white, 0.1f, 1.f, 1.f}, Model::standard);
    EXPECT_TRUE(std::isfinite(rough[0]));
    const auto ref = shade(Inputs<double>{{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {1, 1, 1}, 0.1, 1.0, 1.0}, Model::standard);
    EXPECT_NEAR(rough[0], ref[0], ref[0] * 4e-3);  // a few half ulps
}

// White furnace: ∫ f_s(v, l) N·L dω_l with F = 1 is the share of light the specular lobe
// reflects; energy conservation demands ≤ 1 at every roughness and angle. The quadrature
// (brdf_reference.hpp: visible-normal mapping, 256² points) is converged to < 6e-4 everywhere
// and to < 1e-5 where E approaches 1 (QuadratureConverged).
TEST(WhiteFurnace, SpecularAlbedoAtMostOne) {
    const std::vector<double> rough = {0.0, 0.045, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0};
    const std::vector<double> nov = {0.0, 1e-7, 1e-4, 1e-3, 0.01, 0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 0.9, 1.0};
    for (Model m : {Model::standard, Model::accurate}) {
        double max_e = 0.0;
        for (double r : rough)
            for (double mu : nov) {
                const double e = specular_albedo(m, mu, r);
                EXPECT_LE(e, 1.0 + 2e-4) << "roughness " << r << " N·V " << mu;
                EXPECT_GT(e, 0.0);
                max_e = std::max(max_e, e);
            }
        // A smooth lobe at normal incidence reflects nearly everything (Smith G → 1).
        EXPECT_GT(specular_albedo(m, 1.0, 0.045), 0.9999);
        EXPECT_GT(max_e, 0.9999);
        // Closed form at α = 1, v = n: D = 1/π, G = 2 N·L / (N·L + 1) in both models, so
        // E = ∫₀¹ μ / (μ + 1) dμ = 1 − ln 2.
        EXPECT_NEAR(specular_albedo(m, 1.0, 1.0, 1024, 1024), 1.0 - std::log(2.0), 1e-5);
    }
    // The punctual remap k = (r + 1)² / 8 over-shadows at grazing angles: the standard lobe
    // keeps < 1 % at N·V = 1e-4 for a smooth surface, where height-correlated Smith keeps 99 %.
    EXPECT_LT(specular_albedo(Model::standard, 1e-4, 0.045), 0.01);
    EXPECT_GT(specular_albedo(Model::accurate, 1e-4, 0.045), 0.98);
}

TEST(WhiteFurnace, QuadratureConverged) {
    for (Model m : {Model::standard, Model::accurate})
        for (double r : {0.045, 0.3, 1.0})
            for (double mu : {1e-4, 0.05, 0.5, 1.0})
                EXPECT_NEAR(specular_albedo(m, mu, r), specular_albedo(m, mu, r, 1024, 1024), 6e-4) << r << " " << mu;
}

// The accurate model's lobes with the 32 × 32 table, F0 = 1 (F = F_ms = 1): single scattering
// reflects E(μ), the multiple-scattering lobe (1 − E_t(μ)) · 2∫(1 − E_t(μ_l)) μ_l dμ_l / (1 − E_avg),
// E_t and E_avg from the table. With the exact E the sum is 1; with the table, 1 within its
// interpolation error. Kulla & Conty's F_ms is 1 for F0 = 1 and below F_avg² (one more bounce
// than single scattering's F_avg) otherwise.
TEST(WhiteFurnace, MultipleScatteringLobeConservesEnergy) {
    const auto& table = EnergyTable::get();
    for (double r : {0.045, 0.1, 0.25, 0.5, 0.75, 1.0}) {
        const double lost_avg_table = table.lookup_dfg(0.5, r)[3];
        double lost_avg = 0.0;  // 2 ∫ (1 − E_t(μ)) μ dμ over the interpolated table
        constexpr int kSteps = 400;
        for (int k = 0; k < kSteps; ++k) {
            const double mu = (k + 0.5) / kSteps;
            lost_avg += 2.0 * table.lookup_dfg(mu, r)[2] * mu / kSteps;
        }
        EXPECT_NEAR(lost_avg, lost_avg_table, 2e-3) << r;
        for (double mu : {0.02, 0.1, 0.3, 0.6, 0.95}) {
            const double e = specular_albedo(Model::accurate, mu, r, 256, 128);
            const double albedo = e + table.lookup_dfg(mu, r)[2] * lost_avg / std::max(lost_avg_table, 1e-4);
            EXPECT_LE(albedo, 1.0 + 0.02) << r << " " << mu;
            EXPECT_GE(albedo, 0.98) << r << " " << mu;
        }
    }
}

// The furnace through the evaluator itself (not the closed-form integrand): integrate
// shade() · ... over a hemisphere grid of l for a white metal (F0 = 1, F = 1) at roughness 0.5.
TEST(WhiteFurnace, EvaluatorIntegratesBelowOne) {
    const V3<double> n{0, 0, 1};
    for (double theta_v : {0.0, 0.8, 1.4, 1.55}) {
        const V3<double> v{std::sin(theta_v), 0, std::cos(theta_v)};
        double sum = 0.0;
        const int nt = 400, np = 400;
        for (int i = 0; i < nt; ++i) {
            const double ct = (i + 0.5) / nt;  // uniform in cos θ: dω = d(cos θ) dφ
            const double st = std::sqrt(1 - ct * ct);
            for (int j = 0; j < np; ++j) {
                const double phi = (j + 0.5) / np * 2 * std::numbers::pi;
                const V3<double> l{st * std::cos(phi), st * std::sin(phi), ct};
                sum += shade(Inputs<double>{n, v, l, {1, 1, 1}, 0.5, 1.0, 1.0}, Model::standard)[0];
            }
        }
        const double e = sum * (2 * std::numbers::pi) / (double(nt) * np);
        EXPECT_LE(e, 1.0 + 2e-3) << theta_v;
        EXPECT_NEAR(e, specular_albedo(Model::standard, std::cos(theta_v), 0.5), 5e-3) << theta_v;
    }
}

// The accurate model's white dielectric (albedo 1, metalness 0: F0 = 0.04) and white metal
// (albedo 1, metalness 1: F0 = 1) reflect all the light they receive, at every view angle. The
// dielectric's diffuse lobe is weighted by 1 − E_spec(N·V), the specular lobes' own directional
// albedo (Kulla & Conty 2017's albedo scaling); the metal's multiple-scattering lobe returns
// exactly what single scattering loses. Integrated through the evaluator on a grid uniform in
// (cos θ_l, φ), not the visible-normal quadrature that gives (A, B); (A, B) here at the exact N·V
// and N·L, not from the table, and E_avg by the same grid's cos θ_l, so that the lobe's own
// normalization is exact. The weight 1 − F(v·h) the dielectric had before gave 0.978 at
// roughness 0.9, N·V = 1, and the metal's lobe scaled by 1 + F0 (1/E − 1) reflects 1 too, but
// puts the energy in the single-scattering lobe's shape (docs/accuracy/pathtracer.md).
TEST(WhiteFurnace, AccurateDielectricAndMetalReflectEverything) {
    const V3<double> n{0, 0, 1};
    const int nt = 400, np = 400;
    for (double r : {0.5, 0.8, 1.0}) {
        // (A, B) at the grid's cos θ_l, and 1 − E_avg = 2 Σ (1 − E) μ / nt over them.
        std::vector<std::array<double, 2>> ab_l(nt);
        double lost_avg = 0.0;
        for (int i = 0; i < nt; ++i) {
            const double ct = (i + 0.5) / nt;
            ab_l[size_t(i)] = specular_dfg(Model::accurate, ct, r, 128, 128);
            lost_avg += 2.0 * (1.0 - ab_l[size_t(i)][0] - ab_l[size_t(i)][1]) * ct / nt;
        }
        for (double theta_v : {0.0, 0.8, 1.2, 1.45}) {
            const double mu = std::cos(theta_v);
            const V3<double> v{std::sin(theta_v), 0, mu};
            const auto ab_v = specular_dfg(Model::accurate, mu, r);
            for (double metal : {0.0, 1.0}) {
                double sum = 0.0;
                for (int i = 0; i < nt; ++i) {
                    const double ct = (i + 0.5) / nt;  // uniform in cos θ: dω = d(cos θ) dφ
                    const double st = std::sqrt(1 - ct * ct);
                    // Asked at N·V first, then at this N·L.
                    const auto dfg = [&](double x, double) -> std::array<double, 4> {
                        const auto& ab = x == mu ? ab_v : ab_l[size_t(i)];
                        return {ab[0], ab[1], 1.0 - ab[0] - ab[1], lost_avg};
                    };
                    for (int j = 0; j < np; ++j) {
                        const double phi = (j + 0.5) / np * 2 * std::numbers::pi;
                        const V3<double> l{st * std::cos(phi), st * std::sin(phi), ct};
                        sum += light_radiance<double>(Model::accurate, n, v, l, mu, r, metal, {1.0, 1.0, 1.0},
                                                      {1.0, 1.0, 1.0}, dfg)[0];
                    }
                }
                const double a = sum * (2 * std::numbers::pi) / (double(nt) * np);
                EXPECT_NEAR(a, 1.0, 2e-3) << "roughness " << r << " N·V " << mu << " metalness " << metal;
            }
        }
    }
}

}  // namespace
