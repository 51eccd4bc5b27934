// Internal: the state behind Renderer and GpuMaterial, and which source file does what.
//
//   renderer.cpp   construction order, scene and material checks, accessors
//   pipelines.cpp  descriptor and pipeline layouts, shading variants (specialization constants
//                  by name), the encode pipeline
//   upload.cpp     buffers, the mesh, textures with their mips, placeholders; Renderer::upload
//   frame.cpp      per-frame uniforms (camera, material constants, lights), frame descriptors
//   draw.cpp       render targets; Renderer::render: shade (raster pass or shade.comp), encode or
//                  copy, readback
//   ibl.cpp        load-time passes: BRDF table, environment cube and its prefiltered maps
#pragma once
#include <cstddef>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "render/internal.hpp"
#include "render/shaders/interface.h"

namespace mf::render {

inline constexpr VkFormat kTargetFormat = VK_FORMAT_R32G32B32A32_SFLOAT;  // linear radiance
// Depth (fp32), only where back-face culling cannot order the surfaces: the shaderball is not
// convex (its ring passes in front of and behind the ball) and the ground is a second surface.
// The sphere, cube and plane alone need none (on the H200 a depth buffer adds 28 % to a 2048²
// shade pass, which is bound by writing pixels: docs/bench/README.md).
inline constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
inline constexpr uint32_t kQueryCount = 16;  // two timestamps for each of up to 8 passes

// Descriptor needs of the image-based-lighting passes (ibl.cpp), reserved in the renderer's pool.
inline constexpr uint32_t kIblSets = 24;
inline constexpr uint32_t kIblSamplers = 24;
inline constexpr uint32_t kIblStorageImages = 24;  // 1 table + 1 cube + ≤ 9 mips + 6 levels + 1

// Workgroups of kTile × kTile invocations covering `n` texels.
inline uint32_t tile_groups(uint32_t n) { return (n + gpu::kTile - 1) / gpu::kTile; }

// shade.frag's (and shade.comp's) specialization constants, mapped by name: adding one cannot
// shift the others. pipelines.cpp makes the pipelines' map entries of it; export.cpp hands the
// same constants to the report's WebGL2 view.
inline constexpr detail::SpecField kShadeFields[] = {
    {gpu::kSpecNumDirectional, offsetof(gpu::ShadeSpecialization, num_directional), false},
    {gpu::kSpecNumPoint, offsetof(gpu::ShadeSpecialization, num_point), false},
    {gpu::kSpecBrdfModel, offsetof(gpu::ShadeSpecialization, brdf_model), false},
    {gpu::kSpecAnalyticSphere, offsetof(gpu::ShadeSpecialization, analytic_sphere), true},
    {gpu::kSpecHasEnv, offsetof(gpu::ShadeSpecialization, has_env), true},
    {gpu::kSpecAlbedoTex, offsetof(gpu::ShadeSpecialization, albedo_tex), false},
    {gpu::kSpecEmissiveTex, offsetof(gpu::ShadeSpecialization, emissive_tex), false},
    {gpu::kSpecNormalTex, offsetof(gpu::ShadeSpecialization, normal_tex), false},
    {gpu::kSpecNormalGreenDown, offsetof(gpu::ShadeSpecialization, normal_green_down), true},
    {gpu::kSpecRoughnessTex, offsetof(gpu::ShadeSpecialization, roughness_tex), false},
    {gpu::kSpecRoughnessChannel, offsetof(gpu::ShadeSpecialization, roughness_channel), false},
    {gpu::kSpecRoughnessInvert, offsetof(gpu::ShadeSpecialization, roughness_invert), true},
    {gpu::kSpecMetalnessTex, offsetof(gpu::ShadeSpecialization, metalness_tex), false},
    {gpu::kSpecMetalnessChannel, offsetof(gpu::ShadeSpecialization, metalness_channel), false},
    {gpu::kSpecMetalnessInvert, offsetof(gpu::ShadeSpecialization, metalness_invert), true},
    {gpu::kSpecOcclusionTex, offsetof(gpu::ShadeSpecialization, occlusion_tex), false},
    {gpu::kSpecOcclusionChannel, offsetof(gpu::ShadeSpecialization, occlusion_channel), false},
    {gpu::kSpecOcclusionInvert, offsetof(gpu::ShadeSpecialization, occlusion_invert), true},
    {gpu::kSpecOpacityTex, offsetof(gpu::ShadeSpecialization, opacity_tex), false},
    {gpu::kSpecOpacityChannel, offsetof(gpu::ShadeSpecialization, opacity_channel), false},
    {gpu::kSpecOpacityInvert, offsetof(gpu::ShadeSpecialization, opacity_invert), true},
    {gpu::kSpecNormalZFromXy, offsetof(gpu::ShadeSpecialization, normal_z_from_xy), true},
    {gpu::kSpecGround, offsetof(gpu::ShadeSpecialization, ground), true},
    {gpu::kSpecFillOnly, offsetof(gpu::ShadeSpecialization, fill_only), true},
    {gpu::kSpecMsaa, offsetof(gpu::ShadeSpecialization, msaa), true},
    {gpu::kSpecShape, offsetof(gpu::ShadeSpecialization, shape), false},
    {gpu::kSpecSamples, offsetof(gpu::ShadeSpecialization, samples), false},
    {gpu::kSpecAlphaMode, offsetof(gpu::ShadeSpecialization, alpha_mode), false},
    {gpu::kSpecDoubleSided, offsetof(gpu::ShadeSpecialization, double_sided), true},
};

struct Renderer::Impl {
    detail::Device& d;
    Scene scene;
    std::vector<PassTime> load_times, frame_times;
    mutable Renderer::HostTimes host_times;  // added to where upload() and render() run, as `notes`
    // What was changed to fit the device (textures reduced to its size limit), for the user;
    // upload_texture is const (it records into the caller's command buffer) but may add here.
    mutable std::vector<std::string> notes;

