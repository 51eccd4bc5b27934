#version 460
// Table in RGBA32F where the device filters it linearly (the usual case).
#define LUT_FORMAT rgba32f
#include "brdf_lut.glsl"
