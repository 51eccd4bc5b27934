// Descriptor and pipeline layouts, the shading pipeline's variants and the encode pipeline.
//
// Specialization constants are mapped by name: each VkSpecializationMapEntry pairs an id of
// shaders/interface.h with the offset of its field in gpu::ShadeSpecialization, so adding a
// constant cannot shift the others.
#include <cstddef>
#include <exception>
#include <future>
#include <mutex>
#include <sstream>

#include "render/internal.hpp"
#include "render/renderer_impl.hpp"

namespace mf::render {

using namespace detail;

namespace {

constexpr uint32_t kShadeVert[] =
#include "shaders/shade.vert.inc"
    ;
constexpr uint32_t kShadeFrag[] =
#include "shaders/shade.frag.inc"
    ;
constexpr uint32_t kShadeComp[] =
#include "shaders/shade.comp.inc"
    ;
constexpr uint32_t kEncodeComp[] =
#include "shaders/encode.comp.inc"
    ;

using gpu::ShadeSpecialization;

constexpr auto kShadeEntries = spec_entries(kShadeFields);
static_assert(spec_entries_distinct(kShadeEntries), "an id or field mapped twice");

uint32_t flag(bool b) { return b ? 1u : 0u; }

static_assert(static_cast<int>(ShapeType::sphere) == gpu::kShapeSphere &&
                  static_cast<int>(ShapeType::cube) == gpu::kShapeCube &&
                  static_cast<int>(ShapeType::plane) == gpu::kShapePlane,
              "ShadeSpecialization::shape carries render::ShapeType as it is");

const char* role_text(int texture) { return texture >= 0 ? "tex" : "const"; }

}  // namespace

Unique<VkDescriptorSetLayout> Renderer::Impl::make_set_layout(
    const std::vector<VkDescriptorSetLayoutBinding>& bindings) const {
    auto ci = vk_struct<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
    ci.bindingCount = static_cast<uint32_t>(bindings.size());
    ci.pBindings = bindings.data();
    VkDescriptorSetLayout h = VK_NULL_HANDLE;
    VK_CHECK(d.fn.vkCreateDescriptorSetLayout(d.device, &ci, nullptr, &h));
    return Unique<VkDescriptorSetLayout>(d, h);
}

Unique<VkPipelineLayout> Renderer::Impl::make_pipeline_layout(const std::vector<VkDescriptorSetLayout>& sets,
                                                              uint32_t push_bytes,
                                                              VkShaderStageFlags push_stages) const {
    VkPushConstantRange range{push_stages, 0, push_bytes};
    auto ci = vk_struct<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
    ci.setLayoutCount = static_cast<uint32_t>(sets.size());
    ci.pSetLayouts = sets.data();
    ci.pushConstantRangeCount = push_bytes ? 1u : 0u;
    ci.pPushConstantRanges = &range;
    VkPipelineLayout h = VK_NULL_HANDLE;
    VK_CHECK(d.fn.vkCreatePipelineLayout(d.device, &ci, nullptr, &h));
    return Unique<VkPipelineLayout>(d, h);
}

Unique<VkPipeline> Renderer::Impl::make_compute_pipeline(const uint32_t* code, size_t bytes, VkPipelineLayout layout,
                                                         const VkSpecializationInfo* spec) const {
    Unique<VkShaderModule> module = create_shader(d, code, bytes);
    auto ci = vk_struct<VkComputePipelineCreateInfo>(VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO);
    ci.stage = vk_struct<VkPipelineShaderStageCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO);
    ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    ci.stage.module = module;
    ci.stage.pName = "main";
    ci.stage.pSpecializationInfo = spec;
    ci.layout = layout;
    VkPipeline h = VK_NULL_HANDLE;
    VK_CHECK(d.fn.vkCreateComputePipelines(d.device, d.pipeline_cache, 1, &ci, nullptr, &h));
    return Unique<VkPipeline>(d, h);
}

VkDescriptorSet Renderer::Impl::allocate_set(VkDescriptorPool pool, VkDescriptorSetLayout layout) const {
    auto ai = vk_struct<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
    ai.descriptorPool = pool;
    ai.descriptorSetCount = 1;
    ai.pSetLayouts = &layout;
    VkDescriptorSet set = VK_NULL_HANDLE;
    VK_CHECK(d.fn.vkAllocateDescriptorSets(d.device, &ai, &set));
    return set;
}

