// To the device: buffers, the mesh, textures with their mip chains, the placeholders bound
// where a variant samples nothing, and Renderer::upload (a material's textures and set).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <type_traits>

#include "base/parallel.hpp"
#include "base/stopwatch.hpp"
#include "render/internal.hpp"
#include "render/renderer_impl.hpp"

namespace mf::render {

using namespace detail;

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
    float bottom = 0.f;
    for (const Vertex& v : mesh.vertices) {
        bottom = std::min(bottom, v.position[1]);
        shape_radius = std::max(shape_radius, std::sqrt(v.position[0] * v.position[0] + v.position[1] * v.position[1] +
                                                        v.position[2] * v.position[2]));
    }
    ground_y = bottom - 1e-3f * scene.shape.size;
    if (!scene.ground.enabled) return;  // simulated only when asked
    // A square facing +Y at ground_y, 16 × the shape's size a side.
    const float half = 8.f * std::max(scene.shape.size, 1e-3f), y = ground_y;
    std::vector<Vertex> quad(4);
    for (int c = 0; c < 4; ++c) {
        const float u = (c == 1 || c == 2) ? 1.f : 0.f, v = c >= 2 ? 1.f : 0.f;
        quad[size_t(c)] =
            Vertex{{(2.f * u - 1.f) * half, y, (1.f - 2.f * v) * half}, {0.f, 1.f, 0.f}, {1.f, 0.f, 0.f, 1.f}, {u, v}};
    }
    const uint32_t quad_indices[] = {0, 1, 2, 0, 2, 3};  // counter-clockwise seen from above
    ground_vertices = upload_buffer(quad.data(), quad.size() * sizeof(Vertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    ground_indices = upload_buffer(quad_indices, sizeof quad_indices, VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
}

namespace {

// A level into mapped staging memory, in 1 MiB pieces on up to 4 threads: one thread's stores
// to the H200 host's upload memory ran at 6 GB/s, 1.9 ms of a 1K material's 5.8 ms
// (docs/bench/README.md, A library on the H200).
void copy_to_staging(uint8_t* to, const uint8_t* from, size_t bytes) {
    constexpr size_t kPiece = size_t{1} << 20;
    const size_t pieces = (bytes + kPiece - 1) / kPiece;
    parallel_for(pieces, 4, [&](size_t i) {
        const size_t at = i * kPiece;
        std::memcpy(to + at, from + at, std::min(kPiece, bytes - at));
    });
}

}  // namespace

ImageDesc Renderer::Impl::texture_desc(const PreparedTexture& t) {
    ImageDesc desc;
    desc.format = t.format;
    desc.width = t.levels[0].width;
    desc.height = t.levels[0].height;
    const auto given = static_cast<uint32_t>(t.levels.size());
    desc.mips = std::max(t.mips, given);  // past `given`: blitted on the device from the level above
    desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                 (desc.mips > given ? VkImageUsageFlags{VK_IMAGE_USAGE_TRANSFER_SRC_BIT} : VkImageUsageFlags{0});
    return desc;
}

Image Renderer::Impl::upload_texture(const PreparedTexture& prepared, VkCommandBuffer cmd,
                                     std::vector<Buffer>& staging) const {
    // An image past the device's size limit is undefined behaviour in Vulkan (a crash on
    // lavapipe): reduced to fit, or refused naming both sizes.
    std::optional<PreparedTexture> fitted;
    const uint32_t limit = d.properties.limits.maxImageDimension2D;
    if (!prepared.levels.empty() && std::max(prepared.levels[0].width, prepared.levels[0].height) > limit) {
        fitted = prepared;
        fit_to_device(d, *fitted, prepared.levels.size() == 1 ? "the environment image" : "texture");
    }
    const PreparedTexture& t = fitted ? *fitted : prepared;
    Stopwatch watch;
    Image img = create_image(d, texture_desc(t));
    host_times.images += watch.lap();
    record_texture(t, img, cmd, staging);
    return img;
}

void Renderer::Impl::record_texture(const PreparedTexture& t, const Image& img, VkCommandBuffer cmd,
                                    std::vector<Buffer>& staging) const {
    if (!t.note.empty()) notes.push_back(t.note);
    const ImageDesc& desc = img.desc;
    const auto given = static_cast<uint32_t>(t.levels.size());
    Stopwatch watch;
    VkDeviceSize total = 0;
    for (const TextureLevel& l : t.levels) total += (l.bytes.size() + 15) & ~VkDeviceSize{15};
    Buffer buf = take_staging(total);
    std::vector<VkBufferImageCopy> regions;
    VkDeviceSize offset = 0;
    for (uint32_t i = 0; i < t.levels.size(); ++i) {
        const TextureLevel& l = t.levels[i];
        copy_to_staging(static_cast<uint8_t*>(buf.mapped) + offset, l.bytes.data(), l.bytes.size());
        VkBufferImageCopy r{};
        r.bufferOffset = offset;
        r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, i, 0, 1};
        r.imageExtent = {l.width, l.height, 1};
        regions.push_back(r);
        offset += (l.bytes.size() + 15) & ~VkDeviceSize{15};
    }
    flush(d, buf);
    host_times.staging += watch.lap();
    // Every level a transfer destination: of the copy, and of the blits that make the rest.
    image_barrier(d, cmd, img.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                  VK_PIPELINE_STAGE_2_NONE, 0,
                  VK_PIPELINE_STAGE_2_COPY_BIT | (desc.mips > given ? VK_PIPELINE_STAGE_2_BLIT_BIT : 0),
                  VK_ACCESS_2_TRANSFER_WRITE_BIT);
    d.fn.vkCmdCopyBufferToImage(cmd, buf.buffer, img.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                static_cast<uint32_t>(regions.size()), regions.data());
    constexpr VkPipelineStageFlags2 kSampledBy = VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
                                                 VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    if (desc.mips > given) {
        if (given != 1) throw Error("internal: mips are made on the device from level 0 alone");
        // The rest of the chain on the device: each level blitted from the one above with a
        // linear filter (a 2×2 average at even sizes), which then turns into a source. The
        // levels given and the blitted ones end up sampled-read-only, each with its last writer.
        uint32_t w = desc.width, h = desc.height;
        for (uint32_t level = given; level < desc.mips; ++level) {
            const VkPipelineStageFlags2 writer = level - 1 < given ? VK_PIPELINE_STAGE_2_COPY_BIT
                                                                   : VK_PIPELINE_STAGE_2_BLIT_BIT;
            image_barrier(d, cmd, img.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                          writer, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_BLIT_BIT,
                          VK_ACCESS_2_TRANSFER_READ_BIT, level - 1, 1);
            const uint32_t nw = std::max(1u, w / 2), nh = std::max(1u, h / 2);
            VkImageBlit b{};
            b.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level - 1, 0, 1};
            b.srcOffsets[1] = {static_cast<int32_t>(w), static_cast<int32_t>(h), 1};
            b.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, 1};
            b.dstOffsets[1] = {static_cast<int32_t>(nw), static_cast<int32_t>(nh), 1};
            d.fn.vkCmdBlitImage(cmd, img.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, img.image,
                                VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &b, VK_FILTER_LINEAR);
            w = nw;
            h = nh;
        }
        image_barrier(d, cmd, img.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                      VK_PIPELINE_STAGE_2_BLIT_BIT, 0, kSampledBy, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, 0,
                      desc.mips - 1);
        image_barrier(d, cmd, img.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                      VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, kSampledBy,
                      VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, desc.mips - 1, 1);
    } else {
        image_barrier(d, cmd, img.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                      VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, kSampledBy,
                      VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    }
    staging.push_back(std::move(buf));
}

Buffer Renderer::Impl::take_staging(VkDeviceSize bytes) const {
    auto best = staging_free.end();
    for (auto it = staging_free.begin(); it != staging_free.end(); ++it)
        if (it->size >= bytes && (best == staging_free.end() || it->size < best->size)) best = it;
    if (best == staging_free.end()) return create_buffer(d, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    Buffer b = std::move(*best);
    staging_free.erase(best);
    return b;
}

void Renderer::Impl::keep_staging(std::vector<Buffer>& used) const {
    for (Buffer& b : used) staging_free.push_back(std::move(b));
    used.clear();
    // Smallest first; past the bound the largest go (a 4K or 8K library then allocates as before).
    std::sort(staging_free.begin(), staging_free.end(),
              [](const Buffer& a, const Buffer& b) { return a.size < b.size; });
    VkDeviceSize kept = 0;
    size_t n = 0;
    while (n < staging_free.size() && kept + staging_free[n].size <= kStagingKept) kept += staging_free[n++].size;
    staging_free.resize(n);
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
                  VK_ACCESS_2_TRANSFER_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                  VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    staging.push_back(std::move(buf));
    std::vector<PassTime> unused;
    s.finish(unused);
}

bool samples(Context& context, uint32_t block_format) {
    const Device& d = device_of(context);
    const BlockFormatDesc* f = block_format_desc(block_format);
    return f && d.supports(f->unorm, kSampledTextureFeatures) &&
           (f->srgb == VK_FORMAT_UNDEFINED || d.supports(f->srgb, kSampledTextureFeatures));
}

bool decodes_exactly(uint32_t block_format) {
    return block_format == VK_FORMAT_BC7_UNORM_BLOCK || block_format == VK_FORMAT_BC7_SRGB_BLOCK;
}

namespace {

// A material's roles and constants without its texels: copying the whole Material and then
// clearing `textures` would copy every texel first (tens of megabytes a material).
Material roles_of(const Material& m) {
    Material c;
    c.name = m.name;
    c.albedo = m.albedo;
    c.emissive = m.emissive;
    c.normal = m.normal;
    c.roughness = m.roughness;
    c.metalness = m.metalness;
    c.occlusion = m.occlusion;
    c.opacity = m.opacity;
    c.uv_scale = m.uv_scale;
    c.uv_offset = m.uv_offset;
    c.alpha_mode = m.alpha_mode;
    c.alpha_cutoff = m.alpha_cutoff;
    c.double_sided = m.double_sided;
    return c;
}

}  // namespace

PreparedMaterial::PreparedMaterial() = default;
PreparedMaterial::~PreparedMaterial() = default;
PreparedMaterial::PreparedMaterial(PreparedMaterial&&) noexcept = default;
PreparedMaterial& PreparedMaterial::operator=(PreparedMaterial&&) noexcept = default;
size_t PreparedMaterial::bytes() const {
    size_t n = 0;
    if (impl_)
        for (const auto& t : impl_->textures)
            if (t)
                for (const TextureLevel& l : t->levels) n += l.bytes.size();
    return n;
}

std::string PreparedMaterial::variant_key() const {
    if (!impl_) return {};
    static_assert(std::has_unique_object_representations_v<gpu::ShadeSpecialization>,
                  "no padding: its bytes are its value");
    const gpu::ShadeSpecialization& c = impl_->specialization;
    return {reinterpret_cast<const char*>(&c), sizeof c};
}

void Renderer::warm(const PreparedMaterial& prepared) {
    if (!prepared.impl_) return;
    Impl& r = *impl_;
    gpu::ShadeSpecialization c = prepared.impl_->specialization;
    r.place(c);
    r.shade_pipeline(c);
    if (r.scene.ground.enabled) r.shade_pipeline(Impl::ground_specialization(c));
}

PreparedMaterial Renderer::prepare(const Material& material) const {
    PreparedMaterial out;
    out.impl_ = prepare_material(impl_->d, impl_->scene, material);
    return out;
}

PreparedMaterial prepare(Context& context, const Scene& scene, const Material& material) {
    PreparedMaterial out;
    out.impl_ = prepare_material(device_of(context), scene, material);
    return out;
}

std::unique_ptr<PreparedMaterial::Impl> prepare_material(const Device& d, const Scene& scene,
                                                         const Material& material) {
    check_material(material);
    auto out = std::make_unique<PreparedMaterial::Impl>();
    PreparedMaterial::Impl& p = *out;
    p.device = &d;
    p.fast_textures = scene.fast_textures;
    p.constants = roles_of(material);
    gpu::ShadeSpecialization& c = p.specialization;
    c = scene_specialization(scene, material);
    const size_t n = material.textures.size();
    p.textures.resize(n);

    // The fast path stores a channel read inverted (smoothness, a DirectX normal's green) as its
    // complement and the shader reads it plainly: one surface in any channel layout then uploads
    // the same values, which 8-bit filtering and blitted mips treat alike. Not a channel that
    // another role reads plainly.
    struct Read {
        int32_t texture, channel;
        uint32_t* inverted;  // the variant's flag, cleared where the channel is stored inverted
    };
    uint32_t green_down = c.normal_green_down;
    const Read reads[] = {
        {c.roughness_tex, c.roughness_channel, &c.roughness_invert},
        {c.metalness_tex, c.metalness_channel, &c.metalness_invert},
        {c.occlusion_tex, c.occlusion_channel, &c.occlusion_invert},
        {c.opacity_tex, c.opacity_channel, &c.opacity_invert},
        {c.normal_tex, 1, &green_down},
    };
    std::vector<uint32_t> inverted_reads(n, 0), plain_reads(n, 0);
    for (const Read& rd : reads)
        if (rd.texture >= 0)
            (*rd.inverted ? inverted_reads : plain_reads)[static_cast<size_t>(rd.texture)] |= 1u << rd.channel;
    for (const int32_t slot : {c.albedo_tex, c.emissive_tex})
        if (slot >= 0) plain_reads[static_cast<size_t>(slot)] |= 7u;              // RGB
    if (c.normal_tex >= 0) plain_reads[static_cast<size_t>(c.normal_tex)] |= 5u;  // X and Z

    // Which textures the variant samples: the rest are not prepared nor uploaded at all.
    for (const int32_t slot : c.texture_slots()) {
        if (slot < 0 || p.textures[static_cast<size_t>(slot)]) continue;
        const auto i = static_cast<size_t>(slot);
        const Texture& t = material.textures[i];
        const MipKind kind = slot == material.normal.texture ? MipKind::normal
                             : t.srgb                        ? MipKind::color
                                                             : MipKind::data;
        p.textures[i] = prepare_texture(d, t, kind, scene.fast_textures,
                                        scene.fast_textures ? inverted_reads[i] & ~plain_reads[i] : 0);
    }
    for (const Read& rd : reads)
        if (rd.texture >= 0 && *rd.inverted &&
            ((p.textures[static_cast<size_t>(rd.texture)]->inverted >> rd.channel) & 1u))
            *rd.inverted = 0;
    c.normal_green_down = green_down;
    return out;
}

std::vector<Image> Renderer::Impl::material_images(const PreparedMaterial::Impl& p, GpuMaterial::Impl& m) const {
    // Every texture that fits the device in one block of the pool (placed at its alignment); any
    // other (too large: fitted by upload_texture; or no memory type common to all) on its own.
    const Stopwatch watch;
    std::vector<Image> images(p.textures.size());
    std::vector<VkDeviceSize> offsets(p.textures.size(), 0);
    const uint32_t limit = d.properties.limits.maxImageDimension2D;
    VkDeviceSize total = 0;
    uint32_t types = ~0u;
    for (size_t i = 0; i < p.textures.size(); ++i) {
        const PreparedTexture* t = p.textures[i] ? &*p.textures[i] : nullptr;
        if (!t || t->levels.empty() || std::max(t->levels[0].width, t->levels[0].height) > limit) continue;
        VkMemoryRequirements req{};
        images[i] = create_unbound_image(d, texture_desc(*t), req);
        offsets[i] = (total + req.alignment - 1) / req.alignment * req.alignment;
        total = offsets[i] + req.size;
        types &= req.memoryTypeBits;
    }
    const bool shared = total > 0 && types != 0 && (d.max_allocation == 0 || total <= d.max_allocation);
    if (shared) {
        m.blocks = blocks;
        m.block = blocks->take(total, d.memory_type(types, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT),
                               "material '" + p.constants.name + "''s textures");
        for (size_t i = 0; i < images.size(); ++i)
            if (images[i].image) bind_image(d, images[i], m.block.memory, offsets[i]);
    } else {
        for (Image& img : images) img = Image{};  // each made by upload_texture
    }
    host_times.images += watch.elapsed();
    return images;
}

void Renderer::Impl::retire_upload() {
    if (!pending_upload) return;
    pending_upload->submission->wait(load_times);
    host_times.upload_device += load_times.back().ms * 1e-3;
    keep_staging(pending_upload->staging);
    pending_upload.reset();
}

GpuMaterial::Impl::~Impl() {
    if (uploaded && owner) {  // done unless freed before any render() (or upload()) followed
        const VkFence f = *uploaded;
        owner->d.fn.vkWaitForFences(owner->d.device, 1, &f, VK_TRUE, UINT64_MAX);
    }
    textures.clear();  // unbound before the block goes back
    if (blocks) blocks->keep(std::move(block));
}

GpuMaterial Renderer::upload(const Material& material) { return upload(prepare(material)); }

GpuMaterial Renderer::upload(PreparedMaterial prepared) {
    Impl& r = *impl_;
    const Device& d = r.d;
    if (!prepared.impl_) throw Error("upload of an empty PreparedMaterial");
    PreparedMaterial::Impl& p = *prepared.impl_;
    // Prepared by render::prepare before this renderer existed, or by another renderer: its
    // textures must be this device's formats read as this scene reads them, and its variant this
    // scene's (all but the channels stored inverted, which prepare decided from the texels).
    gpu::ShadeSpecialization expect = r.specialization(p.constants);
    r.place(p.specialization);
    for (auto field : {&gpu::ShadeSpecialization::roughness_invert, &gpu::ShadeSpecialization::metalness_invert,
                       &gpu::ShadeSpecialization::occlusion_invert, &gpu::ShadeSpecialization::opacity_invert,
                       &gpu::ShadeSpecialization::normal_green_down})
        expect.*field = p.specialization.*field;
    if (p.device != &d || p.fast_textures != r.scene.fast_textures || expect != p.specialization)
        throw Error("material '" + p.constants.name + "' was prepared for another device or scene");
    GpuMaterial out;
    out.impl_ = std::make_unique<GpuMaterial::Impl>();
    GpuMaterial::Impl& m = *out.impl_;
    m.owner = impl_.get();
    m.name = p.constants.name;
    m.constants = std::move(p.constants);

    const Stopwatch whole;
    const HostTimes before = r.host_times;
    Stopwatch watch;
    m.variant = r.describe(p.specialization);
    m.pipeline = r.shade_pipeline(p.specialization);
    if (r.scene.ground.enabled) m.ground_pipeline = r.shade_pipeline(Impl::ground_specialization(p.specialization));
    r.host_times.pipelines += watch.lap();

    Stopwatch part;
    r.retire_upload();  // its query pool and staging buffers are this upload's to use
    r.host_times.upload_retire += part.elapsed();
    std::vector<Buffer> staging;
    auto submission = std::make_unique<Submission>(d, r.command_pool, r.upload_queries, kQueryCount);
    Submission& s = *submission;
    s.begin_pass("upload " + m.name);
    m.textures = r.material_images(p, m);
    for (size_t i = 0; i < p.textures.size(); ++i)
        if (p.textures[i]) {
            if (m.textures[i].image) r.record_texture(*p.textures[i], m.textures[i], s.cmd(), staging);
            else m.textures[i] = r.upload_texture(*p.textures[i], s.cmd(), staging);
            p.textures[i].reset();  // its host copy is in the staging buffer now
        }
    part.lap();
    s.submit();
    r.host_times.upload_submit += part.elapsed();
    m.uploaded = s.fence();
    r.pending_upload = Impl::PendingUpload{std::move(submission), std::move(staging)};

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
    w.dstBinding = static_cast<uint32_t>(gpu::kBindingMaterialTextures);
    w.descriptorCount = static_cast<uint32_t>(kMaxTextures);
    w.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    w.pImageInfo = infos.data();
    d.fn.vkUpdateDescriptorSets(d.device, 1, &w, 0, nullptr);
    HostTimes& t = r.host_times;
    t.upload_rest += whole.elapsed() - (t.pipelines - before.pipelines) - (t.images - before.images) -
                     (t.staging - before.staging);
    return out;
}

}  // namespace mf::render
