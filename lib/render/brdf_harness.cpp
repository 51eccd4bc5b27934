// Accuracy harness of the preview's BRDF (see brdf_harness.hpp).
#include "render/brdf_harness.hpp"

#include <cstring>

#include "render/internal.hpp"
#include "render/shaders/interface.h"

namespace mf::render {

using namespace detail;

namespace {

constexpr uint32_t kBrdfGridComp[] =
#include "shaders/brdf_grid.comp.inc"
    ;
constexpr uint32_t kBrdfGridF16Comp[] =
#include "shaders/brdf_grid_f16.comp.inc"
    ;

constexpr auto kEnergyN = static_cast<size_t>(gpu::kEnergyTableSize);
constexpr uint32_t kMaxGroupsX = 32768;  // ≤ the guaranteed maxComputeWorkGroupCount[0] (65535)

static_assert(sizeof(BrdfInput) == sizeof(gpu::GridInput), "BrdfInput is brdf_grid.glsl's GridInput");
// The inputs mode writes model m of input i at 3 i + m (evaluate()'s order).
static_assert(gpu::kBrdfStandard == 0 && gpu::kBrdfAccurate == 1 && gpu::kBrdfUnnormalizedDiffuse == 2);

constexpr VkSpecializationMapEntry kGridEntries[] = {
    spec_entry(gpu::kSpecGridMode, offsetof(gpu::GridSpecialization, mode)),
};

// The storage buffers of brdf_grid.glsl, in binding order.
constexpr int kGridBindings[] = {gpu::kBindingGridInputs, gpu::kBindingGridOutputs, gpu::kBindingGridEnergy};

}  // namespace

struct BrdfHarness::Impl {
    Device& d;
    Unique<VkCommandPool> pool;
    Unique<VkQueryPool> queries;
    Unique<VkDescriptorSetLayout> set_layout;
    Unique<VkPipelineLayout> layout;
    Unique<VkDescriptorPool> descriptor_pool;
    VkDescriptorSet set = VK_NULL_HANDLE;
    Unique<VkPipeline> pipelines[2][2];  // [precision][gpu::kGridMode*]
    Buffer energy;

    Impl(Context& context, const std::vector<float>& e) : d(device_of(context)) {
        if (e.size() != 4 * kEnergyN * kEnergyN)
            throw Error("BRDF harness: the energy table must be 32 × 32 (A, B, 1 − E, 1 − E_avg)");
        auto pi = vk_struct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
        pi.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
        pi.queueFamilyIndex = d.queue_family;
        VkCommandPool ph = VK_NULL_HANDLE;
        VK_CHECK(d.fn.vkCreateCommandPool(d.device, &pi, nullptr, &ph));
        pool = Unique<VkCommandPool>(d, ph);
        if (d.info.timestamps) {
            auto qi = vk_struct<VkQueryPoolCreateInfo>(VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO);
            qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
            qi.queryCount = 2;
            VkQueryPool q = VK_NULL_HANDLE;
            VK_CHECK(d.fn.vkCreateQueryPool(d.device, &qi, nullptr, &q));
            queries = Unique<VkQueryPool>(d, q);
        }
        VkDescriptorSetLayoutBinding b[3];
        for (size_t i = 0; i < 3; ++i)
            b[i] = {static_cast<uint32_t>(kGridBindings[i]), VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1,
                    VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
        auto sci = vk_struct<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
        sci.bindingCount = 3;
        sci.pBindings = b;
        VkDescriptorSetLayout sl = VK_NULL_HANDLE;
        VK_CHECK(d.fn.vkCreateDescriptorSetLayout(d.device, &sci, nullptr, &sl));
        set_layout = Unique<VkDescriptorSetLayout>(d, sl);
        const VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(gpu::GridPush)};
        auto lci = vk_struct<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
        lci.setLayoutCount = 1;
        lci.pSetLayouts = &sl;
        lci.pushConstantRangeCount = 1;
        lci.pPushConstantRanges = &range;
        VkPipelineLayout pl = VK_NULL_HANDLE;
        VK_CHECK(d.fn.vkCreatePipelineLayout(d.device, &lci, nullptr, &pl));
        layout = Unique<VkPipelineLayout>(d, pl);
        const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 3};
        auto dci = vk_struct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
        dci.maxSets = 1;
        dci.poolSizeCount = 1;
        dci.pPoolSizes = &size;
        VkDescriptorPool dp = VK_NULL_HANDLE;
        VK_CHECK(d.fn.vkCreateDescriptorPool(d.device, &dci, nullptr, &dp));
        descriptor_pool = Unique<VkDescriptorPool>(d, dp);
        auto ai = vk_struct<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
        ai.descriptorPool = dp;
        ai.descriptorSetCount = 1;
        ai.pSetLayouts = &sl;
        VK_CHECK(d.fn.vkAllocateDescriptorSets(d.device, &ai, &set));

