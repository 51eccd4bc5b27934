// Buffers, images, shader modules, barriers and one-shot submissions.
#include <cstring>
#include <memory>
#include <string>

#include "render/vk.hpp"

namespace mf::render::detail {

Buffer create_buffer(const Device& d, VkDeviceSize size, VkBufferUsageFlags usage, bool host_visible) {
    Buffer b;
    b.size = size;
    auto ci = vk_struct<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
    ci.size = size;
    ci.usage = usage;
    ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VkBuffer h = VK_NULL_HANDLE;
    VK_CHECK(d.fn.vkCreateBuffer(d.device, &ci, nullptr, &h));
    b.buffer = Unique<VkBuffer>(d, h);

    VkMemoryRequirements req{};
    d.fn.vkGetBufferMemoryRequirements(d.device, h, &req);
    uint32_t type = 0;
    if (host_visible) {
        // Prefer cached memory for readbacks; coherent saves the flushes when available.
        const VkMemoryPropertyFlags want = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        try {
            type = d.memory_type(req.memoryTypeBits, want);
            b.coherent = true;
        } catch (const Error&) {
            type = d.memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT);
        }
    } else {
        type = d.memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    }
    const VkDeviceMemory m = d.allocate(req, type, "a buffer");
    b.memory = Unique<VkDeviceMemory>(d, m);
    VK_CHECK(d.fn.vkBindBufferMemory(d.device, h, m, 0));
    if (host_visible) VK_CHECK(d.fn.vkMapMemory(d.device, m, 0, VK_WHOLE_SIZE, 0, &b.mapped));
    return b;
}

void flush(const Device& d, const Buffer& b) {
    if (b.coherent || !b.mapped) return;
    auto r = vk_struct<VkMappedMemoryRange>(VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE);
    r.memory = b.memory;
    r.size = VK_WHOLE_SIZE;
    VK_CHECK(d.fn.vkFlushMappedMemoryRanges(d.device, 1, &r));
}

void invalidate(const Device& d, const Buffer& b) {
    if (b.coherent || !b.mapped) return;
    auto r = vk_struct<VkMappedMemoryRange>(VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE);
    r.memory = b.memory;
    r.size = VK_WHOLE_SIZE;
    VK_CHECK(d.fn.vkInvalidateMappedMemoryRanges(d.device, 1, &r));
}

Image create_unbound_image(const Device& d, const ImageDesc& desc, VkMemoryRequirements& req) {
    Image img;
    img.desc = desc;
    auto ci = vk_struct<VkImageCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO);
    ci.flags = desc.cube ? VkImageCreateFlags{VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT} : VkImageCreateFlags{0};
    ci.imageType = VK_IMAGE_TYPE_2D;
    ci.format = desc.format;
    ci.extent = {desc.width, desc.height, 1};
    ci.mipLevels = desc.mips;
    ci.arrayLayers = desc.layers;
    ci.samples = desc.samples;
    ci.tiling = VK_IMAGE_TILING_OPTIMAL;
    ci.usage = desc.usage;
    ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImage h = VK_NULL_HANDLE;
    VK_CHECK(d.fn.vkCreateImage(d.device, &ci, nullptr, &h));
    img.image = Unique<VkImage>(d, h);
    req = {};
    d.fn.vkGetImageMemoryRequirements(d.device, h, &req);
    return img;
}

void bind_image(const Device& d, Image& img, VkDeviceMemory memory, VkDeviceSize offset) {
    VK_CHECK(d.fn.vkBindImageMemory(d.device, img.image, memory, offset));
    const ImageDesc& desc = img.desc;
    img.view = create_view(d, img,
                           desc.cube         ? VK_IMAGE_VIEW_TYPE_CUBE
                           : desc.layers > 1 ? VK_IMAGE_VIEW_TYPE_2D_ARRAY
                                             : VK_IMAGE_VIEW_TYPE_2D,
                           0, desc.mips, 0, desc.layers);
}

