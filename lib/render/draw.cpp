// The frame: render targets, then Renderer::render's passes — shade into the linear fp32
// target, encode to 8 bits (or copy the floats), read back.
#include <algorithm>
#include <cstring>

#include "base/stopwatch.hpp"
#include "render/internal.hpp"
#include "render/renderer_impl.hpp"

namespace mf::render {

using namespace detail;

void Renderer::Impl::create_targets() {
    try {
        create_frame_resources();
    } catch (const Error& e) {  // name the frame: its size is the user's --size or the scene's image
        throw Error("the " + std::to_string(scene.width) + "x" + std::to_string(scene.height) + " frame: " + e.what());
    }
}

void Renderer::Impl::create_frame_resources() {
    const uint32_t limit = d.properties.limits.maxImageDimension2D;
    if (std::max(scene.width, scene.height) * scene.supersample > limit)
        throw Error("with " + std::to_string(scene.supersample) + "x" + std::to_string(scene.supersample) +
                    " samples a pixel it is shaded at " + std::to_string(scene.width * scene.supersample) + "x" +
                    std::to_string(scene.height * scene.supersample) + ", past this device's limit of " +
                    std::to_string(limit) + " pixels a side: use a smaller --size or --aa");
    ImageDesc td;
    td.format = kTargetFormat;
    td.width = scene.width * scene.supersample;  // shaded at every sample; encode averages them
    td.height = scene.height * scene.supersample;
    td.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    target = create_image(d, td);
    if (samples != VK_SAMPLE_COUNT_1_BIT) {  // Scene::msaa: shaded here, resolved into `target`
        ImageDesc md;
        md.format = kTargetFormat;
        md.width = td.width;
        md.height = td.height;
        md.samples = samples;
        md.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT;
        msaa_target = create_image(d, md);
    }
    if (uses_depth()) {
        ImageDesc dd;
        dd.format = kDepthFormat;
        dd.width = td.width;
        dd.height = td.height;
        dd.samples = samples;
        dd.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
        dd.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
        depth = create_image(d, dd);
    }
    readback = create_buffer(d, VkDeviceSize{scene.width} * scene.height * 16,
                             VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    uniforms = create_buffer(d, sizeof(gpu::FrameData), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);

    VkDescriptorImageInfo ii{VK_NULL_HANDLE, target.view, VK_IMAGE_LAYOUT_GENERAL};
    VkDescriptorBufferInfo bi{readback.buffer, 0, VK_WHOLE_SIZE};
    VkWriteDescriptorSet w[2]{};
    w[0] = vk_struct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
    w[0].dstSet = encode_set;
    w[0].dstBinding = static_cast<uint32_t>(gpu::kBindingEncodeRadiance);
    w[0].descriptorCount = 1;
    w[0].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    w[0].pImageInfo = &ii;
    w[1] = vk_struct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
    w[1].dstSet = encode_set;
    w[1].dstBinding = static_cast<uint32_t>(gpu::kBindingEncodePixels);
    w[1].descriptorCount = 1;
    w[1].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    w[1].pBufferInfo = &bi;
    d.fn.vkUpdateDescriptorSets(d.device, 2, w, 0, nullptr);
}

void Renderer::Impl::record_raster(VkCommandBuffer cmd, const GpuMaterial::Impl& m) const {
    const uint32_t tw = scene.width * scene.supersample, th = scene.height * scene.supersample;  // the shaded samples
    // The previous frame read the target (encode or copy); this one overwrites it.
    image_barrier(d, cmd, target.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                  VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT, 0,
                  VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);

    // The multisampled target likewise: the previous frame's writes and resolve are done.
    const bool msaa = samples != VK_SAMPLE_COUNT_1_BIT;
    if (msaa)
        image_barrier(d, cmd, msaa_target.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                      VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                      VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);

    // Depth is cleared every frame: the previous frame's depth tests are done before the clear.
    if (uses_depth())
        image_barrier(d, cmd, depth.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                      VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, 0,
                      VK_REMAINING_MIP_LEVELS, VK_IMAGE_ASPECT_DEPTH_BIT);

    auto att = vk_struct<VkRenderingAttachmentInfo>(VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO);
    att.imageView = target.view;
    att.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    att.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    att.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    att.clearValue.color = {{scene.background[0], scene.background[1], scene.background[2], 1.f}};
    if (msaa) {
        // Shaded into the samples, averaged into the target as the pass ends (for a float
        // format the resolve is the average: VK_RESOLVE_MODE_AVERAGE_BIT).
        att.imageView = msaa_target.view;
        att.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
        att.resolveMode = VK_RESOLVE_MODE_AVERAGE_BIT;
        att.resolveImageView = target.view;
        att.resolveImageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    }
    auto depth_att = vk_struct<VkRenderingAttachmentInfo>(VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO);
    depth_att.imageView = depth.view;
    depth_att.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depth_att.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth_att.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    depth_att.clearValue.depthStencil = {1.f, 0};
    auto ri = vk_struct<VkRenderingInfo>(VK_STRUCTURE_TYPE_RENDERING_INFO);
    ri.renderArea = {{0, 0}, {tw, th}};
    ri.layerCount = 1;
    ri.colorAttachmentCount = 1;
    ri.pColorAttachments = &att;
    if (uses_depth()) ri.pDepthAttachment = &depth_att;
    d.fn.vkCmdBeginRendering(cmd, &ri);
    d.fn.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, m.pipeline);
    const VkViewport viewport{0.f, 0.f, static_cast<float>(tw), static_cast<float>(th), 0.f, 1.f};
    const VkRect2D scissor{{0, 0}, {tw, th}};
    d.fn.vkCmdSetViewport(cmd, 0, 1, &viewport);
    d.fn.vkCmdSetScissor(cmd, 0, 1, &scissor);
    const VkDescriptorSet sets[] = {frame_set, m.set};  // gpu::kSetFrame, gpu::kSetMaterial
    d.fn.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, shade_layout, 0, 2, sets, 0, nullptr);
    const VkDeviceSize zero = 0;
    const VkBuffer vb = vertices.buffer;
    d.fn.vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &zero);
    d.fn.vkCmdBindIndexBuffer(cmd, indices.buffer, 0, VK_INDEX_TYPE_UINT32);
    if (m.constants.double_sided) {  // the far side first: the near one blends over it
        d.fn.vkCmdSetCullMode(cmd, VK_CULL_MODE_FRONT_BIT);
        d.fn.vkCmdDrawIndexed(cmd, index_count, 1, 0, 0, 0);
    }
    d.fn.vkCmdSetCullMode(cmd, VK_CULL_MODE_BACK_BIT);
    d.fn.vkCmdDrawIndexed(cmd, index_count, 1, 0, 0, 0);
    if (m.ground_pipeline) {  // Scene::ground: the floor under the shape, its own variant
        d.fn.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, m.ground_pipeline);
        const VkBuffer gvb = ground_vertices.buffer;
        d.fn.vkCmdBindVertexBuffers(cmd, 0, 1, &gvb, &zero);
        d.fn.vkCmdBindIndexBuffer(cmd, ground_indices.buffer, 0, VK_INDEX_TYPE_UINT32);
        d.fn.vkCmdDrawIndexed(cmd, 6, 1, 0, 0, 0);
    }
    d.fn.vkCmdEndRendering(cmd);

    image_barrier(d, cmd, target.image, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL,
                  VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
}

