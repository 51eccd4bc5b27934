// Instance, device selection (auto | gpu | cpu), logical device and the validation messenger.
#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <sstream>

#include "render/vk.hpp"

namespace mf::render {

std::optional<DeviceKind> parse_device_kind(std::string_view s) {
    if (s == "auto") return DeviceKind::automatic;
    if (s == "gpu") return DeviceKind::gpu;
    if (s == "cpu") return DeviceKind::cpu;
    return std::nullopt;
}

void MessageLog::add(std::string message) {
    std::lock_guard lock(mutex_);
    messages_.push_back(std::move(message));
}
size_t MessageLog::count() const {
    std::lock_guard lock(mutex_);
    return messages_.size();
}
std::vector<std::string> MessageLog::messages() const {
    std::lock_guard lock(mutex_);
    return messages_;
}

namespace detail {

const char* result_name(VkResult r) {
    switch (r) {
#define MF_CASE(x) \
    case x: return #x;
        MF_CASE(VK_SUCCESS)
        MF_CASE(VK_NOT_READY)
        MF_CASE(VK_TIMEOUT)
        MF_CASE(VK_INCOMPLETE)
        MF_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
        MF_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        MF_CASE(VK_ERROR_INITIALIZATION_FAILED)
        MF_CASE(VK_ERROR_DEVICE_LOST)
        MF_CASE(VK_ERROR_MEMORY_MAP_FAILED)
        MF_CASE(VK_ERROR_LAYER_NOT_PRESENT)
        MF_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
        MF_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
        MF_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
        MF_CASE(VK_ERROR_TOO_MANY_OBJECTS)
        MF_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
        MF_CASE(VK_ERROR_FRAGMENTED_POOL)
        MF_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
        MF_CASE(VK_ERROR_UNKNOWN)
#undef MF_CASE
        default: return "VkResult(?)";
    }
}

void throw_vk_error(VkResult r, const char* expr, const char* file, int line) {
    std::ostringstream os;
    os << "Vulkan call failed: " << expr << " returned " << result_name(r) << " (" << static_cast<int>(r) << ") at "
       << file << ':' << line;
    if (r == VK_ERROR_DEVICE_LOST || r == VK_ERROR_INITIALIZATION_FAILED) throw NoDeviceError(os.str());
    throw Error(os.str());
}

uint32_t Device::memory_type(uint32_t type_bits, VkMemoryPropertyFlags flags) const {
    for (uint32_t i = 0; i < memory.memoryTypeCount; ++i)
        if ((type_bits & (1u << i)) && (memory.memoryTypes[i].propertyFlags & flags) == flags) return i;
    throw Error("no Vulkan memory type with the required properties");
}

VkDeviceMemory Device::allocate(const VkMemoryRequirements& req, uint32_t type, const std::string& what) const {
    auto mb = [](VkDeviceSize b) { return std::to_string((b + (1u << 20) - 1) >> 20) + " MB"; };
    const VkDeviceSize heap = memory.memoryHeaps[memory.memoryTypes[type].heapIndex].size;
    const std::string asked = what + " needs " + mb(req.size) + " of device memory";
    if (max_allocation > 0 && req.size > max_allocation)
        throw Error(asked + " in one allocation; " + info.name + " allows at most " + mb(max_allocation) +
                    " (maxMemoryAllocationSize): use a smaller --size or smaller textures");
    if (req.size > heap)
        throw Error(asked + "; " + info.name + "'s memory heap holds " + mb(heap) +
                    ": use a smaller --size or smaller textures");
    auto ai = vk_struct<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
    ai.allocationSize = req.size;
    ai.memoryTypeIndex = type;
    VkDeviceMemory m = VK_NULL_HANDLE;
    const VkResult r = fn.vkAllocateMemory(device, &ai, nullptr, &m);
    if (r == VK_ERROR_OUT_OF_DEVICE_MEMORY || r == VK_ERROR_OUT_OF_HOST_MEMORY)
        throw Error(asked + ", and " + info.name + " is out of " +
                    (r == VK_ERROR_OUT_OF_HOST_MEMORY ? "host" : "device") + " memory (its heap holds " + mb(heap) +
                    "): use a smaller --size or smaller textures");
    VK_CHECK(r);
    return m;
}

bool Device::supports(VkFormat format, VkFormatFeatureFlags features) const {
    VkFormatProperties p{};
    fn.vkGetPhysicalDeviceFormatProperties(physical, format, &p);
    return (p.optimalTilingFeatures & features) == features;
}

VkSampleCountFlags Device::sample_counts(VkFormat format, VkImageUsageFlags usage) const {
    VkImageFormatProperties p{};
    if (fn.vkGetPhysicalDeviceImageFormatProperties(physical, format, VK_IMAGE_TYPE_2D, VK_IMAGE_TILING_OPTIMAL, usage,
                                                    0, &p) != VK_SUCCESS)
        return 0;
    return p.sampleCounts;
}

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";
constexpr const char* kDriverHint =
    "install mesa-vulkan-drivers (lavapipe, the CPU renderer) or your GPU's Vulkan driver";

// The loader stays loaded for the life of the process: unloading it while a driver keeps
// threads or atexit handlers is what makes leak checkers and some drivers unhappy.
PFN_vkGetInstanceProcAddr load_loader() {
    static void* handle = [] {
#if defined(MATFORGE_SANITIZE_BUILD)
        // LeakSanitizer checks after the loader has unloaded the driver and layer, so their
        // one-time allocations show up as leaks in "<unknown module>" that no suppression can
        // name. Pinning them (RTLD_NODELETE) keeps their symbols for LSan's report and its
        // suppressions (scripts/lsan.supp). Only sanitizer builds do this.
        for (const char* pinned : {"libvulkan_lvp.so", "libVkLayer_khronos_validation.so"})
            dlopen(pinned, RTLD_NOW | RTLD_NODELETE);
#endif
        void* h = dlopen("libvulkan.so.1", RTLD_NOW | RTLD_LOCAL);
        if (!h) h = dlopen("libvulkan.so", RTLD_NOW | RTLD_LOCAL);
        return h;
    }();
    if (!handle)
        throw NoDeviceError("no Vulkan loader (libvulkan.so.1): install the libvulkan1 package, and "
                            "mesa-vulkan-drivers for the CPU renderer if the machine has no GPU driver");
    auto* gipa = reinterpret_cast<PFN_vkGetInstanceProcAddr>(dlsym(handle, "vkGetInstanceProcAddr"));
    if (!gipa) throw NoDeviceError("libvulkan.so.1 has no vkGetInstanceProcAddr: reinstall libvulkan1");
    return gipa;
}

VKAPI_ATTR VkBool32 VKAPI_CALL on_debug_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                VkDebugUtilsMessageTypeFlagsEXT,
                                                const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    auto* log = static_cast<MessageLog*>(user);
    std::string text = severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error: " : "warning: ";
    if (data && data->pMessageIdName) text += std::string(data->pMessageIdName) + ": ";
    if (data && data->pMessage) text += data->pMessage;
    log->add(std::move(text));
    return VK_FALSE;  // never abort the call: the test counts, the program carries on
}

VkDebugUtilsMessengerCreateInfoEXT messenger_info(MessageLog* log) {
    auto ci =
        detail::vk_struct<VkDebugUtilsMessengerCreateInfoEXT>(VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT);
    ci.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                         VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    ci.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    ci.pfnUserCallback = on_debug_message;
    ci.pUserData = log;
    return ci;
}

// Lower is preferred by --device auto.
int rank(VkPhysicalDeviceType t) {
    switch (t) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
        case VK_PHYSICAL_DEVICE_TYPE_OTHER: return 3;
        default: return 4;  // CPU
    }
}

}  // namespace
}  // namespace detail

