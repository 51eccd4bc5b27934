// Per-frame data: the uniform block (camera, the material's constants, lights) and the frame's
// descriptor set.
#include <cmath>
#include <cstring>
#include <numbers>

#include "render/internal.hpp"
#include "render/renderer_impl.hpp"

namespace mf::render {

using namespace detail;

namespace {

// Scene vectors in double: the camera basis and the view-projection product are formed in
// double and rounded once.
using D3 = std::array<double, 3>;
D3 d3(const Vec3& v) { return {v[0], v[1], v[2]}; }
D3 sub(const D3& a, const D3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const D3& a, const D3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
D3 cross(const D3& a, const D3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
D3 normalized(const D3& a) {
    const double l = std::sqrt(dot(a, a));
    if (!(l > 0)) throw Error("degenerate vector in the scene (zero length)");
    return {a[0] / l, a[1] / l, a[2] / l};
}
void put(gpu::vec4& dst, const D3& v, double w = 0.0) {
    for (size_t i = 0; i < 3; ++i) dst[i] = static_cast<float>(v[i]);
    dst[3] = static_cast<float>(w);
}

}  // namespace

void Renderer::Impl::write_frame_descriptors() {
    VkDescriptorBufferInfo ub{uniforms.buffer, 0, sizeof(gpu::FrameData)};
    const bool lut = lighting && lighting->brdf_lut.view;
    const bool env = lighting && lighting->env_specular.view;
    // The dummies keep every descriptor valid where the variant samples nothing.
    struct Sampled {
        int binding;
        VkImageView view;
    };
    const Sampled sampled[] = {
        {gpu::kBindingBrdfLut, lut ? lighting->brdf_lut.view.get() : dummy_2d.view.get()},
        {gpu::kBindingEnvSpecular, env ? lighting->env_specular.view.get() : dummy_cube.view.get()},
        {gpu::kBindingEnvIrradiance, env ? lighting->env_irradiance.view.get() : dummy_cube.view.get()},
    };
    VkDescriptorImageInfo images[3]{};
    VkWriteDescriptorSet w[4]{};
    w[0] = vk_struct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
    w[0].dstSet = frame_set;
    w[0].dstBinding = static_cast<uint32_t>(gpu::kBindingFrameData);
    w[0].descriptorCount = 1;
    w[0].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    w[0].pBufferInfo = &ub;
    for (size_t i = 0; i < 3; ++i) {
        images[i] = {sampler_clamp, sampled[i].view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        VkWriteDescriptorSet& wi = w[i + 1];
        wi = vk_struct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
        wi.dstSet = frame_set;
        wi.dstBinding = static_cast<uint32_t>(sampled[i].binding);
        wi.descriptorCount = 1;
        wi.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        wi.pImageInfo = &images[i];
    }
    d.fn.vkUpdateDescriptorSets(d.device, 4, w, 0, nullptr);
}

void Renderer::Impl::write_frame(const Material& m) {
    gpu::FrameData f{};
    const D3 pos = d3(scene.camera.position);
    const D3 fwd = normalized(sub(d3(scene.camera.target), pos));
    const D3 right = normalized(cross(fwd, d3(scene.camera.up)));
    const D3 up = cross(right, fwd);
    const double aspect = static_cast<double>(scene.width) / scene.height;
    const double tan_half = std::tan(scene.camera.yfov_deg * std::numbers::pi / 360.0);
    if (!(scene.camera.yfov_deg > 0.f && scene.camera.yfov_deg < 180.f))
        throw Error("camera yfov_deg must be in (0, 180)");

    // view: rows right, up, −forward; projection: Vulkan clip space (y down, depth 0..1),
    // the image's top row looking along +up. Column-major for GLSL.
    const double near_plane = 0.01, far_plane = 1000.0;
    const double view[4][4] = {{right[0], right[1], right[2], -dot(right, pos)},
                               {up[0], up[1], up[2], -dot(up, pos)},
                               {-fwd[0], -fwd[1], -fwd[2], dot(fwd, pos)},
                               {0, 0, 0, 1}};
    const double fy = 1.0 / tan_half;
    const double proj[4][4] = {{fy / aspect, 0, 0, 0},
                               {0, -fy, 0, 0},
                               {0, 0, far_plane / (near_plane - far_plane),
                                near_plane * far_plane / (near_plane - far_plane)},
                               {0, 0, -1, 0}};
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) {
            double v = 0;
            for (int k = 0; k < 4; ++k) v += proj[r][k] * view[k][c];
            f.view_proj[c * 4 + r] = static_cast<float>(v);
        }
    put(f.camera_position, pos, 1.0);
    put(f.ray_right, {right[0] * tan_half * aspect, right[1] * tan_half * aspect, right[2] * tan_half * aspect});
    put(f.ray_up, {up[0] * tan_half, up[1] * tan_half, up[2] * tan_half});
    put(f.ray_forward, fwd);
    // The shaded target: N×N samples a pixel (Scene::supersample), each at its own centre.
    const auto tw = static_cast<float>(scene.width * scene.supersample),
               th = static_cast<float>(scene.height * scene.supersample);
    f.viewport[0] = tw;
    f.viewport[1] = th;
    f.viewport[2] = 1.f / tw;
    f.viewport[3] = 1.f / th;
    put(f.background, d3(scene.background), 1.0);
    put(f.albedo, d3(m.albedo.value), 1.0);
    put(f.emissive, d3(m.emissive.value), m.emissive.strength);
    f.scalars[0] = m.roughness.value;
    f.scalars[1] = m.metalness.value;
    f.scalars[2] = m.occlusion.value;
    f.scalars[3] = m.opacity.value;
    f.shape[0] = scene.shape.size;
    f.shape[1] = scene.environment ? scene.environment->intensity : 0.f;
    const uint32_t mips = lighting ? lighting->env_specular_mips : 0;
    f.shape[2] = static_cast<float>(mips > 0 ? mips - 1 : 0);
    f.ground[0] = ground_y;
    f.ground[1] = scene.ground.albedo;
    f.ground[2] = scene.ground.roughness;
    f.ground[3] = static_cast<float>(std::tan(double{scene.ground.light_deg} * std::numbers::pi / 180.0));
    f.occluder[3] = shape_radius;  // centred at the origin, where every shape sits
    f.alpha[0] = m.alpha_cutoff;
    // Column-major for GLSL; the identity but for the cube (the sphere and plane are not turned).
    const Rotation rot = scene.shape.type == ShapeType::cube ? cube_rotation()
                                                             : Rotation{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
    for (size_t c = 0; c < 3; ++c)
        for (size_t r = 0; r < 3; ++r) f.shape_rotation[c * 4 + r] = static_cast<float>(rot[r][c]);
    f.shape_rotation[15] = 1.f;
    f.uv[0] = m.uv_scale[0];
    f.uv[1] = m.uv_scale[1];
    f.uv[2] = m.uv_offset[0];
    f.uv[3] = m.uv_offset[1];

    // Directional lights first, then point lights: the order the shader's loop expects.
    size_t slot = 0;
    for (int pass = 0; pass < 2; ++pass)
        for (const Light& l : scene.lights) {
            if ((pass == 0) != (l.type == LightType::directional)) continue;
            gpu::LightData& dst = f.lights[slot++];
            if (l.type == LightType::directional) {
                const D3 dir = normalized(d3(l.direction));
                put(dst.position, {-dir[0], -dir[1], -dir[2]}, 0.0);
            } else {
                put(dst.position, d3(l.position), 1.0);
            }
            put(dst.irradiance,
                {double{l.color[0]} * l.intensity, double{l.color[1]} * l.intensity, double{l.color[2]} * l.intensity});
        }
    std::memcpy(uniforms.mapped, &f, sizeof f);
    flush(d, uniforms);
}

}  // namespace mf::render
