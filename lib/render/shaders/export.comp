#version 460
// Read-back of a sampled image for render/export.cpp: one mip of every layer as floats, texel by
// texel (texelFetch: no filtering). The image-based-lighting maps are made as storage and sampled
// images only; sampling them, as the shading does, needs no other usage.
#include "interface.h"

layout(local_size_x = kTile, local_size_y = kTile) in;

layout(set = 0, binding = kBindingExportSource) uniform sampler2DArray source;
layout(set = 0, binding = kBindingExportTexels, std430) writeonly buffer Texels { vec4 texels[]; };
layout(push_constant) uniform ExportPush {
    ExportParams params;
};

void main() {
    uvec3 at = gl_GlobalInvocationID;  // x, y, layer
    if (at.x >= params.width || at.y >= params.height || at.z >= params.layers) return;
    texels[(at.z * params.height + at.y) * params.width + at.x] = texelFetch(source, ivec3(at), int(params.mip));
}
