// Load-time passes: the split-sum BRDF table and, with an environment, its prefiltered maps.
// Only what the scene calls for is computed. All of it is recorded into one submission:
//
//   brdf_lut        the table (A, B, 1 − E, 1 − E_avg) over (√(n·v), roughness)   accurate BRDF or env
//   env_upload      the equirectangular image to the device                  env
//   env_cube        equirect → cube mip 0, then each mip from the one above  env
//   env_prefilter   GGX-prefiltered cube, one roughness per mip             env
//   env_irradiance  E(n)/π cube                                              env
//
// The three cube stages are rows of one table (kCubeStages) run by one loop.
#include <algorithm>
#include <cstring>
#include <deque>
#include <utility>

#include "render/renderer_impl.hpp"

namespace mf::render {

using namespace detail;

namespace {

constexpr uint32_t kBrdfLutComp[] =
#include "shaders/brdf_lut.comp.inc"
    ;
constexpr uint32_t kBrdfLutF16Comp[] =
#include "shaders/brdf_lut_f16.comp.inc"
    ;
constexpr uint32_t kEnvToCubeComp[] =
#include "shaders/env_to_cube.comp.inc"
    ;
constexpr uint32_t kCubeDownsampleComp[] =
#include "shaders/cube_downsample.comp.inc"
    ;
constexpr uint32_t kPrefilterComp[] =
#include "shaders/prefilter.comp.inc"
    ;
constexpr uint32_t kIrradianceComp[] =
#include "shaders/irradiance.comp.inc"
    ;

constexpr uint32_t kLutSize = gpu::kBrdfLutSize;  // one workgroup a row (brdf_lut.glsl)
constexpr uint32_t kLutSamples = 1024;
constexpr uint32_t kSpecularFace = 128;  // prefiltered cube: mip m holds roughness m / (levels − 1)
constexpr uint32_t kSpecularLevels = 6;
constexpr uint32_t kIrradianceFace = 32;  // E(n)/π varies slowly
constexpr uint32_t kPrefilterSamples = 256;
constexpr uint32_t kIrradianceSamples = 512;

constexpr VkSpecializationMapEntry kLutEntries[] = {
    spec_entry(gpu::kSpecLutCorrelated, offsetof(gpu::LutSpecialization, correlated)),
    spec_entry(gpu::kSpecLutSamples, offsetof(gpu::LutSpecialization, samples)),
};
static_assert(spec_entries_distinct(kLutEntries));

constexpr auto kCompute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
// The maps are read by the shading pass: shade.frag, or shade.comp on the compute path.
constexpr auto kFragment = VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
constexpr auto kWrite = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
constexpr auto kSampled = VK_ACCESS_2_SHADER_SAMPLED_READ_BIT;

uint32_t mip_count(uint32_t size) {
    uint32_t n = 1;
    while (size > 1) {
        size /= 2;
        ++n;
    }
    return n;
}

// ---- what the recorded commands use: alive until the submission has completed

struct Recording {
    Recording(Renderer::Impl& renderer, Lighting& made)
        : r(renderer), out(made), s(renderer.d, renderer.command_pool, renderer.queries, kQueryCount) {}
    Renderer::Impl& r;
    Lighting& out;  // what the recorded passes make
    Submission s;
    std::deque<Image> images;  // temporaries (the equirectangular image, the source cube)
    std::vector<Buffer> staging;
    std::vector<Unique<VkSampler>> samplers;
    std::vector<Unique<VkImageView>> views;
    std::vector<Unique<VkDescriptorSetLayout>> set_layouts;
    std::vector<Unique<VkPipelineLayout>> pipeline_layouts;
    std::vector<Unique<VkPipeline>> pipelines;
};

// ---- the cube stages, one table

enum class Shader { EnvToCube, Downsample, Prefilter, Irradiance };
enum class Source {
    Equirect,  // the uploaded environment (longitude wraps, latitude clamps)
    MipAbove,  // the target's previous mip, made readable just before
    Cube,      // the finished source cube, all mips
};
enum class Target { Cube, Specular, Irradiance };

// Dispatches into mips [first_mip, first_mip + mips) of the stage's target, all six faces at
// once; mips = 0: to the target's last mip.
struct CubeStep {
    Shader shader;
    Source source;
    uint32_t first_mip, mips;
    uint32_t samples;        // IblParams::samples
    bool roughness_per_mip;  // IblParams::roughness = m / (mips − 1), else 0
};
// One timed pass: its steps write `target`, which `consumer` then samples.
struct CubeStage {
    const char* name;
    Target target;
    VkPipelineStageFlags2 consumer;
    std::vector<CubeStep> steps;
};

const CubeStage kCubeStages[] = {
    {"env_cube",
     Target::Cube,
     kCompute,
     {{Shader::EnvToCube, Source::Equirect, 0, 1, 0, false},
      {Shader::Downsample, Source::MipAbove, 1, 0, 0, false}}},  // 2×2 box per mip: radiance is linear
    {"env_prefilter", Target::Specular, kFragment, {{Shader::Prefilter, Source::Cube, 0, 0, kPrefilterSamples, true}}},
    {"env_irradiance",
     Target::Irradiance,
     kFragment,
     {{Shader::Irradiance, Source::Cube, 0, 0, kIrradianceSamples, false}}},
};

// What the stages read and write.
struct CubeResources {
    VkPipeline pipelines[4];  // by Shader
    VkDescriptorSetLayout set_layout;
    VkPipelineLayout layout;
    VkSampler equirect_sampler;
    VkImageView equirect;
    uint32_t face;            // the source cube's face size (IblParams::src_size)
    const Image* targets[3];  // by Target
};

// One dispatch over the six faces of one mip: `src` sampled, mip `mip` of `dst` a storage view.
void dispatch(Recording& rec, const CubeResources& res, VkPipeline pipeline, VkSampler sampler, VkImageView src,
              const Image& dst, uint32_t mip, const gpu::IblParams& params) {
    const Device& d = rec.r.d;
    VkCommandBuffer cmd = rec.s.cmd();
    rec.views.push_back(create_view(d, dst, VK_IMAGE_VIEW_TYPE_2D_ARRAY, mip, 1, 0, 6));
    VkDescriptorSet ds = rec.r.allocate_set(rec.r.descriptor_pool, res.set_layout);
    VkDescriptorImageInfo in{sampler, src, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkDescriptorImageInfo out{VK_NULL_HANDLE, rec.views.back(), VK_IMAGE_LAYOUT_GENERAL};
    VkWriteDescriptorSet writes[2] = {vk_struct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET),
                                      vk_struct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET)};
    writes[0].dstSet = writes[1].dstSet = ds;
    writes[0].dstBinding = static_cast<uint32_t>(gpu::kBindingIblSource);
    writes[0].descriptorCount = 1;
    writes[0].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    writes[0].pImageInfo = &in;
    writes[1].dstBinding = static_cast<uint32_t>(gpu::kBindingIblTarget);
    writes[1].descriptorCount = 1;
    writes[1].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    writes[1].pImageInfo = &out;
    d.fn.vkUpdateDescriptorSets(d.device, 2, writes, 0, nullptr);
    d.fn.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    d.fn.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, res.layout, 0, 1, &ds, 0, nullptr);
    d.fn.vkCmdPushConstants(cmd, res.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof params, &params);
    d.fn.vkCmdDispatch(cmd, tile_groups(params.size), tile_groups(params.size), 6);
}