    detail::Unique<VkCommandPool> command_pool;
    detail::Unique<VkQueryPool> queries;  // null without timestamp support
    // upload()'s own: its timestamps are read after render() has reset `queries`.
    detail::Unique<VkQueryPool> upload_queries;
    // upload()'s submission, not waited for: render() submits after it on the same queue (its
    // barriers make the draw wait for the copies on the device, not on this thread), then
    // retires it; so does the next upload() before submitting its own. Its staging buffers are
    // kept until then. Declared after command_pool: its command buffer is freed first.
    struct PendingUpload {
        std::unique_ptr<detail::Submission> submission;
        std::vector<detail::Buffer> staging;
    };
    std::optional<PendingUpload> pending_upload;
    void retire_upload();  // waits for it, counts its device time, keeps its staging
    detail::Unique<VkSampler> sampler_repeat, sampler_clamp;
    detail::Unique<VkDescriptorSetLayout> frame_layout, material_layout, encode_set_layout;
    detail::Unique<VkPipelineLayout> shade_layout, encode_layout;
    // Scene::shading resolved: shade.comp (compute_layout: the shade sets and encode's, whose
    // storage image is the target) instead of shade.vert + shade.frag.
    bool compute = false;
    detail::Unique<VkPipelineLayout> compute_layout;
    detail::Unique<VkShaderModule> vert, frag;
    detail::Unique<VkPipeline> encode_pipeline;
    // Shading pipelines by specialization constants: materials of one variant share one. Each is
    // made once, by the first thread to ask (upload(), or Renderer::warm from a batch's workers,
    // so a lane does not stop to compile); a thread asking while it is made waits for it.
    struct PipelineSlot {
        std::shared_future<VkPipeline> ready;
        detail::Unique<VkPipeline> owned;
    };
    std::map<gpu::ShadeSpecialization, PipelineSlot> shade_pipelines;
    std::mutex shade_pipelines_mutex;
    detail::Unique<VkDescriptorPool> descriptor_pool;
    VkDescriptorSet frame_set = VK_NULL_HANDLE, encode_set = VK_NULL_HANDLE;

