// Texture placement (render::Material::uv_scale, uv_offset) and the shaderball shape, on
// lavapipe under the validation layer.
#include <cmath>
#include <cstdint>

#include "vulkan_fixture.hpp"

namespace mf::test {
namespace {

class PlacementTest : public VulkanTest {
protected:
    // A plane filling the view, lit by nothing but its emissive texture: dark left half, bright
    // right half (4x1 texels). Returns the red channel of the linear frame.
    std::vector<float> render_plane(std::array<float, 2> scale, std::array<float, 2> offset) {
        render::Scene s;
        s.width = s.height = 64;
        s.lights.clear();
        s.shape.type = render::ShapeType::plane;
        s.shape.size = 2.f;
        s.camera.position = {0.f, 0.f, 2.f};
        s.camera.yfov_deg = 50.f;  // the plane's 2 m fill more than the view from 2 m away
        render::Renderer r(context(), s);
        render::Material m;
        m.albedo.value = {0.f, 0.f, 0.f};
        render::Texture t;
        t.width = 4;
        t.height = 1;
        t.channels = 1;
        t.data = {0, 0, 255, 255};
        m.textures.push_back(t);
        m.emissive.texture = 0;
        m.uv_scale = scale;
        m.uv_offset = offset;
        const render::GpuMaterial gm = r.upload(m);
        render::OutputOptions o;
        o.format = render::PixelFormat::rgba32f;
        const render::Frame f = r.render(gm, o);
        std::vector<float> red(size_t{f.width} * f.height);
        for (size_t p = 0; p < red.size(); ++p) red[p] = f.rgba32f[4 * p];
        return red;
    }
};

TEST_F(PlacementTest, OffsetAndScaleMoveTheTexture) {
    auto at = [](const std::vector<float>& img, int x) { return img[32 * 64 + static_cast<size_t>(x)]; };
    const auto plain = render_plane({1.f, 1.f}, {0.f, 0.f});
    EXPECT_LT(at(plain, 8), 0.05f);   // left: the dark half
    EXPECT_GT(at(plain, 56), 0.95f);  // right: the bright half
    // Half a texture to the side: the halves trade places.
    const auto shifted = render_plane({1.f, 1.f}, {0.5f, 0.f});
    EXPECT_GT(at(shifted, 8), 0.95f);
    EXPECT_LT(at(shifted, 56), 0.05f);
    // Twice across: dark, bright, dark, bright in quarters.
    const auto tiled = render_plane({2.f, 1.f}, {0.f, 0.f});
    EXPECT_LT(at(tiled, 6), 0.05f);
    EXPECT_GT(at(tiled, 26), 0.95f);
    EXPECT_LT(at(tiled, 38), 0.05f);
    EXPECT_GT(at(tiled, 58), 0.95f);
}

TEST_F(PlacementTest, ShaderballRendersItsRingAndBall) {
    render::Scene s;
    s.width = s.height = 64;
    s.shape.type = render::ShapeType::shaderball;
    render::Renderer r(context(), s);
    render::Material m;
    m.albedo.value = {0.8f, 0.8f, 0.8f};
    const render::GpuMaterial gm = r.upload(m);
    EXPECT_NE(gm.variant().find("shaderball"), std::string::npos) << gm.variant();
    render::OutputOptions o;
    o.format = render::PixelFormat::rgba32f;
    const render::Frame f = r.render(gm, o);
    // The ring reaches past the ball: 4 m away with a 35° view, a metre spans 25.4 px, so the
    // ball's silhouette ends 17.8 px from the centre and the ring's at 21.8 px. Lit pixels
    // beyond 19.5 px on the light's side (left) are the ring's.
    size_t covered = 0, beyond = 0;
    for (uint32_t y = 0; y < f.height; ++y)
        for (uint32_t x = 0; x < f.width; ++x) {
            const bool lit = f.rgba32f[(size_t{y} * f.width + x) * 4] > 0.01f;
            covered += lit;
            beyond += lit && static_cast<float>(x) + 0.5f < 32.f - 19.5f;
        }
    EXPECT_GT(covered, 350u)
        << beyond;  // the ball alone covers π · 17.8² ≈ 1000 px, the lit part about half (measured 471)
    EXPECT_GT(beyond, 10u);
}

// The ground (Scene::ground), only when asked: the key light (travelling down, back and right)
// casts the sphere's shadow back and to the right on the floor; the same floor to the left is
// lit. Without it the variant has no ground and the frame's floor area is background.
TEST_F(PlacementTest, GroundOnlyWhenAskedWithTheKeyLightsShadow) {
    render::Scene s;
    s.width = s.height = 64;
    s.background = {0.f, 0.f, 0.f};
    render::Material m;
    m.albedo.value = {0.8f, 0.8f, 0.8f};
    render::OutputOptions o;
    o.format = render::PixelFormat::rgba32f;
    auto at = [](const render::Frame& f, int x, int y) { return f.rgba32f[(size_t(y) * f.width + size_t(x)) * 4]; };
    {
        render::Renderer plain(context(), s);
        const render::GpuMaterial gm = plain.upload(m);
        EXPECT_EQ(gm.variant().find("ground"), std::string::npos) << gm.variant();
        EXPECT_EQ(at(plain.render(gm, o), 12, 52), 0.f) << "no ground: background";
    }
    s.ground.enabled = true;
    render::Renderer r(context(), s);
    const render::GpuMaterial gm = r.upload(m);
    EXPECT_NE(gm.variant().find("ground"), std::string::npos) << gm.variant();
    const render::Frame f = r.render(gm, o);
    // The light travels along (1, −1, −1)/√3: from the sphere's centre it meets the floor
    // (y = −1) at (1, −1, −1), seen at about pixel (52, 52); its mirror image (12, 52) is lit.
    const float lit = at(f, 12, 52), shadowed = at(f, 52, 52);
    EXPECT_GT(lit, 0.1f);
    EXPECT_LT(shadowed, 0.2f * lit) << "lit " << lit << ", in the shadow " << shadowed;
    // Far from the sphere the floor is plain Lambert + specular under the key light: no shadow.
    EXPECT_GT(at(f, 2, 62), 0.1f);
}

}  // namespace
}  // namespace mf::test
