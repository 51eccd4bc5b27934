// Tone mapping in the encode pass (render::Tonemap): the 8-bit frame equals the CPU oracle below
// applied to the same frame's linear radiance, within one code, for every tone mapper, over a
// range of radiance well past 1; and the oracle itself keeps the published properties.
#include <algorithm>
#include <array>
#include <cmath>

#include "base/srgb.hpp"
#include "vulkan_fixture.hpp"

namespace mf::test {
namespace {

using Rgb = std::array<double, 3>;

// Khronos PBR Neutral (Khronos 3D Commerce, "PBR Neutral Specification"), in double.
Rgb neutral(Rgb c) {
    const double start = 0.8 - 0.04, desaturation = 0.15;
    const double x = std::min({c[0], c[1], c[2]});
    const double offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
    for (double& v : c) v -= offset;
    const double peak = std::max({c[0], c[1], c[2]});
    if (peak < start) return c;
    const double d = 1.0 - start;
    const double new_peak = 1.0 - d * d / (peak + d - start);
    for (double& v : c) v *= new_peak / peak;
    const double g = 1.0 - 1.0 / (desaturation * (peak - new_peak) + 1.0);
    for (double& v : c) v = v + (new_peak - v) * g;
    return c;
}

// ACES fitted by Hill (2016): Rec.709 -> RRT space, RRT+ODT rational fit, -> Rec.709.
Rgb aces(const Rgb& c) {
    static constexpr double in[3][3] = {{0.59719, 0.35458, 0.04823},
                                        {0.07600, 0.90834, 0.01566},
                                        {0.02840, 0.13383, 0.83777}};
    static constexpr double out[3][3] = {{1.60475, -0.53108, -0.07367},
                                         {-0.10208, 1.10813, -0.00605},
                                         {-0.00327, -0.07276, 1.07602}};
    Rgb v{}, r{};
    for (int i = 0; i < 3; ++i) v[i] = in[i][0] * c[0] + in[i][1] * c[1] + in[i][2] * c[2];
    for (double& x : v) x = (x * (x + 0.0245786) - 0.000090537) / (x * (0.983729 * x + 0.4329510) + 0.238081);
    for (int i = 0; i < 3; ++i) r[i] = std::clamp(out[i][0] * v[0] + out[i][1] * v[1] + out[i][2] * v[2], 0.0, 1.0);
    return r;
}

int code(double linear_display) {
    const double e = mf::linear_to_srgb(std::clamp(linear_display, 0.0, 1.0));
    return static_cast<int>(std::lround(e * 255.0));
}

TEST(ToneOracle, NeutralKeepsBaseColorsAndCompressesHighlights) {
    // Below the compression start, a colour is only shifted by the toe offset of 0.04.
    const Rgb mid = neutral({0.5, 0.4, 0.3});
    EXPECT_NEAR(mid[0], 0.46, 1e-12);
    EXPECT_NEAR(mid[2], 0.26, 1e-12);
    // Bright values approach 1 and never pass it; monotonic in the input.
    double last = 0.0;
    for (double x = 0.5; x < 1000.0; x *= 1.1) {
        const Rgb t = neutral({x, x, x});
        EXPECT_LE(t[0], 1.0);
        EXPECT_GE(t[0], last);
        last = t[0];
    }
    EXPECT_GT(last, 0.999);
    // A saturated highlight desaturates toward white.
    const Rgb hot = neutral({20.0, 2.0, 2.0});
    EXPECT_GT(hot[1] / hot[0], 2.0 / 20.0);
}

TEST(ToneOracle, AcesIsAFilmicCurve) {
    EXPECT_NEAR(aces({0.0, 0.0, 0.0})[0], 0.0, 1e-3);
    EXPECT_GT(aces({100.0, 100.0, 100.0})[0], 0.99);
    const Rgb grey = aces({0.18, 0.18, 0.18});
    EXPECT_GT(grey[0], 0.1);  // mid grey stays a mid tone
    EXPECT_LT(grey[0], 0.25);
}

class TonemapTest : public VulkanTest {};

TEST_F(TonemapTest, EncodePassMatchesTheOracleWithinOneCode) {
    render::Scene s;
    s.width = s.height = 64;
    s.background = {0.6f, 0.3f, 0.1f};
    // A hot key light: the sphere spans radiance from 0 to well above 1 (highlights near 30).
    s.lights = {render::Light{render::LightType::directional, {0.3f, -0.5f, -0.8f}, {}, {1.f, 0.9f, 0.7f}, 40.f}};
    render::Renderer r(context(), s);
    render::Material m;
    m.albedo.value = {0.8f, 0.5f, 0.2f};
    m.roughness.value = 0.25f;
    m.metalness.value = 0.f;
    const render::GpuMaterial gm = r.upload(m);
    render::OutputOptions lin;
    lin.format = render::PixelFormat::rgba32f;
    const render::Frame radiance = r.render(gm, lin);
    float brightest = 0.f;
    for (float v : radiance.rgba32f) brightest = std::max(brightest, v);
    ASSERT_GT(brightest, 8.f) << "the frame reaches well past 1";
    for (const render::Tonemap tm : {render::Tonemap::none, render::Tonemap::neutral, render::Tonemap::aces}) {
        render::OutputOptions o;
        o.tonemap = tm;
        o.exposure = 1.5f;
        const render::Frame f = r.render(gm, o);
        int worst = 0;
        for (size_t p = 0; p < size_t{f.width} * f.height; ++p) {
            Rgb c{};
            for (int k = 0; k < 3; ++k) c[size_t(k)] = std::max(0.0, double{radiance.rgba32f[4 * p + size_t(k)]} * 1.5);
            const Rgb t = tm == render::Tonemap::neutral ? neutral(c) : tm == render::Tonemap::aces ? aces(c) : c;
            for (int k = 0; k < 3; ++k)
                worst = std::max(worst, std::abs(int{f.rgba8[4 * p + size_t(k)]} - code(t[size_t(k)])));
        }
        EXPECT_LE(worst, 1) << "tone mapper " << static_cast<int>(tm);
    }
}

}  // namespace
}  // namespace mf::test
