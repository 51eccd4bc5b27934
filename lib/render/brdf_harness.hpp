// Accuracy harness of the preview's BRDF: runs the functions of shaders/brdf.glsl (the ones the
// preview's fragment shader calls) in a compute shader (shaders/brdf_grid.glsl) on arbitrary
// inputs, or over the accuracy benchmark's sphere. For tests/render/brdf_grid_test.cpp and
// bench/brdf_bench.cpp; the preview itself does not use it. Names no Vulkan type.
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "render/render.hpp"

namespace mf::render {

// One input of the grid; the layout of gpu::GridInput (render/shaders/interface.h, std430).
struct BrdfInput {
    std::array<float, 4> n;       // w: roughness
    std::array<float, 4> v;       // w: metalness
    std::array<float, 4> l;       // w: light intensity (irradiance at normal incidence)
    std::array<float, 4> albedo;  // rgb
};
static_assert(sizeof(BrdfInput) == 64);

enum class BrdfPrecision { fp32, fp16 };

class BrdfHarness {
public:
    // energy: the split-sum terms (A, B) of the height-correlated lobe (its directional albedo
    // with Schlick's F is F0 A + B, with F = 1 it is E = A + B), the loss 1 − E and the row's
    // 1 − E_avg (E_avg the cosine-weighted average of E) at the 32 × 32 texel centres
    // ((i + 0.5)/32, (j + 0.5)/32), row j = roughness, as A, B, 1 − E, 1 − E_avg (4 × 32² floats,
    // cpubrdf::EnergyTable::texels()): the accurate model's multiple-scattering lobe and diffuse
    // weight.
    BrdfHarness(Context& context, const std::vector<float>& energy);
    ~BrdfHarness();
    BrdfHarness(const BrdfHarness&) = delete;
    BrdfHarness& operator=(const BrdfHarness&) = delete;

    // Whether the device can run BrdfPrecision::fp16 (the shaderFloat16 feature).
    bool supports_fp16() const;

    // Radiance of each input under Standard, Accurate and UnnormalizedDiffuse (in that order): 3 RGB
    // triples per input. gpu_ms (optional): GPU time of the dispatch from timestamp queries.
    std::vector<std::array<float, 3>> evaluate(const std::vector<BrdfInput>& inputs,
                                               BrdfPrecision precision = BrdfPrecision::fp32, double* gpu_ms = nullptr);

    // The same inputs through another compute shader with brdf_grid.glsl's interface, given as
    // SPIR-V: inputs (GridInput) at binding kBindingGridInputs, outputs (vec4, model m of input i
    // at 3 i + m) at kBindingGridOutputs, the energy table at kBindingGridEnergy, GridPush as push
    // constants with `width` the invocations per row of the dispatch (index = y · width + x),
    // kGridGroup invocations per group. For the d3d11 preset's HLSL BRDF, compiled by glslang
    // (tests/render): the same oracle and bounds as the GLSL. Outputs the shader does not write
    // are 0.
    std::vector<std::array<float, 3>> evaluate_spirv(const uint32_t* code, size_t bytes,
                                                     const std::vector<BrdfInput>& inputs, double* gpu_ms = nullptr);

    // The benchmark's sphere (bench/accuracy/knobs_brdf.cpp's scene) at size × size pixels,
    // `spp` ∈ {1, 4, 8} samples per pixel. Returns GPU milliseconds of the shading dispatch; with
    // `rgb`, also reads the radiance back (rows top to bottom, 3 floats per pixel).
    double sphere(uint32_t size, Brdf model, uint32_t spp, BrdfPrecision precision, std::vector<float>* rgb = nullptr);

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace mf::render