Image create_image(const Device& d, const ImageDesc& desc) {
    VkMemoryRequirements req{};
    Image img = create_unbound_image(d, desc, req);
    const VkDeviceMemory m = d.allocate(req, d.memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT),
                                        "a " + std::to_string(desc.width) + "x" + std::to_string(desc.height) +
                                            " image");
    img.memory = Unique<VkDeviceMemory>(d, m);
    bind_image(d, img, m, 0);
    return img;
}

BlockPool::Block BlockPool::take(VkDeviceSize size, uint32_t type, const std::string& what) {
    constexpr VkDeviceSize kMiB = VkDeviceSize{1} << 20;
    const VkDeviceSize rounded = (size + kMiB - 1) / kMiB * kMiB;
    {
        const std::lock_guard<std::mutex> lock(mutex_);
        auto best = free_.end();
        for (auto it = free_.begin(); it != free_.end(); ++it)
            if (it->type == type && it->size >= size && it->size <= 2 * rounded &&
                (best == free_.end() || it->size < best->size))
                best = it;
        if (best != free_.end()) {
            Block b = std::move(*best);
            free_.erase(best);
            kept_ -= b.size;
            return b;
        }
    }
    VkMemoryRequirements req{};
    req.size = rounded;
    req.alignment = 1;
    req.memoryTypeBits = 1u << type;
    Block b;
    b.size = rounded;
    b.type = type;
    b.memory = Unique<VkDeviceMemory>(d_, d_.allocate(req, type, what));
    return b;
}

void BlockPool::keep(Block b) noexcept {
    if (!b.memory) return;
    const std::lock_guard<std::mutex> lock(mutex_);
    if (kept_ + b.size > kKept) return;  // freed as `b` goes
    kept_ += b.size;
    try {
        free_.push_back(std::move(b));
    } catch (...) {  // no memory for the list: the block is freed instead
        kept_ -= b.size;
    }
}

Unique<VkImageView> create_view(const Device& d, const Image& img, VkImageViewType type, uint32_t base_mip,
                                uint32_t mips, uint32_t base_layer, uint32_t layers) {
    auto vi = vk_struct<VkImageViewCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO);
    vi.image = img.image;
    vi.viewType = type;
    vi.format = img.desc.format;
    vi.subresourceRange = {img.desc.aspect, base_mip, mips, base_layer, layers};
    VkImageView v = VK_NULL_HANDLE;
    VK_CHECK(d.fn.vkCreateImageView(d.device, &vi, nullptr, &v));
    return Unique<VkImageView>(d, v);
}

Unique<VkShaderModule> create_shader(const Device& d, const uint32_t* words, size_t bytes) {
    auto ci = vk_struct<VkShaderModuleCreateInfo>(VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO);
    ci.codeSize = bytes;
    ci.pCode = words;
    VkShaderModule m = VK_NULL_HANDLE;
    VK_CHECK(d.fn.vkCreateShaderModule(d.device, &ci, nullptr, &m));
    return Unique<VkShaderModule>(d, m);
}

void image_barrier(const Device& d, VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to,
                   VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access, VkPipelineStageFlags2 dst_stage,
                   VkAccessFlags2 dst_access, uint32_t base_mip, uint32_t mips, VkImageAspectFlags aspect) {
    auto b = vk_struct<VkImageMemoryBarrier2>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2);
    b.srcStageMask = src_stage;
    b.srcAccessMask = src_access;
    b.dstStageMask = dst_stage;
    b.dstAccessMask = dst_access;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {aspect, base_mip, mips, 0, VK_REMAINING_ARRAY_LAYERS};
    auto dep = vk_struct<VkDependencyInfo>(VK_STRUCTURE_TYPE_DEPENDENCY_INFO);
    dep.imageMemoryBarrierCount = 1;
    dep.pImageMemoryBarriers = &b;
    d.fn.vkCmdPipelineBarrier2(cmd, &dep);
}

