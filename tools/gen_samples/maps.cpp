#include "maps.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

namespace gen {

int channels_of(Map m) {
    switch (m) {
        case Map::albedo:
        case Map::normal_gl:
        case Map::normal_dx:
        case Map::emissive:
        case Map::arm:
        case Map::ort:
        case Map::metal_rough:
        case Map::preview: return 3;
        default: return 1;
    }
}
bool is_color(Map m) { return m == Map::albedo || m == Map::emissive || m == Map::preview; }

namespace {

Vec3 encode_normal(Vec3 n) { return {n.x * 0.5f + 0.5f, n.y * 0.5f + 0.5f, n.z * 0.5f + 0.5f}; }

// One texel of a map, as stored. Packed maps follow interface.md: ARM R=AO G=rough B=metal,
// ORT R=AO G=rough B=translucency, glTF metallicRoughness G=rough B=metal (R unused, 0).
Vec3 texel(const Baked& b, size_t i, Map m) {
    const Sample& s = b.s[i];
    switch (m) {
        case Map::albedo: return encode_srgb(s.albedo);
        case Map::normal_gl: return encode_normal(b.normal[i]);
        case Map::normal_dx: return encode_normal({b.normal[i].x, -b.normal[i].y, b.normal[i].z});
        case Map::roughness: return {s.rough, 0, 0};
        case Map::gloss: return {1.f - s.rough, 0, 0};
        case Map::metalness: return {s.metal, 0, 0};
        case Map::occlusion: return {b.ao[i], 0, 0};
        case Map::height: return {s.height, 0, 0};
        case Map::opacity: return {s.opacity, 0, 0};
        case Map::emissive: return encode_srgb(s.emissive);
        case Map::arm: return {b.ao[i], s.rough, s.metal};
        case Map::ort: return {b.ao[i], s.rough, s.translucency};
        case Map::metal_rough: return {0.f, s.rough, s.metal};
        case Map::specular: return {s.specular, 0, 0};
        case Map::preview: break;
    }
    return {};
}

}  // namespace

Pixels extract(const Baked& b, Map m) {
    Pixels p{b.n, b.n, channels_of(m), {}};
    p.v.reserve(static_cast<size_t>(p.w) * p.h * p.c);
    for (size_t i = 0; i < b.s.size(); ++i) {
        const Vec3 t = texel(b, i, m);
        const std::array<float, 3> c{t.x, t.y, t.z};
        p.v.insert(p.v.end(), c.begin(), c.begin() + p.c);
    }
    return p;
}

Pixels render_preview(const Baked& b, int size) {
    Pixels p{size, size, 3, {}};
    const Vec3 light{-0.5f, 0.6f, 0.62f};
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const float sx = (fl(x) + 0.5f) / fl(size) * 2.f - 1.f, sy = 1.f - (fl(y) + 0.5f) / fl(size) * 2.f;
            const float r2 = (sx * sx + sy * sy) / 0.81f;
            Vec3 c{0.02f, 0.02f, 0.02f};
            if (r2 < 1.f) {
                const Vec3 nrm{sx / 0.9f, sy / 0.9f, std::sqrt(1.f - r2)};
                const float tu = fract(std::atan2(nrm.x, nrm.z) / kPi + 0.5f), tv = std::acos(nrm.y) / kPi;
                const size_t i = at(static_cast<int>(tu * fl(b.n)), static_cast<int>(tv * fl(b.n)), b.n);
                const float lambert = std::max(0.f, nrm.x * light.x + nrm.y * light.y + nrm.z * light.z);
                c = b.s[i].albedo * (b.ao[i] * (0.85f * lambert + 0.1f));
            }
            const Vec3 e = encode_srgb(c);
            p.v.insert(p.v.end(), {e.x, e.y, e.z});
        }
    return p;
}

}  // namespace gen
