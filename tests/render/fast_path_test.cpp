// The look-dev preview's fast paths against the exact ones: textures that go up as read with
// their mips made on the device (Scene::fast_textures), multisampling's fallback, and
// Renderer::prepare on another thread.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <future>
#include <numbers>

#include "reference.hpp"
#include "render/internal.hpp"
#include "render/renderer_impl.hpp"
#include "vulkan_fixture.hpp"

namespace mf::test {
namespace {

using render::Channel;
using render::Material;
using render::Scene;
using render::Texture;
using render::detail::MipKind;
using render::detail::PreparedTexture;

// Pseudo-random codes (xorshift), the same on every run.
std::vector<uint8_t> noise(size_t n, uint32_t seed) {
    std::vector<uint8_t> v(n);
    uint32_t x = seed * 2654435761u + 1u;
    for (uint8_t& b : v) {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        b = static_cast<uint8_t>(x >> 24);
    }
    return v;
}

// A surface with detail at every scale: smooth waves of several periods plus a little noise, so
// that each mip level averages something different.
Material detailed_material(uint32_t size) {
    const double pi = std::numbers::pi;
    std::vector<uint8_t> albedo(size_t{size} * size * 3), orm(size_t{size} * size * 3), normal(size_t{size} * size * 3);
    const std::vector<uint8_t> grain = noise(size_t{size} * size, 7);
    for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x) {
            const size_t p = size_t{y} * size + x;
            const double s = (x + 0.5) / size, t = (y + 0.5) / size, g = grain[p] / 255.0 - 0.5;
            auto wave = [&](double fx, double fy, double phase) {
                return 0.5 + 0.25 * std::sin(2 * pi * fx * s + phase) + 0.2 * std::cos(2 * pi * fy * t + phase) +
                       0.05 * g;
            };
            auto q = [](double v) { return static_cast<uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255)); };
            albedo[3 * p + 0] = q(wave(3, 5, 0.0));
            albedo[3 * p + 1] = q(wave(7, 2, 1.0));
            albedo[3 * p + 2] = q(wave(13, 11, 2.0));
            orm[3 * p + 0] = q(wave(5, 3, 3.0));
            orm[3 * p + 1] = q(0.2 + 0.6 * wave(9, 6, 4.0));
            orm[3 * p + 2] = q(wave(2, 17, 5.0) > 0.5 ? 1.0 : 0.0);
            const double nx = 0.3 * std::sin(2 * pi * 8 * s) + 0.1 * g, ny = 0.3 * std::cos(2 * pi * 6 * t);
            const double len = std::sqrt(nx * nx + ny * ny + 1);
            normal[3 * p + 0] = q(nx / len * 0.5 + 0.5);
            normal[3 * p + 1] = q(ny / len * 0.5 + 0.5);
            normal[3 * p + 2] = q(1 / len * 0.5 + 0.5);
        }
    Material m;
    m.name = "detailed";
    m.textures = {texture_of(albedo, size, size, 3, true), texture_of(orm, size, size, 3, false),
                  texture_of(normal, size, size, 3, false)};
    m.albedo.texture = 0;
    m.occlusion = {1, Channel::R, false, 1.f};
    m.roughness = {1, Channel::G, false, 0.5f};
    m.metalness = {1, Channel::B, false, 0.f};
    m.normal.texture = 2;
    m.uv_scale = {2.f, 1.f};  // a square map twice around, as the look-dev scene places it
    return m;
}

// A sky brighter above than below, smoothly (as the studio's softboxes are soft-edged), so that
// no side of the sphere is black: as in the look-dev scene, a normal that moves near the
// terminator does not flip a pixel between black and lit (which the sRGB curve's steep start
// would magnify to tens of codes), nor moves a sharp reflected edge across pixels.
std::shared_ptr<const render::Environment> sky() {
    static const auto env = [] {
        auto e = std::make_shared<render::Environment>();
        e->width = 32;
        e->height = 16;
        e->rgba.resize(size_t{32} * 16 * 4);
        for (uint32_t y = 0; y < 16; ++y)
            for (uint32_t x = 0; x < 32; ++x) {
                float* p = &e->rgba[(size_t{y} * 32 + x) * 4];
                const float v = 0.25f + 0.55f * (0.5f + 0.5f * std::cos(std::numbers::pi_v<float> *
                                                                        (static_cast<float>(y) + 0.5f) / 16.f));
                p[0] = v;
                p[1] = v;
                p[2] = v * 1.1f;
                p[3] = 1.f;
            }
        return e;
    }();
    return env;
}

