#include "reference.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <mutex>
#include <numbers>
#include <stdexcept>

namespace mf::test {

using render::Channel;
using render::Material;
using render::Scene;
using render::Texture;
using render::TexelType;

namespace {

constexpr double kPi = std::numbers::pi;
// The renderer's documented floors (lib/render/shaders/brdf.glsl), part of "the same BRDF".
constexpr double kMinRoughness = 0.045;
constexpr double kMinNoV = 1e-4;

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

struct RGB {
    double c[3] = {0, 0, 0};
};

// ---- the BRDF, term by term, from the papers

// GGX NDF, Walter et al. 2007, eq. 33.
double ndf_ggx(double NoH, double alpha) {
    const double a2 = alpha * alpha;
    const double t = NoH * NoH * (a2 - 1.0) + 1.0;
    return a2 / (kPi * t * t);
}

// Schlick 1994 Fresnel.
double fresnel_schlick(double f0, double VoH) { return f0 + (1.0 - f0) * std::pow(1.0 - VoH, 5.0); }

// Schlick-GGX G1 with Karis's k = (r + 1)² / 8.
double g1_schlick(double x, double roughness) {
    const double k = (roughness + 1.0) * (roughness + 1.0) / 8.0;
    return x / (x * (1.0 - k) + k);
}

// Smith Λ for GGX (Heitz 2014, eq. 72) and the height-correlated G2 = 1 / (1 + Λ(v) + Λ(l)).
double lambda_ggx(double cos_theta, double alpha) {
    const double tan2 = (1.0 - cos_theta * cos_theta) / (cos_theta * cos_theta);
    return 0.5 * (-1.0 + std::sqrt(1.0 + alpha * alpha * tan2));
}
double g2_correlated(double NoV, double NoL, double alpha) {
    return 1.0 / (1.0 + lambda_ggx(NoV, alpha) + lambda_ggx(NoL, alpha));
}

struct Surface {
    double albedo[3];
    double roughness, metalness, opacity;
    double emissive[3];
    V3 n;
};

RGB shade(const Scene& scene, const Surface& s, V3 p, V3 v) {
    const double r = std::clamp(s.roughness, kMinRoughness, 1.0);
    const double metal = std::clamp(s.metalness, 0.0, 1.0);
    const double alpha = r * r;
    const V3 n = s.n;
    const double NoV = std::clamp(dot(n, v), kMinNoV, 1.0);
    double f0[3], diffuse_color[3], comp[3] = {1, 1, 1};
    for (int i = 0; i < 3; ++i) {
        f0[i] = 0.04 * (1.0 - metal) + s.albedo[i] * metal;
        diffuse_color[i] = s.albedo[i] * (1.0 - metal);
    }
    if (scene.brdf == render::Brdf::Accurate) {
        const double E = specular_albedo_correlated(NoV, r);
        for (int i = 0; i < 3; ++i) comp[i] = 1.0 + f0[i] * (1.0 / E - 1.0);
    }
    const double diffuse_norm = scene.brdf == render::Brdf::Assignment ? 1.0 : 1.0 / kPi;

    RGB out;
    for (const render::Light& light : scene.lights) {
        V3 l;
        double E[3];
        for (int i = 0; i < 3; ++i) E[i] = double{light.color[static_cast<size_t>(i)]} * light.intensity;
        if (light.type == render::LightType::Directional) {
            l = normalize(v3(light.direction)) * -1.0;
        } else {
            const V3 d = v3(light.position) - p;
            const double d2 = dot(d, d);
            if (d2 < 1e-12) continue;
            l = d * (1.0 / std::sqrt(d2));
            for (double& e : E) e /= d2;
        }
        const double NoL = std::min(dot(n, l), 1.0);
        if (!(NoL > 0.0)) continue;
        V3 h = v + l;
        h = dot(h, h) > 1e-12 ? normalize(h) : n;
        const double NoH = std::clamp(dot(n, h), 0.0, 1.0);
        const double VoH = std::clamp(dot(v, h), 0.0, 1.0);
        const double D = ndf_ggx(NoH, alpha);
        const double G = scene.brdf == render::Brdf::Accurate
                             ? g2_correlated(NoV, NoL, alpha)
                             : g1_schlick(NoL, r) * g1_schlick(NoV, r);
        for (int i = 0; i < 3; ++i) {
            const double F = fresnel_schlick(f0[i], VoH);
            const double specular = D * F * G / (4.0 * NoL * NoV) * comp[i];
            const double diffuse = (1.0 - F) * diffuse_color[i] * diffuse_norm;
            out.c[i] += (diffuse + specular) * E[i] * NoL;
        }
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
        case TexelType::U8: v = t.data[i] / 255.0; break;
        case TexelType::U16: {
            uint16_t q;
            std::memcpy(&q, t.data.data() + 2 * i, 2);
            v = q / 65535.0;
            break;
        }
        case TexelType::F32: {
            float f;
            std::memcpy(&f, t.data.data() + 4 * i, 4);
            v = f;
            break;
        }
    }
    if (t.srgb && c < 3) v = srgb_decode(v);
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

double srgb_encode(double l) { return l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1 / 2.4) - 0.055; }
double srgb_decode(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }
int to_code(double e) { return static_cast<int>(std::floor(std::clamp(e, 0.0, 1.0) * 255.0 + 0.5)); }

namespace {

// E by quasi-Monte Carlo over visible normals (Heitz 2018), where the estimator G2/G1(v) is
// bounded: 16384 Hammersley points in double precision reach about 1e-5.
double specular_albedo_qmc(double NoV, double alpha) {
    constexpr uint32_t kSamples = 16384;
    const V3 v{std::sqrt(std::max(0.0, 1 - NoV * NoV)), 0, NoV};
    const V3 vh = normalize(V3{alpha * v.x, alpha * v.y, v.z});
    const double len2 = vh.x * vh.x + vh.y * vh.y;
    const V3 t1 = len2 > 0 ? V3{-vh.y, vh.x, 0} * (1 / std::sqrt(len2)) : V3{1, 0, 0};
    const V3 t2 = cross(vh, t1);
    const double g1 = 1.0 / (1.0 + lambda_ggx(NoV, alpha));
    double sum = 0;
    for (uint32_t i = 0; i < kSamples; ++i) {
        uint32_t bits = i;
        bits = (bits << 16u) | (bits >> 16u);
        bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
        bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
        bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
        bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
        const double u1 = (i + 0.5) / kSamples, u2 = bits * 0x1p-32;
        const double r = std::sqrt(u1), phi = 2 * kPi * u2;
        const double p1 = r * std::cos(phi);
        const double s = 0.5 * (1 + vh.z);
        const double p2 = (1 - s) * std::sqrt(1 - p1 * p1) + s * r * std::sin(phi);
        const V3 nh = t1 * p1 + t2 * p2 + vh * std::sqrt(std::max(0.0, 1 - p1 * p1 - p2 * p2));
        const V3 h = normalize(V3{alpha * nh.x, alpha * nh.y, std::max(0.0, nh.z)});
        const double VoH = dot(v, h);
        const double NoL = 2 * VoH * h.z - v.z;
        if (NoL <= 0 || VoH <= 0) continue;
        sum += g2_correlated(NoV, NoL, alpha) / g1;
    }
    return sum / kSamples;
}

}  // namespace

double specular_albedo_correlated(double NoV, double roughness) {
    // Tabulated per roughness over √(n·v) (E is steepest at grazing angles), 257 entries,
    // linear in between: the interpolation error stays near 1e-6.
    static std::map<double, std::vector<double>> tables;
    static std::mutex mutex;
    const double r = std::max(roughness, kMinRoughness);
    constexpr int kEntries = 257;
    std::vector<double>* table;
    {
        std::lock_guard lock(mutex);
        table = &tables[r];
        if (table->empty()) {
            table->resize(kEntries);
            for (int i = 0; i < kEntries; ++i) {
                const double x = double(i) / (kEntries - 1);
                (*table)[size_t(i)] = specular_albedo_qmc(std::max(x * x, kMinNoV), r * r);
            }
        }
    }
    const double x = std::sqrt(std::clamp(NoV, 0.0, 1.0)) * (kEntries - 1);
    const int i = std::min(int(x), kEntries - 2);
    const double f = x - i;
    return (*table)[size_t(i)] * (1 - f) + (*table)[size_t(i) + 1] * f;
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
    if (scene.shape.type != render::ShapeType::Sphere) throw std::invalid_argument("reference: spheres only");
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
                footprint = std::max({std::abs(wrap(s1 - s)) * fw, std::abs(t1 - t) * fh,
                                      std::abs(wrap(s2 - s)) * fw, std::abs(t2 - t) * fh});
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
                // Tangent ∂p/∂u and bitangent toward +v (spec: three.js sphere).
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
