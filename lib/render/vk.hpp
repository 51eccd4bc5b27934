// Internal: Vulkan function table, the one check macro, and move-only owners of Vulkan handles.
//
// The loader is opened with dlopen (see context.cpp) and every entry point is fetched into a
// table held by the context, so the library has no link-time dependency on libvulkan and a
// machine without it gets a clear NoDeviceError instead of a failed program start.
#pragma once
#include <vulkan/vulkan.h>

#include <condition_variable>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "render/render.hpp"

namespace mf::render::detail {

static_assert(sizeof(void*) == 8, "non-dispatchable handles must be distinct types (64-bit)");

// Entry points fetched with vkGetInstanceProcAddr(nullptr, …).
#define MF_VK_GLOBAL_FUNCTIONS(X)             \
    X(vkCreateInstance)                       \
    X(vkEnumerateInstanceLayerProperties)     \
    X(vkEnumerateInstanceExtensionProperties) \
    X(vkEnumerateInstanceVersion)

// Entry points fetched with vkGetInstanceProcAddr(instance, …).
#define MF_VK_INSTANCE_FUNCTIONS(X)             \
    X(vkDestroyInstance)                        \
    X(vkEnumeratePhysicalDevices)               \
    X(vkGetPhysicalDeviceProperties)            \
    X(vkGetPhysicalDeviceFeatures2)             \
    X(vkGetPhysicalDeviceProperties2)           \
    X(vkGetPhysicalDeviceQueueFamilyProperties) \
    X(vkGetPhysicalDeviceMemoryProperties)      \
    X(vkGetPhysicalDeviceFormatProperties)      \
    X(vkGetPhysicalDeviceImageFormatProperties) \
    X(vkEnumerateDeviceExtensionProperties)     \
    X(vkCreateDevice)                           \
    X(vkGetDeviceProcAddr)

#define MF_VK_DEBUG_FUNCTIONS(X)      \
    X(vkCreateDebugUtilsMessengerEXT) \
    X(vkDestroyDebugUtilsMessengerEXT)

// Entry points fetched with vkGetDeviceProcAddr(device, …).
#define MF_VK_DEVICE_FUNCTIONS(X)     \
    X(vkDestroyDevice)                \
    X(vkGetDeviceQueue)               \
    X(vkQueueSubmit)                  \
    X(vkDeviceWaitIdle)               \
    X(vkCreateCommandPool)            \
    X(vkDestroyCommandPool)           \
    X(vkAllocateCommandBuffers)       \
    X(vkFreeCommandBuffers)           \
    X(vkBeginCommandBuffer)           \
    X(vkEndCommandBuffer)             \
    X(vkResetCommandBuffer)           \
    X(vkCreateFence)                  \
    X(vkDestroyFence)                 \
    X(vkWaitForFences)                \
    X(vkResetFences)                  \
    X(vkCreateBuffer)                 \
    X(vkDestroyBuffer)                \
    X(vkGetBufferMemoryRequirements)  \
    X(vkAllocateMemory)               \
    X(vkFreeMemory)                   \
    X(vkBindBufferMemory)             \
    X(vkMapMemory)                    \
    X(vkUnmapMemory)                  \
    X(vkFlushMappedMemoryRanges)      \
    X(vkInvalidateMappedMemoryRanges) \
    X(vkCreateImage)                  \
    X(vkDestroyImage)                 \
    X(vkGetImageMemoryRequirements)   \
    X(vkBindImageMemory)              \
    X(vkCreateImageView)              \
    X(vkDestroyImageView)             \
    X(vkCreateSampler)                \
    X(vkDestroySampler)               \
    X(vkCreateShaderModule)           \
    X(vkDestroyShaderModule)          \
    X(vkCreateDescriptorSetLayout)    \
    X(vkDestroyDescriptorSetLayout)   \
    X(vkCreatePipelineLayout)         \
    X(vkDestroyPipelineLayout)        \
    X(vkCreateGraphicsPipelines)      \
    X(vkCreateComputePipelines)       \
    X(vkDestroyPipeline)              \
    X(vkCreatePipelineCache)          \
    X(vkDestroyPipelineCache)         \
    X(vkCreateDescriptorPool)         \
    X(vkDestroyDescriptorPool)        \
    X(vkAllocateDescriptorSets)       \
    X(vkUpdateDescriptorSets)         \
    X(vkCreateQueryPool)              \
    X(vkDestroyQueryPool)             \
    X(vkGetQueryPoolResults)          \
    X(vkCmdResetQueryPool)            \
    X(vkCmdWriteTimestamp2)           \
    X(vkCmdPipelineBarrier2)          \
    X(vkCmdBeginRendering)            \
    X(vkCmdEndRendering)              \
    X(vkCmdBindPipeline)              \
    X(vkCmdBindDescriptorSets)        \
    X(vkCmdBindVertexBuffers)         \
    X(vkCmdBindIndexBuffer)           \
    X(vkCmdDrawIndexed)               \
    X(vkCmdDispatch)                  \
    X(vkCmdCopyBuffer)                \
    X(vkCmdCopyBufferToImage)         \
    X(vkCmdBlitImage)                 \
    X(vkCmdCopyImageToBuffer)         \
    X(vkCmdPushConstants)             \
    X(vkCmdSetViewport)               \
    X(vkCmdSetScissor)                \
    X(vkCmdSetCullMode)

struct Functions {
    PFN_vkGetInstanceProcAddr vkGetInstanceProcAddr = nullptr;
#define MF_VK_DECLARE(name) PFN_##name name = nullptr;
    MF_VK_GLOBAL_FUNCTIONS(MF_VK_DECLARE)
    MF_VK_INSTANCE_FUNCTIONS(MF_VK_DECLARE)
    MF_VK_DEBUG_FUNCTIONS(MF_VK_DECLARE)
    MF_VK_DEVICE_FUNCTIONS(MF_VK_DECLARE)
#undef MF_VK_DECLARE
};

const char* result_name(VkResult r);
[[noreturn]] void throw_vk_error(VkResult r, const char* expr, const char* file, int line);

// The one check: any result other than VK_SUCCESS throws mf::render::Error naming the call.
#define VK_CHECK(expr)                                                                      \
    do {                                                                                    \
        const VkResult mf_vk_result_ = (expr);                                              \
        if (mf_vk_result_ != VK_SUCCESS)                                                    \
            ::mf::render::detail::throw_vk_error(mf_vk_result_, #expr, __FILE__, __LINE__); \
    } while (0)

// A zeroed Vulkan structure with its sType set.
template <class T>
T vk_struct(VkStructureType type) {
    T s{};
    s.sType = type;
    return s;
}

struct Lighting;  // below

// What the renderer needs of the context.
struct Device {
    Functions fn;
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queue_family = 0;
    VkPhysicalDeviceProperties properties{};
    VkPhysicalDeviceMemoryProperties memory{};
    DeviceInfo info;
    uint64_t timestamp_mask = 0;  // valid bits of a timestamp (differences wrap there)
    float anisotropy = 0.f;
    bool shader_float16 = false;      // VkPhysicalDeviceVulkan12Features::shaderFloat16 enabled
    bool precise_textures = false;    // ContextOptions::precise_cpu_textures, on a CPU device
    VkDeviceSize max_allocation = 0;  // maxMemoryAllocationSize (Vulkan 1.1): the largest single allocation
    // Scene::shading automatic: measured by the first renderer that needs it, then kept for every
    // later one of this context. Renderers may be made on several threads at once (preview's
    // lanes): the others wait under `mutex` for the one measuring.
    struct ShadingChoice {
        std::mutex mutex;
        bool measured = false, compute = false;
        double raster_ms = 0.0, compute_ms = 0.0;
    } shading_choice;
    // vkQueueSubmit and vkDeviceWaitIdle need the queue externally synchronized: several
    // renderers of one context may submit from their own threads (preview's lanes).
    mutable std::mutex queue_mutex;
    // ibl.cpp's Lighting, made once for the renderers alive at once with one environment and
    // BRDF (a batch's lanes, made together): the first makes it, the others wait and share it.
    // Keyed by the environment's address, which the Lighting keeps alive (so it names one).
    struct LightingCache {
        using Key = std::pair<const Environment*, bool>;  // the environment, the accurate BRDF's table
        std::mutex mutex;
        std::condition_variable changed;
        std::map<Key, std::weak_ptr<const Lighting>> made;
        std::set<Key> making;
    };
    mutable LightingCache lighting_cache;
    // Every pipeline of the context is made through it (internally synchronized): a variant a
    // second renderer (a preview lane) needs again is not compiled again.
    VkPipelineCache pipeline_cache = VK_NULL_HANDLE;

    // A memory type index with all of `flags` among `type_bits`; throws when there is none.
    uint32_t memory_type(uint32_t type_bits, VkMemoryPropertyFlags flags) const;
    // Memory for `req` of memory type `type`, for `what` (named in the error): a request past the
    // device's limits (one allocation, the heap) or one the device refuses for want of memory
    // throws an Error that says how much was asked for and what the device has, never a bare
    // VK_ERROR_OUT_OF_DEVICE_MEMORY.
    VkDeviceMemory allocate(const VkMemoryRequirements& req, uint32_t type, const std::string& what) const;
    bool supports(VkFormat format, VkFormatFeatureFlags optimal_tiling_features) const;
    // The sample counts a 2D optimal-tiling image of `format` with `usage` may have (0: none).
    VkSampleCountFlags sample_counts(VkFormat format, VkImageUsageFlags usage) const;
};

Device& device_of(Context& context);

// ---------------------------------------------------------------------------------------------
// Move-only owner of one handle; destroy() overloads below say how each kind is released.

inline void destroy(const Device& d, VkBuffer h) { d.fn.vkDestroyBuffer(d.device, h, nullptr); }
inline void destroy(const Device& d, VkImage h) { d.fn.vkDestroyImage(d.device, h, nullptr); }
inline void destroy(const Device& d, VkImageView h) { d.fn.vkDestroyImageView(d.device, h, nullptr); }
inline void destroy(const Device& d, VkDeviceMemory h) { d.fn.vkFreeMemory(d.device, h, nullptr); }
inline void destroy(const Device& d, VkSampler h) { d.fn.vkDestroySampler(d.device, h, nullptr); }
inline void destroy(const Device& d, VkShaderModule h) { d.fn.vkDestroyShaderModule(d.device, h, nullptr); }
inline void destroy(const Device& d, VkPipeline h) { d.fn.vkDestroyPipeline(d.device, h, nullptr); }
inline void destroy(const Device& d, VkPipelineLayout h) { d.fn.vkDestroyPipelineLayout(d.device, h, nullptr); }
inline void destroy(const Device& d, VkDescriptorSetLayout h) {
    d.fn.vkDestroyDescriptorSetLayout(d.device, h, nullptr);
}
inline void destroy(const Device& d, VkDescriptorPool h) { d.fn.vkDestroyDescriptorPool(d.device, h, nullptr); }
inline void destroy(const Device& d, VkQueryPool h) { d.fn.vkDestroyQueryPool(d.device, h, nullptr); }
inline void destroy(const Device& d, VkFence h) { d.fn.vkDestroyFence(d.device, h, nullptr); }
inline void destroy(const Device& d, VkCommandPool h) { d.fn.vkDestroyCommandPool(d.device, h, nullptr); }

template <class H>
class Unique {
public:
    Unique() = default;
    Unique(const Device& d, H h) : d_(&d), h_(h) {}
    ~Unique() { reset(); }
    Unique(Unique&& o) noexcept : d_(o.d_), h_(std::exchange(o.h_, VK_NULL_HANDLE)) {}
    Unique& operator=(Unique&& o) noexcept {
        if (this != &o) {
            reset();
            d_ = o.d_;
            h_ = std::exchange(o.h_, VK_NULL_HANDLE);
        }
        return *this;
    }
    Unique(const Unique&) = delete;
    Unique& operator=(const Unique&) = delete;

    H get() const { return h_; }
    operator H() const { return h_; }  // NOLINT: handles pass straight into Vulkan calls
    explicit operator bool() const { return h_ != VK_NULL_HANDLE; }
    void reset() {
        if (h_ != VK_NULL_HANDLE) destroy(*d_, h_);
        h_ = VK_NULL_HANDLE;
    }

private:
    const Device* d_ = nullptr;
    H h_ = VK_NULL_HANDLE;
};

// ---------------------------------------------------------------------------------------------
// Buffers and images with their own memory (a preview holds a few dozen: no sub-allocator).

struct Buffer {
    Unique<VkBuffer> buffer;
    Unique<VkDeviceMemory> memory;
    VkDeviceSize size = 0;
    void* mapped = nullptr;  // host-visible buffers stay mapped for their lifetime
    bool coherent = false;
};
// host_visible: mapped, for uploads, readbacks and uniforms; else device-local.
Buffer create_buffer(const Device& d, VkDeviceSize size, VkBufferUsageFlags usage, bool host_visible);
void flush(const Device& d, const Buffer& b);       // after the host wrote (non-coherent memory)
void invalidate(const Device& d, const Buffer& b);  // before the host reads

struct ImageDesc {
    VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
    uint32_t width = 1, height = 1, mips = 1, layers = 1;
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;  // > 1: a multisampled render target
    VkImageUsageFlags usage = VK_IMAGE_USAGE_SAMPLED_BIT;
    bool cube = false;                                      // layers == 6, viewed as a cube map
    VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;  // VK_IMAGE_ASPECT_DEPTH_BIT for a depth buffer
};
struct Image {
    Unique<VkImage> image;
    Unique<VkDeviceMemory> memory;
    Unique<VkImageView> view;  // all mips and layers (a cube view for cube images)
    ImageDesc desc;
};
Image create_image(const Device& d, const ImageDesc& desc);

// The image-based lighting ibl.cpp computes for a scene's environment and BRDF, shared by the
// renderers of a device made with the same ones (Device::LightingCache); read-only once made.
struct Lighting {
    Image brdf_lut;                      // when the accurate BRDF or an environment needs it
    Image env_specular, env_irradiance;  // when the scene has an environment
    uint32_t env_specular_mips = 0;
    std::shared_ptr<const Environment> environment;  // kept alive: its address names it in the cache
};
// create_image in two halves, for images that share one allocation (BlockPool): the image alone
// and its memory requirements, then bound at `offset` of `memory` and its view made.
Image create_unbound_image(const Device& d, const ImageDesc& desc, VkMemoryRequirements& req);
void bind_image(const Device& d, Image& img, VkDeviceMemory memory, VkDeviceSize offset);

// Device-local allocations kept for reuse: a material's images share one block, and a freed
// material's block serves the next material that fits (freeing and making ~4 allocations a
// material cost a lane 5.5 ms of its 23.5 ms on the H200; docs/bench/h200_preview_timings.txt).
// Thread-safe: a lane takes, the thread that frees a material keeps.
class BlockPool {
public:
    struct Block {
        Unique<VkDeviceMemory> memory;
        VkDeviceSize size = 0;
        uint32_t type = 0;
    };
    explicit BlockPool(const Device& d) : d_(d) {}
    // A kept block of `type` that holds `size` bytes and is at most twice that rounded up to a
    // 1 MiB multiple, else a new one of that rounded size (so that similar materials share).
    Block take(VkDeviceSize size, uint32_t type, const std::string& what);
    // Kept while the pool holds at most kKept bytes; past that the block is freed.
    void keep(Block b) noexcept;
    static constexpr VkDeviceSize kKept = VkDeviceSize{256} << 20;

private:
    const Device& d_;
    std::mutex mutex_;
    std::vector<Block> free_;
    VkDeviceSize kept_ = 0;
};
Unique<VkImageView> create_view(const Device& d, const Image& img, VkImageViewType type, uint32_t base_mip,
                                uint32_t mips, uint32_t base_layer, uint32_t layers);

Unique<VkShaderModule> create_shader(const Device& d, const uint32_t* words, size_t bytes);

// Image layout transition of all mips and layers, with the given scopes (synchronization2).
void image_barrier(const Device& d, VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to,
                   VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access, VkPipelineStageFlags2 dst_stage,
                   VkAccessFlags2 dst_access, uint32_t base_mip = 0, uint32_t mips = VK_REMAINING_MIP_LEVELS,
                   VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT);
void memory_barrier(const Device& d, VkCommandBuffer cmd, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                    VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access);

// Records into a fresh primary command buffer, submits, waits. With timestamps, the passes
// between begin_pass and end_pass are timed; their GPU times are appended to `times`.
class Submission {
public:
    Submission(const Device& d, VkCommandPool pool, VkQueryPool queries, uint32_t query_count);
    ~Submission();  // waits for a submission not waited for: its command buffer is freed
    Submission(const Submission&) = delete;
    Submission& operator=(const Submission&) = delete;
    VkCommandBuffer cmd() const { return cmd_; }
    void begin_pass(std::string name);
    void end_pass();
    // Submits; fence() signals its completion.
    void submit();
    // Waits for completion (after submit) and appends each pass's GPU time.
    void wait(std::vector<PassTime>& times);
    void finish(std::vector<PassTime>& times) {
        submit();
        wait(times);
    }
    // Shared: what the submission wrote may wait on it after the submission is gone.
    const std::shared_ptr<Unique<VkFence>>& fence() const { return fence_; }

private:
    const Device& d_;
    VkCommandPool pool_;
    VkQueryPool queries_;
    uint32_t query_count_;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
    std::vector<std::string> names_;
    bool open_ = false;
    std::shared_ptr<Unique<VkFence>> fence_;
    bool waited_ = false;
};

}  // namespace mf::render::detail