// One row of kCubeStages: the target goes from undefined to written, each mip made readable
// for the next step that reads it or, at the end, for the stage's consumer.
void record_cube_stage(Recording& rec, const CubeResources& res, const CubeStage& stage) {
    const Device& d = rec.r.d;
    VkCommandBuffer cmd = rec.s.cmd();
    const Image& dst = *res.targets[static_cast<int>(stage.target)];
    const uint32_t mips = dst.desc.mips;
    rec.s.begin_pass(stage.name);
    image_barrier(d, cmd, dst.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_NONE, 0,
                  kCompute, kWrite);
    uint32_t unread = 0;  // mips below this one are already readable
    for (const CubeStep& step : stage.steps) {
        const uint32_t end = step.mips ? step.first_mip + step.mips : mips;
        for (uint32_t m = step.first_mip; m < end; ++m) {
            VkSampler sampler = rec.r.sampler_clamp;
            VkImageView src = VK_NULL_HANDLE;
            switch (step.source) {
                case Source::Equirect:
                    sampler = res.equirect_sampler;
                    src = res.equirect;
                    break;
                case Source::MipAbove:
                    image_barrier(d, cmd, dst.image, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                                  kCompute, kWrite, kCompute, kSampled, m - 1, 1);
                    unread = m;
                    rec.views.push_back(create_view(d, dst, VK_IMAGE_VIEW_TYPE_2D_ARRAY, m - 1, 1, 0, 6));
                    src = rec.views.back();
                    break;
                case Source::Cube: src = res.targets[static_cast<int>(Target::Cube)]->view; break;
            }
            const float roughness = step.roughness_per_mip && mips > 1 ? float(m) / float(mips - 1) : 0.f;
            const gpu::IblParams params{std::max(1u, dst.desc.width >> m), roughness, step.samples, float(res.face)};
            dispatch(rec, res, res.pipelines[static_cast<int>(step.shader)], sampler, src, dst, m, params);
        }
    }
    image_barrier(d, cmd, dst.image, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, kCompute,
                  kWrite, stage.consumer, kSampled, unread, mips - unread);
    rec.s.end_pass();
}

