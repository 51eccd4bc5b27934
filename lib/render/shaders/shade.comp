#version 460
// The compute path (Scene::shading compute): for devices whose raster units are few (an H200's
// fragment pass is bound by them, 40x slower than the same BRDF in a compute shader: see
// docs/bench/README.md). Each invocation
// casts its pixel's primary rays at the analytic shape (sphere, cube or plane), with the (u, v),
// normal and tangent frame the mesh gives the raster path, shades the hits with shading.glsl, as
// shade.frag does, and writes the linear radiance into the same RGBA32F target (then encode.comp
// runs unchanged). A miss is the background, as the raster pass's clear color.
#include "shading.glsl"

layout(local_size_x = kTile, local_size_y = kTile) in;

layout(constant_id = kSpecShape) const int SHAPE = kShapeSphere;  // a kShape* value
layout(constant_id = kSpecSamples) const int SAMPLES = 1;         // Scene::msaa: 1, 2, 4 or 8

layout(set = kSetShadeTarget, binding = kBindingEncodeRadiance, rgba32f) uniform writeonly image2D radiance;

// Vulkan's standard sample locations within a pixel (y down): those the raster path's
// multisampled coverage uses, shaded here each and averaged (Scene::msaa).
vec2 sample_position(int i) {
    const vec2 p2[2] = vec2[](vec2(0.75, 0.75), vec2(0.25, 0.25));
    const vec2 p4[4] = vec2[](vec2(0.375, 0.125), vec2(0.875, 0.375), vec2(0.125, 0.625), vec2(0.625, 0.875));
    const vec2 p8[8] = vec2[](vec2(0.5625, 0.3125), vec2(0.4375, 0.6875), vec2(0.8125, 0.5625), vec2(0.3125, 0.1875),
                              vec2(0.1875, 0.8125), vec2(0.0625, 0.4375), vec2(0.6875, 0.9375), vec2(0.9375, 0.0625));
    if (SAMPLES == 2) return p2[i];
    if (SAMPLES == 4) return p4[i];
    if (SAMPLES == 8) return p8[i];
    return vec2(0.5);
}

// The primary ray through `pos` (target pixels, y down), as shade.frag's sphere_hit makes it.
vec3 ray_direction(vec2 pos) {
    vec2 ndc = pos * frame.viewport.zw * 2.0 - 1.0;
    return normalize(frame.ray_forward.xyz + ndc.x * frame.ray_right.xyz - ndc.y * frame.ray_up.xyz);
}

// The cube and plane are squares of half-size h at the origin: a face's (u, v) is its point's
// offset along the face's tangent t and bitangent b = n × t (geometry.cpp's add_face: every face
// has t × b = n, the bitangent sign is +1).
vec2 face_st(vec3 p, vec3 t, vec3 b, float h) {
    return vec2(dot(p, t), -dot(p, b)) * (0.5 / h) + 0.5;  // st's t = 1 − v
}

// The face of the cube (edge frame.shape.x, turned by frame.shape_rotation) that the ray enters
// (or with `far`, leaves: a double-sided material's far side), by the slab method in object
// space. Faces as geometry.cpp's make_cube: ±X and ±Z have b = +Y and t = b × n, ±Y have t = +X
// and b = n × t.
bool cube_hit(vec3 o, vec3 d, bool far, out SurfacePoint s) {
    mat3 rot = mat3(frame.shape_rotation);
    vec3 lo = transpose(rot) * o, ld = transpose(rot) * d;
    float h = 0.5 * frame.shape.x;
    vec3 inv = 1.0 / mix(ld, vec3(1e-30), equal(ld, vec3(0.0)));  // a ray parallel to a slab never leaves it
    vec3 t0 = (-h - lo) * inv, t1 = (h - lo) * inv;
    vec3 near3 = min(t0, t1), far3 = max(t0, t1);
    float tn = max(max(near3.x, near3.y), near3.z), tf = min(min(far3.x, far3.y), far3.z);
    s.p = vec3(0.0);
    s.back = far;
    if (tn > tf || tn <= 0.0) return false;  // missed, or seen from inside (never in a scene)
    float th = far ? tf : tn;
    int axis = far ? (far3.x == tf ? 0 : far3.y == tf ? 1 : 2) : (near3.x == tn ? 0 : near3.y == tn ? 1 : 2);
    vec3 ln = vec3(0.0);
    ln[axis] = (ld[axis] < 0.0) != far ? 1.0 : -1.0;  // outward: the face the ray enters faces it
    vec3 lt = axis == 1 ? vec3(1.0, 0.0, 0.0) : cross(vec3(0.0, 1.0, 0.0), ln);
    vec3 lb = cross(ln, lt);
    vec3 lp = lo + th * ld;
    lp[axis] = ln[axis] * h;  // exactly on the face
    s.p = rot * lp;
    s.n = rot * ln;
    s.t = rot * lt;
    s.bsign = 1.0;
    s.st = face_st(lp, lt, lb, h);
    return true;
}