struct Context::Impl {
    detail::Device dev;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    std::shared_ptr<MessageLog> log;

    explicit Impl(const ContextOptions& opt);
    ~Impl() { release(); }
    Impl(const Impl&) = delete;
    Impl& operator=(const Impl&) = delete;
    void release();
    void create_instance(const ContextOptions& opt);
    void pick_device(DeviceKind kind);
    void create_device();
};

Context::Impl::Impl(const ContextOptions& opt) : log(opt.log) {
    if (opt.validation && !log) throw Error("ContextOptions::validation needs a MessageLog");
    try {
        create_instance(opt);
        pick_device(opt.device);
        dev.precise_textures = opt.precise_cpu_textures && dev.info.cpu;
        create_device();
    } catch (...) {
        release();  // a throwing constructor runs no destructor
        throw;
    }
}

void Context::Impl::release() {
    auto& f = dev.fn;
    if (dev.device) {
        f.vkDeviceWaitIdle(dev.device);
        if (dev.pipeline_cache) f.vkDestroyPipelineCache(dev.device, dev.pipeline_cache, nullptr);
        f.vkDestroyDevice(dev.device, nullptr);  // the validation layer reports leaks here
        dev.device = VK_NULL_HANDLE;
    }
    if (messenger) {
        f.vkDestroyDebugUtilsMessengerEXT(dev.instance, messenger, nullptr);
        messenger = VK_NULL_HANDLE;
    }
    if (dev.instance) {
        f.vkDestroyInstance(dev.instance, nullptr);
        dev.instance = VK_NULL_HANDLE;
    }
}