void Renderer::Impl::create_layouts() {
    // Read by the fragment shader, or by shade.comp on the compute path.
    constexpr auto kFrag = VK_SHADER_STAGE_FRAGMENT_BIT | VK_SHADER_STAGE_COMPUTE_BIT;
    constexpr auto kComputeShader = VK_SHADER_STAGE_COMPUTE_BIT;
    auto binding = [](int b, VkDescriptorType type, uint32_t count, VkShaderStageFlags stages) {
        return VkDescriptorSetLayoutBinding{static_cast<uint32_t>(b), type, count, stages, nullptr};
    };
    frame_layout = make_set_layout({
        binding(gpu::kBindingFrameData, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_VERTEX_BIT | kFrag),
        binding(gpu::kBindingBrdfLut, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, kFrag),
        binding(gpu::kBindingEnvSpecular, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, kFrag),
        binding(gpu::kBindingEnvIrradiance, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, kFrag),
    });
    material_layout = make_set_layout({
        binding(gpu::kBindingMaterialTextures, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                static_cast<uint32_t>(kMaxTextures), kFrag),
    });
    encode_set_layout = make_set_layout({
        binding(gpu::kBindingEncodeRadiance, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, kComputeShader),
        binding(gpu::kBindingEncodePixels, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, kComputeShader),
    });
    static_assert(gpu::kSetFrame == 0 && gpu::kSetMaterial == 1, "the order of shade_layout's sets");
    shade_layout = make_pipeline_layout({frame_layout, material_layout}, 0, 0);
    encode_layout = make_pipeline_layout({encode_set_layout}, sizeof(gpu::EncodeParams), kComputeShader);
    static_assert(gpu::kSetShadeTarget == 2, "the order of compute_layout's sets");
    compute_layout = make_pipeline_layout({frame_layout, material_layout, encode_set_layout}, 0, 0);
    encode_pipeline = make_compute_pipeline(kEncodeComp, sizeof(kEncodeComp), encode_layout, nullptr);
    vert = create_shader(d, kShadeVert, sizeof(kShadeVert));
    frag = create_shader(d, kShadeFrag, sizeof(kShadeFrag));

    // One pool for the renderer's own sets; materials bring their own.
    const VkDescriptorPoolSize sizes[] = {
        {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
        {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 3 + kIblSamplers},
        {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1 + kIblStorageImages},
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1},
    };
    auto pci = vk_struct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
    pci.maxSets = 2 + kIblSets;
    pci.poolSizeCount = 4;
    pci.pPoolSizes = sizes;
    VkDescriptorPool h = VK_NULL_HANDLE;
    VK_CHECK(d.fn.vkCreateDescriptorPool(d.device, &pci, nullptr, &h));
    descriptor_pool = Unique<VkDescriptorPool>(d, h);
    frame_set = allocate_set(descriptor_pool, frame_layout);
    encode_set = allocate_set(descriptor_pool, encode_set_layout);
}

ShadeSpecialization scene_specialization(const Scene& scene, const Material& m) {
    ShadeSpecialization c{};
    for (const Light& l : scene.lights) ++(l.type == LightType::directional ? c.num_directional : c.num_point);
    const bool env = static_cast<bool>(scene.environment);
    c.brdf_model = brdf_model_id(scene.brdf);
    c.analytic_sphere = flag(scene.shape.type == ShapeType::sphere);
    c.has_env = flag(env);
    c.albedo_tex = m.albedo.texture;
    c.emissive_tex = m.emissive.texture;
    c.normal_tex = m.normal.texture;
    c.normal_green_down = flag(m.normal.green_down);
    c.normal_z_from_xy = flag(m.normal.texture >= 0 && m.normal.z_from_xy);
    c.fill_only = flag(scene.fill_only);
    c.shape = static_cast<int32_t>(scene.shape.type);
    auto scalar = [](const ScalarRole& r, int32_t& tex, int32_t& channel, uint32_t& invert) {
        tex = r.texture;
        channel = static_cast<int32_t>(r.channel);
        invert = flag(r.invert);
    };
    scalar(m.roughness, c.roughness_tex, c.roughness_channel, c.roughness_invert);
    scalar(m.metalness, c.metalness_tex, c.metalness_channel, c.metalness_invert);
    // Occlusion only darkens light from the environment: without one it is never sampled.
    ScalarRole occlusion = m.occlusion;
    if (!env) occlusion.texture = -1;
    scalar(occlusion, c.occlusion_tex, c.occlusion_channel, c.occlusion_invert);
    scalar(m.opacity, c.opacity_tex, c.opacity_channel, c.opacity_invert);
    c.alpha_mode = static_cast<int32_t>(m.alpha_mode);
    c.double_sided = flag(m.double_sided);
    return c;
}