        energy = create_buffer(d, e.size() * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
        std::memcpy(energy.mapped, e.data(), e.size() * sizeof(float));
        flush(d, energy);
    }

    VkPipeline pipeline(BrdfPrecision p, int mode) {
        const int pi = p == BrdfPrecision::fp16 ? 1 : 0;
        if (pi == 1 && !d.shader_float16) throw Error(d.info.name + " lacks shaderFloat16");
        Unique<VkPipeline>& slot = pipelines[pi][mode];
        if (slot) return slot;
        Unique<VkShaderModule> module = pi ? create_shader(d, kBrdfGridF16Comp, sizeof kBrdfGridF16Comp)
                                           : create_shader(d, kBrdfGridComp, sizeof kBrdfGridComp);
        gpu::GridSpecialization values;
        values.mode = mode;
        const VkSpecializationInfo spec = spec_info(kGridEntries, values);
        auto ci = vk_struct<VkComputePipelineCreateInfo>(VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO);
        ci.stage = vk_struct<VkPipelineShaderStageCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO);
        ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
        ci.stage.module = module;
        ci.stage.pName = "main";
        ci.stage.pSpecializationInfo = &spec;
        ci.layout = layout;
        VkPipeline h = VK_NULL_HANDLE;
        VK_CHECK(d.fn.vkCreateComputePipelines(d.device, VK_NULL_HANDLE, 1, &ci, nullptr, &h));
        slot = Unique<VkPipeline>(d, h);
        return slot;
    }

    // Groups per row of a dispatch of `count` invocations (rows of at most kMaxGroupsX groups).
    static uint32_t groups_x(uint32_t count) {
        const uint32_t groups = (count + gpu::kGridGroup - 1) / gpu::kGridGroup;
        return groups < kMaxGroupsX ? groups : kMaxGroupsX;
    }