void Context::Impl::create_instance(const ContextOptions& opt) {
    auto& f = dev.fn;
    f.vkGetInstanceProcAddr = detail::load_loader();
#define MF_VK_LOAD(name) f.name = reinterpret_cast<PFN_##name>(f.vkGetInstanceProcAddr(nullptr, #name));
    MF_VK_GLOBAL_FUNCTIONS(MF_VK_LOAD)
#undef MF_VK_LOAD
    if (!f.vkCreateInstance || !f.vkEnumerateInstanceVersion)
        throw NoDeviceError("the Vulkan loader is older than 1.1: upgrade libvulkan1");

    uint32_t loader_version = 0;
    VK_CHECK(f.vkEnumerateInstanceVersion(&loader_version));
    if (loader_version < VK_API_VERSION_1_3)
        throw NoDeviceError("the Vulkan loader supports only Vulkan " +
                            std::to_string(VK_API_VERSION_MAJOR(loader_version)) + "." +
                            std::to_string(VK_API_VERSION_MINOR(loader_version)) +
                            "; the preview needs 1.3: upgrade libvulkan1");

    std::vector<const char*> layers, extensions;
    if (opt.validation) {
        uint32_t n = 0;
        VK_CHECK(f.vkEnumerateInstanceLayerProperties(&n, nullptr));
        std::vector<VkLayerProperties> props(n);
        VK_CHECK(f.vkEnumerateInstanceLayerProperties(&n, props.data()));
        const bool found = std::any_of(props.begin(), props.end(), [](const VkLayerProperties& p) {
            return std::strcmp(p.layerName, detail::kValidationLayer) == 0;
        });
        if (!found)
            throw Error("validation requested but VK_LAYER_KHRONOS_validation is not installed: "
                        "install vulkan-validationlayers");
        layers.push_back(detail::kValidationLayer);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
        extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
    }

    // lavapipe prints a non-conformance banner on every device creation; a CLI wants its
    // stderr for its own messages. The user's own setting wins (overwrite = 0).
    setenv("MESA_VK_IGNORE_CONFORMANCE_WARNING", "1", 0);

    auto app = detail::vk_struct<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
    app.pApplicationName = "matforge preview";
    app.pEngineName = "matforge";
    app.apiVersion = VK_API_VERSION_1_3;

    // Synchronization validation catches missing barriers, which lavapipe would forgive.
    const VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    auto features = detail::vk_struct<VkValidationFeaturesEXT>(VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT);
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = enables;
    // Chained into the instance create info, the messenger also sees vkCreateInstance and
    // vkDestroyInstance (a leaked instance-level object is reported there).
    VkDebugUtilsMessengerCreateInfoEXT instance_messenger = detail::messenger_info(log.get());
    instance_messenger.pNext = &features;

    auto ci = detail::vk_struct<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
    ci.pApplicationInfo = &app;
    ci.enabledLayerCount = static_cast<uint32_t>(layers.size());
    ci.ppEnabledLayerNames = layers.data();
    ci.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    ci.ppEnabledExtensionNames = extensions.data();
    if (opt.validation) ci.pNext = &instance_messenger;

    const VkResult r = f.vkCreateInstance(&ci, nullptr, &dev.instance);
    if (r == VK_ERROR_INCOMPATIBLE_DRIVER)
        throw NoDeviceError(std::string("no Vulkan driver found: ") + detail::kDriverHint);
    VK_CHECK(r);

#define MF_VK_LOAD(name) f.name = reinterpret_cast<PFN_##name>(f.vkGetInstanceProcAddr(dev.instance, #name));
    MF_VK_INSTANCE_FUNCTIONS(MF_VK_LOAD)
    if (opt.validation) {
        MF_VK_DEBUG_FUNCTIONS(MF_VK_LOAD)
        VkDebugUtilsMessengerCreateInfoEXT mi = detail::messenger_info(log.get());
        VK_CHECK(f.vkCreateDebugUtilsMessengerEXT(dev.instance, &mi, nullptr, &messenger));
    }
#undef MF_VK_LOAD
}

