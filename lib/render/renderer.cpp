// The preview renderer: one shading pass into a linear fp32 target, one encoding pass, readback.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <numbers>
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
constexpr uint32_t kEncodeComp[] =
#include "shaders/encode.comp.inc"
    ;

constexpr VkFormat kTargetFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
constexpr uint32_t kQueryCount = 16;  // two timestamps for each of up to 8 passes

// Mirrors FrameData in shaders/common.glsl (std140: vec4s and a mat4 only).
struct FrameData {
    float view_proj[16];  // column-major
    float camera_position[4];
    float ray_right[4];
    float ray_up[4];
    float ray_forward[4];
    float viewport[4];
    float background[4];
    float albedo[4];
    float emissive[4];
    float scalars[4];
    float shape[4];
    float lights[kMaxLights][8];
};
static_assert(sizeof(FrameData) == 64 + 10 * 16 + kMaxLights * 32, "std140 layout");

struct EncodeParams {
    uint32_t size[2];
    float exposure;
    uint32_t srgb;
};

using D3 = std::array<double, 3>;
D3 d3(const Vec3& v) { return {v[0], v[1], v[2]}; }
D3 sub(const D3& a, const D3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const D3& a, const D3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
D3 cross(const D3& a, const D3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
D3 normalized(const D3& a) {
    const double l = std::sqrt(dot(a, a));
    if (!(l > 0)) throw Error("degenerate vector in the scene (zero length)");
    return {a[0] / l, a[1] / l, a[2] / l};
}
void put(float* dst, const D3& v, double w = 0.0) {
    for (int i = 0; i < 3; ++i) dst[i] = static_cast<float>(v[i]);
    dst[3] = static_cast<float>(w);
}

const char* role_text(int texture) { return texture >= 0 ? "tex" : "const"; }

}  // namespace

std::optional<Brdf> parse_brdf(std::string_view s) {
    if (s == "standard") return Brdf::Standard;
    if (s == "accurate") return Brdf::Accurate;
    if (s == "assignment") return Brdf::Assignment;
    return std::nullopt;
}

void check_material(const Material& m) {
    const auto n = static_cast<int>(m.textures.size());
    if (m.textures.size() > kMaxTextures)
        throw Error("material '" + m.name + "' has more than " + std::to_string(kMaxTextures) + " textures");
    auto check_index = [&](int t, const char* role) {
        if (t >= n) throw Error("material '" + m.name + "': " + role + " names texture " + std::to_string(t) + " of " + std::to_string(n));
    };
    check_index(m.albedo.texture, "albedo");
    check_index(m.emissive.texture, "emissive");
    check_index(m.normal.texture, "normal");
    const std::pair<const ScalarRole*, const char*> scalars[] = {
        {&m.roughness, "roughness"}, {&m.metalness, "metalness"}, {&m.occlusion, "occlusion"}, {&m.opacity, "opacity"}};
    for (auto [r, name] : scalars) {
        check_index(r->texture, name);
        // RGB of an sRGB texture are decoded by the sampler: only its alpha holds plain data.
        if (r->texture >= 0 && m.textures[static_cast<size_t>(r->texture)].srgb && r->channel != Channel::A)
            throw Error("material '" + m.name + "': " + name + " is read from a color channel of an sRGB texture");
    }
    if (m.normal.texture >= 0 && m.textures[static_cast<size_t>(m.normal.texture)].srgb)
        throw Error("material '" + m.name + "': the normal map is marked sRGB");
}

// ---------------------------------------------------------------------------------------------

GpuMaterial::GpuMaterial() = default;
GpuMaterial::~GpuMaterial() = default;
GpuMaterial::GpuMaterial(GpuMaterial&&) noexcept = default;
GpuMaterial& GpuMaterial::operator=(GpuMaterial&&) noexcept = default;
const std::string& GpuMaterial::name() const { return impl_->name; }
const std::string& GpuMaterial::variant() const { return impl_->variant; }

Renderer::Impl::Impl(Context& context, Scene s) : d(device_of(context)), scene(std::move(s)) {
    if (scene.width == 0 || scene.height == 0 || scene.width > 16384 || scene.height > 16384)
        throw Error("image size must be 1..16384 pixels a side");
    if (scene.lights.size() > kMaxLights)
        throw Error("at most " + std::to_string(kMaxLights) + " lights");
    if (!d.supports(kTargetFormat, VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT | VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT))
        throw NoDeviceError(d.info.name + " cannot render to RGBA32F");

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
    }

    create_samplers();
    create_layouts();
    create_targets();
    upload_mesh();
    create_dummies();
    build_environment();  // BRDF table and environment maps, only when the scene calls for them
    write_frame_descriptors();
}

