// The look-dev default scene: a studio environment generated here (no file to ship, the same
// radiance on every machine), one key light, a neutral grey background and Khronos PBR Neutral
// tone mapping, as the look-dev viewers people judge materials in default to; and the reference
// scene (one white key light on black, no tone mapping) that the exactness tests use.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "preview/preview.hpp"

namespace mf::preview {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// A softbox: a rectangle of constant radiance on the sphere of directions, centred at azimuth
// `az` (degrees, 0 = the camera's view direction −Z, positive toward +X) and elevation `el`
// (degrees above the horizon), `w` x `h` degrees, edges softened over `soft` degrees as a real
// diffuser's falloff.
struct Softbox {
    float az, el, w, h, radiance, soft;
    render::Vec3 tint;
};

// Radiance arriving from the direction with azimuth `a` and elevation `e` (degrees).
render::Vec3 studio_radiance(float a, float e) {
    // The room: a grey cyclorama, brighter above than at the floor (0.08 below, 0.12 at the
    // horizon, 0.16 overhead), so that a rough material is never lit from one side only and a
    // metal's far side reflects something: the floor it would in a photo studio.
    const float up = std::clamp(e / 90.f, -1.f, 1.f);
    const float room = 0.12f + 0.04f * up;
    render::Vec3 c{room, room, room};
    // Key (large, camera left, above), fill (camera right, low, weaker, slightly cool), rim
    // strip (behind, right, tall and narrow: outlines the silhouette), top (overhead). The key
    // light of the scene shines from the key softbox's direction.
    static const Softbox boxes[] = {
        {-135.f, 35.f, 40.f, 30.f, 5.f, 4.f, {1.f, 0.97f, 0.92f}},
        {120.f, 10.f, 30.f, 40.f, 1.2f, 6.f, {0.92f, 0.96f, 1.f}},
        {20.f, 25.f, 10.f, 50.f, 3.f, 2.f, {1.f, 1.f, 1.f}},
        {0.f, 85.f, 30.f, 30.f, 1.5f, 8.f, {1.f, 1.f, 1.f}},
    };
    for (const Softbox& b : boxes) {
        float da = std::fabs(a - b.az);
        da = std::min(da, 360.f - da);  // azimuth wraps
        // Near the poles a box spans more azimuth: compare arc lengths along the parallel.
        da *= std::cos(e * kPi / 180.f);
        const float de = std::fabs(e - b.el);
        auto inside = [&](float d, float half) { return std::clamp((half - d) / b.soft + 0.5f, 0.f, 1.f); };
        const float k = inside(da, b.w / 2.f) * inside(de, b.h / 2.f);
        if (k <= 0.f) continue;
        const float s = k * k * (3.f - 2.f * k);  // smoothstep: no visible edge ringing in reflections
        c[0] += s * b.radiance * b.tint[0];
        c[1] += s * b.radiance * b.tint[1];
        c[2] += s * b.radiance * b.tint[2];
    }
    return c;
}

}  // namespace

std::shared_ptr<const render::Environment> studio_environment() {
    static const std::shared_ptr<const render::Environment> env = [] {
        auto e = std::make_shared<render::Environment>();
        e->width = 512;
        e->height = 256;
        e->rgba.resize(size_t{e->width} * e->height * 4);
        for (uint32_t y = 0; y < e->height; ++y)
            for (uint32_t x = 0; x < e->width; ++x) {
                // render::Environment's mapping: u = 0.5 + atan2(d.x, −d.z) / 2π, v = acos(d.y) / π.
                const float u = (static_cast<float>(x) + 0.5f) / static_cast<float>(e->width);
                const float v = (static_cast<float>(y) + 0.5f) / static_cast<float>(e->height);
                const float az = (u - 0.5f) * 360.f, el = 90.f - v * 180.f;
                const render::Vec3 c = studio_radiance(az, el);
                float* o = &e->rgba[(size_t{y} * e->width + x) * 4];
                o[0] = c[0];
                o[1] = c[1];
                o[2] = c[2];
                o[3] = 1.f;
            }
        return e;
    }();
    return env;
}