// The look-dev scene's kind: a key light, the sky, PBR Neutral tone mapping (render_with).
Scene small_scene(uint32_t size, bool fast) {
    Scene s;
    s.width = s.height = size;
    s.environment = sky();
    s.lights[0].intensity = 2.f;
    s.background = {0.18f, 0.18f, 0.18f};
    s.fast_textures = fast;
    return s;
}

// Code differences of two frames over RGB, over the pixels `use` keeps (all when empty).
struct Diff {
    int max_code = 0, p99 = 0;
    double mean = 0, psnr = 0;
};
Diff diff(const render::Frame& a, const render::Frame& b, const std::vector<bool>& use = {}) {
    Diff d;
    double se = 0, sum = 0;
    std::vector<int> all;
    for (size_t i = 0; i < a.rgba8.size(); ++i) {
        if (i % 4 == 3 || (!use.empty() && !use[i / 4])) continue;
        const int e = std::abs(int(a.rgba8[i]) - int(b.rgba8[i]));
        sum += e;
        se += double(e) * e;
        all.push_back(e);
    }
    std::sort(all.begin(), all.end());
    d.max_code = all.back();
    d.p99 = all[all.size() * 99 / 100];
    d.mean = sum / double(all.size());
    d.psnr = se > 0 ? 10 * std::log10(255.0 * 255.0 * double(all.size()) / se) : 99.0;
    return d;
}

render::Frame render_frame(render::Renderer& renderer, const Material& m) {
    render::OutputOptions out;
    out.tonemap = render::Tonemap::neutral;
    return renderer.render(renderer.upload(m), out);
}

render::Frame render_with(render::Context& context, const Scene& scene, const Material& m) {
    render::Renderer renderer(context, scene);
    return render_frame(renderer, m);
}

// The GPU's 8-bit formats on lavapipe too (precise_cpu_textures off), so that the exact and the
// fast path upload the same formats and differ only in who makes the mips.
class FastTexturesTest : public VulkanTest {
protected:
    void configure(render::ContextOptions& o) override { o.precise_cpu_textures = false; }
    PreparedTexture prepare(const Texture& t, MipKind kind, bool fast) {
        return render::detail::prepare_texture(render::detail::device_of(context()), t, kind, fast);
    }
};

// Level 0 as the fast path expands it (a table of each code's stored value) is byte for byte what
// the CPU chain stores, for every channel count and kind; the chain's length is the same.
TEST_F(FastTexturesTest, LevelZeroIsTheExactPathsLevelZero) {
    const uint32_t w = 37, h = 20;  // odd: rows are not padded anywhere
    for (uint32_t channels = 1; channels <= 4; ++channels)
        for (const MipKind kind : {MipKind::color, MipKind::normal, MipKind::data}) {
            const bool srgb = kind == MipKind::color;
            const Texture t = texture_of(noise(size_t{w} * h * channels, channels), w, h, channels, srgb);
            const PreparedTexture exact = prepare(t, kind, false), fast = prepare(t, kind, true);
            ASSERT_EQ(fast.levels.size(), 1u) << channels;
            EXPECT_EQ(fast.format, exact.format) << channels;
            EXPECT_EQ(fast.mips, static_cast<uint32_t>(exact.levels.size())) << channels;
            EXPECT_EQ(exact.mips, static_cast<uint32_t>(exact.levels.size())) << channels;
            EXPECT_TRUE(fast.levels[0].bytes == exact.levels[0].bytes)
                << channels << " channels, kind " << static_cast<int>(kind);
        }
    // 16-bit and float textures take the exact path whatever is asked.
    Texture t16 = texture_of(std::vector<uint8_t>(32, 7), 4, 4, 1, false);
    t16.type = render::TexelType::u16;
    EXPECT_EQ(prepare(t16, MipKind::data, true).levels.size(), 3u);
}