void Renderer::Impl::place(ShadeSpecialization& c) const {
    c.msaa = flag(samples != VK_SAMPLE_COUNT_1_BIT);
    c.samples = compute ? static_cast<int32_t>(scene.msaa) : 1;  // raster: coverage samples instead
}

ShadeSpecialization Renderer::Impl::specialization(const Material& m) const {
    ShadeSpecialization c = scene_specialization(scene, m);
    place(c);
    return c;
}

ShadeSpecialization Renderer::Impl::ground_specialization(const ShadeSpecialization& c) {
    ShadeSpecialization g{};
    g.num_directional = c.num_directional;
    g.num_point = c.num_point;
    g.brdf_model = c.brdf_model;
    g.has_env = c.has_env;
    g.ground = 1;
    g.msaa = c.msaa;
    g.shape = c.shape;
    return g;  // every *_tex −1: nothing sampled; no analytic sphere
}

std::string Renderer::Impl::describe(const ShadeSpecialization& c) const {
    static const char* const brdf_names[] = {"standard", "accurate", "assignment"};  // CLI values
    static const char* const shape_names[] = {"sphere", "cube", "plane", "shaderball"};
    std::ostringstream os;
    os << shape_names[static_cast<int>(scene.shape.type)] << ' ' << brdf_names[static_cast<int>(scene.brdf)] << " dir"
       << c.num_directional << " point" << c.num_point << (c.has_env ? " env" : "")
       << " albedo:" << role_text(c.albedo_tex)
       << " normal:" << (c.normal_tex >= 0 ? (c.normal_green_down ? "dx" : "gl") : "none")
       << (c.normal_z_from_xy ? "+z" : "") << " roughness:" << role_text(c.roughness_tex)
       << " metalness:" << role_text(c.metalness_tex);
    if (c.emissive_tex >= 0) os << " emissive:tex";
    if (c.opacity_tex >= 0) os << " opacity:tex";
    if (c.occlusion_tex >= 0) os << " occlusion:tex";
    if (c.alpha_mode == gpu::kAlphaMask) os << " mask";
    if (c.alpha_mode == gpu::kAlphaOpaque) os << " opaque";
    if (c.double_sided) os << " double-sided";
    if (scene.ground.enabled) os << " ground";
    if (c.msaa) os << " msaa" << static_cast<uint32_t>(samples);
    if (compute) os << " compute" << (c.samples > 1 ? " samples" + std::to_string(c.samples) : "");
    return os.str();
}

VkPipeline Renderer::Impl::shade_pipeline(const ShadeSpecialization& constants) {
    std::promise<VkPipeline> made;
    std::shared_future<VkPipeline> ready;
    bool mine = false;
    {
        const std::lock_guard<std::mutex> lock(shade_pipelines_mutex);
        PipelineSlot& slot = shade_pipelines[constants];
        if (!slot.ready.valid()) {
            slot.ready = made.get_future().share();
            mine = true;
        }
        ready = slot.ready;
    }
    if (!mine) return ready.get();  // made by another thread (its error rethrown here)
    // Compiled outside the lock: the variants of one renderer compile at once on several threads
    // (the layouts and shader modules they use are made with the renderer and never change; the
    // context's VkPipelineCache synchronizes itself).
    try {
        Unique<VkPipeline> pipeline;
        if (!compute) {
            pipeline = graphics_pipeline(constants);
        } else {
            const VkSpecializationInfo spec = spec_info(kShadeEntries, constants);
            pipeline = make_compute_pipeline(kShadeComp, sizeof(kShadeComp), compute_layout, &spec);
        }
        const VkPipeline handle = pipeline.get();
        {
            const std::lock_guard<std::mutex> lock(shade_pipelines_mutex);
            shade_pipelines[constants].owned = std::move(pipeline);
        }
        made.set_value(handle);
        return handle;
    } catch (...) {
        made.set_exception(std::current_exception());
        throw;
    }
}