void memory_barrier(const Device& d, VkCommandBuffer cmd, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                    VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access) {
    auto b = vk_struct<VkMemoryBarrier2>(VK_STRUCTURE_TYPE_MEMORY_BARRIER_2);
    b.srcStageMask = src_stage;
    b.srcAccessMask = src_access;
    b.dstStageMask = dst_stage;
    b.dstAccessMask = dst_access;
    auto dep = vk_struct<VkDependencyInfo>(VK_STRUCTURE_TYPE_DEPENDENCY_INFO);
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &b;
    d.fn.vkCmdPipelineBarrier2(cmd, &dep);
}

Submission::Submission(const Device& d, VkCommandPool pool, VkQueryPool queries, uint32_t query_count)
    : d_(d), pool_(pool), queries_(queries), query_count_(query_count) {
    auto ai = vk_struct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
    ai.commandPool = pool;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    VK_CHECK(d.fn.vkAllocateCommandBuffers(d.device, &ai, &cmd_));
    auto bi = vk_struct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(d.fn.vkBeginCommandBuffer(cmd_, &bi));
    if (queries_) d.fn.vkCmdResetQueryPool(cmd_, queries_, 0, query_count_);
}

Submission::~Submission() {
    if (fence_ && !waited_) {
        const VkFence f = *fence_;
        d_.fn.vkWaitForFences(d_.device, 1, &f, VK_TRUE, UINT64_MAX);
    }
    d_.fn.vkFreeCommandBuffers(d_.device, pool_, 1, &cmd_);
}

void Submission::begin_pass(std::string name) {
    if (open_) end_pass();
    const auto q = static_cast<uint32_t>(2 * names_.size());
    if (queries_ && q + 2 > query_count_) throw Error("too many timed passes in one submission");
    names_.push_back(std::move(name));
    // ALL_COMMANDS on both ends: the time from "everything before is done" to "everything in
    // the pass is done", the only span every implementation measures the same way.
    if (queries_) d_.fn.vkCmdWriteTimestamp2(cmd_, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, queries_, q);
    open_ = true;
}

void Submission::end_pass() {
    if (!open_) return;
    const auto q = static_cast<uint32_t>(2 * names_.size() - 1);
    if (queries_) d_.fn.vkCmdWriteTimestamp2(cmd_, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, queries_, q);
    open_ = false;
}

void Submission::submit() {
    end_pass();
    VK_CHECK(d_.fn.vkEndCommandBuffer(cmd_));
    auto fi = vk_struct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
    VkFence fence_handle = VK_NULL_HANDLE;
    VK_CHECK(d_.fn.vkCreateFence(d_.device, &fi, nullptr, &fence_handle));
    auto fence = std::make_shared<Unique<VkFence>>(d_, fence_handle);
    auto si = vk_struct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd_;
    {
        const std::lock_guard<std::mutex> lock(d_.queue_mutex);
        VK_CHECK(d_.fn.vkQueueSubmit(d_.queue, 1, &si, fence_handle));
    }
    fence_ = std::move(fence);
}

void Submission::wait(std::vector<PassTime>& times) {
    const VkFence fence_handle = *fence_;
    VK_CHECK(d_.fn.vkWaitForFences(d_.device, 1, &fence_handle, VK_TRUE, UINT64_MAX));
    waited_ = true;

    std::vector<uint64_t> stamps(2 * names_.size(), 0);
    if (queries_ && !names_.empty())
        VK_CHECK(d_.fn.vkGetQueryPoolResults(d_.device, queries_, 0, static_cast<uint32_t>(stamps.size()),
                                             stamps.size() * sizeof(uint64_t), stamps.data(), sizeof(uint64_t),
                                             VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    for (size_t i = 0; i < names_.size(); ++i) {
        const auto ticks = static_cast<double>((stamps[2 * i + 1] - stamps[2 * i]) & d_.timestamp_mask);
        times.push_back({names_[i], queries_ ? ticks * d_.info.timestamp_period_ns * 1e-6 : 0.0});
    }
}

}  // namespace mf::render::detail