    detail::Buffer vertices, indices, uniforms, readback;
    uint32_t index_count = 0;
    // The ground plane's height (a thousandth of the shape's size under its lowest point: no depth
    // fight where they touch) and the shape's bounding-sphere radius, from its mesh.
    float ground_y = 0.f, shape_radius = 0.f;
    detail::Buffer ground_vertices, ground_indices;  // only with Scene::ground
    detail::Image target;                            // linear radiance, kTargetFormat
    // Scene::msaa where the device has it: the multisampled target shaded into and resolved
    // (averaged) into `target` at the end of the pass; depth then has as many samples.
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
    detail::Image msaa_target;
    detail::Image depth;  // kDepthFormat, the target's size, when uses_depth()
    bool uses_depth() const { return scene.shape.type == ShapeType::shaderball || scene.ground.enabled; }
    detail::Image dummy_2d, dummy_cube;
    std::shared_ptr<const detail::Lighting> lighting;  // null when the scene needs none (ibl.cpp)

    Impl(Context& context, Scene scene);
    ~Impl();
    Impl(const Impl&) = delete;
    Impl& operator=(const Impl&) = delete;

    // renderer.cpp
    // Scene::shading to a path (sets `compute`): compute where it covers the scene, automatic by
    // measurement; its notes go to `said`. Runs beside the load-time work, which reads neither.
    void choose_shading(Context& context, std::vector<std::string>& said);
    bool compute_covers() const { return scene.shape.type != ShapeType::shaderball && !scene.ground.enabled; }
    void choose_samples();  // Scene::msaa, or the supersampling that stands in for it
    detail::Unique<VkSampler> make_sampler(VkSamplerAddressMode mode, bool anisotropic) const;
    void create_samplers();

    // pipelines.cpp. The factories create Vulkan objects through d and touch no state of the
    // renderer.
    detail::Unique<VkDescriptorSetLayout> make_set_layout(const std::vector<VkDescriptorSetLayoutBinding>& b) const;
    detail::Unique<VkPipelineLayout> make_pipeline_layout(const std::vector<VkDescriptorSetLayout>& sets,
                                                          uint32_t push_bytes, VkShaderStageFlags push_stages) const;
    detail::Unique<VkPipeline> make_compute_pipeline(const uint32_t* code, size_t bytes, VkPipelineLayout layout,
                                                     const VkSpecializationInfo* spec) const;
    // Allocates from `pool`, which the caller owns (and synchronizes).
    VkDescriptorSet allocate_set(VkDescriptorPool pool, VkDescriptorSetLayout layout) const;
    void create_layouts();
    // The variant of shade.frag a material needs in this scene, and its one-line description.
    gpu::ShadeSpecialization specialization(const Material& m) const;
    // Into a variant made by scene_specialization (before this renderer existed): this
    // renderer's own choices, its sample count and shading path.
    void place(gpu::ShadeSpecialization& c) const;
    // The ground plane's variant beside the shape's `c`: the scene's lights, environment and
    // BRDF, no texture, flat, not the analytic sphere.
    static gpu::ShadeSpecialization ground_specialization(const gpu::ShadeSpecialization& c);
    std::string describe(const gpu::ShadeSpecialization& c) const;
    VkPipeline shade_pipeline(const gpu::ShadeSpecialization& c);
    detail::Unique<VkPipeline> graphics_pipeline(const gpu::ShadeSpecialization& c) const;

