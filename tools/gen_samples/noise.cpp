#include "noise.hpp"

#include <cmath>

#include "math.hpp"

namespace gen {

namespace {

// Integer hash (lowbias32): good avalanche.
uint32_t mix32(uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

}  // namespace

uint32_t hash(int x, int y, uint32_t seed) {
    return mix32(static_cast<uint32_t>(x) * 0x9E3779B1U + mix32(static_cast<uint32_t>(y) + mix32(seed)));
}
float hash01(int x, int y, uint32_t seed) { return static_cast<float>(hash(x, y, seed) >> 8) / 16777216.f; }

float value_noise(float u, float v, int px, int py, uint32_t seed) {
    const float x = u * fl(px), y = v * fl(py);
    const float fx = std::floor(x), fy = std::floor(y);
    const int ix = static_cast<int>(fx), iy = static_cast<int>(fy);
    float tx = x - fx, ty = y - fy;
    tx = tx * tx * (3.f - 2.f * tx);
    ty = ty * ty * (3.f - 2.f * ty);
    auto h = [&](int dx, int dy) { return hash01(wrap(ix + dx, px), wrap(iy + dy, py), seed); };
    return lerp(lerp(h(0, 0), h(1, 0), tx), lerp(h(0, 1), h(1, 1), tx), ty);
}

float fbm(float u, float v, int px, int py, int octaves, uint32_t seed) {
    float sum = 0.f, amp = 1.f, total = 0.f;
    for (int o = 0; o < octaves; ++o) {
        sum += amp * value_noise(u, v, px << o, py << o, seed + static_cast<uint32_t>(o) * 7919U);
        total += amp;
        amp *= 0.5f;
    }
    return sum / total;
}
float fbm(float u, float v, int period, int octaves, uint32_t seed) { return fbm(u, v, period, period, octaves, seed); }

Cells worley(float u, float v, int period, uint32_t seed) {
    const float x = u * fl(period), y = v * fl(period);
    const int ix = static_cast<int>(std::floor(x)), iy = static_cast<int>(std::floor(y));
    Cells c;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const int wx = wrap(ix + dx, period), wy = wrap(iy + dy, period);
            const float px = fl(ix + dx) + 0.15f + 0.7f * hash01(wx, wy, seed);
            const float py = fl(iy + dy) + 0.15f + 0.7f * hash01(wx, wy, seed + 1);
            const float d = std::hypot(x - px, y - py);
            if (d < c.f1) {
                c.f2 = c.f1;
                c.f1 = d;
                c.id = hash(wx, wy, seed + 2);
            } else if (d < c.f2) {
                c.f2 = d;
            }
        }
    return c;
}

}  // namespace gen