// Magnified everywhere (a 16×8 texture on a 128² sphere, as TexturedTest), the sampler reads
// level 0 only: the fast path's image is the exact path's, byte for byte.
TEST_F(FastTexturesTest, WhereLevelZeroIsSampledTheImageIsTheSame) {
    Material m = detailed_material(16);
    for (Texture& t : m.textures) {  // 16×8: the detailed surface's top half
        t.height = 8;
        t.data.resize(size_t{16} * 8 * t.channels);
    }
    m.uv_scale = {1.f, 1.f};
    // Where the reference says level 0 is sampled (the rim, minified, excepted; its lighting is
    // not needed, only where the sphere is and the texels' footprint).
    Scene geometry = small_scene(128, false);
    geometry.environment.reset();
    const ReferenceImage ref = render_reference(geometry, m);
    std::vector<bool> use(size_t{128} * 128);
    size_t used = 0;
    for (uint32_t y = 0; y < 128; ++y)
        for (uint32_t x = 0; x < 128; ++x) {
            const ReferencePixel& r = ref.at(x, y);
            used += use[size_t{y} * 128 + x] = r.hit && !r.minified && !ref.silhouette(x, y);
        }
    EXPECT_GT(used, 8000u);
    const Diff d = diff(render_with(context(), small_scene(128, false), m),
                        render_with(context(), small_scene(128, true), m), use);
    EXPECT_EQ(d.max_code, 0);
}

// Minified (a 512² map on a 96² sphere samples levels 2 to 5 over most of it): mips blitted on the
// device against mips averaged on the CPU, the same 8-bit formats (a GPU's). The blit averages
// each level from the one above rounded to 8 bits (the CPU chain from floats, rounded once) and
// does not renormalize normals (the shader normalizes after filtering). Albedo, ORM and normal
// map alone each stay within 5 codes; together, a roughness one code off at a deep level moves
// the key light's peak on a smooth metal by up to 20 codes in a few pixels (measured on lavapipe:
// max 20, 99th percentile 3, mean 0.32, PSNR 49.7 dB).
TEST_F(FastTexturesTest, DeviceMipsAgreeWithCpuMips) {
    const Material m = detailed_material(512);
    const Diff d = diff(render_with(context(), small_scene(96, false), m),
                        render_with(context(), small_scene(96, true), m));
    std::printf("  device vs CPU mips, 8-bit formats: max |Δcode| %d, 99th percentile %d, mean %.3f, PSNR %.1f dB\n",
                d.max_code, d.p99, d.mean, d.psnr);
    EXPECT_LE(d.p99, 4);
    EXPECT_LT(d.mean, 0.4);
    EXPECT_GE(d.psnr, 47.0);
    EXPECT_LE(d.max_code, 24);
}

// Against the exact path lavapipe uses by default (8-bit texels promoted to 16-bit UNORM and
// float, filtered in float): what the fast path changes in total on a CPU device, color in 8-bit
// sRGB and mips blitted (data keeps its 16 bits). Measured: max 2, mean 0.19, PSNR 55.2 dB.
class FastVersusPreciseTest : public VulkanTest {};

TEST_F(FastVersusPreciseTest, FastTexturesStayCloseToThePreciseOnes) {
    const Material m = detailed_material(512);
    const Diff d = diff(render_with(context(), small_scene(96, false), m),
                        render_with(context(), small_scene(96, true), m));
    std::printf("  fast vs precise textures: max |Δcode| %d, 99th percentile %d, mean %.3f, PSNR %.1f dB\n", d.max_code,
                d.p99, d.mean, d.psnr);
    EXPECT_LE(d.max_code, 3);
    EXPECT_LT(d.mean, 0.3);
    EXPECT_GE(d.psnr, 52.0);
}

