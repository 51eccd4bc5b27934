#version 460
// The raster path: the shape's mesh decides coverage and gives the surface point (or the analytic
// sphere does, below); shading.glsl does the rest, as for shade.comp.
#include "shading.glsl"

layout(location = 0) in vec3 v_position;
layout(location = 1) in vec3 v_normal;
layout(location = 2) in vec4 v_tangent;
layout(location = 3) in vec2 v_uv;
// On the mesh within the covered samples (the pixel's centre may lie off it at a silhouette).
layout(location = kVaryingCentroidPosition) centroid in vec3 v_position_centroid;

layout(location = 0) out vec4 out_radiance;

// Exact hit on the sphere of the primary ray through this pixel's centre. The mesh (three.js
// UV sphere) decides coverage; position, normal, (u, v) and tangent frame come from the sphere
// itself, so shading has no faceting and matches an analytic reference. Returns false when the
// ray misses (only possible at the silhouette, in the last bits of precision).
//
// Multisampled, the shader runs once for all covered samples of a pixel, whose centre may lie
// outside the sphere at the silhouette: the ray goes through the centroid of the covered samples
// on the mesh instead, which lies within the sphere (the mesh's triangles are chords of it), so
// it always hits. A back face (double-sided materials) takes the ray's far hit.
bool sphere_hit(bool far, out vec3 p) {
    vec3 o = frame.camera_position.xyz;
    vec3 d;
    if (MSAA) {
        d = normalize(v_position_centroid - o);
    } else {
        vec2 ndc = gl_FragCoord.xy * frame.viewport.zw * 2.0 - 1.0;  // y grows downward
        d = normalize(frame.ray_forward.xyz + ndc.x * frame.ray_right.xyz - ndc.y * frame.ray_up.xyz);
    }
    float t;
    bool hit = sphere_intersect(o, d, frame.shape.x, far, t);
    p = o + t * d;
    return hit;
}

void main() {
    if (FILL_ONLY) {
        out_radiance = vec4(frame.albedo.rgb, 1.0);
        return;
    }
    // Gradients of the mesh's (u, v): continuous across the seam at u = 0|1, unlike the
    // analytic u, so the sampler picks the right mip everywhere.
    SurfacePoint s;
    s.st = vec2(v_uv.x, 1.0 - v_uv.y);
    s.st_dx = dFdx(s.st);
    s.st_dy = dFdy(s.st);
    s.p = v_position;
    s.n = normalize(v_normal);
    s.t = v_tangent.xyz;
    s.bsign = v_tangent.w;
    s.back = !gl_FrontFacing;  // drawn only for double-sided materials (pipelines culls them otherwise)
    if (ANALYTIC_SPHERE) {
        vec3 hit;
        if (sphere_hit(s.back, hit)) {
            s.p = hit;
            s.n = normalize(hit);
            s.st = sphere_st(s.n);
            s.t = sphere_tangent(s.n, s.t);  // the mesh's tangent at the poles
            s.bsign = 1.0;
        }
    }
    vec4 c = shade_surface(s);
    // A cut-out texel leaves what is behind it, and no depth (the shaderball's ring over its ball).
    if (ALPHA_MODE == kAlphaMask && c.a == 0.0) discard;
    // Double-sided: far faces first, then near ones, each blended over the target (premultiplied:
    // ONE, ONE_MINUS_SRC_ALPHA), which starts as the background. Single-sided: written as it is.
    out_radiance = DOUBLE_SIDED ? vec4(c.rgb * c.a, c.a) : vec4(mix(frame.background.rgb, c.rgb, c.a), 1.0);
}
