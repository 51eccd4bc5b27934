#version 460
// Object space is world space: the shapes sit at the origin (the cube's turn is baked in).
#include "common.glsl"

layout(location = kLocationPosition) in vec3 in_position;
layout(location = kLocationNormal) in vec3 in_normal;
layout(location = kLocationTangent) in vec4 in_tangent;  // xyz: tangent (+u); w: bitangent sign (+v)
layout(location = kLocationUv) in vec2 in_uv;

layout(location = 0) out vec3 v_position;
layout(location = 1) out vec3 v_normal;
layout(location = 2) out vec4 v_tangent;
layout(location = 3) out vec2 v_uv;
layout(location = kVaryingCentroidPosition) centroid out vec3 v_position_centroid;

void main() {
    v_position = in_position;
    v_normal = in_normal;
    v_tangent = in_tangent;
    v_uv = in_uv;
    v_position_centroid = in_position;
    gl_Position = frame.view_proj * vec4(in_position, 1.0);
}