// The same surface with roughness stored as smoothness (in alpha) and a DirectX normal map: the
// fast path stores those channels complemented, so both layouts upload the same values.
Material inverted_layout(const Material& plain) {
    Material inverted = plain;
    Texture ms = plain.textures[1];  // metalness in R, occlusion in G, smoothness in A
    ms.channels = 4;
    ms.data.assign(size_t{ms.width} * ms.height * 4, 0);
    Texture dx = plain.textures[2];
    for (size_t p = 0; p < size_t{ms.width} * ms.height; ++p) {
        ms.data[4 * p + 0] = plain.textures[1].data[3 * p + 2];
        ms.data[4 * p + 1] = plain.textures[1].data[3 * p + 0];
        ms.data[4 * p + 3] = static_cast<uint8_t>(255 - plain.textures[1].data[3 * p + 1]);
        dx.data[3 * p + 1] = static_cast<uint8_t>(255 - dx.data[3 * p + 1]);
    }
    inverted.textures[1] = ms;
    inverted.textures[2] = dx;
    inverted.roughness = {1, Channel::A, true, 0.5f};
    inverted.metalness = {1, Channel::R, false, 0.f};
    inverted.occlusion = {1, Channel::G, false, 1.f};
    inverted.normal.green_down = true;
    return inverted;
}

// 8-bit formats: the complemented channels are the plain layout's values exactly and each channel
// is filtered alone, so the images are the same bytes; the variant reads them plainly.
TEST_F(FastTexturesTest, InvertedChannelsAreStoredPlainAndGiveTheSameImage) {
    const Material plain = detailed_material(256), inverted = inverted_layout(plain);
    render::Renderer renderer(context(), small_scene(96, true));
    const render::GpuMaterial gm = renderer.upload(inverted);
    EXPECT_NE(gm.variant().find("normal:gl"), std::string::npos) << gm.variant();
    EXPECT_EQ(diff(render_frame(renderer, plain), render_frame(renderer, inverted)).max_code, 0);
    render::Renderer exact(context(), small_scene(96, false));
    EXPECT_NE(exact.upload(inverted).variant().find("normal:dx"), std::string::npos);
    // A channel another role reads plainly is not complemented (the shader inverts it for the
    // one role): the image is the exact path's but for the mips (a complemented channel read
    // plainly, or an inverted one read twice, would be tens of codes off on average).
    Material shared = inverted;
    shared.metalness = {1, Channel::A, false, 0.f};
    const Diff d = diff(render_frame(renderer, shared), render_frame(exact, shared));
    EXPECT_LT(d.mean, 0.5);
    EXPECT_LE(d.p99, 4);
}

// lavapipe's promoted 16-bit data: the same, within a code (PreviewCli.EveryPresetPreviews... holds
// whole ingests to that).
TEST_F(FastVersusPreciseTest, InvertedChannelsGiveTheSameImage) {
    const Material plain = detailed_material(256);
    const Scene s = small_scene(96, true);
    EXPECT_LE(diff(render_with(context(), s, plain), render_with(context(), s, inverted_layout(plain))).max_code, 1);
}

// The fast path's blits and their barriers under the validation layer (the fixture fails on any
// message), with sizes that are not powers of two (the chain still ends at 1×1).
TEST_F(FastTexturesTest, OddSizesMakeFullChains) {
    const Texture t = texture_of(noise(size_t{300} * 7 * 4, 3), 300, 7, 4, true);
    const PreparedTexture p = prepare(t, MipKind::color, true);
    EXPECT_EQ(p.mips, 9u);  // 300, 150, 75, 37, 18, 9, 4, 2, 1
    Material m;
    m.name = "odd";
    m.textures = {t};
    m.albedo.texture = 0;
    const render::Frame f = render_with(context(), small_scene(32, true), m);
    EXPECT_EQ(f.width, 32u);
}

// Multisampling at a count the device lacks (lavapipe: 1 and 4) falls back to supersampling with
// at least as many samples, and says so; the image is then the supersampled one.
using MsaaTest = VulkanTest;

