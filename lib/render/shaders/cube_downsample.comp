#version 460
// One mip of a cube map from the one above: 2×2 box average per face (radiance is linear).
#include "ibl_common.glsl"

layout(set = 0, binding = kBindingIblSource) uniform sampler2DArray src;  // the mip above, all six faces
layout(set = 0, binding = kBindingIblTarget, rgba16f) uniform writeonly image2DArray dst;

void main() {
    uvec3 id = gl_GlobalInvocationID;
    if (id.x >= params.size || id.y >= params.size) return;
    ivec3 s = ivec3(2 * id.xy, id.z);
    vec3 c = texelFetch(src, s, 0).rgb + texelFetch(src, s + ivec3(1, 0, 0), 0).rgb +
             texelFetch(src, s + ivec3(0, 1, 0), 0).rgb + texelFetch(src, s + ivec3(1, 1, 0), 0).rgb;
    imageStore(dst, ivec3(id), vec4(0.25 * c, 1.0));
}
