// Image-based lighting: only when an environment is given; energy-conserving in a furnace.
#include <algorithm>
#include <cmath>
#include <memory>
#include <thread>
#include <vector>

#include "reference.hpp"
#include "vulkan_fixture.hpp"

namespace mf::test {
namespace {

using render::Material;
using render::Scene;

std::shared_ptr<render::Environment> environment(uint32_t w, uint32_t h, float (*radiance)(float u, float v)) {
    auto env = std::make_shared<render::Environment>();
    env->width = w;
    env->height = h;
    env->rgba.resize(size_t{w} * h * 4);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const float L = radiance((float(x) + 0.5f) / float(w), (float(y) + 0.5f) / float(h));
            float* p = &env->rgba[(size_t{y} * w + x) * 4];
            p[0] = p[1] = p[2] = L;
            p[3] = 1.f;
        }
    return env;
}

Scene furnace(render::Brdf brdf) {
    Scene s;
    s.width = s.height = 48;
    s.lights.clear();  // the environment alone
    s.brdf = brdf;
    s.environment = environment(64, 32, [](float, float) { return 1.f; });
    return s;
}

Material white(float roughness, float metalness) {
    Material m;
    m.albedo.value = {1, 1, 1};
    m.roughness.value = roughness;
    m.metalness.value = metalness;
    return m;
}

class IblTest : public VulkanTest {
protected:
    // Min and max radiance over the sphere's pixels (the background is set apart by its value).
    std::pair<float, float> sphere_range(render::Renderer& r, const Material& m) {
        const render::GpuMaterial gm = r.upload(m);
        render::OutputOptions o;
        o.format = render::PixelFormat::rgba32f;
        const render::Frame f = r.render(gm, o);
        float lo = 1e9f, hi = -1e9f;
        const uint32_t c = f.width / 2;
        // a disc well inside the silhouette (sphere radius ≈ 0.41 of the image at the defaults)
        for (uint32_t y = 0; y < f.height; ++y)
            for (uint32_t x = 0; x < f.width; ++x) {
                const float dx = float(x) - float(c) + 0.5f, dy = float(y) - float(c) + 0.5f;
                if (dx * dx + dy * dy > 0.3f * 0.3f * float(f.width * f.width)) continue;
                lo = std::min(lo, f.rgba32f[(size_t{y} * f.width + x) * 4]);
                hi = std::max(hi, f.rgba32f[(size_t{y} * f.width + x) * 4]);
            }
        return {lo, hi};
    }
};

TEST_F(IblTest, WhiteDielectricInAWhiteFurnaceIsWhite) {
    // Whatever the specular lobe reflects, the diffuse lobe gets the rest: exactly 1. On both
    // shading paths.
    for (const render::Shading path : kShadingPaths) {
        Scene scene = furnace(render::Brdf::standard);
        scene.shading = path;
        render::Renderer r(context(), scene);
        ASSERT_EQ(r.shading(), path);
        for (float roughness : {0.f, 0.5f, 1.f}) {
            const auto [lo, hi] = sphere_range(r, white(roughness, 0.f));
            EXPECT_NEAR(lo, 1.f, 2e-3f) << roughness << ' ' << shading_name(path);
            EXPECT_NEAR(hi, 1.f, 2e-3f) << roughness << ' ' << shading_name(path);
        }
    }
}

TEST_F(IblTest, MultipleScatteringKeepsAWhiteMetalWhite) {
    // Single scattering loses up to half the energy of a rough metal; the accurate BRDF's
    // compensation (Fdez-Agüera 2019) gives it back. The standard one does lose it.
    render::Renderer standard(context(), furnace(render::Brdf::standard));
    for (const render::Shading path : kShadingPaths) {
        Scene scene = furnace(render::Brdf::accurate);
        scene.shading = path;
        render::Renderer accurate(context(), scene);
        ASSERT_EQ(accurate.shading(), path);
        for (float roughness : {0.2f, 0.6f, 1.f}) {
            const auto [lo, hi] = sphere_range(accurate, white(roughness, 1.f));
            EXPECT_NEAR(lo, 1.f, 3e-3f) << roughness << ' ' << shading_name(path);
            EXPECT_NEAR(hi, 1.f, 3e-3f) << roughness << ' ' << shading_name(path);
        }
    }
    const auto [lo, hi] = sphere_range(standard, white(1.f, 1.f));
    EXPECT_LT(lo, 0.8f);
    (void)hi;
}

TEST_F(IblTest, SkyAboveLightsTheTopOfTheSphere) {
    Scene s = furnace(render::Brdf::standard);
    s.environment = environment(64, 32, [](float, float v) { return v < 0.5f ? 2.f : 0.1f; });
    render::Renderer r(context(), s);
    const render::GpuMaterial gm = r.upload(white(0.8f, 0.f));
    render::OutputOptions o;
    o.format = render::PixelFormat::rgba32f;
    const render::Frame f = r.render(gm, o);
    const float top = f.rgba32f[(size_t{12} * 48 + 24) * 4], bottom = f.rgba32f[(size_t{36} * 48 + 24) * 4];
    EXPECT_GT(top, 2 * bottom);  // n.y = ±0.61 there: about 1.6 against 0.5 for a Lambertian sphere
}

TEST_F(IblTest, EnvironmentPassesRunOnlyWhenOneIsGiven) {
    auto names = [](const std::vector<render::PassTime>& t) {
        std::string s;
        for (const auto& p : t) s += p.name + " ";
        return s;
    };
    Scene plain;
    plain.width = plain.height = 16;
    render::Renderer a(context(), plain);
    EXPECT_EQ(names(a.load_times()), "");
    EXPECT_EQ(a.upload(white(0.5f, 0.f)).variant().find("env"), std::string::npos);

    Scene accurate = plain;
    accurate.brdf = render::Brdf::accurate;
    render::Renderer b(context(), accurate);
    EXPECT_EQ(names(b.load_times()), "brdf_lut ");

    render::Renderer c(context(), furnace(render::Brdf::standard));
    EXPECT_EQ(names(c.load_times()), "brdf_lut env_upload env_cube env_prefilter env_irradiance ");
    EXPECT_NE(c.upload(white(0.5f, 0.f)).variant().find(" env "), std::string::npos);
}

// The renderers of a device alive at once with one environment share its lighting (a batch's
// lanes, made at once on their threads): one of them runs the passes, the others wait for its
// result and draw the same picture. Once none is left, the next renderer makes it again; another
// environment, even an equal one, gets its own.
TEST_F(IblTest, RenderersAliveAtOnceShareTheirEnvironmentsLighting) {
    auto env_passes = [](const render::Renderer& r) {
        size_t n = 0;
        for (const auto& p : r.load_times()) n += p.name.rfind("env_", 0) == 0 ? 1 : 0;
        return n;
    };
    Scene s = furnace(render::Brdf::standard);
    s.environment = environment(64, 32, [](float, float v) { return v < 0.5f ? 2.f : 0.1f; });
    const Material m = white(0.4f, 0.f);
    render::Frame alone;
    {
        render::Renderer r(context(), s);
        EXPECT_EQ(env_passes(r), 4u);
        alone = r.render(r.upload(m));
    }
    std::vector<std::unique_ptr<render::Renderer>> lanes(3);
    std::vector<std::thread> threads;
    for (auto& lane : lanes) threads.emplace_back([&] { lane = std::make_unique<render::Renderer>(context(), s); });
    for (std::thread& t : threads) t.join();
    size_t made = 0;
    for (const auto& lane : lanes) {
        made += env_passes(*lane);
        EXPECT_EQ(lane->render(lane->upload(m)).rgba8, alone.rgba8);
    }
    EXPECT_EQ(made, 4u) << "one renderer of the three made the lighting";
    Scene same = s;
    same.environment = std::make_shared<render::Environment>(*s.environment);
    render::Renderer other(context(), same);
    EXPECT_EQ(env_passes(other), 4u) << "another environment object, its own lighting";
    lanes.clear();
    render::Renderer again(context(), s);
    EXPECT_EQ(env_passes(again), 4u) << "none alive: made again";
    EXPECT_EQ(again.render(again.upload(m)).rgba8, alone.rgba8);
}

}  // namespace
}  // namespace mf::test