Unique<VkPipeline> Renderer::Impl::graphics_pipeline(const ShadeSpecialization& constants) const {
    const VkSpecializationInfo spec = spec_info(kShadeEntries, constants);

    VkPipelineShaderStageCreateInfo stages[2]{};
    stages[0] = vk_struct<VkPipelineShaderStageCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO);
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = vert;
    stages[0].pName = "main";
    stages[1] = vk_struct<VkPipelineShaderStageCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO);
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = frag;
    stages[1].pName = "main";
    stages[1].pSpecializationInfo = &spec;

    const VkVertexInputBindingDescription binding{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX};
    auto attribute = [](int location, VkFormat format, size_t offset) {
        return VkVertexInputAttributeDescription{static_cast<uint32_t>(location), 0, format,
                                                 static_cast<uint32_t>(offset)};
    };
    const VkVertexInputAttributeDescription attributes[] = {
        attribute(gpu::kLocationPosition, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)),
        attribute(gpu::kLocationNormal, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal)),
        attribute(gpu::kLocationTangent, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, tangent)),
        attribute(gpu::kLocationUv, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv)),
    };
    auto vi =
        vk_struct<VkPipelineVertexInputStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO);
    vi.vertexBindingDescriptionCount = 1;
    vi.pVertexBindingDescriptions = &binding;
    vi.vertexAttributeDescriptionCount = 4;
    vi.pVertexAttributeDescriptions = attributes;
    auto ia =
        vk_struct<VkPipelineInputAssemblyStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO);
    ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    auto vp = vk_struct<VkPipelineViewportStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO);
    vp.viewportCount = 1;
    vp.scissorCount = 1;
    // Back faces culled (every shape is closed), but for a double-sided material: its back faces
    // are drawn first (record_raster sets the cull mode per draw); a depth test where culling is
    // not enough.
    auto rs =
        vk_struct<VkPipelineRasterizationStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO);
    rs.polygonMode = VK_POLYGON_MODE_FILL;
    rs.cullMode = VK_CULL_MODE_BACK_BIT;
    rs.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    rs.lineWidth = 1.f;
    auto dss =
        vk_struct<VkPipelineDepthStencilStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO);
    dss.depthTestEnable = uses_depth() ? VK_TRUE : VK_FALSE;
    dss.depthWriteEnable = uses_depth() ? VK_TRUE : VK_FALSE;
    dss.depthCompareOp = VK_COMPARE_OP_LESS;
    auto ms = vk_struct<VkPipelineMultisampleStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO);
    ms.rasterizationSamples = samples;
    VkPipelineColorBlendAttachmentState blend{};
    blend.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                           VK_COLOR_COMPONENT_A_BIT;
    if (constants.double_sided) {  // shade.frag writes premultiplied radiance: the far side shows through
        blend.blendEnable = VK_TRUE;
        blend.srcColorBlendFactor = VK_BLEND_FACTOR_ONE;
        blend.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
        blend.colorBlendOp = VK_BLEND_OP_ADD;
        blend.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
        blend.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
        blend.alphaBlendOp = VK_BLEND_OP_ADD;
    }
    auto cb = vk_struct<VkPipelineColorBlendStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO);
    cb.attachmentCount = 1;
    cb.pAttachments = &blend;
    const VkDynamicState dyn[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR, VK_DYNAMIC_STATE_CULL_MODE};
    auto ds = vk_struct<VkPipelineDynamicStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO);
    ds.dynamicStateCount = 3;
    ds.pDynamicStates = dyn;
    auto rendering = vk_struct<VkPipelineRenderingCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO);
    rendering.colorAttachmentCount = 1;
    rendering.pColorAttachmentFormats = &kTargetFormat;
    rendering.depthAttachmentFormat = uses_depth() ? kDepthFormat : VK_FORMAT_UNDEFINED;

    auto ci = vk_struct<VkGraphicsPipelineCreateInfo>(VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO);
    ci.pNext = &rendering;
    ci.stageCount = 2;
    ci.pStages = stages;
    ci.pVertexInputState = &vi;
    ci.pInputAssemblyState = &ia;
    ci.pViewportState = &vp;
    ci.pRasterizationState = &rs;
    ci.pMultisampleState = &ms;
    ci.pDepthStencilState = &dss;
    ci.pColorBlendState = &cb;
    ci.pDynamicState = &ds;
    ci.layout = shade_layout;
    VkPipeline h = VK_NULL_HANDLE;
    VK_CHECK(d.fn.vkCreateGraphicsPipelines(d.device, d.pipeline_cache, 1, &ci, nullptr, &h));
    return Unique<VkPipeline>(d, h);
}

}  // namespace mf::render