    // Binds inputs/outputs, dispatches `count` invocations (timed), copies `out` to `readback`
    // when given. Returns GPU milliseconds.
    double run(VkPipeline pipe, const Buffer& in, const Buffer& out, const Buffer* readback,
               const gpu::GridPush& push) {
        VkDescriptorBufferInfo bi[3] = {{in.buffer, 0, VK_WHOLE_SIZE},
                                        {out.buffer, 0, VK_WHOLE_SIZE},
                                        {energy.buffer, 0, VK_WHOLE_SIZE}};
        VkWriteDescriptorSet w[3];
        for (size_t i = 0; i < 3; ++i) {
            w[i] = vk_struct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
            w[i].dstSet = set;
            w[i].dstBinding = static_cast<uint32_t>(kGridBindings[i]);
            w[i].descriptorCount = 1;
            w[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
            w[i].pBufferInfo = &bi[i];
        }
        d.fn.vkUpdateDescriptorSets(d.device, 3, w, 0, nullptr);

        const uint32_t groups = (push.count + gpu::kGridGroup - 1) / gpu::kGridGroup;
        const uint32_t gx = groups_x(push.count);
        const uint32_t gy = (groups + gx - 1) / gx;
        Submission s(d, pool, queries, 2);
        VkCommandBuffer cmd = s.cmd();
        // The host wrote the inputs before submission (the submission makes them visible).
        d.fn.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipe);
        d.fn.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0, nullptr);
        d.fn.vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
        s.begin_pass("brdf");
        d.fn.vkCmdDispatch(cmd, gx, gy, 1);
        s.end_pass();
        if (readback) {
            memory_barrier(d, cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                           VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
            const VkBufferCopy region{0, 0, out.size};
            d.fn.vkCmdCopyBuffer(cmd, out.buffer, readback->buffer, 1, &region);
            memory_barrier(d, cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                           VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
        } else {
            memory_barrier(d, cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                           VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
        }
        std::vector<PassTime> times;
        s.finish(times);
        return times.empty() ? 0.0 : times.front().ms;
    }
};

BrdfHarness::BrdfHarness(Context& context, const std::vector<float>& energy)
    : impl_(std::make_unique<Impl>(context, energy)) {}
BrdfHarness::~BrdfHarness() = default;

bool BrdfHarness::supports_fp16() const { return impl_->d.shader_float16; }

namespace {

std::vector<std::array<float, 3>> evaluate_with(BrdfHarness::Impl& m, VkPipeline pipe,
                                                const std::vector<BrdfInput>& inputs, double* gpu_ms) {
    std::vector<std::array<float, 3>> result(inputs.size() * 3);
    if (inputs.empty()) return result;
    Buffer in = create_buffer(m.d, inputs.size() * sizeof(BrdfInput), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
    std::memcpy(in.mapped, inputs.data(), inputs.size() * sizeof(BrdfInput));
    flush(m.d, in);
    Buffer out = create_buffer(m.d, inputs.size() * 3 * 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
    std::memset(out.mapped, 0, inputs.size() * 3 * 16);
    flush(m.d, out);
    const auto count = static_cast<uint32_t>(inputs.size());
    const gpu::GridPush push{count, BrdfHarness::Impl::groups_x(count) * gpu::kGridGroup, 0, 0};
    const double ms = m.run(pipe, in, out, nullptr, push);
    if (gpu_ms) *gpu_ms = ms;
    invalidate(m.d, out);
    const auto* f = static_cast<const float*>(out.mapped);
    for (size_t i = 0; i < result.size(); ++i) result[i] = {f[4 * i], f[4 * i + 1], f[4 * i + 2]};
    return result;
}

}  // namespace

std::vector<std::array<float, 3>> BrdfHarness::evaluate(const std::vector<BrdfInput>& inputs, BrdfPrecision precision,
                                                        double* gpu_ms) {
    if (inputs.size() > 0xffffffffu / 3) throw Error("BRDF harness: too many inputs");
    return evaluate_with(*impl_, impl_->pipeline(precision, gpu::kGridModeInputs), inputs, gpu_ms);
}

std::vector<std::array<float, 3>> BrdfHarness::evaluate_spirv(const uint32_t* code, size_t bytes,
                                                              const std::vector<BrdfInput>& inputs, double* gpu_ms) {
    if (inputs.size() > 0xffffffffu / 3) throw Error("BRDF harness: too many inputs");
    Impl& m = *impl_;
    Unique<VkShaderModule> module = create_shader(m.d, code, bytes);
    auto ci = vk_struct<VkComputePipelineCreateInfo>(VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO);
    ci.stage = vk_struct<VkPipelineShaderStageCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO);
    ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    ci.stage.module = module;
    ci.stage.pName = "main";
    ci.layout = m.layout;
    VkPipeline h = VK_NULL_HANDLE;
    VK_CHECK(m.d.fn.vkCreateComputePipelines(m.d.device, VK_NULL_HANDLE, 1, &ci, nullptr, &h));
    const Unique<VkPipeline> pipe(m.d, h);
    return evaluate_with(m, pipe, inputs, gpu_ms);
}

double BrdfHarness::sphere(uint32_t size, Brdf model, uint32_t spp, BrdfPrecision precision, std::vector<float>* rgb) {
    Impl& m = *impl_;
    if (size == 0 || size > 8192) throw Error("BRDF harness: sphere size must be 1..8192");
    if (spp != 1 && spp != 4 && spp != 8) throw Error("BRDF harness: 1, 4 or 8 samples per pixel");
    VkPipeline pipe = m.pipeline(precision, gpu::kGridModeSphere);
    const VkDeviceSize bytes = VkDeviceSize{size} * size * 16;
    Buffer dummy = create_buffer(m.d, sizeof(BrdfInput), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
    // Device-local output: on a GPU the shading is timed against its own memory, as the preview's.
    Buffer out = create_buffer(m.d, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                               false);
    Buffer readback;
    if (rgb) readback = create_buffer(m.d, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    const gpu::GridPush push{size * size, size, spp, brdf_model_id(model)};
    const double ms = m.run(pipe, dummy, out, rgb ? &readback : nullptr, push);
    if (rgb) {
        invalidate(m.d, readback);
        const auto* f = static_cast<const float*>(readback.mapped);
        rgb->resize(size_t{size} * size * 3);
        for (size_t i = 0; i < size_t{size} * size; ++i)
            for (size_t c = 0; c < 3; ++c) (*rgb)[3 * i + c] = f[4 * i + c];
    }
    return ms;
}

}  // namespace mf::render