// ---- the stages before

// The split-sum table that shade.frag samples (kBindingBrdfLut).
void record_brdf_lut(Recording& rec) {
    Renderer::Impl& r = rec.r;
    const Device& d = r.d;
    VkCommandBuffer cmd = rec.s.cmd();
    ImageDesc ld;
    // fp32 where it can be filtered: half floats alone would put 2.4e-4 of rounding into E ≈ 1.
    const bool f32 = d.supports(VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT |
                                                                   VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT);
    ld.format = f32 ? VK_FORMAT_R32G32B32A32_SFLOAT : VK_FORMAT_R16G16B16A16_SFLOAT;
    ld.width = ld.height = kLutSize;
    ld.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    Image& lut = rec.out.brdf_lut;
    lut = create_image(d, ld);
    rec.set_layouts.push_back(r.make_set_layout({{static_cast<uint32_t>(gpu::kBindingLut),
                                                  VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT,
                                                  nullptr}}));
    const VkDescriptorSetLayout set_layout = rec.set_layouts.back();
    rec.pipeline_layouts.push_back(r.make_pipeline_layout({set_layout}, 0, 0));
    const VkPipelineLayout layout = rec.pipeline_layouts.back();
    gpu::LutSpecialization values;
    values.correlated = r.scene.brdf == Brdf::accurate ? 1u : 0u;
    values.samples = kLutSamples;
    const VkSpecializationInfo spec = spec_info(kLutEntries, values);
    rec.pipelines.push_back(f32 ? r.make_compute_pipeline(kBrdfLutComp, sizeof(kBrdfLutComp), layout, &spec)
                                : r.make_compute_pipeline(kBrdfLutF16Comp, sizeof(kBrdfLutF16Comp), layout, &spec));
    const VkPipeline pipeline = rec.pipelines.back();
    VkDescriptorSet set = r.allocate_set(r.descriptor_pool, set_layout);
    VkDescriptorImageInfo ii{VK_NULL_HANDLE, lut.view, VK_IMAGE_LAYOUT_GENERAL};
    auto w = vk_struct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
    w.dstSet = set;
    w.dstBinding = static_cast<uint32_t>(gpu::kBindingLut);
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    w.pImageInfo = &ii;
    d.fn.vkUpdateDescriptorSets(d.device, 1, &w, 0, nullptr);

    image_barrier(d, cmd, lut.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_NONE, 0,
                  kCompute, kWrite);
    rec.s.begin_pass("brdf_lut");
    d.fn.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    d.fn.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0, nullptr);
    d.fn.vkCmdDispatch(cmd, 1, kLutSize, 1);
    rec.s.end_pass();
    image_barrier(d, cmd, lut.image, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, kCompute,
                  kWrite, kFragment, kSampled);
}

// The equirectangular image as a sampled texture (fp32 where filterable, else half floats).
const Image& upload_equirect(Recording& rec, const Environment& env) {
    const Device& d = rec.r.d;
    PreparedTexture eq;
    const bool eq32 = d.supports(VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT);
    eq.format = eq32 ? VK_FORMAT_R32G32B32A32_SFLOAT : VK_FORMAT_R16G16B16A16_SFLOAT;
    TextureLevel level0{env.width, env.height, {}};
    if (eq32) {
        level0.bytes.resize(env.rgba.size() * 4);
        std::memcpy(level0.bytes.data(), env.rgba.data(), level0.bytes.size());
    } else {
        level0.bytes.resize(env.rgba.size() * 2);
        for (size_t i = 0; i < env.rgba.size(); ++i) {
            const uint16_t h = float_to_half(env.rgba[i]);
            std::memcpy(level0.bytes.data() + 2 * i, &h, 2);
        }
    }
    eq.levels.push_back(std::move(level0));
    rec.s.begin_pass("env_upload");
    const Image& img = rec.images.emplace_back(rec.r.upload_texture(eq, rec.s.cmd(), rec.staging));
    rec.s.end_pass();
    return img;
}

