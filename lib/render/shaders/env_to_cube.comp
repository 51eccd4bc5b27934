#version 460
// Equirectangular environment → cube map (mip 0). u = 0.5 + atan2(d.x, −d.z)/2π,
// v = acos(d.y)/π: the image's centre is seen looking along −Z, its top row is straight up.
#include "ibl_common.glsl"

layout(set = 0, binding = kBindingIblSource) uniform sampler2D equirect;
layout(set = 0, binding = kBindingIblTarget, rgba16f) uniform writeonly image2DArray cube;

void main() {
    uvec3 id = gl_GlobalInvocationID;
    if (id.x >= params.size || id.y >= params.size) return;
    vec3 d = cube_direction(id.xy, id.z, params.size);
    vec2 uv = vec2(0.5 + atan(d.x, -d.z) * (0.5 / PI), atan(length(d.xz), d.y) / PI);
    imageStore(cube, ivec3(id), vec4(textureLod(equirect, uv, 0.0).rgb, 1.0));
}
