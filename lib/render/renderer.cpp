// The preview renderer: construction order, scene and material checks, accessors. One shading
// pass into a linear fp32 target, one encoding pass, readback (see renderer_impl.hpp for which
// file does what).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <future>
#include <memory>
#include <vector>

#include <utility>

#include "base/limits.hpp"
#include "base/parallel.hpp"
#include "base/stopwatch.hpp"
#include "render/internal.hpp"
#include "render/renderer_impl.hpp"

namespace mf::render {

using namespace detail;

std::optional<Brdf> parse_brdf(std::string_view s) {
    if (s == "standard") return Brdf::standard;
    if (s == "accurate") return Brdf::accurate;
    if (s == "assignment") return Brdf::unnormalized_diffuse;
    return std::nullopt;
}

static_assert(static_cast<int>(AlphaMode::blend) == gpu::kAlphaBlend &&
                  static_cast<int>(AlphaMode::mask) == gpu::kAlphaMask &&
                  static_cast<int>(AlphaMode::opaque) == gpu::kAlphaOpaque,
              "ShadeSpecialization::alpha_mode carries render::AlphaMode as it is");

static_assert(static_cast<int>(Tonemap::none) == gpu::kTonemapNone &&
                  static_cast<int>(Tonemap::neutral) == gpu::kTonemapNeutral &&
                  static_cast<int>(Tonemap::aces) == gpu::kTonemapAces,
              "EncodeParams::tonemap carries render::Tonemap as it is");

std::optional<Shading> parse_shading(std::string_view s) {
    if (s == "auto") return Shading::automatic;
    if (s == "raster") return Shading::raster;
    if (s == "compute") return Shading::compute;
    return std::nullopt;
}

std::optional<Tonemap> parse_tonemap(std::string_view s) {
    if (s == "none") return Tonemap::none;
    if (s == "neutral") return Tonemap::neutral;
    if (s == "aces") return Tonemap::aces;
    return std::nullopt;
}

int32_t detail::brdf_model_id(Brdf b) {
    switch (b) {
        case Brdf::standard: return gpu::kBrdfStandard;
        case Brdf::accurate: return gpu::kBrdfAccurate;
        case Brdf::unnormalized_diffuse: return gpu::kBrdfUnnormalizedDiffuse;
    }
    throw Error("unknown BRDF model");
}

void check_material(const Material& m) {
    const auto n = static_cast<int>(m.textures.size());
    if (m.textures.size() > kMaxTextures)
        throw Error("material '" + m.name + "' has more than " + std::to_string(kMaxTextures) + " textures");
    auto check_index = [&](int t, const char* role) {
        if (t >= n)
            throw Error("material '" + m.name + "': " + role + " names texture " + std::to_string(t) + " of " +
                        std::to_string(n));
    };
    check_index(m.albedo.texture, "albedo");
    check_index(m.emissive.texture, "emissive");
    check_index(m.normal.texture, "normal");
    const std::pair<const ScalarRole*, const char*> scalars[] = {{&m.roughness, "roughness"},
                                                                 {&m.metalness, "metalness"},
                                                                 {&m.occlusion, "occlusion"},
                                                                 {&m.opacity, "opacity"}};
    for (auto [r, name] : scalars) {
        check_index(r->texture, name);
        // RGB of an sRGB texture are decoded by the sampler: only its alpha holds plain data.
        if (r->texture >= 0 && m.textures[static_cast<size_t>(r->texture)].srgb && r->channel != Channel::A)
            throw Error("material '" + m.name + "': " + name + " is read from a color channel of an sRGB texture");
    }
    if (m.normal.texture >= 0 && m.textures[static_cast<size_t>(m.normal.texture)].srgb)
        throw Error("material '" + m.name + "': the normal map is marked sRGB");
    if (!(m.alpha_cutoff >= 0.f && m.alpha_cutoff <= 1.f))
        throw Error("material '" + m.name + "': alpha_cutoff must be within [0, 1]");
    for (const float v : {m.uv_scale[0], m.uv_scale[1], m.uv_offset[0], m.uv_offset[1]})
        if (!std::isfinite(v)) throw Error("material '" + m.name + "': uv_scale and uv_offset must be finite");
    if (!(m.uv_scale[0] > 0.f && m.uv_scale[1] > 0.f))
        throw Error("material '" + m.name + "': uv_scale must be positive (a mirrored texture would flip its normals)");
}

// ---------------------------------------------------------------------------------------------

GpuMaterial::GpuMaterial() = default;
GpuMaterial::~GpuMaterial() = default;
GpuMaterial::GpuMaterial(GpuMaterial&&) noexcept = default;
GpuMaterial& GpuMaterial::operator=(GpuMaterial&&) noexcept = default;
const std::string& GpuMaterial::name() const { return impl_->name; }
const std::string& GpuMaterial::variant() const { return impl_->variant; }

Renderer::Impl::Impl(Context& context, Scene s) : d(device_of(context)), scene(std::move(s)) {
    if (scene.width == 0 || scene.height == 0 || scene.width > kMaxImageSide || scene.height > kMaxImageSide)
        throw Error("image size must be 1.." + std::to_string(kMaxImageSide) + " pixels a side");
    if (scene.lights.size() > kMaxLights) throw Error("at most " + std::to_string(kMaxLights) + " lights");
    if (scene.supersample < 1 || scene.supersample > 4) throw Error("supersample must be 1..4 samples a side");
    if (scene.msaa != 1 && scene.msaa != 2 && scene.msaa != 4 && scene.msaa != 8)
        throw Error("msaa must be 1, 2, 4 or 8 samples a pixel");
    if (scene.ground.enabled &&
        !(scene.ground.albedo >= 0.f && scene.ground.albedo <= 1.f && scene.ground.roughness >= 0.f &&
          scene.ground.roughness <= 1.f && scene.ground.light_deg > 0.f && scene.ground.light_deg <= 45.f))
        throw Error(
            "ground: albedo and roughness must be within [0, 1], the key light's radius within (0, 45] degrees");
    if (!d.supports(kTargetFormat, VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT | VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT))
        throw NoDeviceError(d.info.name + " cannot render to RGBA32F");
    if (uses_depth() && !d.supports(kDepthFormat, VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT))
        throw NoDeviceError(d.info.name + " has no 32-bit float depth buffer");

    blocks = std::make_shared<BlockPool>(d);
    auto pi = vk_struct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
    pi.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
    pi.queueFamilyIndex = d.queue_family;
    VkCommandPool pool_handle = VK_NULL_HANDLE;
    VK_CHECK(d.fn.vkCreateCommandPool(d.device, &pi, nullptr, &pool_handle));
    command_pool = Unique<VkCommandPool>(d, pool_handle);

    if (d.info.timestamps) {
        auto qi = vk_struct<VkQueryPoolCreateInfo>(VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO);
        qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
        qi.queryCount = kQueryCount;
        VkQueryPool q = VK_NULL_HANDLE;
        VK_CHECK(d.fn.vkCreateQueryPool(d.device, &qi, nullptr, &q));
        queries = Unique<VkQueryPool>(d, q);
        VK_CHECK(d.fn.vkCreateQueryPool(d.device, &qi, nullptr, &q));
        upload_queries = Unique<VkQueryPool>(d, q);
    }

    const Stopwatch made;
    // The shading path is chosen (by measurement, the first renderer of a device; the others
    // wait for it) on another thread while this one makes what does not depend on it.
    std::vector<std::string> shading_notes;
    std::future<void> choosing = std::async(std::launch::async, [&] { choose_shading(context, shading_notes); });
    create_samplers();
    create_layouts();  // pipelines.cpp
    const double load_from = made.elapsed();
    upload_mesh();        // upload.cpp
    create_dummies();     // upload.cpp
    build_environment();  // ibl.cpp: BRDF table and environment maps, only when called for
    const double load_to = made.elapsed();
    choosing.get();
    const double shading_s = made.elapsed() - load_to;
    const double load_s = load_to - load_from;
    notes.insert(notes.begin(), shading_notes.begin(), shading_notes.end());
    choose_samples();
    create_targets();           // draw.cpp
    write_frame_descriptors();  // frame.cpp
    // HostTimes count upload() and render() only: the load-time uploads above (placeholders, the
    // environment) went through upload_texture too.
    host_times = {};
    host_times.made = made.elapsed();
    host_times.made_shading = shading_s;
    host_times.made_load = load_s;
}

Renderer::Impl::~Impl() {
    if (d.device) {
        const std::lock_guard<std::mutex> lock(d.queue_mutex);
        d.fn.vkDeviceWaitIdle(d.device);
    }
}

namespace {

// Compute shading is chosen when its shade pass is at least this much faster than raster's: a
// margin for the measurement's noise, favouring the path that covers every scene.
constexpr double kComputeMargin = 1.5;
constexpr uint32_t kMeasureSize = 512;  // the measured frame: a constant sphere, this many pixels a side

constexpr int kWarmupFrames = 2, kTimedFrames = 5;

std::string fixed(double v, int digits) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.*f", digits, v);
    return buf;
}

}  // namespace