Renderer::Impl::~Impl() {
    if (d.device) d.fn.vkDeviceWaitIdle(d.device);
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

Unique<VkDescriptorSetLayout> Renderer::Impl::make_set_layout(
    const std::vector<VkDescriptorSetLayoutBinding>& bindings) const {
    auto ci = vk_struct<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
    ci.bindingCount = static_cast<uint32_t>(bindings.size());
    ci.pBindings = bindings.data();
    VkDescriptorSetLayout h = VK_NULL_HANDLE;
    VK_CHECK(d.fn.vkCreateDescriptorSetLayout(d.device, &ci, nullptr, &h));
    return Unique<VkDescriptorSetLayout>(d, h);
}

Unique<VkPipelineLayout> Renderer::Impl::make_pipeline_layout(
    const std::vector<VkDescriptorSetLayout>& sets, uint32_t push_bytes, VkShaderStageFlags push_stages) const {
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

Unique<VkPipeline> Renderer::Impl::make_compute_pipeline(const uint32_t* code, size_t bytes,
                                                         VkPipelineLayout layout,
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
    VK_CHECK(d.fn.vkCreateComputePipelines(d.device, VK_NULL_HANDLE, 1, &ci, nullptr, &h));
    return Unique<VkPipeline>(d, h);
}

void Renderer::Impl::create_layouts() {
    constexpr auto kFrag = VK_SHADER_STAGE_FRAGMENT_BIT;
    frame_layout = make_set_layout({
        {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_VERTEX_BIT | kFrag, nullptr},
        {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, kFrag, nullptr},
        {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, kFrag, nullptr},
        {3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, kFrag, nullptr},
    });
    material_layout = make_set_layout({
        {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, static_cast<uint32_t>(kMaxTextures), kFrag, nullptr},
    });
    encode_set_layout = make_set_layout({
        {0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
        {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
    });
    shade_layout = make_pipeline_layout({frame_layout, material_layout}, 0, 0);
    encode_layout = make_pipeline_layout({encode_set_layout}, sizeof(EncodeParams), VK_SHADER_STAGE_COMPUTE_BIT);
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

VkDescriptorSet Renderer::Impl::allocate_set(VkDescriptorPool pool, VkDescriptorSetLayout layout) const {
    auto ai = vk_struct<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
    ai.descriptorPool = pool;
    ai.descriptorSetCount = 1;
    ai.pSetLayouts = &layout;
    VkDescriptorSet set = VK_NULL_HANDLE;
    VK_CHECK(d.fn.vkAllocateDescriptorSets(d.device, &ai, &set));
    return set;
}

void Renderer::Impl::create_targets() {
    ImageDesc td;
    td.format = kTargetFormat;
    td.width = scene.width;
    td.height = scene.height;
    td.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    target = create_image(d, td);
    readback = create_buffer(d, VkDeviceSize{scene.width} * scene.height * 16,
                             VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    uniforms = create_buffer(d, sizeof(FrameData), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);

    VkDescriptorImageInfo ii{VK_NULL_HANDLE, target.view, VK_IMAGE_LAYOUT_GENERAL};
    VkDescriptorBufferInfo bi{readback.buffer, 0, VK_WHOLE_SIZE};
    VkWriteDescriptorSet w[2]{};
    w[0] = vk_struct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
    w[0].dstSet = encode_set;
    w[0].dstBinding = 0;
    w[0].descriptorCount = 1;
    w[0].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    w[0].pImageInfo = &ii;
    w[1] = vk_struct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
    w[1].dstSet = encode_set;
    w[1].dstBinding = 1;
    w[1].descriptorCount = 1;
    w[1].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    w[1].pBufferInfo = &bi;
    d.fn.vkUpdateDescriptorSets(d.device, 2, w, 0, nullptr);
}

// Not const, though it would compile so: it allocates, submits and frees a command buffer of the renderer's own
// command pool, which Vulkan requires externally synchronized; const would read as safe to call concurrently.
// NOLINTNEXTLINE(readability-make-member-function-const): mutates the renderer's command pool (see above)
Buffer Renderer::Impl::upload_buffer(const void* data, VkDeviceSize bytes, VkBufferUsageFlags usage) {
    Buffer staging = create_buffer(d, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    std::memcpy(staging.mapped, data, bytes);
    flush(d, staging);
    Buffer dst = create_buffer(d, bytes, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, false);
    Submission s(d, command_pool, VK_NULL_HANDLE, 0);
    VkBufferCopy region{0, 0, bytes};
    d.fn.vkCmdCopyBuffer(s.cmd(), staging.buffer, dst.buffer, 1, &region);
    std::vector<PassTime> unused;
    s.finish(unused);  // the fence wait orders the copy before any later submission's reads
    return dst;
}

void Renderer::Impl::upload_mesh() {
    const Mesh mesh = make_shape(scene.shape);
    vertices = upload_buffer(mesh.vertices.data(), mesh.vertices.size() * sizeof(Vertex),
                             VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    indices = upload_buffer(mesh.indices.data(), mesh.indices.size() * sizeof(uint32_t),
                            VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
    index_count = static_cast<uint32_t>(mesh.indices.size());
}

Image Renderer::Impl::upload_texture(const PreparedTexture& t, VkCommandBuffer cmd,
                                     std::vector<Buffer>& staging) const {
    ImageDesc desc;
    desc.format = t.format;
    desc.width = t.levels[0].width;
    desc.height = t.levels[0].height;
    desc.mips = static_cast<uint32_t>(t.levels.size());
    desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    Image img = create_image(d, desc);

    VkDeviceSize total = 0;
    for (const TextureLevel& l : t.levels) total += (l.bytes.size() + 15) & ~VkDeviceSize{15};
    Buffer buf = create_buffer(d, total, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    std::vector<VkBufferImageCopy> regions;
    VkDeviceSize offset = 0;
    for (uint32_t i = 0; i < t.levels.size(); ++i) {
        const TextureLevel& l = t.levels[i];
        std::memcpy(static_cast<uint8_t*>(buf.mapped) + offset, l.bytes.data(), l.bytes.size());
        VkBufferImageCopy r{};
        r.bufferOffset = offset;
        r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, i, 0, 1};
        r.imageExtent = {l.width, l.height, 1};
        regions.push_back(r);
        offset += (l.bytes.size() + 15) & ~VkDeviceSize{15};
    }
    flush(d, buf);
    image_barrier(d, cmd, img.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                  VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    d.fn.vkCmdCopyBufferToImage(cmd, buf.buffer, img.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                static_cast<uint32_t>(regions.size()), regions.data());
    image_barrier(d, cmd, img.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                  VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
                  VK_ACCESS_2_TRANSFER_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                  VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    staging.push_back(std::move(buf));
    return img;
}

void Renderer::Impl::create_dummies() {
    // Bound wherever a variant samples nothing, so that every descriptor is valid.
    PreparedTexture flat;
    flat.format = VK_FORMAT_R8G8B8A8_UNORM;
    flat.levels.push_back({1, 1, {128, 128, 255, 255}});
    PreparedTexture cube;
    cube.format = VK_FORMAT_R8G8B8A8_UNORM;
    cube.levels.push_back({1, 1, {0, 0, 0, 255}});

    std::vector<Buffer> staging;
    Submission s(d, command_pool, VK_NULL_HANDLE, 0);
    dummy_2d = upload_texture(flat, s.cmd(), staging);

    ImageDesc cd;
    cd.format = VK_FORMAT_R8G8B8A8_UNORM;
    cd.layers = 6;
    cd.cube = true;
    cd.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    dummy_cube = create_image(d, cd);
    Buffer buf = create_buffer(d, 6 * 4, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    std::memset(buf.mapped, 0, 24);
    flush(d, buf);
    image_barrier(d, s.cmd(), dummy_cube.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                  VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    VkBufferImageCopy r{};
    r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 6};
    r.imageExtent = {1, 1, 1};
    d.fn.vkCmdCopyBufferToImage(s.cmd(), buf.buffer, dummy_cube.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &r);
    image_barrier(d, s.cmd(), dummy_cube.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                  VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
                  VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                  VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    staging.push_back(std::move(buf));
    std::vector<PassTime> unused;
    s.finish(unused);
}

void Renderer::Impl::write_frame_descriptors() {
    VkDescriptorBufferInfo ub{uniforms.buffer, 0, sizeof(FrameData)};
    const bool lut = static_cast<bool>(brdf_lut.view);
    const bool env = static_cast<bool>(env_specular.view);
    VkDescriptorImageInfo images[3] = {
        {sampler_clamp, lut ? brdf_lut.view.get() : dummy_2d.view.get(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
        {sampler_clamp, env ? env_specular.view.get() : dummy_cube.view.get(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
        {sampler_clamp, env ? env_irradiance.view.get() : dummy_cube.view.get(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
    };
    VkWriteDescriptorSet w[4]{};
    for (uint32_t i = 0; i < 4; ++i) {
        w[i] = vk_struct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
        w[i].dstSet = frame_set;
        w[i].dstBinding = i;
        w[i].descriptorCount = 1;
        if (i == 0) {
            w[i].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
            w[i].pBufferInfo = &ub;
        } else {
            w[i].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
            w[i].pImageInfo = &images[i - 1];
        }
    }
    d.fn.vkUpdateDescriptorSets(d.device, 4, w, 0, nullptr);
}

VkPipeline Renderer::Impl::shade_pipeline(const std::vector<int32_t>& constants) {
    auto it = shade_pipelines.find(constants);
    if (it != shade_pipelines.end()) return it->second;

    std::vector<VkSpecializationMapEntry> entries(constants.size());
    for (uint32_t i = 0; i < entries.size(); ++i) entries[i] = {i, 4 * i, 4};
    VkSpecializationInfo spec{static_cast<uint32_t>(entries.size()), entries.data(),
                              constants.size() * sizeof(int32_t), constants.data()};

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
    const VkVertexInputAttributeDescription attributes[] = {
        {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)},
        {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal)},
        {2, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, tangent)},
        {3, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv)},
    };
    auto vi = vk_struct<VkPipelineVertexInputStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO);
    vi.vertexBindingDescriptionCount = 1;
    vi.pVertexBindingDescriptions = &binding;
    vi.vertexAttributeDescriptionCount = 4;
    vi.pVertexAttributeDescriptions = attributes;
    auto ia = vk_struct<VkPipelineInputAssemblyStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO);
    ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    auto vp = vk_struct<VkPipelineViewportStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO);
    vp.viewportCount = 1;
    vp.scissorCount = 1;
    // The shapes are convex: culling back faces is all the visibility they need (no depth buffer).
    auto rs = vk_struct<VkPipelineRasterizationStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO);
    rs.polygonMode = VK_POLYGON_MODE_FILL;
    rs.cullMode = VK_CULL_MODE_BACK_BIT;
    rs.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    rs.lineWidth = 1.f;
    auto ms = vk_struct<VkPipelineMultisampleStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO);
    ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineColorBlendAttachmentState blend{};
    blend.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                           VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
    auto cb = vk_struct<VkPipelineColorBlendStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO);
    cb.attachmentCount = 1;
    cb.pAttachments = &blend;
    const VkDynamicState dyn[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    auto ds = vk_struct<VkPipelineDynamicStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO);
    ds.dynamicStateCount = 2;
    ds.pDynamicStates = dyn;
    auto rendering = vk_struct<VkPipelineRenderingCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO);
    rendering.colorAttachmentCount = 1;
    rendering.pColorAttachmentFormats = &kTargetFormat;

    auto ci = vk_struct<VkGraphicsPipelineCreateInfo>(VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO);
    ci.pNext = &rendering;
    ci.stageCount = 2;
    ci.pStages = stages;
    ci.pVertexInputState = &vi;
    ci.pInputAssemblyState = &ia;
    ci.pViewportState = &vp;
    ci.pRasterizationState = &rs;
    ci.pMultisampleState = &ms;
    ci.pColorBlendState = &cb;
    ci.pDynamicState = &ds;
    ci.layout = shade_layout;
    VkPipeline h = VK_NULL_HANDLE;
    VK_CHECK(d.fn.vkCreateGraphicsPipelines(d.device, VK_NULL_HANDLE, 1, &ci, nullptr, &h));
    return shade_pipelines.emplace(constants, Unique<VkPipeline>(d, h)).first->second;
}

std::vector<int32_t> Renderer::Impl::variant_constants(const Material& m, std::string& description) const {
    int32_t dirs = 0, points = 0;
    for (const Light& l : scene.lights) (l.type == LightType::Directional ? dirs : points)++;
    const bool env = static_cast<bool>(scene.environment);
    auto scalar = [](const ScalarRole& r, std::vector<int32_t>& c) {
        c.push_back(r.texture);
        c.push_back(static_cast<int32_t>(r.channel));
        c.push_back(r.invert ? 1 : 0);
    };
    std::vector<int32_t> c = {dirs,
                              points,
                              static_cast<int32_t>(scene.brdf),
                              scene.shape.type == ShapeType::Sphere ? 1 : 0,
                              env ? 1 : 0,
                              m.albedo.texture,
                              m.emissive.texture,
                              m.normal.texture,
                              m.normal.green_down ? 1 : 0};
    scalar(m.roughness, c);
    scalar(m.metalness, c);
    // Occlusion only darkens light from the environment: without one it is never sampled.
    ScalarRole occlusion = m.occlusion;
    if (!env) occlusion.texture = -1;
    scalar(occlusion, c);
    scalar(m.opacity, c);

    static const char* const brdf_names[] = {"standard", "accurate", "assignment"};
    static const char* const shape_names[] = {"sphere", "cube", "plane"};
    std::ostringstream os;
    os << shape_names[static_cast<int>(scene.shape.type)] << ' ' << brdf_names[static_cast<int>(scene.brdf)]
       << " dir" << dirs << " point" << points << (env ? " env" : "") << " albedo:" << role_text(m.albedo.texture)
       << " normal:" << (m.normal.texture >= 0 ? (m.normal.green_down ? "dx" : "gl") : "none")
       << " roughness:" << role_text(m.roughness.texture) << " metalness:" << role_text(m.metalness.texture);
    if (m.emissive.texture >= 0) os << " emissive:tex";
    if (m.opacity.texture >= 0) os << " opacity:tex";
    if (env && m.occlusion.texture >= 0) os << " occlusion:tex";
    description = os.str();
    return c;
}

void Renderer::Impl::write_frame(const Material& m) {
    FrameData f{};
    const D3 pos = d3(scene.camera.position);
    const D3 fwd = normalized(sub(d3(scene.camera.target), pos));
    const D3 right = normalized(cross(fwd, d3(scene.camera.up)));
    const D3 up = cross(right, fwd);
    const double aspect = static_cast<double>(scene.width) / scene.height;
    const double tan_half = std::tan(scene.camera.yfov_deg * std::numbers::pi / 360.0);
    if (!(scene.camera.yfov_deg > 0.f && scene.camera.yfov_deg < 180.f))
        throw Error("camera yfov_deg must be in (0, 180)");

    // view: rows right, up, −forward; projection: Vulkan clip space (y down, depth 0..1),
    // the image's top row looking along +up. Column-major for GLSL.
    const double near_plane = 0.01, far_plane = 1000.0;
    const double view[4][4] = {{right[0], right[1], right[2], -dot(right, pos)},
                               {up[0], up[1], up[2], -dot(up, pos)},
                               {-fwd[0], -fwd[1], -fwd[2], dot(fwd, pos)},
                               {0, 0, 0, 1}};
    const double fy = 1.0 / tan_half;
    const double proj[4][4] = {{fy / aspect, 0, 0, 0},
                               {0, -fy, 0, 0},
                               {0, 0, far_plane / (near_plane - far_plane), near_plane * far_plane / (near_plane - far_plane)},
                               {0, 0, -1, 0}};
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) {
            double v = 0;
            for (int k = 0; k < 4; ++k) v += proj[r][k] * view[k][c];
            f.view_proj[c * 4 + r] = static_cast<float>(v);
        }
    put(f.camera_position, pos, 1.0);
    put(f.ray_right, {right[0] * tan_half * aspect, right[1] * tan_half * aspect, right[2] * tan_half * aspect});
    put(f.ray_up, {up[0] * tan_half, up[1] * tan_half, up[2] * tan_half});
    put(f.ray_forward, fwd);
    f.viewport[0] = static_cast<float>(scene.width);
    f.viewport[1] = static_cast<float>(scene.height);
    f.viewport[2] = 1.f / static_cast<float>(scene.width);
    f.viewport[3] = 1.f / static_cast<float>(scene.height);
    put(f.background, d3(scene.background), 1.0);
    put(f.albedo, d3(m.albedo.value), 1.0);
    put(f.emissive, d3(m.emissive.value), 1.0);
    f.scalars[0] = m.roughness.value;
    f.scalars[1] = m.metalness.value;
    f.scalars[2] = m.occlusion.value;
    f.scalars[3] = m.opacity.value;
    f.shape[0] = scene.shape.size;
    f.shape[1] = scene.environment ? scene.environment->intensity : 0.f;
    f.shape[2] = static_cast<float>(env_specular_mips > 0 ? env_specular_mips - 1 : 0);

    // Directional lights first, then point lights: the order the shader's loop expects.
    size_t slot = 0;
    for (int pass = 0; pass < 2; ++pass)
        for (const Light& l : scene.lights) {
            if ((pass == 0) != (l.type == LightType::Directional)) continue;
            float* dst = f.lights[slot++];
            if (l.type == LightType::Directional) {
                const D3 dir = normalized(d3(l.direction));
                put(dst, {-dir[0], -dir[1], -dir[2]}, 0.0);
            } else {
                put(dst, d3(l.position), 1.0);
            }
            put(dst + 4, {double{l.color[0]} * l.intensity, double{l.color[1]} * l.intensity,
                          double{l.color[2]} * l.intensity});
        }
    std::memcpy(uniforms.mapped, &f, sizeof f);
    flush(d, uniforms);
}

// ---------------------------------------------------------------------------------------------

Renderer::Renderer(Context& context, const Scene& scene)
    : impl_(std::make_unique<Impl>(context, scene)) {}
Renderer::~Renderer() = default;
const Scene& Renderer::scene() const { return impl_->scene; }
const std::vector<PassTime>& Renderer::load_times() const { return impl_->load_times; }
const std::vector<PassTime>& Renderer::frame_times() const { return impl_->frame_times; }

GpuMaterial Renderer::upload(const Material& material) {
    check_material(material);
    Impl& r = *impl_;
    const Device& d = r.d;
    GpuMaterial out;
    out.impl_ = std::make_unique<GpuMaterial::Impl>();
    GpuMaterial::Impl& m = *out.impl_;
    m.owner = impl_.get();
    m.name = material.name;
    m.constants = material;
    m.constants.textures.clear();
    m.constants.textures.shrink_to_fit();

    const std::vector<int32_t> constants = r.variant_constants(material, m.variant);
    m.pipeline = r.shade_pipeline(constants);

    // Which textures the variant samples: the rest are not uploaded at all.
    std::vector<bool> used(material.textures.size(), false);
    for (size_t i = 5; i < constants.size(); ++i) {
        const bool is_texture_slot = i == 5 || i == 6 || i == 7 || i == 9 || i == 12 || i == 15 || i == 18;
        if (is_texture_slot && constants[i] >= 0) used[static_cast<size_t>(constants[i])] = true;
    }

    std::vector<Buffer> staging;
    Submission s(d, r.command_pool, r.queries, kQueryCount);
    s.begin_pass("upload " + material.name);
    m.textures.resize(material.textures.size());
    for (size_t i = 0; i < material.textures.size(); ++i) {
        if (!used[i]) continue;
        const Texture& t = material.textures[i];
        const MipKind kind = static_cast<int>(i) == material.normal.texture ? MipKind::Normal
                             : t.srgb                                        ? MipKind::Color
                                                                             : MipKind::Data;
        m.textures[i] = r.upload_texture(prepare_texture(d, t, kind), s.cmd(), staging);
    }
    s.finish(r.load_times);

    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, static_cast<uint32_t>(kMaxTextures)};
    auto pci = vk_struct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
    pci.maxSets = 1;
    pci.poolSizeCount = 1;
    pci.pPoolSizes = &size;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VK_CHECK(d.fn.vkCreateDescriptorPool(d.device, &pci, nullptr, &pool));
    m.pool = Unique<VkDescriptorPool>(d, pool);
    m.set = r.allocate_set(pool, r.material_layout);
    std::vector<VkDescriptorImageInfo> infos(kMaxTextures);
    for (size_t i = 0; i < kMaxTextures; ++i) {
        const bool have = i < m.textures.size() && m.textures[i].view;
        infos[i] = {r.sampler_repeat, have ? m.textures[i].view.get() : r.dummy_2d.view.get(),
                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    }
    auto w = vk_struct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
    w.dstSet = m.set;
    w.dstBinding = 0;
    w.descriptorCount = static_cast<uint32_t>(kMaxTextures);
    w.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    w.pImageInfo = infos.data();
    d.fn.vkUpdateDescriptorSets(d.device, 1, &w, 0, nullptr);
    return out;
}

Frame Renderer::render(const GpuMaterial& material, const OutputOptions& output) {
    Impl& r = *impl_;
    const Device& d = r.d;
    const GpuMaterial::Impl& m = material.impl();
    if (m.owner != impl_.get()) throw Error("material '" + m.name + "' was uploaded by another renderer");
    const uint32_t w = r.scene.width, h = r.scene.height;
    r.write_frame(m.constants);
    r.frame_times.clear();

    Submission s(d, r.command_pool, r.queries, kQueryCount);
    VkCommandBuffer cmd = s.cmd();
    // The previous frame read the target (encode or copy); this one overwrites it.
    image_barrier(d, cmd, r.target.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                  VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT, 0,
                  VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);

    s.begin_pass("shade");
    auto att = vk_struct<VkRenderingAttachmentInfo>(VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO);
    att.imageView = r.target.view;
    att.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    att.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    att.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    att.clearValue.color = {{r.scene.background[0], r.scene.background[1], r.scene.background[2], 1.f}};
    auto ri = vk_struct<VkRenderingInfo>(VK_STRUCTURE_TYPE_RENDERING_INFO);
    ri.renderArea = {{0, 0}, {w, h}};
    ri.layerCount = 1;
    ri.colorAttachmentCount = 1;
    ri.pColorAttachments = &att;
    d.fn.vkCmdBeginRendering(cmd, &ri);
    d.fn.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, m.pipeline);
    const VkViewport viewport{0.f, 0.f, static_cast<float>(w), static_cast<float>(h), 0.f, 1.f};
    const VkRect2D scissor{{0, 0}, {w, h}};
    d.fn.vkCmdSetViewport(cmd, 0, 1, &viewport);
    d.fn.vkCmdSetScissor(cmd, 0, 1, &scissor);
    const VkDescriptorSet sets[] = {r.frame_set, m.set};
    d.fn.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, r.shade_layout, 0, 2, sets, 0, nullptr);
    const VkDeviceSize zero = 0;
    const VkBuffer vb = r.vertices.buffer;
    d.fn.vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &zero);
    d.fn.vkCmdBindIndexBuffer(cmd, r.indices.buffer, 0, VK_INDEX_TYPE_UINT32);
    d.fn.vkCmdDrawIndexed(cmd, r.index_count, 1, 0, 0, 0);
    d.fn.vkCmdEndRendering(cmd);
    s.end_pass();

    if (output.format == PixelFormat::Rgba8) {
        image_barrier(d, cmd, r.target.image, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL,
                      VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
        s.begin_pass("encode");
        d.fn.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r.encode_pipeline);
        d.fn.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r.encode_layout, 0, 1, &r.encode_set, 0, nullptr);
        const EncodeParams params{{w, h}, output.exposure, output.transfer == Transfer::Srgb ? 1u : 0u};
        d.fn.vkCmdPushConstants(cmd, r.encode_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof params, &params);
        d.fn.vkCmdDispatch(cmd, (w + 7) / 8, (h + 7) / 8, 1);
        s.end_pass();
        memory_barrier(d, cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    } else {
        image_barrier(d, cmd, r.target.image, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                      VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                      VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                      VK_ACCESS_2_TRANSFER_READ_BIT);
        s.begin_pass("readback");
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {w, h, 1};
        d.fn.vkCmdCopyImageToBuffer(cmd, r.target.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, r.readback.buffer, 1, &region);
        s.end_pass();
        memory_barrier(d, cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    }
    s.finish(r.frame_times);
    invalidate(d, r.readback);

    Frame frame;
    frame.width = w;
    frame.height = h;
    const size_t n = size_t{w} * h * 4;
    if (output.format == PixelFormat::Rgba8) {
        frame.rgba8.resize(n);
        std::memcpy(frame.rgba8.data(), r.readback.mapped, n);
    } else {
        frame.rgba32f.resize(n);
        std::memcpy(frame.rgba32f.data(), r.readback.mapped, n * sizeof(float));
    }
    return frame;
}

}  // namespace mf::render
