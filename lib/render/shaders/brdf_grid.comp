#version 460
// Accuracy harness of the preview's BRDF, fp32 (the preview's precision). See brdf_grid.glsl.
#include "brdf_grid.glsl"