ShadingTimes measure_shading(Context& context, uint32_t msaa, uint32_t supersample) {
    Scene s;
    s.width = s.height = kMeasureSize;
    s.msaa = msaa;
    s.supersample = supersample;
    // The two renderers made at once, each compiling its own pipelines.
    std::array<std::unique_ptr<Renderer>, 2> renderers;
    std::array<GpuMaterial, 2> materials;
    parallel_for_rethrow(2, 2, [&](size_t i) {
        Scene path = s;
        path.shading = i == 0 ? Shading::raster : Shading::compute;
        renderers[i] = std::make_unique<Renderer>(context, path);
        materials[i] = renderers[i]->upload(Material{});
    });
    std::array<double, 2> best{0.0, 0.0};
    for (int frame = 0; frame < kWarmupFrames + kTimedFrames; ++frame)
        for (size_t i = 0; i < 2; ++i) {
            renderers[i]->render(materials[i]);
            for (const PassTime& t : renderers[i]->frame_times())
                if (t.name == "shade" && frame >= kWarmupFrames && (best[i] == 0.0 || t.ms < best[i])) best[i] = t.ms;
        }
    return {best[0], best[1]};
}

void Renderer::Impl::choose_shading(Context& context, std::vector<std::string>& said) {
    if (scene.shading == Shading::raster) return;
    if (!compute_covers()) {
        // The shaderball is a mesh and the ground's shadow is drawn with depth: raster alone.
        if (scene.shading == Shading::compute)
            said.push_back(std::string("compute shading covers the sphere, cube and plane, not ") +
                           (scene.ground.enabled ? "the ground plane" : "the shaderball") +
                           ": shaded on the raster path");
        return;
    }
    if (scene.shading == Shading::compute) {
        compute = true;
        return;
    }
    if (d.info.cpu) return;  // raster, unmeasured: see Shading::automatic
    Device::ShadingChoice& c = d.shading_choice;
    const std::lock_guard<std::mutex> lock(c.mutex);  // measure_shading's renderers name their path: no re-entry
    if (!c.measured) {
        if (!d.info.timestamps) {
            c.measured = true;
            said.push_back("shading auto: raster (" + d.info.name + " has no timestamp queries to measure with)");
            return;
        }
        // With this scene's anti-aliasing: multisampling costs the two paths differently (compute
        // shades every sample). A failure throws: measured again by the next renderer.
        const ShadingTimes ms = measure_shading(context, scene.msaa, scene.supersample);
        c.measured = true;
        c.raster_ms = ms.raster_ms;
        c.compute_ms = ms.compute_ms;
        c.compute = c.compute_ms > 0.0 && c.raster_ms >= kComputeMargin * c.compute_ms;
        said.push_back("shading auto: " + std::string(c.compute ? "compute" : "raster") + " on " + d.info.name +
                       " (shade pass of a " + std::to_string(kMeasureSize) + "x" + std::to_string(kMeasureSize) +
                       " constant sphere, msaa " + std::to_string(scene.msaa) + ", supersample " +
                       std::to_string(scene.supersample) + ": raster " + fixed(c.raster_ms, 3) + " ms, compute " +
                       fixed(c.compute_ms, 3) + " ms; compute when at least " + fixed(kComputeMargin, 1) + "x faster)");
    }
    compute = c.compute;
}

