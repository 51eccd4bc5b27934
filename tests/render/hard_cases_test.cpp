// Numerically hard inputs give finite, sensible output: v = −l (no half vector), N·L ≤ 0 or NaN,
// the mirror-like highlight at the roughness floor, lights on the surface, non-finite texels.
#include <cmath>
#include <cstring>

#include "reference.hpp"
#include "vulkan_fixture.hpp"

namespace mf::test {
namespace {

using render::Light;
using render::LightType;
using render::Material;
using render::Scene;

constexpr uint32_t kSize = 65;  // odd: the centre pixel's ray is the optical axis (v = +Z there)

Scene one_light(Light l) {
    Scene s;
    s.width = s.height = kSize;
    s.lights = {l};
    return s;
}

Light directional(render::Vec3 dir, float intensity = 3.f) {
    Light l;
    l.direction = dir;
    l.intensity = intensity;
    return l;
}

Material plain(float roughness, float metalness) {
    Material m;
    m.name = "hard";
    m.albedo.value = {0.9f, 0.9f, 0.9f};
    m.roughness.value = roughness;
    m.metalness.value = metalness;
    return m;
}

// Every case on both shading paths (the parameter: Scene::shading).
class HardCaseTest : public VulkanTest, public ::testing::WithParamInterface<render::Shading> {
protected:
    render::Frame linear(const Scene& scene, const Material& m) {
        Scene s = scene;
        s.shading = GetParam();
        render::Renderer r(context(), s);
        EXPECT_EQ(r.shading(), GetParam());
        const render::GpuMaterial gm = r.upload(m);
        render::OutputOptions o;
        o.format = render::PixelFormat::rgba32f;
        return r.render(gm, o);
    }
    static size_t nonfinite(const render::Frame& f) {
        size_t n = 0;
        for (float v : f.rgba32f) n += std::isfinite(v) ? 0 : 1;
        return n;
    }
    static float at(const render::Frame& f, uint32_t x, uint32_t y, int c) {
        return f.rgba32f[(size_t{y} * f.width + x) * 4 + size_t(c)];
    }
};

TEST_P(HardCaseTest, RoughnessZeroHasAFiniteHighlightMatchingTheReference) {
    // Mirror-like metal lit along the view axis: the highlight sits at the centre pixel, where
    // n·h = 1 and D = 1/(π α²) peaks (7.7e4 at the 0.045 floor; a 1e-6 floor on α² would give
    // 3.2e5, past fp16's 65504).
    const Scene s = one_light(directional({0.f, 0.f, -1.f}));
    for (float metal : {0.f, 1.f}) {
        const render::Frame f = linear(s, plain(0.f, metal));
        EXPECT_EQ(nonfinite(f), 0u);
        const float peak = at(f, kSize / 2, kSize / 2, 0);
        const ReferenceImage ref = render_reference(s, plain(0.f, metal));
        const double expected = ref.at(kSize / 2, kSize / 2).rgb[0];
        EXPECT_GT(peak, 1000.f);  // a highlight, not a clamp to a dull value
        EXPECT_NEAR(peak, expected, expected * 1e-3);
    }
}

TEST_P(HardCaseTest, LightBehindTheSurfaceGivesBlackNotNaN) {
    // The light travels toward the camera: at the centre v = −l exactly (no half vector), and every
    // visible point has n·l ≤ 0.
    const render::Frame f = linear(one_light(directional({0.f, 0.f, 1.f})), plain(0.3f, 0.f));
    EXPECT_EQ(nonfinite(f), 0u);
    for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x)
            for (int c = 0; c < 3; ++c) EXPECT_EQ(at(f, x, y, c), 0.f) << x << "," << y;
}

TEST_P(HardCaseTest, ViewOppositeLightWithTiltedNormalStaysFinite) {
    // A normal map that turns the normal fully around makes n·l > 0 where v = −l: the half
    // vector v + l is zero there. Output must be finite and non-negative.
    Material m = plain(0.2f, 1.f);
    render::Texture t;
    t.width = t.height = 2;
    t.channels = 3;
    t.data = {128, 128, 0, 128, 128, 0, 128, 128, 0, 128, 128, 0};  // tangent-space (0, 0, −1)
    m.textures = {t};
    m.normal.texture = 0;
    const render::Frame f = linear(one_light(directional({0.f, 0.f, 1.f})), m);
    EXPECT_EQ(nonfinite(f), 0u);
    for (float v : f.rgba32f) EXPECT_GE(v, 0.f);
}

TEST_P(HardCaseTest, GrazingLightMatchesReference) {
    // Light at 90° to the view: the terminator crosses the middle of the sphere.
    const Scene s = one_light(directional({-1.f, 0.f, 0.f}));
    for (const Material& m : {plain(0.f, 0.f), plain(0.5f, 1.f), plain(1.f, 0.f)}) {
        const render::Frame f = linear(s, m);
        EXPECT_EQ(nonfinite(f), 0u);
        const ReferenceImage ref = render_reference(s, m);
        double max_abs = 0;
        for (uint32_t y = 0; y < kSize; ++y)
            for (uint32_t x = 0; x < kSize; ++x) {
                if (ref.silhouette(x, y)) continue;
                for (int c = 0; c < 3; ++c)
                    max_abs = std::max(max_abs, std::abs(at(f, x, y, c) - ref.at(x, y).rgb[c]) /
                                                    std::max(ref.at(x, y).rgb[c], 1e-4));
            }
        EXPECT_LE(max_abs, 1e-3);
    }
}

TEST_P(HardCaseTest, PointLightOnTheSurfaceStaysFinite) {
    // The light sits on the sphere where the centre ray meets it: d → 0 (a zero-length
    // vector); E = I/d² is skipped below d² = 1e-12 and huge but finite above.
    Light l;
    l.type = LightType::point;
    l.position = {0.f, 0.f, 1.f};
    l.intensity = 1.f;
    for (float roughness : {0.f, 0.5f}) {
        const render::Frame f = linear(one_light(l), plain(roughness, 0.f));
        EXPECT_EQ(nonfinite(f), 0u);
    }
}

TEST_P(HardCaseTest, NonFiniteTexelsAreNeutralized) {
    Material m = plain(0.5f, 0.f);
    render::Texture t;
    t.width = t.height = 2;
    t.channels = 1;
    t.type = render::TexelType::f32;
    const float bad[4] = {NAN, INFINITY, -INFINITY, 0.5f};
    t.data.resize(sizeof bad);
    std::memcpy(t.data.data(), bad, sizeof bad);
    m.textures = {t};
    m.roughness.texture = 0;
    const render::Frame f = linear(one_light(directional({0.57735f, -0.57735f, -0.57735f})), m);
    EXPECT_EQ(nonfinite(f), 0u);
}

TEST_P(HardCaseTest, DegenerateSceneVectorsAreErrors) {
    render::Scene s = one_light(directional({0.f, 0.f, 0.f}));
    s.shading = GetParam();
    render::Renderer r(context(), s);
    const render::GpuMaterial gm = r.upload(plain(0.5f, 0.f));
    EXPECT_THROW(r.render(gm), render::Error);
}

INSTANTIATE_TEST_SUITE_P(BothPaths, HardCaseTest, ::testing::ValuesIn(kShadingPaths),
                         [](const ::testing::TestParamInfo<render::Shading>& i) { return shading_name(i.param); });

}  // namespace
}  // namespace mf::test
