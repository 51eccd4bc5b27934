// Mip chains per role, pipeline variants, device selection.
#include <cmath>
#include <cstring>

#include "base/srgb.hpp"
#include "reference.hpp"
#include "render/internal.hpp"
#include "vulkan_fixture.hpp"

namespace mf::test {
namespace {

using render::Material;
using render::Texture;
using render::detail::MipKind;
using render::detail::PreparedTexture;

// Channel c of texel 0 of `level`, as the sampler would read it before any sRGB decode.
double texel(const PreparedTexture& p, size_t level, int c) {
    const auto& b = p.levels[level].bytes;
    switch (p.format) {
        case VK_FORMAT_R8G8B8A8_UNORM:
        case VK_FORMAT_R8G8B8A8_SRGB: return b[size_t(c)] / 255.0;
        case VK_FORMAT_R16G16B16A16_UNORM: {
            uint16_t v;
            std::memcpy(&v, b.data() + 2 * size_t(c), 2);
            return v / 65535.0;
        }
        case VK_FORMAT_R32G32B32A32_SFLOAT: {
            float v;
            std::memcpy(&v, b.data() + 4 * size_t(c), 4);
            return v;
        }
        default: ADD_FAILURE() << "unexpected format " << p.format; return 0;
    }
}

// Both upload paths: the GPU's 8-bit formats and lavapipe's promoted ones.
class MipTest : public VulkanTest, public ::testing::WithParamInterface<bool> {
protected:
    void configure(render::ContextOptions& o) override { o.precise_cpu_textures = GetParam(); }
    PreparedTexture prepare(const Texture& t, MipKind kind) {
        return render::detail::prepare_texture(render::detail::device_of(context()), t, kind);
    }
};

TEST_P(MipTest, ColorIsAveragedInLinearLight) {
    const PreparedTexture p = prepare(texture_of({0, 255}, 2, 1, 1, true), MipKind::color);
    ASSERT_EQ(p.levels.size(), 2u);
    double v = texel(p, 1, 0);
    if (p.format == VK_FORMAT_R8G8B8A8_SRGB) {
        // black and white average to linear 0.5, sRGB 0.7354 → code 188, not the naive 128
        EXPECT_EQ(p.levels[1].bytes[0], 188);
        v = mf::srgb_to_linear(v);
    }
    EXPECT_NEAR(v, 0.5, 4e-3);               // 188 decodes to 0.5029
    EXPECT_NEAR(texel(p, 1, 3), 1.0, 1e-6);  // alpha is plain data
}

TEST_P(MipTest, FloatColorIsDecodedExactlyNegativesMirrored) {
    // A float texture tagged sRGB is decoded on the CPU with the exact curve (base/srgb.hpp) and
    // stored linear. Negatives are mirrored, −f(−x): down to −0.04045 that is the linear segment
    // continued (x / 12.92), below it the power segment, not a clamp to 0.
    const float values[6] = {0.5f, -0.02f, -0.5f, 0.04045f, 1.f, 0.f};
    Texture t;
    t.width = 2;
    t.height = 1;
    t.channels = 3;
    t.type = render::TexelType::f32;
    t.srgb = true;
    t.data.resize(sizeof values);
    std::memcpy(t.data.data(), values, sizeof values);
    const PreparedTexture p = prepare(t, MipKind::color);
    ASSERT_EQ(p.format, VK_FORMAT_R32G32B32A32_SFLOAT);
    for (int c = 0; c < 3; ++c)
        EXPECT_EQ(texel(p, 0, c), static_cast<float>(mf::srgb_to_linear(double{values[c]}))) << c;
    EXPECT_FLOAT_EQ(static_cast<float>(texel(p, 0, 1)), -0.02f / 12.92f);
    EXPECT_NEAR(texel(p, 0, 2), -0.214041140482232, 1e-7);
    EXPECT_EQ(texel(p, 0, 3), 1.0);  // alpha
}

TEST_P(MipTest, NormalsAreRenormalized) {
    // +X and +Z average to (0.5, 0, 0.5), renormalized to (0.707, 0, 0.707): code 218, not 191.
    const PreparedTexture p = prepare(texture_of({255, 128, 128, 128, 128, 255}, 2, 1, 3, false), MipKind::normal);
    ASSERT_EQ(p.levels.size(), 2u);
    const double x = texel(p, 1, 0) * 2 - 1, y = texel(p, 1, 1) * 2 - 1, z = texel(p, 1, 2) * 2 - 1;
    EXPECT_NEAR(std::sqrt(x * x + y * y + z * z), 1.0, 1e-2);
    EXPECT_NEAR(x, std::sqrt(0.5), 1e-2);
    EXPECT_NEAR(z, std::sqrt(0.5), 1e-2);
}

TEST_P(MipTest, DataIsAveragedAsStored) {
    const PreparedTexture p = prepare(texture_of({0, 255}, 2, 1, 1, false), MipKind::data);
    EXPECT_NEAR(texel(p, 1, 0), 0.5, 2.5e-3);
}

TEST_P(MipTest, OddSizesUseAreaWeights) {
    std::vector<uint8_t> v;
    for (uint8_t i = 0; i < 9; ++i) v.push_back(static_cast<uint8_t>(i * 30));
    const PreparedTexture p = prepare(texture_of(v, 3, 3, 1, false), MipKind::data);
    ASSERT_EQ(p.levels.size(), 2u);  // 3×3 → 1×1
    EXPECT_NEAR(texel(p, 1, 0), 120 / 255.0, 2.5e-3);
}

TEST_P(MipTest, ChainGoesDownToOneTexel) {
    const PreparedTexture p = prepare(texture_of(std::vector<uint8_t>(5 * 3, 7), 5, 3, 1, false), MipKind::data);
    ASSERT_EQ(p.levels.size(), 3u);  // 5×3, 2×1, 1×1
    EXPECT_EQ(p.levels[1].width, 2u);
    EXPECT_EQ(p.levels[1].height, 1u);
    EXPECT_EQ(p.levels[2].width, 1u);
}

INSTANTIATE_TEST_SUITE_P(Formats, MipTest, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& p) { return p.param ? "Promoted" : "EightBit"; });

using VariantTest = VulkanTest;

TEST_F(VariantTest, OnlyWhatTheMaterialAndSceneCallForIsCompiledIn) {
    render::Scene s;
    s.width = s.height = 16;
    s.lights.resize(3);
    s.lights[2].type = render::LightType::point;
    s.lights[2].position = {2, 2, 2};
    render::Renderer r(context(), s);

    Material constant;
    const render::GpuMaterial a = r.upload(constant);
    EXPECT_EQ(a.variant(), "sphere standard dir2 point1 albedo:const normal:none roughness:const metalness:const");

    Material textured;
    Texture t = texture_of(std::vector<uint8_t>(4 * 4 * 3, 128), 4, 4, 3, false);
    textured.textures = {t, t};
    textured.textures[0].srgb = true;
    textured.albedo.texture = 0;
    textured.normal.texture = 1;
    textured.normal.green_down = true;
    textured.occlusion.texture = 0;  // occlusion scales environment light only: none here
    textured.occlusion.channel = render::Channel::A;
    const render::GpuMaterial b = r.upload(textured);
    EXPECT_EQ(b.variant(), "sphere standard dir2 point1 albedo:tex normal:dx roughness:const metalness:const");
    r.render(b);
}

TEST_F(VariantTest, BadMaterialsAreRejected) {
    render::Scene s;
    s.width = s.height = 8;
    render::Renderer r(context(), s);
    Material m;
    m.albedo.texture = 0;  // no such texture
    EXPECT_THROW(r.upload(m), render::Error);
    Material n;
    n.textures = {texture_of({1, 2, 3}, 1, 1, 3, true)};
    n.roughness.texture = 0;  // an sRGB texture's R channel as data
    EXPECT_THROW(r.upload(n), render::Error);
}

TEST(Device, GpuRequestWithoutGpuNamesTheWayOut) {
    use_lavapipe_only();
    render::ContextOptions o;
    o.device = render::DeviceKind::gpu;
    try {
        render::Context c(o);
        EXPECT_FALSE(c.info().cpu);  // a machine with a GPU: it was found
    } catch (const render::NoDeviceError& e) {
        EXPECT_NE(std::string(e.what()).find("--device cpu"), std::string::npos) << e.what();
    }
}

TEST(Device, ParsesItsOptions) {
    EXPECT_EQ(render::parse_device_kind("gpu"), render::DeviceKind::gpu);
    EXPECT_EQ(render::parse_device_kind("GPU"), std::nullopt);
    EXPECT_EQ(render::parse_brdf("accurate"), render::Brdf::accurate);
}

}  // namespace
}  // namespace mf::test

