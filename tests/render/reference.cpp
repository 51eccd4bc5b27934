#include "reference.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <mutex>
#include <numbers>
#include <stdexcept>

#include "../stability/brdf_reference.hpp"
#include "base/srgb.hpp"

namespace mf::test {

using render::Channel;
using render::Material;
using render::Scene;
using render::TexelType;
using render::Texture;

namespace {

constexpr double kPi = std::numbers::pi;
using cpubrdf::kMinNoV;
using cpubrdf::kMinRoughness;

struct V3 {
    double x = 0, y = 0, z = 0;
};
V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V3 operator*(V3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
V3 normalize(V3 a) { return a * (1.0 / std::sqrt(dot(a, a))); }
V3 v3(const render::Vec3& a) { return {a[0], a[1], a[2]}; }
cpubrdf::V3<double> to_oracle(V3 a) { return {a.x, a.y, a.z}; }

cpubrdf::Model model_of(render::Brdf b) {
    switch (b) {
        case render::Brdf::standard: return cpubrdf::Model::standard;
        case render::Brdf::accurate: return cpubrdf::Model::accurate;
        case render::Brdf::unnormalized_diffuse: return cpubrdf::Model::unnormalized_diffuse;
    }
    throw std::invalid_argument("reference: unknown BRDF");
}

struct RGB {
    double c[3] = {0, 0, 0};
};

struct Surface {
    double albedo[3];
    double roughness, metalness, opacity;
    double emissive[3];
    V3 n;
};

// The scene's lights through the BRDF oracle (tests/stability/brdf_reference.hpp), prepared as
// shade.frag prepares them: roughness and metalness clamped, albedo as sampled; the split-sum
// terms (A, B)(μ, r) and the losses 1 − E(μ, r), 1 − E_avg(r) of the accurate model's multiple-scattering lobe and
// diffuse weight by the oracle's own quadrature (specular_dfg_correlated), where the GPU reads its BRDF lookup table.
RGB shade(const Scene& scene, const Surface& s, V3 p, V3 v) {
    const double r = std::clamp(s.roughness, kMinRoughness, 1.0);
    const double metal = std::clamp(s.metalness, 0.0, 1.0);
    const V3 n = s.n;
    const double NoV = std::clamp(dot(n, v), kMinNoV, 1.0);
    const std::array<double, 3> albedo{s.albedo[0], s.albedo[1], s.albedo[2]};
    const cpubrdf::Model model = model_of(scene.brdf);

    RGB out;
    for (const render::Light& light : scene.lights) {
        V3 l;
        std::array<double, 3> E{};
        for (size_t i = 0; i < 3; ++i) E[i] = double{light.color[i]} * light.intensity;
        if (light.type == render::LightType::directional) {
            l = normalize(v3(light.direction)) * -1.0;
        } else {
            const V3 d = v3(light.position) - p;
            const double d2 = dot(d, d);
            if (d2 < 1e-12) continue;
            l = d * (1.0 / std::sqrt(d2));
            for (double& e : E) e /= d2;
        }
        const auto c = cpubrdf::light_radiance<double>(model, to_oracle(n), to_oracle(v), to_oracle(l), NoV, r, metal,
                                                       albedo, E, specular_dfg_correlated);
        for (size_t i = 0; i < 3; ++i) out.c[i] += c[i];
    }
    for (int i = 0; i < 3; ++i) {
        const double o = std::clamp(s.opacity, 0.0, 1.0);
        out.c[i] = (out.c[i] + s.emissive[i]) * o + double{scene.background[static_cast<size_t>(i)]} * (1.0 - o);
    }
    return out;
}

// ---- textures: level 0, bilinear, repeat, sRGB decoded per texel before filtering

double texel(const Texture& t, int x, int y, int c) {
    x = ((x % static_cast<int>(t.width)) + static_cast<int>(t.width)) % static_cast<int>(t.width);
    y = ((y % static_cast<int>(t.height)) + static_cast<int>(t.height)) % static_cast<int>(t.height);
    const size_t base = (size_t(y) * t.width + size_t(x)) * t.channels;
    int src = c;
    if (t.channels <= 2) src = c < 3 ? 0 : (t.channels == 2 ? 1 : -1);
    else if (c == 3 && t.channels == 3) src = -1;
    if (src < 0) return 1.0;
    const size_t i = base + size_t(src);
    double v = 0;
    switch (t.type) {
        case TexelType::u8: v = t.data[i] / 255.0; break;
        case TexelType::u16: {
            uint16_t q;
            std::memcpy(&q, t.data.data() + 2 * i, 2);
            v = q / 65535.0;
            break;
        }
        case TexelType::f32: {
            float f;
            std::memcpy(&f, t.data.data() + 4 * i, 4);
            v = f;
            break;
        }
    }
    if (t.srgb && c < 3) v = mf::srgb_to_linear(v);
    return v;
}

std::array<double, 4> sample(const Texture& t, double s, double u) {
    const double x = s * t.width - 0.5, y = u * t.height - 0.5;
    const double x0 = std::floor(x), y0 = std::floor(y);
    const double fx = x - x0, fy = y - y0;
    const int ix = static_cast<int>(x0), iy = static_cast<int>(y0);
    std::array<double, 4> out{};
    for (int c = 0; c < 4; ++c)
        out[size_t(c)] = (1 - fx) * (1 - fy) * texel(t, ix, iy, c) + fx * (1 - fy) * texel(t, ix + 1, iy, c) +
                         (1 - fx) * fy * texel(t, ix, iy + 1, c) + fx * fy * texel(t, ix + 1, iy + 1, c);
    return out;
}

double scalar(const Material& m, const render::ScalarRole& r, double s, double t) {
    if (r.texture < 0) return r.value;
    const double x = sample(m.textures[size_t(r.texture)], s, t)[static_cast<size_t>(r.channel)];
    return r.invert ? 1.0 - x : x;
}

struct Camera {
    V3 pos, right, up, fwd;
    uint32_t w, h;
    V3 ray(double px, double py) const {
        const double nx = px / w * 2.0 - 1.0, ny = py / h * 2.0 - 1.0;
        return normalize(fwd + right * nx - up * ny);
    }
};

Camera make_camera(const Scene& s) {
    Camera c;
    c.pos = v3(s.camera.position);
    c.fwd = normalize(v3(s.camera.target) - c.pos);
    c.right = normalize(cross(c.fwd, v3(s.camera.up)));
    c.up = cross(c.right, c.fwd);
    const double tan_half = std::tan(s.camera.yfov_deg * kPi / 360.0);
    const double aspect = static_cast<double>(s.width) / s.height;
    c.right = c.right * (tan_half * aspect);
    c.up = c.up * tan_half;
    c.w = s.width;
    c.h = s.height;
    return c;
}

bool intersect(V3 o, V3 d, double r, V3& p) {
    const double b = dot(o, d);
    const double c = dot(o, o) - r * r;
    const double disc = b * b - c;
    if (disc < 0) return false;
    const double t = -b - std::sqrt(disc);
    if (t <= 0) return false;
    p = o + d * t;
    return true;
}

// (s, t) of the texture image at a point of the sphere (t = 0 at the top row).
void sphere_st(V3 n, double& s, double& t) {
    s = std::atan2(n.z, -n.x) / (2 * kPi);
    if (s < 0) s += 1.0;
    t = std::acos(std::clamp(n.y, -1.0, 1.0)) / kPi;
}

}  // namespace

int to_code(double e) { return static_cast<int>(std::floor(std::clamp(e, 0.0, 1.0) * 255.0 + 0.5)); }

std::array<double, 4> specular_dfg_correlated(double NoV, double roughness) {
    // Tabulated per roughness over √(n·v) (E is steepest at grazing angles), 257 entries,
    // linear in between: the interpolation error stays near 1e-6. Each entry is the oracle's
    // quadrature over visible normals, 128² points. 1 − E_avg = 2 ∫ (1 − E(μ)) μ dμ
    // = 4 ∫ (1 − E(x²)) x³ dx (μ = x²) by the trapezoidal rule over the same entries.
    struct Table {
        std::vector<std::array<double, 2>> ab;
        double lost_avg = 0.0;
    };
    static std::map<double, Table> tables;
    static std::mutex mutex;
    const double r = std::max(roughness, kMinRoughness);
    constexpr int kEntries = 257;
    Table* table;
    {
        std::lock_guard lock(mutex);
        table = &tables[r];
        if (table->ab.empty()) {
            table->ab.resize(kEntries);
            for (int i = 0; i < kEntries; ++i) {
                const double x = double(i) / (kEntries - 1);
                table->ab[size_t(i)] = cpubrdf::specular_dfg(cpubrdf::Model::accurate, std::max(x * x, kMinNoV), r, 128,
                                                             128);
                const double w = (i == 0 || i == kEntries - 1) ? 0.5 : 1.0;
                const double lost = 1.0 - table->ab[size_t(i)][0] - table->ab[size_t(i)][1];
                table->lost_avg += w * 4.0 * lost * x * x * x / (kEntries - 1);
            }
        }
    }
    const double x = std::sqrt(std::clamp(NoV, 0.0, 1.0)) * (kEntries - 1);
    const int i = std::min(int(x), kEntries - 2);
    const double f = x - i;
    const auto& a = table->ab[size_t(i)];
    const auto& b = table->ab[size_t(i) + 1];
    const double A = a[0] * (1 - f) + b[0] * f, B = a[1] * (1 - f) + b[1] * f;
    return {A, B, 1.0 - A - B, table->lost_avg};
}

bool ReferenceImage::silhouette(uint32_t x, uint32_t y) const {
    const bool self = at(x, y).hit;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const int nx = int(x) + dx, ny = int(y) + dy;
            if (nx < 0 || ny < 0 || nx >= int(width) || ny >= int(height)) continue;
            if (at(uint32_t(nx), uint32_t(ny)).hit != self) return true;
        }
    return false;
}

ReferenceImage render_reference(const Scene& scene, const Material& m) {
    if (scene.shape.type != render::ShapeType::sphere) throw std::invalid_argument("reference: spheres only");
    if (scene.environment) throw std::invalid_argument("reference: no environment lighting");
    const Camera cam = make_camera(scene);
    const double radius = scene.shape.size;
    ReferenceImage img;
    img.width = scene.width;
    img.height = scene.height;
    img.pixels.resize(size_t{img.width} * img.height);
    auto st_at = [&](double px, double py, double& s, double& t) {
        V3 p;
        if (!intersect(cam.pos, cam.ray(px, py), radius, p)) return false;
        sphere_st(normalize(p), s, t);
        return true;
    };
    for (uint32_t y = 0; y < img.height; ++y)
        for (uint32_t x = 0; x < img.width; ++x) {
            ReferencePixel& px = img.pixels[size_t{y} * img.width + x];
            for (int i = 0; i < 3; ++i) px.rgb[i] = scene.background[size_t(i)];
            V3 p;
            const V3 d = cam.ray(x + 0.5, y + 0.5);
            if (!intersect(cam.pos, d, radius, p)) continue;
            px.hit = true;
            const V3 n = normalize(p);
            double s, t;
            sphere_st(n, s, t);

            // Texel footprint of one pixel: beyond about one texel the GPU leaves level 0.
            double s1, t1, s2, t2;
            double footprint = 1e9;
            if (st_at(x + 1.5, y + 0.5, s1, t1) && st_at(x + 0.5, y + 1.5, s2, t2)) {
                auto wrap = [](double a) { return a - std::round(a); };
                double fw = 0, fh = 0;
                for (const Texture& tex : m.textures) {
                    fw = std::max(fw, double(tex.width));
                    fh = std::max(fh, double(tex.height));
                }
                footprint = std::max({std::abs(wrap(s1 - s)) * fw, std::abs(t1 - t) * fh, std::abs(wrap(s2 - s)) * fw,
                                      std::abs(t2 - t) * fh});
            }
            px.minified = !m.textures.empty() && footprint > 0.7;

            Surface surf{};
            for (int i = 0; i < 3; ++i) {
                surf.albedo[i] = m.albedo.value[size_t(i)];
                surf.emissive[i] = m.emissive.value[size_t(i)];
            }
            if (m.albedo.texture >= 0) {
                const auto a = sample(m.textures[size_t(m.albedo.texture)], s, t);
                for (int i = 0; i < 3; ++i) surf.albedo[i] = a[size_t(i)];
            }
            if (m.emissive.texture >= 0) {
                const auto e = sample(m.textures[size_t(m.emissive.texture)], s, t);
                for (int i = 0; i < 3; ++i) surf.emissive[i] = e[size_t(i)];
            }
            surf.roughness = scalar(m, m.roughness, s, t);
            surf.metalness = scalar(m, m.metalness, s, t);
            surf.opacity = scalar(m, m.opacity, s, t);
            surf.n = n;
            if (m.normal.texture >= 0) {
                // Tangent ∂p/∂u and bitangent toward +v of three.js's sphere parameterization.
                const V3 tangent = normalize(V3{n.z, 0, -n.x});
                const V3 bitangent = cross(n, tangent);
                const auto c = sample(m.textures[size_t(m.normal.texture)], s, t);
                double tx = c[0] * 2 - 1, ty = c[1] * 2 - 1, tz = c[2] * 2 - 1;
                if (m.normal.green_down) ty = -ty;
                surf.n = normalize(tangent * tx + bitangent * ty + n * tz);
            }
            const RGB c = shade(scene, surf, p, normalize(cam.pos - p));
            for (int i = 0; i < 3; ++i) px.rgb[i] = c.c[i];
        }
    return img;
}

}  // namespace mf::test
