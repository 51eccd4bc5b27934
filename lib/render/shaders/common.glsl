// Data shared by the shading pipeline's stages; mirrors FrameData in renderer.cpp (std140).
#ifndef MF_COMMON_GLSL
#define MF_COMMON_GLSL

const int kMaxLights = 16;

struct LightData {
    vec4 position;    // xyz: unit vector toward a directional light, or a point light's position
    vec4 irradiance;  // rgb: color × intensity (E at 1 m for a point light)
};

layout(set = 0, binding = 0, std140) uniform FrameData {
    mat4 view_proj;
    vec4 camera_position;
    vec4 ray_right;    // camera right × tan(yfov/2) × aspect: primary ray through a pixel
    vec4 ray_up;       // camera up × tan(yfov/2)
    vec4 ray_forward;  // unit view direction
    vec4 viewport;     // width, height, 1/width, 1/height
    vec4 background;   // rgb, linear
    vec4 albedo;       // rgb: constant albedo (linear) where the role has no texture
    vec4 emissive;     // rgb: constant emitted radiance
    vec4 scalars;      // constant roughness, metalness, occlusion, opacity
    vec4 shape;        // x: sphere radius; y: environment intensity; z: last prefiltered mip
    LightData lights[kMaxLights];
} frame;

#endif
