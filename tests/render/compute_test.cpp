// The compute shading path (Scene::shading compute) against the raster path on every shape it
// covers, textured and normal-mapped, with image-based lighting; its fallback to raster where it
// does not cover the scene; the automatic choice by measurement.
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "reference.hpp"
#include "vulkan_fixture.hpp"

namespace mf::test {
namespace {

using render::Material;
using render::Scene;
using render::Shading;
using render::ShapeType;
using render::Texture;

constexpr uint32_t kSize = 128;
constexpr uint32_t kTex = 64;  // tiled twice: minified toward the silhouettes, so mips are selected

uint8_t q(double v) { return static_cast<uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255)); }

// Smooth periodic fields (filtering and mip selection have little to disagree about), but
// varying enough that a wrong (u, v), tangent frame or mip would move pixels by codes.
double wave(uint32_t x, uint32_t y, double phase) {
    const double pi = std::numbers::pi;
    return 0.5 + 0.5 * std::sin(2 * pi * (x + 0.5) / kTex + phase) * std::cos(2 * pi * (y + 0.5) / kTex + 0.5 * phase);
}

Material textured() {
    Material m;
    m.name = "textured";
    Texture albedo, normal, rough;
    for (Texture* t : {&albedo, &normal, &rough}) {
        t->width = t->height = kTex;
        t->channels = t == &rough ? 1 : 3;
        t->data.resize(size_t{kTex} * kTex * t->channels);
    }
    albedo.srgb = true;
    const double pi = std::numbers::pi;
    for (uint32_t y = 0; y < kTex; ++y)
        for (uint32_t x = 0; x < kTex; ++x) {
            const size_t p = size_t{y} * kTex + x;
            albedo.data[3 * p + 0] = q(0.2 + 0.7 * wave(x, y, 0.0));
            albedo.data[3 * p + 1] = q(0.2 + 0.6 * wave(x, y, 2.0));
            albedo.data[3 * p + 2] = q(0.1 + 0.5 * wave(x, y, 4.0));
            // Tilted along u in one half of the period and along v in the other: a swapped or
            // mirrored tangent frame moves the highlights.
            const double nx = 0.4 * std::sin(2 * pi * (x + 0.5) / kTex), ny = 0.3 * std::cos(2 * pi * (y + 0.5) / kTex);
            const double len = std::sqrt(nx * nx + ny * ny + 1);
            normal.data[3 * p + 0] = q(nx / len * 0.5 + 0.5);
            normal.data[3 * p + 1] = q(ny / len * 0.5 + 0.5);
            normal.data[3 * p + 2] = q(1 / len * 0.5 + 0.5);
            rough.data[p] = q(0.25 + 0.6 * wave(x, y, 1.0));
        }
    m.textures = {albedo, normal, rough};
    m.albedo.texture = 0;
    m.normal.texture = 1;
    m.roughness = {2, render::Channel::R, false, 0.f};
    m.metalness.value = 0.3f;
    m.uv_scale = {2.f, 2.f};
    return m;
}

std::shared_ptr<render::Environment> sky() {
    auto env = std::make_shared<render::Environment>();
    env->width = 64;
    env->height = 32;
    env->rgba.resize(size_t{64} * 32 * 4);
    for (uint32_t y = 0; y < 32; ++y)
        for (uint32_t x = 0; x < 64; ++x) {
            float* p = &env->rgba[(size_t{y} * 64 + x) * 4];
            const float up = 1.f - (float(y) + 0.5f) / 32.f;
            p[0] = 0.2f + 0.3f * up;
            p[1] = 0.25f + 0.3f * up + 0.2f * float(x % 16 < 8);
            p[2] = 0.3f + 0.5f * up;
            p[3] = 1.f;
        }
    env->intensity = 0.5f;
    return env;
}

Scene shape_scene(ShapeType type, Shading path) {
    Scene s;
    s.width = s.height = kSize;
    s.shape.type = type;
    s.shape.size = type == ShapeType::sphere ? 1.f : type == ShapeType::cube ? 1.3f : 2.f;
    s.shading = path;
    s.background = {1.f, 0.f, 1.f};  // no material pixel has this code: the shape's coverage
    s.lights.push_back(example_point_light());
    s.environment = sky();
    return s;
}

bool background(const render::Frame& f, size_t p) {
    return f.rgba8[4 * p] == 255 && f.rgba8[4 * p + 1] == 0 && f.rgba8[4 * p + 2] == 255;
}

using ComputeShadingTest = VulkanTest;

