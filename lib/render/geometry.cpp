// The shapes a preview draws, as meshes with (u, v) and tangent frames.
#include <cmath>
#include <numbers>

#include "render/internal.hpp"

namespace mf::render::detail {

Mesh make_sphere(float radius, uint32_t width_segments, uint32_t height_segments) {
    Mesh m;
    const double pi = std::numbers::pi;
    std::vector<std::vector<uint32_t>> grid;
    for (uint32_t iy = 0; iy <= height_segments; ++iy) {
        std::vector<uint32_t> row;
        const double v = static_cast<double>(iy) / height_segments;
        // three.js shifts the pole vertices' u by half a segment so that each pole triangle
        // gets the u of its own column.
        double u_offset = 0.0;
        if (iy == 0) u_offset = 0.5 / width_segments;
        else if (iy == height_segments) u_offset = -0.5 / width_segments;
        for (uint32_t ix = 0; ix <= width_segments; ++ix) {
            const double u = static_cast<double>(ix) / width_segments;
            const double phi = 2.0 * pi * u, theta = pi * v;
            const double x = -std::cos(phi) * std::sin(theta);
            const double y = std::cos(theta);
            const double z = std::sin(phi) * std::sin(theta);
            Vertex vx{};
            vx.position[0] = static_cast<float>(radius * x);
            vx.position[1] = static_cast<float>(radius * y);
            vx.position[2] = static_cast<float>(radius * z);
            vx.normal[0] = static_cast<float>(x);
            vx.normal[1] = static_cast<float>(y);
            vx.normal[2] = static_cast<float>(z);
            // ∂p/∂u ∝ (sin φ, 0, cos φ): defined at the poles too, unlike (z, 0, −x)/ρ.
            vx.tangent[0] = static_cast<float>(std::sin(phi));
            vx.tangent[1] = 0.f;
            vx.tangent[2] = static_cast<float>(std::cos(phi));
            vx.tangent[3] = 1.f;
            vx.uv[0] = static_cast<float>(u + u_offset);
            vx.uv[1] = static_cast<float>(1.0 - v);
            row.push_back(static_cast<uint32_t>(m.vertices.size()));
            m.vertices.push_back(vx);
        }
        grid.push_back(std::move(row));
    }
    for (uint32_t iy = 0; iy < height_segments; ++iy) {
        for (uint32_t ix = 0; ix < width_segments; ++ix) {
            const uint32_t a = grid[iy][ix + 1], b = grid[iy][ix];
            const uint32_t c = grid[iy + 1][ix], d = grid[iy + 1][ix + 1];
            if (iy != 0) m.indices.insert(m.indices.end(), {a, b, d});
            if (iy != height_segments - 1) m.indices.insert(m.indices.end(), {b, c, d});
        }
    }
    return m;
}

namespace {

struct Face {
    float n[3], t[3], b[3];
};

// A square of half-size `half`, `offset` along its normal from the origin.
void add_face(Mesh& m, const Face& f, float half, float offset) {
    const auto base = static_cast<uint32_t>(m.vertices.size());
    for (int corner = 0; corner < 4; ++corner) {
        const float u = (corner == 1 || corner == 2) ? 1.f : 0.f;
        const float v = (corner >= 2) ? 1.f : 0.f;
        Vertex vx{};
        for (int i = 0; i < 3; ++i) {
            vx.position[i] = offset * f.n[i] + half * ((2.f * u - 1.f) * f.t[i] + (2.f * v - 1.f) * f.b[i]);
            vx.normal[i] = f.n[i];
            vx.tangent[i] = f.t[i];
        }
        vx.tangent[3] = 1.f;  // every face below has t × b = n
        vx.uv[0] = u;
        vx.uv[1] = v;
        m.vertices.push_back(vx);
    }
    m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

void rotate(float (&p)[3], const double (&r)[3][3]) {
    double out[3];
    for (int i = 0; i < 3; ++i) out[i] = r[i][0] * p[0] + r[i][1] * p[1] + r[i][2] * p[2];
    for (int i = 0; i < 3; ++i) p[i] = static_cast<float>(out[i]);
}

}  // namespace

Rotation cube_rotation() {
    // R = Rx(25°) · Ry(−35°): the +X and +Y faces turn toward a camera on +Z.
    const double a = -35.0 * std::numbers::pi / 180.0, b = 25.0 * std::numbers::pi / 180.0;
    const double ry[3][3] = {{std::cos(a), 0, std::sin(a)}, {0, 1, 0}, {-std::sin(a), 0, std::cos(a)}};
    const double rx[3][3] = {{1, 0, 0}, {0, std::cos(b), -std::sin(b)}, {0, std::sin(b), std::cos(b)}};
    Rotation r{};
    for (size_t i = 0; i < 3; ++i)
        for (size_t j = 0; j < 3; ++j) r[i][j] = rx[i][0] * ry[0][j] + rx[i][1] * ry[1][j] + rx[i][2] * ry[2][j];
    return r;
}

Mesh make_plane(float side) {
    Mesh m;
    add_face(m, {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}}, side * 0.5f, 0.f);  // through the origin
    return m;
}

Mesh make_cube(float edge) {
    Mesh m;
    const Face faces[] = {
        {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},  {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}}, {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}},
        {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}}, {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}},  {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
    };
    for (const Face& f : faces) add_face(m, f, edge * 0.5f, edge * 0.5f);
    const Rotation rot = cube_rotation();
    double r[3][3];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) r[i][j] = rot[size_t(i)][size_t(j)];
    for (Vertex& v : m.vertices) {
        rotate(v.position, r);
        rotate(v.normal, r);
        float t[3] = {v.tangent[0], v.tangent[1], v.tangent[2]};
        rotate(t, r);
        for (int i = 0; i < 3; ++i) v.tangent[i] = t[i];
    }
    return m;
}