// Equirectangular → cube → mips → prefiltered specular + irradiance (kCubeStages).
void record_environment(Recording& rec, const Environment& env) {
    Renderer::Impl& r = rec.r;
    const Device& d = r.d;
    if (env.width < 2 || env.height < 1 || env.rgba.size() != size_t{env.width} * env.height * 4)
        throw Error("environment image data does not match its size");
    CubeResources res{};
    res.equirect = upload_equirect(rec, env).view;

    // Longitude wraps, latitude clamps (wrapping would blend the poles together).
    auto si = vk_struct<VkSamplerCreateInfo>(VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO);
    si.magFilter = si.minFilter = VK_FILTER_LINEAR;
    si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
    si.addressModeU = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    si.maxLod = VK_LOD_CLAMP_NONE;
    VkSampler eq_sampler = VK_NULL_HANDLE;
    VK_CHECK(d.fn.vkCreateSampler(d.device, &si, nullptr, &eq_sampler));
    rec.samplers.emplace_back(d, eq_sampler);
    res.equirect_sampler = eq_sampler;

    uint32_t face = 16;
    while (face < env.width / 4 && face < 512) face *= 2;
    res.face = face;
    ImageDesc cd;
    cd.format = VK_FORMAT_R16G16B16A16_SFLOAT;  // storage and filtering on every device
    cd.width = cd.height = face;
    cd.mips = mip_count(face);
    cd.layers = 6;
    cd.cube = true;
    cd.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    res.targets[static_cast<int>(Target::Cube)] = &rec.images.emplace_back(create_image(d, cd));

    ImageDesc sd = cd;
    sd.width = sd.height = std::min(face, kSpecularFace);
    sd.mips = std::min(kSpecularLevels, mip_count(sd.width));
    Lighting& out = rec.out;
    out.env_specular = create_image(d, sd);
    out.env_specular_mips = sd.mips;
    res.targets[static_cast<int>(Target::Specular)] = &out.env_specular;
    ImageDesc id = cd;
    id.width = id.height = std::min(face, kIrradianceFace);
    id.mips = 1;
    out.env_irradiance = create_image(d, id);
    res.targets[static_cast<int>(Target::Irradiance)] = &out.env_irradiance;

    rec.set_layouts.push_back(r.make_set_layout({
        {static_cast<uint32_t>(gpu::kBindingIblSource), VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
         VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
        {static_cast<uint32_t>(gpu::kBindingIblTarget), VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1,
         VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
    }));
    res.set_layout = rec.set_layouts.back();
    rec.pipeline_layouts.push_back(r.make_pipeline_layout({res.set_layout}, sizeof(gpu::IblParams),
                                                          VK_SHADER_STAGE_COMPUTE_BIT));
    res.layout = rec.pipeline_layouts.back();
    const std::pair<const uint32_t*, size_t> code[] = {{kEnvToCubeComp, sizeof kEnvToCubeComp},
                                                       {kCubeDownsampleComp, sizeof kCubeDownsampleComp},
                                                       {kPrefilterComp, sizeof kPrefilterComp},
                                                       {kIrradianceComp, sizeof kIrradianceComp}};
    for (size_t i = 0; i < 4; ++i) {
        rec.pipelines.push_back(r.make_compute_pipeline(code[i].first, code[i].second, res.layout, nullptr));
        res.pipelines[i] = rec.pipelines.back();
    }

    for (const CubeStage& stage : kCubeStages) record_cube_stage(rec, res, stage);
}

}  // namespace

void Renderer::Impl::build_environment() {
    const bool need_lut = scene.environment || scene.brdf == Brdf::accurate;
    if (!need_lut) return;
    // Made by the first renderer of the device to need it while another that uses it is alive;
    // the others wait for it (Device::LightingCache).
    Device::LightingCache& cache = d.lighting_cache;
    const Device::LightingCache::Key key{scene.environment.get(), scene.brdf == Brdf::accurate};
    {
        std::unique_lock<std::mutex> lock(cache.mutex);
        for (;;) {
            const auto it = cache.made.find(key);
            if (it != cache.made.end())
                if ((lighting = it->second.lock())) return;
            if (!cache.making.count(key)) break;
            cache.changed.wait(lock);
        }
        cache.making.insert(key);
    }
    auto done = [&](std::shared_ptr<const Lighting> made) {
        {
            const std::lock_guard<std::mutex> lock(cache.mutex);
            if (made) cache.made[key] = made;
            cache.making.erase(key);
        }
        cache.changed.notify_all();
        lighting = std::move(made);
    };
    try {
        auto made = std::make_shared<Lighting>();
        made->environment = scene.environment;
        Recording rec(*this, *made);
        record_brdf_lut(rec);
        if (scene.environment) record_environment(rec, *scene.environment);
        rec.s.finish(load_times);
        done(std::move(made));
    } catch (...) {  // the next renderer to need it makes it
        done(nullptr);
        throw;
    }
}

}  // namespace mf::render