// Raster and compute within one code everywhere but on the silhouette (the raster path's mesh
// and the analytic shape may cover an edge pixel differently): the same (u, v), tangent frame,
// normal mapping, mip selection, lights and environment.
TEST_F(ComputeShadingTest, AgreesWithRasterOnTexturedShapes) {
    const char* const names[] = {"sphere", "cube", "plane"};
    for (const ShapeType type : {ShapeType::sphere, ShapeType::cube, ShapeType::plane}) {
        render::Frame frames[2];
        for (const Shading path : kShadingPaths) {
            render::Renderer r(context(), shape_scene(type, path));
            ASSERT_EQ(r.shading(), path);
            EXPECT_TRUE(r.take_notes().empty());
            frames[path == Shading::compute ? 1 : 0] = r.render(r.upload(textured()));
        }
        const render::Frame &raster = frames[0], &compute = frames[1];
        int max_code = 0;
        size_t compared = 0, edge = 0, coverage_differs = 0;
        for (uint32_t y = 0; y < kSize; ++y)
            for (uint32_t x = 0; x < kSize; ++x) {
                const size_t p = size_t{y} * kSize + x;
                if (background(raster, p) != background(compute, p)) ++coverage_differs;
                bool silhouette = false;  // this pixel or a neighbour is on the other side of the edge
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int nx = int(x) + dx, ny = int(y) + dy;
                        if (nx < 0 || ny < 0 || nx >= int(kSize) || ny >= int(kSize)) continue;
                        const size_t n = size_t(ny) * kSize + size_t(nx);
                        silhouette = silhouette || background(raster, n) != background(raster, p) ||
                                     background(compute, n) != background(raster, p);
                    }
                if (silhouette) {
                    ++edge;
                    continue;
                }
                if (background(raster, p)) continue;
                ++compared;
                for (size_t c = 0; c < 3; ++c)
                    max_code = std::max(max_code,
                                        std::abs(int(raster.rgba8[4 * p + c]) - int(compute.rgba8[4 * p + c])));
            }
        std::printf("  %-6s compute vs raster: max |Δcode| %d over %zu shape px (%zu at the silhouette excepted, %zu "
                    "covered by one path only)\n",
                    names[int(type)], max_code, compared, edge, coverage_differs);
        EXPECT_GT(compared, 4000u) << names[int(type)];
        EXPECT_LE(max_code, 1) << names[int(type)];
        // Coverage differs only where the mesh's chords leave the sphere, or on an edge's ties.
        EXPECT_LE(coverage_differs, edge / 4) << names[int(type)];
    }
}

// The shaderball (a mesh) and the ground plane (its shadow needs depth) stay on the raster path:
// `compute` says so once, `auto` silently.
TEST_F(ComputeShadingTest, FallsBackToRasterWithANote) {
    Scene ball = shape_scene(ShapeType::shaderball, Shading::compute);
    Scene ground = shape_scene(ShapeType::sphere, Shading::compute);
    ground.ground.enabled = true;
    for (const Scene& s : {ball, ground}) {
        render::Renderer r(context(), s);
        EXPECT_EQ(r.shading(), Shading::raster);
        const std::vector<std::string> notes = r.take_notes();
        ASSERT_EQ(notes.size(), 1u);
        EXPECT_NE(notes[0].find("raster path"), std::string::npos) << notes[0];
        std::printf("  %s\n", notes[0].c_str());
        const render::Frame f = r.render(r.upload(textured()));
        EXPECT_FALSE(background(f, size_t{kSize / 2} * kSize + kSize / 2)) << "the shape was drawn";

        Scene automatic = s;
        automatic.shading = Shading::automatic;
        render::Renderer a(context(), automatic);
        EXPECT_EQ(a.shading(), Shading::raster);
        EXPECT_TRUE(a.take_notes().empty()) << "auto falls back silently, without measuring";
    }
}

// `auto` on a CPU device is raster without a measurement (compute never measured 1.5x faster on
// lavapipe, and a measurement near the margin could change the picture from run to run): the
// same picture as raster, nothing said. The measurement a GPU decides by runs here too and
// times both paths, with multisampling as the scene asks.
TEST_F(ComputeShadingTest, AutomaticIsRasterOnACpuDeviceAndTheMeasurementRuns) {
    ASSERT_TRUE(context().info().cpu) << "the tests run on lavapipe";
    render::Renderer automatic(context(), shape_scene(ShapeType::sphere, Shading::automatic));
    EXPECT_EQ(automatic.shading(), Shading::raster);
    EXPECT_TRUE(automatic.take_notes().empty());
    render::Renderer raster(context(), shape_scene(ShapeType::sphere, Shading::raster));
    EXPECT_EQ(automatic.render(automatic.upload(textured())).rgba8, raster.render(raster.upload(textured())).rgba8);
    for (const uint32_t msaa : {1u, 4u}) {
        const render::ShadingTimes t = render::measure_shading(context(), msaa);
        std::printf("  measure_shading msaa %u: raster %.3f ms, compute %.3f ms\n", msaa, t.raster_ms, t.compute_ms);
        EXPECT_GT(t.raster_ms, 0.0);
        EXPECT_GT(t.compute_ms, 0.0);
    }
}

// Scene::msaa on the compute path: every sample shaded and averaged (no multisampled target),
// at 2, 4 and 8 samples; the silhouette's pixels blend, the interior stays the one-sample image
// within a code or two where the texture's detail is averaged.
TEST_F(ComputeShadingTest, MultisamplesAtTheStandardPositions) {
    Scene s = shape_scene(ShapeType::cube, Shading::compute);
    s.environment = nullptr;
    render::Renderer one(context(), s);
    const render::Frame base = one.render(one.upload(textured()));
    for (const uint32_t samples : {2u, 4u, 8u}) {
        Scene m = s;
        m.msaa = samples;
        render::Renderer r(context(), m);
        EXPECT_TRUE(r.take_notes().empty());
        const render::GpuMaterial gm = r.upload(textured());
        EXPECT_NE(gm.variant().find("samples" + std::to_string(samples)), std::string::npos) << gm.variant();
        const render::Frame f = r.render(gm);
        size_t blended = 0;  // edge pixels neither background nor as one sample shades them
        for (size_t p = 0; p < size_t{kSize} * kSize; ++p)
            if (background(base, p) != background(f, p) ||
                (!background(f, p) && std::abs(int(f.rgba8[4 * p + 1]) - int(base.rgba8[4 * p + 1])) > 20))
                ++blended;
        std::printf("  msaa %u: %zu pixels blended at the silhouette\n", samples, blended);
        EXPECT_GT(blended, 100u) << samples;
        EXPECT_LT(blended, 1500u) << samples;
    }
}

}  // namespace
}  // namespace mf::test
