// Export (render.hpp, last block): the state another renderer of the same shaders needs, read
// from this renderer as it draws: the shading variant and uniform block of a material, the
// image-based-lighting maps read back from the device, the shape's mesh.
#include <algorithm>
#include <cstddef>
#include <cstring>
#include <iterator>

#include "render/internal.hpp"
#include "render/renderer_impl.hpp"

namespace mf::render {

using namespace detail;

namespace {

constexpr uint32_t kExportComp[] =
#include "shaders/export.comp.inc"
    ;

using gpu::ShadeSpecialization;

// Reads every mip of `img` (a 2D image or a cube, sampled in SHADER_READ_ONLY_OPTIMAL, as the
// load-time passes leave their maps) through export.comp.
class ImageReader {
public:
    explicit ImageReader(const Renderer::Impl& r) : r_(r) {
        set_layout_ = r.make_set_layout({
            {static_cast<uint32_t>(gpu::kBindingExportSource), VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
             VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
            {static_cast<uint32_t>(gpu::kBindingExportTexels), VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1,
             VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
        });
        layout_ = r.make_pipeline_layout({set_layout_}, sizeof(gpu::ExportParams), VK_SHADER_STAGE_COMPUTE_BIT);
        pipeline_ = r.make_compute_pipeline(kExportComp, sizeof(kExportComp), layout_, nullptr);
    }

    std::vector<ImageExport> read(const std::vector<const Image*>& images) {
        const Device& d = r_.d;
        uint32_t reads = 0;
        for (const Image* img : images) reads += img->desc.mips;
        const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, reads},
                                              {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, reads}};
        auto pci = vk_struct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
        pci.maxSets = reads;
        pci.poolSizeCount = 2;
        pci.pPoolSizes = sizes;
        VkDescriptorPool pool_handle = VK_NULL_HANDLE;
        VK_CHECK(d.fn.vkCreateDescriptorPool(d.device, &pci, nullptr, &pool_handle));
        const Unique<VkDescriptorPool> pool(d, pool_handle);

        std::vector<ImageExport> out(images.size());
        std::vector<Unique<VkImageView>> views;
        std::vector<Buffer> buffers;
        Submission s(d, r_.command_pool, VK_NULL_HANDLE, 0);
        VkCommandBuffer cmd = s.cmd();
        d.fn.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
        for (size_t i = 0; i < images.size(); ++i) {
            const ImageDesc& desc = images[i]->desc;
            out[i].width = desc.width;
            out[i].height = desc.height;
            out[i].layers = desc.layers;
            views.push_back(create_view(d, *images[i], VK_IMAGE_VIEW_TYPE_2D_ARRAY, 0, desc.mips, 0, desc.layers));
            for (uint32_t m = 0; m < desc.mips; ++m) {
                const gpu::ExportParams p{std::max(1u, desc.width >> m), std::max(1u, desc.height >> m), desc.layers,
                                          m};
                const VkDeviceSize bytes = VkDeviceSize{p.width} * p.height * p.layers * 4 * sizeof(float);
                buffers.push_back(create_buffer(d, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true));
                VkDescriptorSet set = r_.allocate_set(pool, set_layout_);
                VkDescriptorImageInfo ii{r_.sampler_clamp, views.back(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
                VkDescriptorBufferInfo bi{buffers.back().buffer, 0, bytes};
                VkWriteDescriptorSet w[2] = {vk_struct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET),
                                             vk_struct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET)};
                w[0].dstSet = w[1].dstSet = set;
                w[0].dstBinding = static_cast<uint32_t>(gpu::kBindingExportSource);
                w[0].descriptorCount = 1;
                w[0].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
                w[0].pImageInfo = &ii;
                w[1].dstBinding = static_cast<uint32_t>(gpu::kBindingExportTexels);
                w[1].descriptorCount = 1;
                w[1].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
                w[1].pBufferInfo = &bi;
                d.fn.vkUpdateDescriptorSets(d.device, 2, w, 0, nullptr);
                d.fn.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set, 0, nullptr);
                d.fn.vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof p, &p);
                d.fn.vkCmdDispatch(cmd, tile_groups(p.width), tile_groups(p.height), p.layers);
            }
        }
        memory_barrier(d, cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
        std::vector<PassTime> untimed;
        s.finish(untimed);
        size_t b = 0;  // buffers in the order recorded: image by image, mip by mip
        for (size_t i = 0; i < images.size(); ++i)
            for (uint32_t m = 0; m < images[i]->desc.mips; ++m, ++b) {
                invalidate(d, buffers[b]);
                std::vector<float>& level = out[i].levels.emplace_back(buffers[b].size / sizeof(float));
                std::memcpy(level.data(), buffers[b].mapped, buffers[b].size);
            }
        return out;
    }

private:
    const Renderer::Impl& r_;
    Unique<VkDescriptorSetLayout> set_layout_;
    Unique<VkPipelineLayout> layout_;
    Unique<VkPipeline> pipeline_;
};

}  // namespace

ShadingExport export_shading(Renderer& renderer, const Material& material) {
    check_material(material);
    // The caller holds `renderer` non-const: its state may be written (its uniform block, below).
    auto& r = const_cast<Renderer::Impl&>(renderer_impl(renderer));
    ShadingExport out;
    const ShadeSpecialization c = r.specialization(material);
    for (const SpecField& f : kShadeFields) {
        int32_t v = 0;
        std::memcpy(&v, reinterpret_cast<const unsigned char*>(&c) + f.offset, sizeof v);
        out.constants.push_back({f.id, v, f.boolean});
    }
    // What render() writes before it draws; the next render() writes its own again.
    r.write_frame(material);
    std::memcpy(&out.frame, r.uniforms.mapped, sizeof out.frame);
    return out;
}

LightingExport export_lighting(Renderer& renderer) {
    const Renderer::Impl& r = renderer_impl(renderer);
    if (!r.lighting || !r.lighting->env_specular.view || !r.lighting->brdf_lut.view)
        throw Error("export_lighting: the scene has no environment");
    const Lighting& l = *r.lighting;
    ImageReader reader(r);
    std::vector<ImageExport> images = reader.read({&l.brdf_lut, &l.env_specular, &l.env_irradiance});
    LightingExport out;
    out.brdf_lut = std::move(images[0]);
    out.specular = std::move(images[1]);
    out.irradiance = std::move(images[2]);
    out.anisotropy = r.d.anisotropy > 1.f ? std::min(16.f, r.d.anisotropy) : 0.f;  // make_sampler's
    return out;
}

MeshExport export_mesh(const Renderer& renderer) {
    static_assert(sizeof(Vertex) == 12 * sizeof(float), "position, normal, tangent, uv: 12 floats");
    const Mesh mesh = make_shape(renderer.scene().shape);  // upload_mesh's
    MeshExport out;
    out.vertices.resize(mesh.vertices.size() * 12);
    std::memcpy(out.vertices.data(), mesh.vertices.data(), out.vertices.size() * sizeof(float));
    out.indices = mesh.indices;
    out.depth_test = renderer_impl(renderer).uses_depth();
    return out;
}

}  // namespace mf::render
