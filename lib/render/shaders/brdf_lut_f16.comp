#version 460
// Fallback table in RGBA16F (storage and linear filtering on every Vulkan device).
#define LUT_FORMAT rgba16f
#include "brdf_lut.glsl"
