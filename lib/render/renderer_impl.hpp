// Internal: the state behind Renderer and GpuMaterial.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "render/internal.hpp"

namespace mf::render {

// Descriptor needs of the image-based-lighting passes (ibl.cpp), reserved in the renderer's pool.
inline constexpr uint32_t kIblSets = 24;
inline constexpr uint32_t kIblSamplers = 24;
inline constexpr uint32_t kIblStorageImages = 24;  // 1 table + 1 cube + ≤ 9 mips + 6 levels + 1

struct Renderer::Impl {
    detail::Device& d;
    Scene scene;
    std::vector<PassTime> load_times, frame_times;

    detail::Unique<VkCommandPool> command_pool;
    detail::Unique<VkQueryPool> queries;  // null without timestamp support
    detail::Unique<VkSampler> sampler_repeat, sampler_clamp;
    detail::Unique<VkDescriptorSetLayout> frame_layout, material_layout, encode_set_layout;
    detail::Unique<VkPipelineLayout> shade_layout, encode_layout;
    detail::Unique<VkShaderModule> vert, frag;
    detail::Unique<VkPipeline> encode_pipeline;
    // Shading pipelines by specialization constants: materials of one variant share one.
    std::map<std::vector<int32_t>, detail::Unique<VkPipeline>> shade_pipelines;
    detail::Unique<VkDescriptorPool> descriptor_pool;
    VkDescriptorSet frame_set = VK_NULL_HANDLE, encode_set = VK_NULL_HANDLE;

    detail::Buffer vertices, indices, uniforms, readback;
    uint32_t index_count = 0;
    detail::Image target;  // linear radiance, RGBA32F
    detail::Image dummy_2d, dummy_cube;
    detail::Image brdf_lut;                      // when the accurate BRDF or an environment needs it
    detail::Image env_specular, env_irradiance;  // when the scene has an environment
    uint32_t env_specular_mips = 0;

    Impl(Context& context, Scene scene);
    ~Impl();
    Impl(const Impl&) = delete;
    Impl& operator=(const Impl&) = delete;

    // Factories: they create Vulkan objects through d and touch no state of the renderer.
    detail::Unique<VkSampler> make_sampler(VkSamplerAddressMode mode, bool anisotropic) const;
    detail::Unique<VkDescriptorSetLayout> make_set_layout(const std::vector<VkDescriptorSetLayoutBinding>& b) const;
    detail::Unique<VkPipelineLayout> make_pipeline_layout(const std::vector<VkDescriptorSetLayout>& sets,
                                                          uint32_t push_bytes, VkShaderStageFlags push_stages) const;
    detail::Unique<VkPipeline> make_compute_pipeline(const uint32_t* code, size_t bytes, VkPipelineLayout layout,
                                                     const VkSpecializationInfo* spec) const;
    // Allocates from `pool`, which the caller owns (and synchronizes).
    VkDescriptorSet allocate_set(VkDescriptorPool pool, VkDescriptorSetLayout layout) const;
    void create_samplers();
    void create_layouts();
    void create_targets();
    void upload_mesh();
    void create_dummies();
    void build_environment();  // ibl.cpp
    void write_frame_descriptors();
    detail::Buffer upload_buffer(const void* data, VkDeviceSize bytes, VkBufferUsageFlags usage);
    // Records into the caller's `cmd`; the staging buffers go to the caller's `staging`.
    detail::Image upload_texture(const detail::PreparedTexture& t, VkCommandBuffer cmd,
                                 std::vector<detail::Buffer>& staging) const;
    VkPipeline shade_pipeline(const std::vector<int32_t>& constants);
    std::vector<int32_t> variant_constants(const Material& m, std::string& description) const;
    void write_frame(const Material& m);
};

struct GpuMaterial::Impl {
    const Renderer::Impl* owner = nullptr;
    std::string name, variant;
    Material constants;  // roles and constant values (no texel data)
    std::vector<detail::Image> textures;
    detail::Unique<VkDescriptorPool> pool;
    VkDescriptorSet set = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;  // owned by the renderer's cache
};

}  // namespace mf::render
