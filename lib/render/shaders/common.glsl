// The per-frame uniform block of the shading pipeline's stages (layout: FrameData in interface.h).
#ifndef MF_COMMON_GLSL
#define MF_COMMON_GLSL

#include "interface.h"

layout(set = kSetFrame, binding = kBindingFrameData, std140) uniform FrameBlock {
    FrameData frame;
};

#endif
