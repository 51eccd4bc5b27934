// Shared by the environment passes: push constants, workgroup size, cube-map texel directions,
// an orthonormal basis and the Hammersley points.
#ifndef MF_IBL_COMMON_GLSL
#define MF_IBL_COMMON_GLSL

#include "brdf.glsl"  // includes interface.h

layout(push_constant) uniform IblPush {
    IblParams params;
};

layout(local_size_x = kTile, local_size_y = kTile) in;

// Direction through texel `xy` of cube face `face` (Vulkan/OpenGL face orientation).
vec3 cube_direction(uvec2 xy, uint face, uint size) {
    vec2 t = (vec2(xy) + 0.5) / float(size) * 2.0 - 1.0;
    vec3 d;
    if (face == 0u) d = vec3(1.0, -t.y, -t.x);
    else if (face == 1u) d = vec3(-1.0, -t.y, t.x);
    else if (face == 2u) d = vec3(t.x, 1.0, t.y);
    else if (face == 3u) d = vec3(t.x, -1.0, -t.y);
    else if (face == 4u) d = vec3(t.x, -t.y, 1.0);
    else d = vec3(-t.x, -t.y, -1.0);
    return normalize(d);
}

// An orthonormal frame around n (Duff et al. 2017, "Building an Orthonormal Basis, Revisited").
void basis(vec3 n, out vec3 t, out vec3 b) {
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float c = n.x * n.y * a;
    t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
    b = vec3(c, s + n.y * n.y * a, -n.y);
}

vec2 hammersley(uint i, uint n) {
    return vec2((float(i) + 0.5) / float(n), float(bitfieldReverse(i)) * 2.3283064365386963e-10);
}

#endif