void place_textures(const SceneFile& sf, render::Material& m) {
    float k = 1.f;
    if (sf.keep_aspect && !m.textures.empty()) {
        const size_t i = m.albedo.texture >= 0 ? static_cast<size_t>(m.albedo.texture) : 0;
        const render::Texture& t = m.textures[i];
        const render::ShapeType s = sf.scene.shape.type;
        const float surface = s == render::ShapeType::sphere || s == render::ShapeType::shaderball ? 2.f : 1.f;
        if (t.width > 0 && t.height > 0) k = surface * static_cast<float>(t.height) / static_cast<float>(t.width);
    }
    m.uv_scale = {sf.uv_scale[0] * k, sf.uv_scale[1]};
    m.uv_offset = sf.uv_offset;
}

std::optional<render::Camera> orbit_camera(const render::Camera& c, std::optional<std::array<float, 2>> az_el,
                                           std::optional<float> distance, std::string& error) {
    const float dx = c.position[0] - c.target[0], dy = c.position[1] - c.target[1], dz = c.position[2] - c.target[2];
    const float current = std::sqrt(dx * dx + dy * dy + dz * dz);
    if (!(current > 0.f)) {
        error = "the camera sits on its target: no direction to orbit from";
        return std::nullopt;
    }
    float az = std::atan2(dx, dz), el = std::asin(std::clamp(dy / current, -1.f, 1.f));
    if (az_el) {
        az = (*az_el)[0] * kPi / 180.f;
        el = (*az_el)[1] * kPi / 180.f;
    }
    if (std::fabs(std::cos(el)) < 1e-3f) {
        error = "an elevation of ±90° looks straight along the camera's up vector: use at most ±89.9";
        return std::nullopt;
    }
    const float r = distance.value_or(current);
    render::Camera out = c;
    out.position = {c.target[0] + r * std::cos(el) * std::sin(az), c.target[1] + r * std::sin(el),
                    c.target[2] + r * std::cos(el) * std::cos(az)};
    return out;
}

SceneFile reference_scene() {
    SceneFile s;  // render::Scene's defaults: one white key light, a sphere, black, no tone mapping
    return s;
}

SceneFile default_scene() {
    SceneFile s;
    render::Scene& sc = s.scene;
    sc.environment = studio_environment();
    // The key light from the key softbox's direction (it travels away from it), weaker than the
    // reference scene's 3: the environment adds the rest.
    const float az = -135.f * kPi / 180.f, el = 35.f * kPi / 180.f;
    const render::Vec3 from{std::cos(el) * std::sin(az), std::sin(el), -std::cos(el) * std::cos(az)};
    sc.lights = {render::Light{
        render::LightType::directional, {-from[0], -from[1], -from[2]}, {0.f, 0.f, 0.f}, {1.f, 0.97f, 0.92f}, 2.f}};
    sc.background = {0.18f, 0.18f, 0.18f};  // mid grey: neither hides a dark rim nor a bright one
    s.output.tonemap = render::Tonemap::neutral;
    s.lookdev = true;
    s.keep_aspect = true;
    // Silhouettes multisampled at 4 samples a pixel, shaded once a pixel; textures on the fast
    // path (8-bit as read, mips made on the device). docs/preview.md gives the measured cost and
    // the difference from 3×3 supersampling with exact textures (`--aa 3 --textures exact`).
    sc.msaa = 4;
    sc.fast_textures = true;
    // On a GPU the faster shading path, measured once (a render farm's datacenter GPUs shade far
    // faster in compute); raster on lavapipe. The reference scene and scene files keep raster.
    sc.shading = render::Shading::automatic;
    return s;
}

}  // namespace mf::preview
