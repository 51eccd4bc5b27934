// Load-time passes: the split-sum BRDF table and, with an environment, its prefiltered maps.
// Only what the scene calls for is computed.
#include <cstring>

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

constexpr uint32_t kLutSize = 128;
constexpr uint32_t kLutSamples = 1024;
constexpr uint32_t kSpecularFace = 128;  // prefiltered cube: mip m holds roughness m / (levels − 1)
constexpr uint32_t kSpecularLevels = 6;
constexpr uint32_t kIrradianceFace = 32;  // E(n)/π varies slowly
constexpr uint32_t kPrefilterSamples = 256;
constexpr uint32_t kIrradianceSamples = 512;

struct IblParams {
    uint32_t size;
    float roughness;
    uint32_t samples;
    float src_size;
};

uint32_t mip_count(uint32_t size) {
    uint32_t n = 1;
    while (size > 1) {
        size /= 2;
        ++n;
    }
    return n;
}

}  // namespace

void Renderer::Impl::build_environment() {
    const bool need_lut = scene.environment || scene.brdf == Brdf::Accurate;
    if (!need_lut) return;

    Submission s(d, command_pool, queries, 16);
    VkCommandBuffer cmd = s.cmd();

    // ---- BRDF table
    ImageDesc ld;
    // fp32 where it can be filtered: half floats alone would put 2.4e-4 of rounding into E ≈ 1.
    const bool f32 = d.supports(VK_FORMAT_R32G32B32A32_SFLOAT,
                                VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT);
    ld.format = f32 ? VK_FORMAT_R32G32B32A32_SFLOAT : VK_FORMAT_R16G16B16A16_SFLOAT;
    ld.width = ld.height = kLutSize;
    ld.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    brdf_lut = create_image(d, ld);
    auto layout = make_set_layout({{0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr}});
    auto pipeline_layout = make_pipeline_layout({layout}, 0, 0);
    const uint32_t spec_values[2] = {scene.brdf == Brdf::Accurate ? 1u : 0u, kLutSamples};
    const VkSpecializationMapEntry entries[2] = {{0, 0, 4}, {1, 4, 4}};
    const VkSpecializationInfo spec{2, entries, sizeof spec_values, spec_values};
    auto pipeline = f32 ? make_compute_pipeline(kBrdfLutComp, sizeof(kBrdfLutComp), pipeline_layout, &spec)
                        : make_compute_pipeline(kBrdfLutF16Comp, sizeof(kBrdfLutF16Comp), pipeline_layout, &spec);
    VkDescriptorSet set = allocate_set(descriptor_pool, layout);
    VkDescriptorImageInfo ii{VK_NULL_HANDLE, brdf_lut.view, VK_IMAGE_LAYOUT_GENERAL};
    auto w = vk_struct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
    w.dstSet = set;
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    w.pImageInfo = &ii;
    d.fn.vkUpdateDescriptorSets(d.device, 1, &w, 0, nullptr);

    image_barrier(d, cmd, brdf_lut.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                  VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                  VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    s.begin_pass("brdf_lut");
    d.fn.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    d.fn.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_layout, 0, 1, &set, 0, nullptr);
    d.fn.vkCmdDispatch(cmd, kLutSize / 8, kLutSize / 8, 1);
    s.end_pass();
    image_barrier(d, cmd, brdf_lut.image, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                  VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);

    if (!scene.environment) {
        s.finish(load_times);
        return;
    }

    // ---- environment: equirectangular → cube → mips → prefiltered specular + irradiance
    const Environment& env = *scene.environment;
    if (env.width < 2 || env.height < 1 || env.rgba.size() != size_t{env.width} * env.height * 4)
        throw Error("environment image data does not match its size");
    std::vector<Buffer> staging;
    std::vector<Unique<VkImageView>> views;  // alive until the submission completes

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
    s.begin_pass("env_upload");
    Image equirect = upload_texture(eq, cmd, staging);
    s.end_pass();

    // Longitude wraps, latitude clamps (wrapping would blend the poles together).
    auto si = vk_struct<VkSamplerCreateInfo>(VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO);
    si.magFilter = si.minFilter = VK_FILTER_LINEAR;
    si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
    si.addressModeU = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    si.maxLod = VK_LOD_CLAMP_NONE;
    VkSampler eq_sampler_handle = VK_NULL_HANDLE;
    VK_CHECK(d.fn.vkCreateSampler(d.device, &si, nullptr, &eq_sampler_handle));
    Unique<VkSampler> eq_sampler(d, eq_sampler_handle);

    uint32_t face = 16;
    while (face < env.width / 4 && face < 512) face *= 2;
    const uint32_t src_mips = mip_count(face);
    ImageDesc cd;
    cd.format = VK_FORMAT_R16G16B16A16_SFLOAT;  // storage and filtering on every device
    cd.width = cd.height = face;
    cd.mips = src_mips;
    cd.layers = 6;
    cd.cube = true;
    cd.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    Image cube = create_image(d, cd);

    ImageDesc sd = cd;
    sd.width = sd.height = std::min(face, kSpecularFace);
    sd.mips = std::min(kSpecularLevels, mip_count(sd.width));
    env_specular = create_image(d, sd);
    env_specular_mips = sd.mips;
    ImageDesc id = cd;
    id.width = id.height = std::min(face, kIrradianceFace);
    id.mips = 1;
    env_irradiance = create_image(d, id);

    auto ibl_layout = make_set_layout({
        {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
        {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
    });
    auto ibl_pipeline_layout = make_pipeline_layout({ibl_layout}, sizeof(IblParams), VK_SHADER_STAGE_COMPUTE_BIT);
    auto to_cube = make_compute_pipeline(kEnvToCubeComp, sizeof(kEnvToCubeComp), ibl_pipeline_layout, nullptr);
    auto downsample = make_compute_pipeline(kCubeDownsampleComp, sizeof(kCubeDownsampleComp), ibl_pipeline_layout, nullptr);
    auto prefilter = make_compute_pipeline(kPrefilterComp, sizeof(kPrefilterComp), ibl_pipeline_layout, nullptr);
    auto irradiance = make_compute_pipeline(kIrradianceComp, sizeof(kIrradianceComp), ibl_pipeline_layout, nullptr);

    // One dispatch over the six faces of one mip: `src` sampled, `dst` a storage view.
    auto dispatch = [&](VkPipeline pass_pipeline, VkSampler sampler, VkImageView src, const Image& dst, uint32_t mip,
                        const IblParams& params) {
        views.push_back(create_view(d, dst, VK_IMAGE_VIEW_TYPE_2D_ARRAY, mip, 1, 0, 6));
        VkDescriptorSet ds = allocate_set(descriptor_pool, ibl_layout);
        VkDescriptorImageInfo in{sampler, src, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        VkDescriptorImageInfo out{VK_NULL_HANDLE, views.back(), VK_IMAGE_LAYOUT_GENERAL};
        VkWriteDescriptorSet writes[2] = {vk_struct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET),
                                          vk_struct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET)};
        writes[0].dstSet = writes[1].dstSet = ds;
        writes[0].dstBinding = 0;
        writes[0].descriptorCount = 1;
        writes[0].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        writes[0].pImageInfo = &in;
        writes[1].dstBinding = 1;
        writes[1].descriptorCount = 1;
        writes[1].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
        writes[1].pImageInfo = &out;
        d.fn.vkUpdateDescriptorSets(d.device, 2, writes, 0, nullptr);
        d.fn.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pass_pipeline);
        d.fn.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, ibl_pipeline_layout, 0, 1, &ds, 0, nullptr);
        d.fn.vkCmdPushConstants(cmd, ibl_pipeline_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof params, &params);
        d.fn.vkCmdDispatch(cmd, (params.size + 7) / 8, (params.size + 7) / 8, 6);
    };
    constexpr auto kCompute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    constexpr auto kWrite = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
    constexpr auto kSampled = VK_ACCESS_2_SHADER_SAMPLED_READ_BIT;

    s.begin_pass("env_cube");
    image_barrier(d, cmd, cube.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_NONE, 0,
                  kCompute, kWrite);
    dispatch(to_cube, eq_sampler, equirect.view, cube, 0, {face, 0.f, 0, float(face)});
    for (uint32_t m = 1; m < src_mips; ++m) {
        // The mip above becomes the source of this one.
        image_barrier(d, cmd, cube.image, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, kCompute,
                      kWrite, kCompute, kSampled, m - 1, 1);
        views.push_back(create_view(d, cube, VK_IMAGE_VIEW_TYPE_2D_ARRAY, m - 1, 1, 0, 6));
        dispatch(downsample, sampler_clamp, views.back(), cube, m, {std::max(1u, face >> m), 0.f, 0, float(face)});
    }
    image_barrier(d, cmd, cube.image, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, kCompute,
                  kWrite, kCompute, kSampled, src_mips - 1, 1);
    s.end_pass();

    s.begin_pass("env_prefilter");
    image_barrier(d, cmd, env_specular.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                  VK_PIPELINE_STAGE_2_NONE, 0, kCompute, kWrite);
    for (uint32_t m = 0; m < env_specular_mips; ++m) {
        const float roughness = env_specular_mips > 1 ? float(m) / float(env_specular_mips - 1) : 0.f;
        dispatch(prefilter, sampler_clamp, cube.view, env_specular, m,
                 {std::max(1u, sd.width >> m), roughness, kPrefilterSamples, float(face)});
    }
    image_barrier(d, cmd, env_specular.image, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                  kCompute, kWrite, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, kSampled);
    s.end_pass();

    s.begin_pass("env_irradiance");
    image_barrier(d, cmd, env_irradiance.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                  VK_PIPELINE_STAGE_2_NONE, 0, kCompute, kWrite);
    dispatch(irradiance, sampler_clamp, cube.view, env_irradiance, 0, {id.width, 0.f, kIrradianceSamples, float(face)});
    image_barrier(d, cmd, env_irradiance.image, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                  kCompute, kWrite, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, kSampled);
    s.end_pass();
    s.finish(load_times);
}

}  // namespace mf::render