void Context::Impl::pick_device(DeviceKind kind) {
    auto& f = dev.fn;
    uint32_t n = 0;
    const VkResult r = f.vkEnumeratePhysicalDevices(dev.instance, &n, nullptr);
    if (r == VK_ERROR_INITIALIZATION_FAILED || n == 0)
        throw NoDeviceError(std::string("no Vulkan device found: ") + detail::kDriverHint);
    VK_CHECK(r);
    std::vector<VkPhysicalDevice> all(n);
    VK_CHECK(f.vkEnumeratePhysicalDevices(dev.instance, &n, all.data()));

    struct Candidate {
        VkPhysicalDevice pd;
        VkPhysicalDeviceProperties props;
        uint32_t family;
    };
    std::vector<Candidate> usable;
    std::string seen;
    for (VkPhysicalDevice pd : all) {
        VkPhysicalDeviceProperties p{};
        f.vkGetPhysicalDeviceProperties(pd, &p);
        seen += std::string(seen.empty() ? "" : ", ") + p.deviceName;
        if (p.apiVersion < VK_API_VERSION_1_3) continue;
        const bool is_cpu = p.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
        if ((kind == DeviceKind::gpu && is_cpu) || (kind == DeviceKind::cpu && !is_cpu)) continue;
        uint32_t qn = 0;
        f.vkGetPhysicalDeviceQueueFamilyProperties(pd, &qn, nullptr);
        std::vector<VkQueueFamilyProperties> q(qn);
        f.vkGetPhysicalDeviceQueueFamilyProperties(pd, &qn, q.data());
        for (uint32_t i = 0; i < qn; ++i) {
            constexpr VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
            if ((q[i].queueFlags & need) == need) {
                usable.push_back({pd, p, i});
                break;
            }
        }
    }
    if (usable.empty()) {
        if (kind == DeviceKind::gpu)
            throw NoDeviceError("no Vulkan 1.3 GPU found (devices: " + seen +
                                "); install the GPU's Vulkan driver, or use --device cpu");
        if (kind == DeviceKind::cpu)
            throw NoDeviceError("no CPU Vulkan device (lavapipe) found (devices: " + seen +
                                "): install mesa-vulkan-drivers");
        throw NoDeviceError("no Vulkan 1.3 device with graphics and compute found (devices: " + seen +
                            "): " + detail::kDriverHint);
    }
    // stable_sort keeps the loader's order among equals (the driver's or the user's choice).
    std::stable_sort(usable.begin(), usable.end(), [](const Candidate& a, const Candidate& b) {
        return detail::rank(a.props.deviceType) < detail::rank(b.props.deviceType);
    });
    const Candidate& c = usable.front();
    dev.physical = c.pd;
    dev.properties = c.props;
    dev.queue_family = c.family;
    f.vkGetPhysicalDeviceMemoryProperties(dev.physical, &dev.memory);

    uint32_t qn = 0;
    f.vkGetPhysicalDeviceQueueFamilyProperties(dev.physical, &qn, nullptr);
    std::vector<VkQueueFamilyProperties> q(qn);
    f.vkGetPhysicalDeviceQueueFamilyProperties(dev.physical, &qn, q.data());

    auto p11 =
        detail::vk_struct<VkPhysicalDeviceVulkan11Properties>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_PROPERTIES);
    auto p12 =
        detail::vk_struct<VkPhysicalDeviceVulkan12Properties>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_PROPERTIES);
    auto p2 = detail::vk_struct<VkPhysicalDeviceProperties2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2);
    p2.pNext = &p12;
    p12.pNext = &p11;
    f.vkGetPhysicalDeviceProperties2(dev.physical, &p2);
    dev.max_allocation = p11.maxMemoryAllocationSize;
    DeviceInfo& info = dev.info;
    info.name = c.props.deviceName;
    info.cpu = c.props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    info.api_version = c.props.apiVersion;
    info.driver = std::string(p12.driverName) + " " + p12.driverInfo;
    info.timestamps = q[c.family].timestampValidBits > 0 && c.props.limits.timestampPeriod > 0.f;
    info.timestamp_period_ns = c.props.limits.timestampPeriod;
    const uint32_t bits = q[c.family].timestampValidBits;
    dev.timestamp_mask = bits >= 64 ? ~uint64_t{0} : (uint64_t{1} << bits) - 1;
}

