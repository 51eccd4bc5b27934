// CPU rendering of the preview's scenes in double precision over the analytic sphere: the
// reference the GPU images are compared with. The BRDF itself is the one CPU oracle of
// tests/stability/brdf_reference.hpp (written from the papers' formulas, not from the shaders);
// this adds the camera, the exact sphere, bilinear texture sampling, lights, opacity.
#pragma once
#include <array>
#include <utility>
#include <vector>

#include "render/render.hpp"

namespace mf::test {

struct ReferencePixel {
    bool hit = false;           // the primary ray meets the sphere
    bool minified = false;      // textures are minified here (the GPU would use mips > 0)
    double rgb[3] = {0, 0, 0};  // linear radiance (before exposure), background where no hit
};

struct ReferenceImage {
    uint32_t width = 0, height = 0;
    std::vector<ReferencePixel> pixels;
    const ReferencePixel& at(uint32_t x, uint32_t y) const { return pixels[size_t{y} * width + x]; }
    // A pixel next to the silhouette: it or one of its 8 neighbours is on the other side.
    bool silhouette(uint32_t x, uint32_t y) const;
};

// Sphere scenes only (the one shape the renderer shades analytically, see shade.frag).
ReferenceImage render_reference(const render::Scene& scene, const render::Material& material);

// Split-sum terms (A, B) of the accurate BRDF's specular lobe (height-correlated Smith GGX): its
// directional albedo is F0 A + B with Schlick's F, E = A + B with F = 1; the loss 1 − E; and
// 1 − E_avg(roughness), E_avg being E's cosine-weighted average. By quadrature
// (cpubrdf::specular_dfg), tabulated per roughness.
std::array<double, 4> specular_dfg_correlated(double NoV, double roughness);

// The sRGB curves are mf::linear_to_srgb / mf::srgb_to_linear (base/srgb.hpp).
int to_code(double encoded);  // round to nearest 8-bit code, clamped

// Both shading paths (Scene::shading), which every reference test runs with the same bounds.
// The example scene's blue point light (docs/interface.md, scene file), used beside other lights.
inline render::Light example_point_light() {
    render::Light point;
    point.type = render::LightType::point;
    point.position = {2.5f, -0.5f, 1.5f};
    point.color = {0.3f, 0.5f, 1.0f};
    point.intensity = 10.f;
    return point;
}

// An 8-bit texture of `w`×`h` texels and `channels` channels holding `codes` as given.
inline render::Texture texture_of(std::vector<uint8_t> codes, uint32_t w, uint32_t h, uint32_t channels, bool srgb) {
    render::Texture t;
    t.width = w;
    t.height = h;
    t.channels = channels;
    t.srgb = srgb;
    t.data = std::move(codes);
    return t;
}

inline constexpr render::Shading kShadingPaths[] = {render::Shading::raster, render::Shading::compute};
inline const char* shading_name(render::Shading s) {
    return s == render::Shading::compute ? "compute" : s == render::Shading::raster ? "raster" : "auto";
}

}  // namespace mf::test
