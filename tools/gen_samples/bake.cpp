#include "bake.hpp"

#include <algorithm>
#include <cmath>

namespace gen {

namespace {

// Normal from height by central differences with wrap-around. Rows go down the image, so
// v (up) = -row and the GL normal's y is -dh/dv = +dh/drow.
std::vector<Vec3> normals_from_height(const std::vector<float>& h, int n, float strength) {
    std::vector<Vec3> out(h.size());
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const float dhdx = (h[at(x + 1, y, n)] - h[at(x - 1, y, n)]) * 0.5f * fl(n);
            const float dhdrow = (h[at(x, y + 1, n)] - h[at(x, y - 1, n)]) * 0.5f * fl(n);
            const Vec3 g{-strength * dhdx, strength * dhdrow, 1.f};
            out[at(x, y, n)] = g * (1.f / std::sqrt(g.x * g.x + g.y * g.y + g.z * g.z));
        }
    return out;
}

// Box blur with wrap-around, one axis (dx, dy) = (1, 0) or (0, 1).
std::vector<float> box_blur(const std::vector<float>& in, int n, int radius, int dx, int dy) {
    std::vector<float> out(in.size());
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            float sum = 0.f;
            for (int k = -radius; k <= radius; ++k) sum += in[at(x + k * dx, y + k * dy, n)];
            out[at(x, y, n)] = sum / fl(2 * radius + 1);
        }
    return out;
}

// Cavity occlusion: points below their neighbourhood's mean height are occluded.
std::vector<float> occlusion_from_height(const std::vector<float>& h, int n, float strength) {
    const int r = std::max(1, n / 40);
    std::vector<float> blur = h;
    for (int pass = 0; pass < 2; ++pass) blur = box_blur(box_blur(blur, n, r, 1, 0), n, r, 0, 1);
    std::vector<float> ao(h.size());
    for (size_t i = 0; i < h.size(); ++i) ao[i] = clamp01(1.f - strength * std::max(0.f, blur[i] - h[i]));
    return ao;
}

}  // namespace

Baked bake(const Material& m, int n) {
    Baked b;
    b.n = n;
    b.s.resize(static_cast<size_t>(n) * n);
    std::vector<float> h(b.s.size());
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const size_t i = at(x, y, n);
            b.s[i] = m.shade((fl(x) + 0.5f) / fl(n), (fl(y) + 0.5f) / fl(n));
            h[i] = clamp01(b.s[i].height);
        }
    b.normal = normals_from_height(h, n, m.normal_strength);
    b.ao = occlusion_from_height(h, n, m.ao_strength);
    return b;
}

}  // namespace gen