void Context::Impl::create_device() {
    auto& f = dev.fn;
    auto have12 =
        detail::vk_struct<VkPhysicalDeviceVulkan12Features>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES);
    auto have13 =
        detail::vk_struct<VkPhysicalDeviceVulkan13Features>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES);
    have13.pNext = &have12;
    auto have = detail::vk_struct<VkPhysicalDeviceFeatures2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2);
    have.pNext = &have13;
    f.vkGetPhysicalDeviceFeatures2(dev.physical, &have);
    if (!have13.dynamicRendering || !have13.synchronization2)
        throw NoDeviceError(std::string(dev.info.name) +
                            " lacks dynamicRendering or synchronization2: update its driver");

    auto want13 =
        detail::vk_struct<VkPhysicalDeviceVulkan13Features>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES);
    want13.dynamicRendering = VK_TRUE;
    want13.synchronization2 = VK_TRUE;
    // Half-float arithmetic where the device has it: only the BRDF accuracy harness's fp16
    // variant (render/brdf_harness.hpp) uses it; the preview shades in fp32.
    auto want12 =
        detail::vk_struct<VkPhysicalDeviceVulkan12Features>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES);
    want12.shaderFloat16 = have12.shaderFloat16;
    want13.pNext = &want12;
    dev.shader_float16 = have12.shaderFloat16 == VK_TRUE;
    auto want = detail::vk_struct<VkPhysicalDeviceFeatures2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2);
    want.pNext = &want13;
    want.features.samplerAnisotropy = have.features.samplerAnisotropy && !dev.info.cpu;

    const float priority = 1.f;
    auto qi = detail::vk_struct<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
    qi.queueFamilyIndex = dev.queue_family;
    qi.queueCount = 1;
    qi.pQueuePriorities = &priority;

    auto ci = detail::vk_struct<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO);
    ci.pNext = &want;
    ci.queueCreateInfoCount = 1;
    ci.pQueueCreateInfos = &qi;
    VK_CHECK(f.vkCreateDevice(dev.physical, &ci, nullptr, &dev.device));

#define MF_VK_LOAD(name)                                                             \
    f.name = reinterpret_cast<PFN_##name>(f.vkGetDeviceProcAddr(dev.device, #name)); \
    if (!f.name) throw Error("Vulkan driver lacks " #name);
    MF_VK_DEVICE_FUNCTIONS(MF_VK_LOAD)
#undef MF_VK_LOAD
    f.vkGetDeviceQueue(dev.device, dev.queue_family, 0, &dev.queue);
    auto pci = detail::vk_struct<VkPipelineCacheCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO);
    VK_CHECK(f.vkCreatePipelineCache(dev.device, &pci, nullptr, &dev.pipeline_cache));
    // lavapipe's anisotropic filter moves magnified texels by up to half a per cent; a
    // software renderer gains little from it anyway.
    dev.anisotropy = have.features.samplerAnisotropy && !dev.info.cpu ? dev.properties.limits.maxSamplerAnisotropy
                                                                      : 0.f;
}

Context::Context(const ContextOptions& options) : impl_(std::make_unique<Impl>(options)) {}
Context::~Context() = default;
const DeviceInfo& Context::info() const { return impl_->dev.info; }

namespace detail {
Device& device_of(Context& context) { return context.impl().dev; }
}  // namespace detail

std::string vulkan_header_version() {
    return "Vulkan headers " + std::to_string(VK_API_VERSION_MAJOR(VK_HEADER_VERSION_COMPLETE)) + "." +
           std::to_string(VK_API_VERSION_MINOR(VK_HEADER_VERSION_COMPLETE)) + "." + std::to_string(VK_HEADER_VERSION);
}

}  // namespace mf::render