Mesh make_torus(float major, float minor, uint32_t major_segments, uint32_t minor_segments) {
    Mesh m;
    const double pi = std::numbers::pi;
    for (uint32_t j = 0; j <= minor_segments; ++j) {
        const double v = static_cast<double>(j) / minor_segments, psi = 2.0 * pi * v;
        for (uint32_t i = 0; i <= major_segments; ++i) {
            const double u = static_cast<double>(i) / major_segments, phi = 2.0 * pi * u;
            // In the XZ plane: the tube's centre circle of radius `major` around +Y.
            const double cx = std::cos(phi), cz = -std::sin(phi);
            const double nx = std::cos(psi) * cx, ny = std::sin(psi), nz = std::cos(psi) * cz;
            Vertex vx{};
            vx.position[0] = static_cast<float>(major * cx + minor * nx);
            vx.position[1] = static_cast<float>(minor * ny);
            vx.position[2] = static_cast<float>(major * cz + minor * nz);
            vx.normal[0] = static_cast<float>(nx);
            vx.normal[1] = static_cast<float>(ny);
            vx.normal[2] = static_cast<float>(nz);
            // ∂p/∂u ∝ (−sin φ, 0, −cos φ): along the ring; ∂p/∂v points around the tube.
            vx.tangent[0] = static_cast<float>(-std::sin(phi));
            vx.tangent[1] = 0.f;
            vx.tangent[2] = static_cast<float>(-std::cos(phi));
            // Handedness of (t, b = ∂p/∂v, n): b ∝ (−sin ψ cos φ, cos ψ, sin ψ sin φ).
            const double bx = -std::sin(psi) * cx, by = std::cos(psi), bz = -std::sin(psi) * cz;
            const double tx = -std::sin(phi), tz = -std::cos(phi);
            const double cxn = 0.0 * bz - tz * by, cyn = tz * bx - tx * bz, czn = tx * by - 0.0 * bx;
            vx.tangent[3] = cxn * nx + cyn * ny + czn * nz >= 0.0 ? 1.f : -1.f;
            // u runs twice around the ring: the ring (2π · major) is about twice the tube's
            // circumference per unit of u at the shaderball's proportions, as the sphere's u is
            // twice its v, so one texel keeps its shape across the ball.
            vx.uv[0] = static_cast<float>(2.0 * u);
            vx.uv[1] = static_cast<float>(v);
            m.vertices.push_back(vx);
        }
    }
    const uint32_t row = major_segments + 1;
    for (uint32_t j = 0; j < minor_segments; ++j)
        for (uint32_t i = 0; i < major_segments; ++i) {
            const uint32_t a = j * row + i, b = a + 1, c = a + row, d = c + 1;
            m.indices.insert(m.indices.end(), {a, c, b, b, c, d});
        }
    return m;
}

Mesh make_shaderball(float size) {
    Mesh m = make_sphere(0.7f * size);
    Mesh ring = make_torus(0.7f * size, 0.16f * size, 128, 32);
    // Tilted 20° about X toward the camera (+Z), so the ring's upper inner crease is in view.
    const double a = 20.0 * std::numbers::pi / 180.0;
    const double rx[3][3] = {{1, 0, 0}, {0, std::cos(a), -std::sin(a)}, {0, std::sin(a), std::cos(a)}};
    const auto base = static_cast<uint32_t>(m.vertices.size());
    for (Vertex v : ring.vertices) {
        rotate(v.position, rx);
        rotate(v.normal, rx);
        float t[3] = {v.tangent[0], v.tangent[1], v.tangent[2]};
        rotate(t, rx);
        for (int i = 0; i < 3; ++i) v.tangent[i] = t[i];
        m.vertices.push_back(v);
    }
    for (const uint32_t i : ring.indices) m.indices.push_back(base + i);
    return m;
}

Mesh make_shape(const Shape& shape) {
    switch (shape.type) {
        case ShapeType::sphere: return make_sphere(shape.size);
        case ShapeType::cube: return make_cube(shape.size);
        case ShapeType::plane: return make_plane(shape.size);
        case ShapeType::shaderball: return make_shaderball(shape.size);
    }
    return make_sphere(shape.size);
}

}  // namespace mf::render::detail