void Renderer::Impl::record_compute(VkCommandBuffer cmd, const GpuMaterial::Impl& m) const {
    const uint32_t tw = scene.width * scene.supersample, th = scene.height * scene.supersample;
    // The previous frame read the target (encode or copy); this one overwrites every pixel.
    image_barrier(d, cmd, target.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                  VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT, 0,
                  VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    d.fn.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, m.pipeline);
    const VkDescriptorSet sets[] = {frame_set, m.set, encode_set};  // kSetFrame, kSetMaterial, kSetShadeTarget
    d.fn.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, compute_layout, 0, 3, sets, 0, nullptr);
    d.fn.vkCmdDispatch(cmd, tile_groups(tw), tile_groups(th), 1);
    memory_barrier(d, cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                   VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
}

Frame Renderer::render(const GpuMaterial& material, const OutputOptions& output) {
    Impl& r = *impl_;
    const Device& d = r.d;
    const GpuMaterial::Impl& m = material.impl();
    if (m.owner != impl_.get()) throw Error("material '" + m.name + "' was uploaded by another renderer");
    const uint32_t w = r.scene.width, h = r.scene.height;
    Stopwatch watch;
    r.write_frame(m.constants);
    r.frame_times.clear();

    Submission s(d, r.command_pool, r.queries, kQueryCount);
    VkCommandBuffer cmd = s.cmd();
    s.begin_pass("shade");  // one name on both paths: bench tables and the auto choice compare it
    if (r.compute) r.record_compute(cmd, m);
    else r.record_raster(cmd, m);
    s.end_pass();

    // One compute pass for both outputs: the N×N samples of each pixel averaged in linear
    // radiance, then either encoded to 8 bits (exposure, tone mapping, transfer) or kept as floats.
    const bool floats = output.format != PixelFormat::rgba8;
    s.begin_pass(floats ? "resolve" : "encode");
    d.fn.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r.encode_pipeline);
    d.fn.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r.encode_layout, 0, 1, &r.encode_set, 0, nullptr);
    const gpu::EncodeParams params{{w, h},
                                   output.exposure,
                                   output.transfer == Transfer::srgb ? 1u : 0u,
                                   static_cast<uint32_t>(output.tonemap),
                                   r.scene.supersample,
                                   floats ? 1u : 0u};
    d.fn.vkCmdPushConstants(cmd, r.encode_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof params, &params);
    d.fn.vkCmdDispatch(cmd, tile_groups(w), tile_groups(h), 1);
    s.end_pass();
    memory_barrier(d, cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                   VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    s.finish(r.frame_times);
    r.retire_upload();  // done: the draw waited for its copies
    r.host_times.draw_wait += watch.lap();
    for (const PassTime& t : r.frame_times) r.host_times.draw_device += t.ms * 1e-3;
    invalidate(d, r.readback);

    Frame frame;
    frame.width = w;
    frame.height = h;
    const size_t n = size_t{w} * h * 4;
    if (output.format == PixelFormat::rgba8) {
        frame.rgba8.resize(n);
        std::memcpy(frame.rgba8.data(), r.readback.mapped, n);
    } else {
        frame.rgba32f.resize(n);
        std::memcpy(frame.rgba32f.data(), r.readback.mapped, n * sizeof(float));
    }
    r.host_times.readback += watch.lap();
    return frame;
}

}  // namespace mf::render