    // upload.cpp
    detail::Buffer upload_buffer(const void* data, VkDeviceSize bytes, VkBufferUsageFlags usage);
    void upload_mesh();
    void create_dummies();
    // Records into the caller's `cmd`; the staging buffers go to the caller's `staging`.
    detail::Image upload_texture(const detail::PreparedTexture& prepared, VkCommandBuffer cmd,
                                 std::vector<detail::Buffer>& staging) const;
    static detail::ImageDesc texture_desc(const detail::PreparedTexture& t);  // the image `t` fills
    // The copies (and blitted mips) that fill `img`, made for `t` (texture_desc).
    void record_texture(const detail::PreparedTexture& t, const detail::Image& img, VkCommandBuffer cmd,
                        std::vector<detail::Buffer>& staging) const;
    // A material's images, bound in one block of `blocks` (m.block); an image left empty is one
    // that upload_texture makes on its own.
    std::vector<detail::Image> material_images(const PreparedMaterial::Impl& p, GpuMaterial::Impl& m) const;
    std::shared_ptr<detail::BlockPool> blocks;  // shared with the materials, which return their block
    // Staging buffers of finished uploads, kept for the next ones (at most kStagingKept bytes):
    // a host-visible allocation is pinned memory, and making and freeing three a material was
    // most of a library's upload on the H200 (docs/bench/README.md, A library on the H200).
    // Touched only where upload() and render() are called; mutable as `notes` is.
    static constexpr VkDeviceSize kStagingKept = VkDeviceSize{96} << 20;
    mutable std::vector<detail::Buffer> staging_free;
    detail::Buffer take_staging(VkDeviceSize bytes) const;       // a kept one that fits, else a new one
    void keep_staging(std::vector<detail::Buffer>& used) const;  // after their submission completed

    // frame.cpp
    void write_frame_descriptors();
    void write_frame(const Material& m);

    // draw.cpp
    void create_targets();  // the frame's resources, an error naming the frame when they do not fit
    void create_frame_resources();
    // Records the shade pass of `m` into the target (raster or compute), the target left for
    // encode.comp to read (GENERAL).
    void record_raster(VkCommandBuffer cmd, const GpuMaterial::Impl& m) const;
    void record_compute(VkCommandBuffer cmd, const GpuMaterial::Impl& m) const;

    // ibl.cpp: the BRDF table and environment maps, only when the scene calls for them.
    void build_environment();
};

// The constants of shade.frag's variant that the scene and the material decide (all but the
// renderer's sample count and shading path, Renderer::Impl::place): what prepare() knows
// before a renderer exists.
gpu::ShadeSpecialization scene_specialization(const Scene& scene, const Material& m);

struct PreparedMaterial::Impl {
    const detail::Device* device = nullptr;  // prepared for this device and this scene's textures
    bool fast_textures = false;
    Material constants;  // roles and constant values (no texel data)
    gpu::ShadeSpecialization specialization;
    std::vector<std::optional<detail::PreparedTexture>> textures;  // by index; none where the variant samples nothing
};

// Renderer::prepare and render::prepare: the textures converted for `d`, read as `scene` reads them.
std::unique_ptr<PreparedMaterial::Impl> prepare_material(const detail::Device& d, const Scene& scene,
                                                         const Material& material);

struct GpuMaterial::Impl {
    Impl() = default;
    ~Impl();  // the images first, then the block back to the pool
    Impl(const Impl&) = delete;
    Impl& operator=(const Impl&) = delete;
    const Renderer::Impl* owner = nullptr;
    std::string name, variant;
    Material constants;                         // roles and constant values (no texel data)
    std::shared_ptr<detail::BlockPool> blocks;  // where `block` returns
    // Its upload's completion: waited for before the images go (a material freed undrawn).
    std::shared_ptr<detail::Unique<VkFence>> uploaded;
    detail::BlockPool::Block block;  // the textures' memory, unless each has its own
    std::vector<detail::Image> textures;
    detail::Unique<VkDescriptorPool> pool;
    VkDescriptorSet set = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;         // owned by the renderer's cache
    VkPipeline ground_pipeline = VK_NULL_HANDLE;  // with Scene::ground: the ground's variant for this scene
};

}  // namespace mf::render