void Renderer::Impl::choose_samples() {
    if (scene.msaa <= 1 || compute) return;  // compute: shaded at the sample positions (shade.comp)
    const auto want = static_cast<VkSampleCountFlagBits>(scene.msaa);
    const VkPhysicalDeviceLimits& l = d.properties.limits;
    bool ok = (l.framebufferColorSampleCounts & want) &&
              (d.sample_counts(kTargetFormat,
                               VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT) &
               want);
    if (uses_depth())
        ok = ok && (l.framebufferDepthSampleCounts & want) &&
             (d.sample_counts(kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT) & want);
    if (ok) {
        samples = want;
        return;
    }
    // As many samples a pixel by supersampling (N×N ≥ msaa), N² times the shading.
    uint32_t n = 1;
    while (n * n < scene.msaa) ++n;
    scene.supersample = std::max(scene.supersample, n);
    notes.push_back(d.info.name + " cannot multisample the frame (RGBA32F" + (uses_depth() ? ", 32-bit depth" : "") +
                    ") at " + std::to_string(scene.msaa) + " samples: " + std::to_string(scene.supersample) + "x" +
                    std::to_string(scene.supersample) + " supersampling instead");
    scene.msaa = 1;
}

Unique<VkSampler> Renderer::Impl::make_sampler(VkSamplerAddressMode mode, bool anisotropic) const {
    auto si = vk_struct<VkSamplerCreateInfo>(VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO);
    si.magFilter = VK_FILTER_LINEAR;
    si.minFilter = VK_FILTER_LINEAR;
    si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
    si.addressModeU = si.addressModeV = si.addressModeW = mode;
    si.maxLod = VK_LOD_CLAMP_NONE;
    if (anisotropic && d.anisotropy > 1.f) {
        si.anisotropyEnable = VK_TRUE;
        si.maxAnisotropy = std::min(16.f, d.anisotropy);
    }
    VkSampler h = VK_NULL_HANDLE;
    VK_CHECK(d.fn.vkCreateSampler(d.device, &si, nullptr, &h));
    return Unique<VkSampler>(d, h);
}

void Renderer::Impl::create_samplers() {
    // Materials repeat (the sphere's u wraps at its seam); tables and cube maps clamp.
    sampler_repeat = make_sampler(VK_SAMPLER_ADDRESS_MODE_REPEAT, true);
    sampler_clamp = make_sampler(VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, false);
}

// ---------------------------------------------------------------------------------------------

const Renderer::Impl& renderer_impl(const Renderer& renderer) { return *renderer.impl_; }

Renderer::Renderer(Context& context, const Scene& scene) : impl_(std::make_unique<Impl>(context, scene)) {}
Renderer::~Renderer() = default;
const Scene& Renderer::scene() const { return impl_->scene; }
Shading Renderer::shading() const { return impl_->compute ? Shading::compute : Shading::raster; }
const std::vector<PassTime>& Renderer::load_times() const {
    impl_->retire_upload();  // a submitted upload's time comes with its completion
    return impl_->load_times;
}
const std::vector<PassTime>& Renderer::frame_times() const { return impl_->frame_times; }
const Renderer::HostTimes& Renderer::host_times() const { return impl_->host_times; }
std::vector<std::string> Renderer::take_notes() { return std::exchange(impl_->notes, {}); }

}  // namespace mf::render