namespace mf::test {
namespace {

using render::detail::Mesh;

TEST(Geometry, SphereIsThreeJsSphereGeometry128x64) {
    const Mesh m = render::detail::make_sphere(2.f);
    EXPECT_EQ(m.vertices.size(), 129u * 65u);
    EXPECT_EQ(m.indices.size(), 128u * (2u * 64u - 2u) * 3u);  // no degenerate pole triangles
    // The point facing +Z is u = 0.25, v = 0.5; tangent +X there, bitangent (+v) is +Y.
    const auto& v = m.vertices[32 * 129 + 32];
    EXPECT_NEAR(v.position[2], 2.f, 1e-6f);
    EXPECT_NEAR(v.uv[0], 0.25f, 1e-6f);
    EXPECT_NEAR(v.uv[1], 0.5f, 1e-6f);
    EXPECT_NEAR(v.tangent[0], 1.f, 1e-6f);
    // First row is the north pole, v = 1 (top of the image), u offset by half a segment.
    EXPECT_NEAR(m.vertices[0].position[1], 2.f, 1e-6f);
    EXPECT_NEAR(m.vertices[0].uv[1], 1.f, 1e-6f);
    EXPECT_NEAR(m.vertices[0].uv[0], 0.5f / 128, 1e-7f);
}

TEST(Geometry, PlaneThroughOriginAndCubeFacesOutward) {
    for (const auto& v : render::detail::make_plane(2.f).vertices) {
        EXPECT_EQ(v.position[2], 0.f);
        EXPECT_EQ(std::abs(v.position[0]), 1.f);
    }
    const Mesh cube = render::detail::make_cube(1.2f);
    ASSERT_EQ(cube.vertices.size(), 24u);
    for (const auto& v : cube.vertices) {
        const float out = v.position[0] * v.normal[0] + v.position[1] * v.normal[1] + v.position[2] * v.normal[2];
        EXPECT_NEAR(out, 0.6f, 1e-5f);
    }
}

// The shaderball's ring: unit normals pointing away from the tube's centre circle, tangents
// along the ring and perpendicular to the normal, and a bitangent sign that makes cross(n, t) ×
// sign point toward increasing v (the shader's convention), checked against finite differences.
TEST(Geometry, ShaderballRingHasAConsistentTangentFrame) {
    const Mesh ring = render::detail::make_torus(0.7f, 0.16f, 64, 16);
    ASSERT_EQ(ring.vertices.size(), 65u * 17u);
    for (uint32_t j = 0; j < 16; ++j)
        for (uint32_t i = 0; i < 64; ++i) {
            const auto& v = ring.vertices[j * 65 + i];
            const auto& next_v = ring.vertices[(j + 1) * 65 + i];  // one step along +v
            float n2 = 0, tn = 0;
            for (int k = 0; k < 3; ++k) n2 += v.normal[k] * v.normal[k], tn += v.normal[k] * v.tangent[k];
            EXPECT_NEAR(n2, 1.f, 1e-5f);
            EXPECT_NEAR(tn, 0.f, 1e-5f);
            // The point lies at distance `minor` from the centre circle, along its normal.
            const float cx = v.position[0] - 0.16f * v.normal[0], cz = v.position[2] - 0.16f * v.normal[2];
            EXPECT_NEAR(std::sqrt(cx * cx + cz * cz), 0.7f, 1e-5f);
            const float b[3] = {v.normal[1] * v.tangent[2] - v.normal[2] * v.tangent[1],
                                v.normal[2] * v.tangent[0] - v.normal[0] * v.tangent[2],
                                v.normal[0] * v.tangent[1] - v.normal[1] * v.tangent[0]};
            float toward_v = 0;
            for (int k = 0; k < 3; ++k) toward_v += b[k] * v.tangent[3] * (next_v.position[k] - v.position[k]);
            EXPECT_GT(toward_v, 0.f) << "vertex " << i << "," << j;
        }
    const Mesh ball = render::detail::make_shaderball(1.f);
    EXPECT_EQ(ball.vertices.size(), 129u * 65u + 129u * 33u);
    EXPECT_EQ(ball.indices.size() % 3, 0u);
    for (const uint32_t i : ball.indices) ASSERT_LT(i, ball.vertices.size());
}

}  // namespace
}  // namespace mf::test
