#version 460
// Accuracy harness, the BRDF's arithmetic in binary16 (needs the shaderFloat16 feature; used by
// the benchmark only). See brdf_grid.glsl.
#extension GL_EXT_shader_explicit_arithmetic_types_float16 : require
#define MF_BRDF_FP16
#include "brdf_grid.glsl"