// The plane: side frame.shape.x in XY through the origin, facing +Z (t = +X, b = +Y); seen from
// behind, its back (`far`: a double-sided material's).
bool plane_hit(vec3 o, vec3 d, bool far, out SurfacePoint s) {
    float h = 0.5 * frame.shape.x;
    s.p = vec3(0.0);
    s.back = far;
    if (far ? d.z <= 0.0 : d.z >= 0.0) return false;  // the other side
    float t = -o.z / d.z;
    vec3 p = o + t * d;
    p.z = 0.0;
    if (t <= 0.0 || abs(p.x) > h || abs(p.y) > h) return false;
    s.p = p;
    s.n = vec3(0.0, 0.0, 1.0);
    s.t = vec3(1.0, 0.0, 0.0);
    s.bsign = 1.0;
    s.st = face_st(p, s.t, vec3(0.0, 1.0, 0.0), h);
    return true;
}

bool sphere_point(vec3 o, vec3 d, bool far, out SurfacePoint s) {
    float t;
    bool hit = sphere_intersect(o, d, frame.shape.x, far, t);
    s.back = far;
    s.p = o + t * d;
    s.n = normalize(s.p);
    s.st = sphere_st(s.n);
    // At the poles, the tangent of the mesh's column at this u (∂p/∂u ∝ (sin 2πu, 0, cos 2πu)).
    s.t = sphere_tangent(s.n, vec3(sin(2.0 * PI * s.st.x), 0.0, cos(2.0 * PI * s.st.x)));
    s.bsign = 1.0;
    return hit && t > 0.0;  // from inside, or behind the camera: back faces, culled by the raster path
}

bool shape_hit(vec3 o, vec3 d, bool far, out SurfacePoint s) {
    if (SHAPE == kShapeCube) return cube_hit(o, d, far, s);
    if (SHAPE == kShapePlane) return plane_hit(o, d, far, s);
    return sphere_point(o, d, far, s);
}

// st where the ray d meets the plane tangent to the surface at s: the first-order (u, v) of the
// neighbouring pixel's ray, defined at a silhouette too (where that ray may miss the shape).
vec2 neighbour_st(vec3 o, vec3 d, SurfacePoint s) {
    float facing = dot(d, s.n);
    facing = abs(facing) < 1e-8 ? -1e-8 : facing;  // grazing: a long way along the plane
    vec3 p = o + (dot(s.p - o, s.n) / facing) * d;
    if (SHAPE == kShapeSphere) return sphere_st(normalize(p));
    return s.st + face_st(p - s.p, s.t, cross(s.n, s.t), 0.5 * frame.shape.x) - 0.5;
}

// The change of st to a neighbouring pixel; across the sphere's seam u wraps, as the mesh's
// (u, v) (which the raster path differentiates) does not jump there.
vec2 st_step(vec2 from, vec2 to) {
    vec2 step = to - from;
    if (SHAPE == kShapeSphere) step.x -= round(step.x);
    return step;
}

// The hit's shading (rgb) and coverage (a), with its texture footprint from the neighbours' rays.
vec4 shade_hit(vec3 o, vec2 pos, SurfacePoint s) {
    s.st_dx = st_step(s.st, neighbour_st(o, ray_direction(pos + vec2(1.0, 0.0)), s));
    s.st_dy = st_step(s.st, neighbour_st(o, ray_direction(pos + vec2(0.0, 1.0)), s));
    return shade_surface(s);
}

vec3 radiance_at(vec2 pos) {
    vec3 o = frame.camera_position.xyz;
    vec3 d = ray_direction(pos);
    SurfacePoint s, back;
    bool front = shape_hit(o, d, false, s);
    // Double-sided: the far side under the near one, as the raster path's two draws blend them.
    bool far_side = DOUBLE_SIDED && shape_hit(o, d, true, back);
    if (!front && !far_side) return frame.background.rgb;
    if (FILL_ONLY) return frame.albedo.rgb;
    vec4 near = front ? shade_hit(o, pos, s) : vec4(0.0);
    vec3 color = frame.background.rgb;
    // The far side only where the near one lets it through (a mask's cut texels: half the
    // shading of a cut-out where the raster path shades both); mix by 1 keeps the near exactly.
    if (far_side && near.a < 1.0) {
        vec4 c = shade_hit(o, pos, back);
        color = mix(color, c.rgb, c.a);
    }
    return mix(color, near.rgb, near.a);
}

void main() {
    uvec2 px = gl_GlobalInvocationID.xy;
    if (px.x >= uint(frame.viewport.x) || px.y >= uint(frame.viewport.y)) return;
    // Scene::msaa: every sample shaded and averaged in linear radiance (as a resolve averages).
    vec3 sum = vec3(0.0);
    for (int i = 0; i < SAMPLES; ++i) sum += radiance_at(vec2(px) + sample_position(i));
    imageStore(radiance, ivec2(px), vec4(sum / float(SAMPLES), 1.0));
}