TEST_F(MsaaTest, UnsupportedCountFallsBackToSupersampling) {
    Scene s = small_scene(48, false);
    s.msaa = 8;
    render::Renderer renderer(context(), s);
    const auto notes = renderer.take_notes();
    if (notes.empty()) GTEST_SKIP() << "this device multisamples RGBA32F at 8 samples";
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_NE(notes[0].find("3x3 supersampling"), std::string::npos) << notes[0];
    EXPECT_EQ(renderer.scene().supersample, 3u);
    EXPECT_EQ(renderer.scene().msaa, 1u);
    Material m;
    m.name = "grey";
    Scene ss = small_scene(48, false);
    ss.supersample = 3;
    EXPECT_EQ(diff(render_frame(renderer, m), render_with(context(), ss, m)).max_code, 0);
    Scene bad = s;
    bad.msaa = 3;
    EXPECT_THROW(render::Renderer(context(), bad), render::Error);
}

// Multisampled, the shaderball (mesh-shaded, with a depth buffer of as many samples) and the
// ground render under the validation layer (the fixture fails on any message), and not as one
// sample a pixel renders them.
TEST_F(MsaaTest, DepthAndGroundMultisampleToo) {
    Scene s = small_scene(64, false);
    s.shape.type = render::ShapeType::shaderball;
    s.ground.enabled = true;
    s.msaa = 4;
    Material m;
    m.name = "grey";
    const render::Frame f = render_with(context(), s, m);
    EXPECT_EQ(f.width, 64u);
    Scene one = s;
    one.msaa = 1;
    EXPECT_GT(diff(f, render_with(context(), one, m)).max_code, 0);
}

// Renderer::prepare on other threads while the renderer uploads and renders: the same images as
// preparing in turn (and nothing for the validation layer to report). A material is prepared for
// a device and a scene, not for a renderer: render::prepare before any renderer exists, or
// another renderer of that scene, gives the same image; a renderer of another scene (textures
// read otherwise, another light) or of another device refuses it.
TEST_F(FastTexturesTest, PrepareRunsOnOtherThreads) {
    const Material m = detailed_material(128);
    render::Renderer renderer(context(), small_scene(48, true));
    const render::Frame expected = renderer.render(renderer.upload(m));
    std::vector<std::future<render::PreparedMaterial>> prepared;
    for (int i = 0; i < 3; ++i) prepared.push_back(std::async(std::launch::async, [&] { return renderer.prepare(m); }));
    for (auto& p : prepared) {
        const render::Frame f = renderer.render(renderer.upload(p.get()));
        EXPECT_EQ(diff(f, expected).max_code, 0);
    }
    render::Renderer other(context(), small_scene(48, true));
    EXPECT_EQ(diff(other.render(other.upload(renderer.prepare(m))), expected).max_code, 0);
    EXPECT_EQ(
        diff(renderer.render(renderer.upload(render::prepare(context(), small_scene(48, true), m))), expected).max_code,
        0);
    render::Renderer precise(context(), small_scene(48, false));
    EXPECT_THROW(precise.upload(renderer.prepare(m)), render::Error);
    Scene two_lights = small_scene(48, true);
    two_lights.lights.push_back(two_lights.lights[0]);
    render::Renderer lit(context(), two_lights);
    EXPECT_THROW(lit.upload(renderer.prepare(m)), render::Error);
    render::Context another;
    render::Renderer elsewhere(another, small_scene(48, true));
    EXPECT_THROW(elsewhere.upload(renderer.prepare(m)), render::Error);
}

// Renderer::warm on other threads while the renderer uploads and renders the same variant: the
// variant is made once, by whichever thread comes first, and draws the image a renderer that
// made it in upload() draws (nothing for the validation layer to report); materials of one
// variant share a key, those of another (no normal map) do not.
TEST_F(FastTexturesTest, VariantsWarmOnOtherThreads) {
    const Material m = detailed_material(128);
    render::Renderer renderer(context(), small_scene(48, true));
    const render::PreparedMaterial p = renderer.prepare(m);
    std::vector<std::future<void>> warming;
    for (int i = 0; i < 3; ++i) warming.push_back(std::async(std::launch::async, [&] { renderer.warm(p); }));
    const render::Frame f = renderer.render(renderer.upload(renderer.prepare(m)));
    for (auto& w : warming) w.get();
    render::Renderer cold(context(), small_scene(48, true));
    EXPECT_EQ(diff(f, cold.render(cold.upload(m))).max_code, 0);
    Material flat = m;
    flat.normal.texture = -1;
    EXPECT_EQ(p.variant_key(), renderer.prepare(m).variant_key());
    EXPECT_NE(p.variant_key(), renderer.prepare(flat).variant_key());
    EXPECT_NE(renderer.render(renderer.upload(renderer.prepare(flat))).rgba8, f.rgba8);
}

// Staging memory is kept from one upload for the next (Renderer::Impl::take_staging): materials
// of other sizes and contents, in any order, render as with a renderer of their own, and each
// may be freed on another thread once drawn (render.hpp's GpuMaterial contract).
TEST_F(FastTexturesTest, StagingIsReusedAcrossMaterialsAndMaterialsFreeElsewhere) {
    std::vector<Material> ms{detailed_material(128), detailed_material(64), detailed_material(256),
                             detailed_material(128)};
    for (uint8_t& v : ms[1].textures[0].data) v = static_cast<uint8_t>(255 - v);  // another albedo
    const Scene s = small_scene(48, true);
    std::vector<render::Frame> alone;
    for (const Material& m : ms) {
        render::Renderer r(context(), s);
        alone.push_back(r.render(r.upload(m)));
    }
    EXPECT_GT(diff(alone[0], alone[1]).max_code, 40);  // what a stale or misplaced staging copy would show
    render::Renderer shared(context(), s);
    std::future<void> freeing;
    for (size_t i = 0; i < ms.size(); ++i) {
        render::GpuMaterial g = shared.upload(ms[i]);
        EXPECT_EQ(diff(shared.render(g), alone[i]).max_code, 0) << "material " << i;
        if (freeing.valid()) freeing.get();
        freeing = std::async(std::launch::async,
                             [g = std::move(g)]() mutable { render::GpuMaterial done = std::move(g); });
    }
    freeing.get();
}

// A material's textures share one device allocation (BlockPool): each image bound at its own
// aligned offset (the validation layer checks the binding), drawn as with images of their own;
// once the material is freed (on another thread), the next material that fits gets its block,
// and one twice as large gets a new one.
TEST_F(FastTexturesTest, AMaterialsTexturesShareOneBlockTheNextReuses) {
    const Scene s = small_scene(48, true);
    const Material a = detailed_material(128), large = detailed_material(256);
    Material b = a;
    for (uint8_t& v : b.textures[0].data) v = static_cast<uint8_t>(255 - v);
    std::vector<render::Frame> alone;
    for (const Material* m : {&a, static_cast<const Material*>(&b), &large}) {
        render::Renderer r(context(), s);
        alone.push_back(r.render(r.upload(*m)));
    }
    render::Renderer shared(context(), s);
    VkDeviceMemory first = VK_NULL_HANDLE;
    {
        render::GpuMaterial g = shared.upload(a);
        const render::GpuMaterial::Impl& m = g.impl();
        ASSERT_TRUE(m.block.memory);
        first = m.block.memory.get();
        size_t bound = 0;
        for (const render::detail::Image& img : m.textures)
            if (img.image) {
                EXPECT_FALSE(img.memory) << "an image with memory of its own";
                ++bound;
            }
        EXPECT_EQ(bound, 3u);
        EXPECT_EQ(diff(shared.render(g), alone[0]).max_code, 0);
        std::async(std::launch::async, [g = std::move(g)]() mutable { render::GpuMaterial done = std::move(g); }).get();
    }
    // Freed undrawn, its copies still in flight (upload() does not wait for them): its images
    // go only once the copies are done (the validation layer reports an image destroyed in use).
    std::async(std::launch::async, [g = shared.upload(large)]() mutable {
        render::GpuMaterial done = std::move(g);
    }).get();
    render::GpuMaterial again = shared.upload(b);
    EXPECT_EQ(again.impl().block.memory.get(), first) << "the freed material's block was not reused";
    EXPECT_EQ(diff(shared.render(again), alone[1]).max_code, 0);
    const render::GpuMaterial bigger = shared.upload(large);
    EXPECT_NE(bigger.impl().block.memory.get(), first);
    EXPECT_GT(bigger.impl().block.size, again.impl().block.size);
    EXPECT_EQ(diff(shared.render(bigger), alone[2]).max_code, 0);
}

}  // namespace
}  // namespace mf::test
