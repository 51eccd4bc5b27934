// gen_samples: writes matforge's sample material library deterministically.
//
//   gen_samples <out-dir>
//
// Each material is one procedural "shader": a function of tileable texture coordinates
// (u, v) in [0,1) giving height, albedo, roughness, metalness... Normals are derived from the
// baked height by finite differences and occlusion from its cavities, so every map of a set
// agrees with the others. A table (sample_sets) says which files each vendor family gets:
// names, sizes, formats, packing, clutter. No clocks and no random devices: the same build
// writes the same bytes on every run.

#include <OpenImageIO/imageio.h>
#include <zip.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

// ---------------------------------------------------------------- small math

constexpr float kPi = 3.14159265358979f;

float fl(int i) { return static_cast<float>(i); }
float fract(float x) { return x - std::floor(x); }
float clamp01(float x) { return std::clamp(x, 0.f, 1.f); }
float lerp(float a, float b, float t) { return a + (b - a) * t; }
int wrap(int i, int n) { return ((i % n) + n) % n; }

float smoothstep(float e0, float e1, float x) {
    const float t = clamp01((x - e0) / (e1 - e0));
    return t * t * (3.f - 2.f * t);
}

struct Vec3 {
    float x = 0, y = 0, z = 0;
};
Vec3 operator*(Vec3 a, float s) { return {a.x * s, a.y * s, a.z * s}; }
Vec3 mix(Vec3 a, Vec3 b, float t) { return {lerp(a.x, b.x, t), lerp(a.y, b.y, t), lerp(a.z, b.z, t)}; }

// IEC 61966-2-1 transfer functions, exact piecewise curve (double keeps 8-bit codes exact).
float srgb_to_linear(float c) {
    const double d = c;
    return static_cast<float>(d <= 0.04045 ? d / 12.92 : std::pow((d + 0.055) / 1.055, 2.4));
}
float linear_to_srgb(float l) {
    const double d = std::clamp(static_cast<double>(l), 0.0, 1.0);
    return static_cast<float>(d <= 0.0031308 ? d * 12.92 : 1.055 * std::pow(d, 1.0 / 2.4) - 0.055);
}

// References publish dielectric albedo as 8-bit sRGB; shaders mix in linear.
Vec3 srgb(int r, int g, int b) {
    return {srgb_to_linear(fl(r) / 255.f), srgb_to_linear(fl(g) / 255.f), srgb_to_linear(fl(b) / 255.f)};
}

// Metal F0 colours, linear, from physicallybased.info.
const Vec3 kIron{0.531f, 0.512f, 0.496f};
const Vec3 kGold{1.000f, 0.766f, 0.336f};
const Vec3 kAluminium{0.912f, 0.914f, 0.920f};

// ---------------------------------------------------------------- tileable noise

// Integer hash (lowbias32): good avalanche, no tables, identical everywhere.
uint32_t mix32(uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}
uint32_t hash(int x, int y, uint32_t seed) {
    return mix32(static_cast<uint32_t>(x) * 0x9E3779B1U + mix32(static_cast<uint32_t>(y) + mix32(seed)));
}
float hash01(int x, int y, uint32_t seed) {
    return static_cast<float>(hash(x, y, seed) >> 8) / 16777216.f;
}

// Value noise on a px × py lattice that wraps at the tile border (so maps tile).
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

// Fractal sum, normalised to [0,1]; periods double per octave so it stays tileable.
float fbm(float u, float v, int px, int py, int octaves, uint32_t seed) {
    float sum = 0.f, amp = 1.f, total = 0.f;
    for (int o = 0; o < octaves; ++o) {
        sum += amp * value_noise(u, v, px << o, py << o, seed + static_cast<uint32_t>(o) * 7919U);
        total += amp;
        amp *= 0.5f;
    }
    return sum / total;
}
float fbm(float u, float v, int period, int octaves, uint32_t seed) {
    return fbm(u, v, period, period, octaves, seed);
}

// Tileable Worley noise: distances (in cell units) to the nearest and second feature points.
struct Cells {
    float f1 = 1e9f, f2 = 1e9f;
    uint32_t id = 0;
};
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

// ---------------------------------------------------------------- material shaders

// What a shader says about one point of the surface. Values are physical: linear colours,
// height in [0,1] (1 = highest), metalness binary by construction.
struct Sample {
    float height = 0.5f;
    Vec3 albedo;
    float rough = 0.5f;
    float metal = 0.f;
    float opacity = 1.f;
    Vec3 emissive;             // linear, kept <= 1 so 8-bit maps hold it
    float translucency = 0.f;  // Megascans ORT blue channel
    float specular = 0.5f;     // legacy REFL level (0.5 = the usual 4 % F0)
};
using Shader = Sample (*)(float u, float v);

struct Material {
    Shader shade;
    float normal_strength;  // height units per uv unit: slope scale of the normal map
    float ao_strength;      // how strongly cavities darken the occlusion map
};

// Regular grid (bricks, tiles, plates). edge: uv distance to the nearest cell border.
struct GridCell {
    int col, row;
    float lx, ly, edge;
};
GridCell grid_cell(float u, float v, int cols, int rows, float odd_row_shift) {
    const float y = v * fl(rows);
    const int row = static_cast<int>(std::floor(y));
    const float x = u * fl(cols) + (wrap(row, 2) == 1 ? odd_row_shift : 0.f);
    const int col = static_cast<int>(std::floor(x));
    GridCell c{wrap(col, cols), wrap(row, rows), fract(x), fract(y), 0.f};
    c.edge = std::min(std::min(c.lx, 1.f - c.lx) / fl(cols), std::min(c.ly, 1.f - c.ly) / fl(rows));
    return c;
}

// Hemispherical dome profile: 1 at the centre, 0 at radius r and beyond.
float dome(float d, float r) { return d < r ? std::sqrt(1.f - (d / r) * (d / r)) : 0.f; }

// Running-bond bricks: mortar joints low, rough and (through the height) occluded.
Sample bricks(float u, float v) {
    const GridCell c = grid_cell(u, v, 4, 12, 0.5f);
    const float chip = (fbm(u, v, 32, 3, 101) - 0.5f) * 0.008f;  // ragged brick edges
    const float t = smoothstep(0.f, 0.006f, c.edge - 0.009f + chip);
    const float tone = hash01(c.col, c.row, 102);
    const float grain = fbm(u, v, 16, 4, 103);
    const float mortar_n = fbm(u, v, 64, 2, 104);
    Sample s;
    s.height = lerp(0.2f + 0.12f * mortar_n, 0.78f + 0.16f * (grain - 0.5f) + 0.05f * (tone - 0.5f), t);
    const Vec3 brick = mix(mix(srgb(150, 66, 46), srgb(178, 94, 64), tone), srgb(108, 50, 36), grain * grain * 0.6f);
    const Vec3 mortar = mix(srgb(172, 166, 154), srgb(138, 132, 122), mortar_n);
    s.albedo = mix(mortar, brick, t);
    s.rough = lerp(0.95f, 0.72f + 0.16f * grain, t);
    return s;
}

// Glazed ceramic tiles: glossy pillowed faces, matte recessed grout.
Sample glazed_tiles(float u, float v) {
    const GridCell c = grid_cell(u, v, 4, 4, 0.f);
    const float d = c.edge - 0.007f;
    const float t = smoothstep(0.f, 0.004f, d);
    const float pillow = smoothstep(0.f, 0.03f, d);
    const float tone = hash01(c.col, c.row, 201);
    const float glaze = fbm(u, v, 8, 4, 202);
    Sample s;
    s.height = lerp(0.18f + 0.1f * fbm(u, v, 64, 2, 203), 0.7f + 0.2f * pillow + 0.02f * glaze, t);
    const Vec3 tile = mix(mix(srgb(52, 104, 128), srgb(74, 134, 152), tone), srgb(92, 150, 166), 0.3f * glaze);
    s.albedo = mix(srgb(196, 192, 182), tile, t);
    s.rough = lerp(0.9f, 0.1f + 0.08f * glaze, t);
    return s;
}

// uv distance to the nearest rivet of a plate whose border carries `count` rivets per side.
float rivet_distance(float lx, float ly, float inset, int count, float plate_uv) {
    const float along_x = (std::floor(lx * fl(count)) + 0.5f) / fl(count);
    const float along_y = (std::floor(ly * fl(count)) + 0.5f) / fl(count);
    const float side_x = std::min(std::abs(lx - inset), std::abs(lx - (1.f - inset)));
    const float side_y = std::min(std::abs(ly - inset), std::abs(ly - (1.f - inset)));
    return plate_uv * std::min(std::hypot(side_x, ly - along_y), std::hypot(lx - along_x, side_y));
}

// Painted iron plates: paint chipped (mostly at the edges) down to bare iron, some rust,
// bare riveted heads. Metalness is exactly 0 or 1.
Sample metal_plates(float u, float v) {
    const GridCell c = grid_cell(u, v, 2, 2, 0.f);
    const float plate = smoothstep(0.f, 0.004f, c.edge - 0.005f);
    const float rivet = dome(rivet_distance(c.lx, c.ly, 0.07f, 6, 0.5f), 0.014f);
    const float wear = fbm(u, v, 16, 5, 301) + 0.3f * (1.f - smoothstep(0.f, 0.04f, c.edge));
    const bool chipped = wear > 0.7f && plate > 0.5f;
    const bool rust = chipped && fbm(u, v, 32, 3, 302) > 0.56f;
    const float grime = fbm(u, v, 8, 4, 304);
    Sample s;
    const float plate_h = 0.55f + 0.04f * fbm(u, v, 4, 3, 303) - (chipped ? 0.04f : 0.f) + 0.3f * rivet;
    s.height = lerp(0.08f, plate_h, plate);
    if (rivet > 0.f || (chipped && !rust)) {
        s.albedo = kIron * (0.97f + 0.03f * grime);
        s.metal = 1.f;
        s.rough = 0.3f + 0.15f * fbm(u, v, 64, 2, 305);
    } else if (rust) {
        s.albedo = mix(srgb(112, 56, 30), srgb(142, 78, 42), fbm(u, v, 64, 2, 306));
        s.rough = 0.9f;
    } else {
        s.albedo = mix(srgb(74, 100, 84), srgb(56, 80, 66), grime);
        s.rough = lerp(0.75f, 0.48f + 0.12f * grime, plate);
    }
    return s;
}

// Stones bedded in soil: Worley cells as pebbles, some cells left as bare ground.
Sample rocky_ground(float u, float v) {
    const Cells w = worley(u, v, 6, 401);
    // Rounded, irregular pebbles: bounded by a noisy per-stone radius and by the cell border.
    const float radius = 0.42f + 0.2f * static_cast<float>((w.id >> 16) & 255U) / 255.f;
    const float inner = std::min(0.5f * (w.f2 - w.f1), radius - w.f1 + 0.25f * (fbm(u, v, 24, 3, 404) - 0.5f));
    const bool stone = w.id % 100U >= 15U;
    const float t = stone ? smoothstep(0.02f, 0.07f, inner) : 0.f;
    const float detail = fbm(u, v, 32, 4, 402);
    const float soil_n = fbm(u, v, 16, 4, 403);
    const float tone = static_cast<float>((w.id >> 8) & 255U) / 255.f;
    Sample s;
    const float stone_h = 0.3f + 0.5f * std::sqrt(smoothstep(0.02f, 0.45f, inner)) + 0.08f * detail;
    s.height = lerp(0.1f + 0.15f * soil_n, stone_h, t);
    const Vec3 rock = mix(srgb(126, 120, 110), srgb(164, 154, 138), tone) * (0.88f + 0.24f * detail);
    const Vec3 soil = mix(srgb(112, 90, 66), srgb(84, 66, 50), soil_n);
    s.albedo = mix(soil, rock, t);
    s.rough = lerp(0.95f, 0.68f + 0.12f * detail, t);
    return s;
}

// Flat-sawn grain: growth rings as thin latewood bands, warped and stretched along x.
float latewood(float u, float v, int rings, float phase, uint32_t seed) {
    const float r = fract(v * fl(rings) + phase + 4.f * fbm(u, v, 3, 6, 4, seed));
    return smoothstep(0.55f, 0.72f, r) * (1.f - smoothstep(0.85f, 1.f, r));
}

// Worn floor boards in random-offset rows; iron nails (the only metal) at the board ends.
Sample wood_planks(float u, float v) {
    constexpr int kRows = 5;
    const int row = static_cast<int>(std::floor(v * fl(kRows)));
    const float x = u * 2.f + hash01(row, 0, 501);
    const int id = row * 2 + wrap(static_cast<int>(std::floor(x)), 2);
    const float lx = fract(x), ly = fract(v * fl(kRows));
    const float edge = std::min(std::min(lx, 1.f - lx) / 2.f, std::min(ly, 1.f - ly) / fl(kRows));
    const float board = smoothstep(0.f, 0.003f, edge - 0.003f);
    const float ring = latewood(u, v, 40, hash01(id, 1, 502), 503U + static_cast<uint32_t>(id));
    const float streak = fbm(u, v, 4, 64, 3, 504);
    const float nx = std::min(std::abs(lx - 0.04f), std::abs(lx - 0.96f)) * 0.5f;
    const float ny = std::min(std::abs(ly - 0.3f), std::abs(ly - 0.7f)) / fl(kRows);
    const bool nail = std::hypot(nx, ny) < 0.0045f;
    Sample s;
    const Vec3 wood = mix(srgb(180, 132, 88), srgb(134, 90, 56), 0.75f * ring + 0.35f * streak);
    s.albedo = mix(srgb(64, 48, 36), wood * (0.9f + 0.15f * hash01(id, 2, 505)), board);
    s.height = lerp(0.05f, 0.68f + 0.07f * ring + 0.03f * streak, board);
    s.rough = lerp(0.9f, 0.62f + 0.12f * streak - 0.08f * ring, board);
    if (nail) {
        s.albedo = kIron;
        s.metal = 1.f;
        s.rough = 0.45f;
        s.height = 0.66f;
    }
    return s;
}

// Polished marble tiles: veins from a warped sine, one vein pattern per tile; thin grout.
Sample marble_tiles(float u, float v) {
    const GridCell c = grid_cell(u, v, 2, 2, 0.f);
    const float t = smoothstep(0.f, 0.002f, c.edge - 0.0035f);
    const uint32_t seed = 601U + static_cast<uint32_t>(c.col * 2 + c.row) * 31U;
    const float big = std::sin(2.f * kPi * (u + 2.f * v) + 9.f * fbm(u, v, 4, 5, seed));
    const float small = std::sin(2.f * kPi * (3.f * u - v) + 7.f * fbm(u, v, 8, 4, seed + 7));
    const float vein = clamp01(std::pow(1.f - std::abs(big), 10.f) + 0.5f * std::pow(1.f - std::abs(small), 24.f));
    const float cloud = fbm(u, v, 8, 4, seed + 9);
    Sample s;
    const Vec3 stone = mix(mix(srgb(234, 230, 222), srgb(212, 206, 196), cloud), srgb(118, 116, 112), 0.85f * vein);
    s.albedo = mix(srgb(150, 144, 134), stone, t);
    s.height = lerp(0.25f + 0.1f * fbm(u, v, 64, 2, 611), 0.8f + 0.01f * cloud, t);
    s.rough = lerp(0.85f, 0.08f + 0.06f * vein, t);
    s.specular = lerp(0.25f, 0.5f, t);
    return s;
}

// One ivy leaf of the decal sheet, in leaf coordinates: t along the midrib (0 stem, 1 tip),
// a across it. Returns false outside the blade.
bool ivy_leaf(int i, int leaves, float t, float a, Sample& s) {
    if (t <= 0.f || t >= 1.f) return false;
    const float w = 0.3f * std::pow(std::sin(kPi * t), 0.7f) * (1.15f - 0.35f * t);  // broad base, pointed tip
    if (std::abs(a) >= w) return false;
    const float q = std::abs(a) / w;  // 0 on the midrib, 1 at the blade's edge
    const float midrib = 1.f - smoothstep(0.f, 0.025f, std::abs(a));
    const float phase = fract(t * 5.f - std::abs(a) * 3.f);
    const float side = (1.f - smoothstep(0.f, 0.06f, std::min(phase, 1.f - phase))) * (1.f - q);
    const float veins = std::max(midrib, 0.7f * side);
    const float tone = hash01(i, 4, 701);
    s.height = 0.35f + 0.4f * fl(i) / fl(leaves) + 0.12f * (1.f - q * q) - 0.03f * veins;
    const Vec3 blade = mix(mix(srgb(52, 86, 32), srgb(80, 118, 44), tone), srgb(120, 150, 76), 0.6f * veins);
    s.albedo = mix(blade, srgb(44, 70, 28), 0.4f * smoothstep(0.7f, 1.f, q));
    s.rough = 0.38f + 0.1f * tone;
    s.translucency = 0.75f - 0.45f * veins;
    s.opacity = 1.f;
    return true;
}

// Ivy leaf decal for cut-out rendering: opacity 1 on leaves, 0 between them. Later leaves
// lie on top; the background carries a dilated leaf colour, as scanned decals do.
Sample ivy_leaves(float u, float v) {
    constexpr int kLeaves = 16;
    Sample s;
    s.height = 0.f;
    s.albedo = srgb(44, 66, 30);
    s.rough = 1.f;
    s.opacity = 0.f;
    for (int i = 0; i < kLeaves; ++i) {
        const float cx = hash01(i, 0, 702), cy = hash01(i, 1, 702);
        const float ang = 2.f * kPi * hash01(i, 2, 702), len = 0.2f + 0.1f * hash01(i, 3, 702);
        const float ca = std::cos(ang), sa = std::sin(ang);
        for (int oy = -1; oy <= 1; ++oy)
            for (int ox = -1; ox <= 1; ++ox) {
                const float dx = u - cx - fl(ox), dy = v - cy - fl(oy);
                if (std::abs(dx) > len || std::abs(dy) > len) continue;
                ivy_leaf(i, kLeaves, (dx * ca + dy * sa) / len + 0.5f, (-dx * sa + dy * ca) / len, s);
            }
    }
    return s;
}

// Sci-fi hull panels: fixed layout of rectangles, grooves, chamfers, bare aluminium bolts and
// paint chips, two recessed emissive light strips.
struct Rect {
    float x0, y0, x1, y1;
};
float rect_edge(const Rect& r, float u, float v) {
    return std::min(std::min(u - r.x0, r.x1 - u), std::min(v - r.y0, r.y1 - v));
}
constexpr std::array<Rect, 6> kPanels{{{0.f, 0.f, 0.5f, 0.5f},
                                       {0.5f, 0.f, 1.f, 0.25f},
                                       {0.5f, 0.25f, 1.f, 0.5f},
                                       {0.f, 0.5f, 1.f / 3.f, 1.f},
                                       {1.f / 3.f, 0.5f, 1.f, 0.75f},
                                       {1.f / 3.f, 0.75f, 1.f, 1.f}}};
constexpr std::array<Rect, 2> kStrips{{{0.56f, 0.115f, 0.94f, 0.135f}, {0.155f, 0.56f, 0.178f, 0.94f}}};

float bolt_distance(const Rect& r, float u, float v) {
    const float inset = 0.022f;
    const float bx = std::min(std::abs(u - r.x0 - inset), std::abs(r.x1 - inset - u));
    const float by = std::min(std::abs(v - r.y0 - inset), std::abs(r.y1 - inset - v));
    return std::hypot(bx, by);
}

Sample scifi_panel(float u, float v) {
    size_t p = 0;
    while (p + 1 < kPanels.size() && rect_edge(kPanels[p], u, v) < 0.f) ++p;
    const float e = rect_edge(kPanels[p], u, v);
    const float panel = smoothstep(0.f, 0.003f, e - 0.004f);
    const float bolt = dome(bolt_distance(kPanels[p], u, v), 0.012f);
    const float grime = fbm(u, v, 8, 4, 802);
    const bool chipped = fbm(u, v, 16, 5, 801) + 0.35f * (1.f - smoothstep(0.f, 0.025f, e)) > 0.8f && panel > 0.5f;
    Sample s;
    s.height = lerp(0.1f, 0.45f + 0.2f * smoothstep(0.004f, 0.02f, e) - (chipped ? 0.02f : 0.f) + 0.12f * bolt, panel);
    const Vec3 paint = p == 4 ? srgb(198, 112, 42) : srgb(168, 170, 172);
    s.albedo = mix(srgb(70, 72, 74), mix(paint, paint * 0.8f, grime), panel);
    s.rough = lerp(0.7f, 0.42f + 0.12f * grime, panel);
    if (bolt > 0.f || chipped) {
        s.albedo = kAluminium;
        s.metal = 1.f;
        s.rough = 0.25f + 0.1f * grime;
    }
    for (const Rect& r : kStrips) {
        const float se = rect_edge(r, u, v);
        if (se < 0.f) continue;
        s = Sample{};
        s.height = 0.3f;
        s.albedo = srgb(52, 60, 64);
        s.rough = 0.1f;
        s.emissive = Vec3{0.1f, 0.75f, 1.f} * smoothstep(0.f, 0.004f, se);
    }
    return s;
}

// Walnut with a gold diamond-lattice inlay and glowing gems set at the crossings.
Sample walnut_inlay(float u, float v) {
    const float ring = latewood(u, v, 24, 0.f, 901);
    const float streak = fbm(u, v, 4, 48, 3, 902);
    const float a = fract(2.f * (u + v)), b = fract(2.f * (u - v));
    const float da = std::min(a, 1.f - a) / (2.f * std::sqrt(2.f));  // uv distance to the lines
    const float db = std::min(b, 1.f - b) / (2.f * std::sqrt(2.f));
    const float gem_d = std::hypot(da, db);
    Sample s;
    s.albedo = mix(srgb(118, 82, 56), srgb(88, 60, 42), 0.7f * ring + 0.3f * streak);
    s.height = 0.5f + 0.03f * ring + 0.02f * streak;
    s.rough = 0.5f + 0.12f * streak;
    if (std::min(da, db) < 0.006f || gem_d < 0.04f) {
        s.albedo = kGold;
        s.metal = 1.f;
        s.rough = 0.22f;
        s.height = gem_d < 0.04f ? 0.58f : 0.54f;
    }
    if (gem_d < 0.03f) {
        const float g = dome(gem_d, 0.03f);
        s.albedo = srgb(36, 140, 156);
        s.metal = 0.f;
        s.rough = 0.05f;
        s.height = 0.58f + 0.2f * g;
        s.emissive = Vec3{0.15f, 0.85f, 0.95f} * (0.6f + 0.4f * g);
    }
    return s;
}

const Material kBricks{bricks, 0.02f, 2.5f};
const Material kTiles{glazed_tiles, 0.015f, 2.5f};
const Material kMetalPlates{metal_plates, 0.015f, 2.f};
const Material kRockyGround{rocky_ground, 0.025f, 2.5f};
const Material kWoodPlanks{wood_planks, 0.02f, 2.f};
const Material kMarbleTiles{marble_tiles, 0.02f, 2.5f};
const Material kIvyLeaves{ivy_leaves, 0.012f, 2.f};
const Material kScifiPanel{scifi_panel, 0.02f, 2.f};
const Material kWalnutInlay{walnut_inlay, 0.02f, 2.f};

// ---------------------------------------------------------------- baking

// All shader samples of one n × n bake plus the maps derived from the height field.
struct Baked {
    int n = 0;
    std::vector<Sample> s;
    std::vector<Vec3> normal;  // tangent space, OpenGL (+Y) convention
    std::vector<float> ao;
};

size_t at(int x, int y, int n) { return static_cast<size_t>(wrap(y, n)) * n + wrap(x, n); }

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

// ---------------------------------------------------------------- maps and files

enum class Map {
    albedo, normal_gl, normal_dx, roughness, gloss, metalness, occlusion, height, opacity,
    emissive, arm, ort, metal_rough, specular, preview
};
enum class Enc { png8, png16, jpg, exr_half };

// Pixel values in their final encoding, [0,1].
struct Pixels {
    int w = 0, h = 0, c = 0;
    std::vector<float> v;
};

int channels_of(Map m) {
    switch (m) {
    case Map::albedo: case Map::normal_gl: case Map::normal_dx: case Map::emissive:
    case Map::arm: case Map::ort: case Map::metal_rough: case Map::preview:
        return 3;
    default:
        return 1;
    }
}
bool is_color(Map m) { return m == Map::albedo || m == Map::emissive || m == Map::preview; }

Vec3 encode_srgb(Vec3 c) { return {linear_to_srgb(c.x), linear_to_srgb(c.y), linear_to_srgb(c.z)}; }
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

// Vendor-style preview: the material on a lit sphere over a dark background (clutter that a
// discoverer must not mistake for a map).
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

// Writes with OpenImageIO. Integer formats are quantised here (round half up) so the bytes do
// not depend on library conversion details; EXR gets a fixed DateTime (else it stamps "now").
bool write_image(const fs::path& path, const Pixels& px, Enc enc, bool srgb_tag, std::string& err) {
    auto out = OIIO::ImageOutput::create(path.string());
    if (!out) {
        err = "no writer for " + path.string();
        return false;
    }
    const OIIO::TypeDesc fmt = enc == Enc::png16 ? OIIO::TypeDesc::UINT16
                               : enc == Enc::exr_half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::UINT8;
    OIIO::ImageSpec spec(px.w, px.h, px.c, fmt);
    if (enc == Enc::exr_half) {
        spec.attribute("DateTime", "2024:01:01 00:00:00");
        spec.attribute("compression", "zip");
        if (px.c == 1) spec.channelnames = {"Y"};
    }
    if (enc == Enc::jpg) spec.attribute("Compression", "jpeg:90");
    if (srgb_tag) spec.attribute("oiio:ColorSpace", "sRGB");
    bool ok = out->open(path.string(), spec);
    if (ok && enc == Enc::exr_half) {
        ok = out->write_image(OIIO::TypeDesc::FLOAT, px.v.data());
    } else if (ok && enc == Enc::png16) {
        std::vector<uint16_t> q(px.v.size());
        for (size_t i = 0; i < q.size(); ++i) q[i] = static_cast<uint16_t>(std::floor(clamp01(px.v[i]) * 65535.f + 0.5f));
        ok = out->write_image(OIIO::TypeDesc::UINT16, q.data());
    } else if (ok) {
        std::vector<uint8_t> q(px.v.size());
        for (size_t i = 0; i < q.size(); ++i) q[i] = static_cast<uint8_t>(std::floor(clamp01(px.v[i]) * 255.f + 0.5f));
        ok = out->write_image(OIIO::TypeDesc::UINT8, q.data());
    }
    ok = out->close() && ok;
    if (!ok) err = path.string() + ": " + out->geterror();
    return ok;
}

// ---------------------------------------------------------------- the sample library

enum class Text { mtlx, megascans_json };

struct FileDef {
    std::string path;  // relative to the set root, '/'-separated
    Map map;
    Enc enc;
    int size;
};
struct TextDef {
    std::string path;
    Text kind;
};
struct SetDef {
    std::string root;    // folder (or .zip) under <out-dir>
    std::string family;  // naming convention, interface.md "convention"
    std::string name;    // material name the files use
    const Material* material;
    std::string exercises;
    std::vector<FileDef> files;
    std::vector<TextDef> texts;
};

std::vector<SetDef> sample_sets() {
    // Name builders per family keep the table to what differs between sets.
    auto acg = [](const std::string& n, const std::string& tag, Map m, int size) {
        return FileDef{n + "_1K-PNG_" + tag + ".png", m, Enc::png8, size};
    };
    auto ph = [](const std::string& dir, const std::string& n, const std::string& tag, Map m, Enc e, int size) {
        static const std::map<Enc, std::string> ext{{Enc::png8, "png"}, {Enc::png16, "png"}, {Enc::jpg, "jpg"}, {Enc::exr_half, "exr"}};
        return FileDef{dir + n + "_" + tag + "_1k." + ext.at(e), m, e, size};
    };
    auto tcom = [](const std::string& n, const std::string& tag, Map m, const std::string& res, int size) {
        return FileDef{n + "_" + tag + "_" + res + ".jpg", m, Enc::jpg, size};
    };
    auto mega = [](const std::string& n, const std::string& tag, Map m) {
        return FileDef{n + "_2K_" + tag + ".jpg", m, Enc::jpg, 256};
    };
    auto sub = [](const std::string& n, const std::string& tag, Map m) {
        return FileDef{n + "_" + tag + ".png", m, Enc::png8, 256};
    };
    auto gltf = [](const std::string& n, const std::string& tag, Map m) {
        return FileDef{n + "_" + tag + ".png", m, Enc::png8, 256};
    };
    return {
        {"Bricks076_1K-PNG", "ambientcg", "Bricks076", &kBricks,
         "no metalness map (dielectric); both _NormalGL and _NormalDX present (name decides, "
         "content agrees); clutter: preview render `Bricks076.png` and a MaterialX sidecar",
         {acg("Bricks076", "Color", Map::albedo, 256), acg("Bricks076", "NormalGL", Map::normal_gl, 256),
          acg("Bricks076", "NormalDX", Map::normal_dx, 256), acg("Bricks076", "Roughness", Map::roughness, 256),
          acg("Bricks076", "AmbientOcclusion", Map::occlusion, 256),
          acg("Bricks076", "Displacement", Map::height, 256), {"Bricks076.png", Map::preview, Enc::png8, 64}},
         {{"Bricks076_1K-PNG.mtlx", Text::mtlx}}},
        {"Tiles101_1K-PNG.zip", "ambientcg", "Tiles101", &kTiles,
         "set shipped as a .zip (flat, as ambientCG ships it); DirectX normal only (_NormalDX); "
         "clutter inside the archive (preview, MaterialX); no metalness",
         {acg("Tiles101", "Color", Map::albedo, 128), acg("Tiles101", "NormalDX", Map::normal_dx, 128),
          acg("Tiles101", "Roughness", Map::roughness, 128), acg("Tiles101", "AmbientOcclusion", Map::occlusion, 128),
          acg("Tiles101", "Displacement", Map::height, 128), {"Tiles101.png", Map::preview, Enc::png8, 64}},
         {{"Tiles101_1K-PNG.mtlx", Text::mtlx}}},
        {"MetalPlates013_1K-PNG", "ambientcg", "MetalPlates013", &kMetalPlates,
         "metal set: binary _Metalness (bare iron where paint chipped, rivet heads; iron albedo "
         "from physicallybased.info, 185-193 sRGB); painted and rusty areas dielectric",
         {acg("MetalPlates013", "Color", Map::albedo, 256), acg("MetalPlates013", "NormalGL", Map::normal_gl, 256),
          acg("MetalPlates013", "Roughness", Map::roughness, 256), acg("MetalPlates013", "Metalness", Map::metalness, 256),
          acg("MetalPlates013", "AmbientOcclusion", Map::occlusion, 256),
          acg("MetalPlates013", "Displacement", Map::height, 256)},
         {{"MetalPlates013_1K-PNG.mtlx", Text::mtlx}}},
        {"rocky_ground_02", "polyhaven", "rocky_ground_02", &kRockyGround,
         "nested folder (maps under `textures/`); 16-bit PNG height; EXR (half) normal map; "
         "JPEG albedo; clutter: `thumbnail.jpg` at the set root; no metalness",
         {ph("textures/", "rocky_ground_02", "diff", Map::albedo, Enc::jpg, 256),
          ph("textures/", "rocky_ground_02", "nor_gl", Map::normal_gl, Enc::exr_half, 256),
          ph("textures/", "rocky_ground_02", "rough", Map::roughness, Enc::png8, 256),
          ph("textures/", "rocky_ground_02", "ao", Map::occlusion, Enc::png8, 256),
          ph("textures/", "rocky_ground_02", "disp", Map::height, Enc::png16, 256),
          {"thumbnail.jpg", Map::preview, Enc::jpg, 64}},
         {}},
        {"wood_planks_worn", "polyhaven", "wood_planks_worn", &kWoodPlanks,
         "packed ARM map (R=AO, G=roughness, B=metalness: iron nail heads are the only metal); "
         "both _nor_gl_ and _nor_dx_; half-float EXR displacement",
         {ph("", "wood_planks_worn", "diff", Map::albedo, Enc::png8, 128),
          ph("", "wood_planks_worn", "nor_gl", Map::normal_gl, Enc::png8, 128),
          ph("", "wood_planks_worn", "nor_dx", Map::normal_dx, Enc::png8, 128),
          ph("", "wood_planks_worn", "arm", Map::arm, Enc::png8, 128),
          ph("", "wood_planks_worn", "disp", Map::height, Enc::exr_half, 128)},
         {}},
        {"MarbleTiles0017", "texturescom", "MarbleTiles0017", &kMarbleTiles,
         "gloss map and no roughness (inverted into roughness); _REFL specular level; all JPEG; "
         "two resolutions of the albedo (_COL_1K 128 px, _COL_2K 256 px: ambiguity, and the 2K "
         "one mismatches the other maps); normal named only _NRM (content is OpenGL +Y)",
         {tcom("MarbleTiles0017", "COL", Map::albedo, "1K", 128), tcom("MarbleTiles0017", "COL", Map::albedo, "2K", 256),
          tcom("MarbleTiles0017", "NRM", Map::normal_gl, "1K", 128), tcom("MarbleTiles0017", "GLOSS", Map::gloss, "1K", 128),
          tcom("MarbleTiles0017", "REFL", Map::specular, "1K", 128), tcom("MarbleTiles0017", "DISP", Map::height, "1K", 128),
          tcom("MarbleTiles0017", "AO", Map::occlusion, "1K", 128)},
         {}},
        {"ivy_leaves", "megascans", "ivy_leaves", &kIvyLeaves,
         "opacity map (cut-out leaves); packed _ORT (R=AO, G=roughness, B=translucency, not "
         "metalness); all JPEG; normal named only _Normal (content is OpenGL +Y); clutter: "
         "`_Preview.png` and a Bridge-style JSON",
         {mega("ivy_leaves", "Albedo", Map::albedo), mega("ivy_leaves", "Normal", Map::normal_gl),
          mega("ivy_leaves", "Displacement", Map::height), mega("ivy_leaves", "ORT", Map::ort),
          mega("ivy_leaves", "Opacity", Map::opacity), {"ivy_leaves_Preview.png", Map::preview, Enc::png8, 64}},
         {{"ivy_leaves.json", Text::megascans_json}}},
        {"ScifiPanel", "substance", "ScifiPanel", &kScifiPanel,
         "Unreal-style export: packed _OcclusionRoughnessMetallic (bare aluminium bolts and paint "
         "chips are metal); _Emissive light strips; _Height; normal named only _Normal and its "
         "content is DirectX (-Y)",
         {sub("ScifiPanel", "BaseColor", Map::albedo), sub("ScifiPanel", "Normal", Map::normal_dx),
          sub("ScifiPanel", "Height", Map::height),
          sub("ScifiPanel", "OcclusionRoughnessMetallic", Map::arm), sub("ScifiPanel", "Emissive", Map::emissive)},
         {}},
        {"WalnutInlay", "gltf", "WalnutInlay", &kWalnutInlay,
         "glTF texture set: _metallicRoughness (G=roughness, B=metalness, R unused) with gold "
         "inlay (physicallybased.info gold); _emissive gems; separate _occlusion; _normal (OpenGL)",
         {gltf("WalnutInlay", "baseColor", Map::albedo), gltf("WalnutInlay", "metallicRoughness", Map::metal_rough),
          gltf("WalnutInlay", "normal", Map::normal_gl), gltf("WalnutInlay", "occlusion", Map::occlusion),
          gltf("WalnutInlay", "emissive", Map::emissive)},
         {}},
    };
}

// ---------------------------------------------------------------- sidecars and README

std::string mtlx_sidecar(const SetDef& set) {
    std::ostringstream o;
    o << "<?xml version=\"1.0\"?>\n<materialx version=\"1.38\" fileprefix=\"./\">\n"
      << "  <nodegraph name=\"NG_" << set.name << "\">\n";
    for (const FileDef& f : set.files) {
        if (f.map == Map::preview) continue;
        const bool color = f.map == Map::albedo;
        const bool normal = f.map == Map::normal_gl || f.map == Map::normal_dx;
        o << "    <image name=\"" << fs::path(f.path).stem().string() << "\" type=\""
          << (color ? "color3" : normal ? "vector3" : "float") << "\">\n"
          << "      <input name=\"file\" type=\"filename\" value=\"" << f.path << "\""
          << (color ? " colorspace=\"srgb_texture\"" : "") << " />\n    </image>\n";
    }
    o << "  </nodegraph>\n</materialx>\n";
    return o.str();
}

std::string megascans_json(const SetDef& set) {
    std::ostringstream o;
    o << "{\n  \"id\": \"" << set.name << "\",\n  \"name\": \"Ivy Leaves\",\n  \"type\": \"atlas\",\n"
      << "  \"maps\": [\n";
    for (size_t i = 0; i < set.files.size(); ++i)
        o << "    {\"uri\": \"" << set.files[i].path << "\", \"resolution\": \"" << set.files[i].size
          << "x" << set.files[i].size << "\"}" << (i + 1 < set.files.size() ? "," : "") << "\n";
    o << "  ]\n}\n";
    return o.str();
}

std::string text_content(const SetDef& set, Text kind) {
    return kind == Text::mtlx ? mtlx_sidecar(set) : megascans_json(set);
}

std::string encoding_name(const FileDef& f) {
    std::string dim = std::to_string(f.size) + "²";
    switch (f.enc) {
    case Enc::png8: return dim + " PNG 8-bit";
    case Enc::png16: return dim + " PNG 16-bit";
    case Enc::jpg: return dim + " JPEG q90";
    case Enc::exr_half: return dim + " EXR half";
    }
    return dim;
}

std::string map_description(Map m) {
    switch (m) {
    case Map::albedo: return "albedo (sRGB)";
    case Map::normal_gl: return "normal, content OpenGL (+Y)";
    case Map::normal_dx: return "normal, content DirectX (-Y)";
    case Map::roughness: return "roughness";
    case Map::gloss: return "gloss (1 - roughness)";
    case Map::metalness: return "metalness (binary)";
    case Map::occlusion: return "ambient occlusion";
    case Map::height: return "height / displacement";
    case Map::opacity: return "opacity (cut-out)";
    case Map::emissive: return "emissive (sRGB)";
    case Map::arm: return "packed R=AO G=roughness B=metalness";
    case Map::ort: return "packed R=AO G=roughness B=translucency";
    case Map::metal_rough: return "packed R=0 G=roughness B=metalness";
    case Map::specular: return "specular level (REFL)";
    case Map::preview: return "clutter: preview render, not a map";
    }
    return "";
}

std::string readme(const std::vector<SetDef>& sets) {
    std::ostringstream o;
    o << "# sample_materials\n\n"
      << "Small procedural PBR material sets named the way vendors name them, for trying matforge\n"
      << "and for its tests. Every map of a set comes from one procedural surface (height, albedo,\n"
      << "roughness, metalness...), so the maps agree: normals are derived from the height by central\n"
      << "differences (wrap-around, tileable), occlusion from its cavities, mortar and grout are low,\n"
      << "rough and occluded. Albedo is computed in linear and encoded with the IEC 61966-2-1 sRGB\n"
      << "curve; metal albedo uses physicallybased.info values.\n\n"
      << "Normal maps: with rows going down the image, OpenGL (+Y) maps store\n"
      << "n = normalize(-s dh/dx, +s dh/drow, 1) as n*0.5+0.5; DirectX (-Y) maps negate the green.\n\n"
      << "**Generated — do not edit by hand.** Regenerate (byte-identical with the same build):\n\n"
      << "```sh\ncmake -S . -B build-gen -G Ninja -DMATFORGE_BENCHMARKS=OFF -DMATFORGE_TESTS=OFF\n"
      << "ninja -C build-gen gen_samples\nbuild-gen/tools/gen_samples/gen_samples sample_materials\n```\n\n"
      << "The generator (`tools/gen_samples/main.cpp`) replaces only the set folders and archives\n"
      << "listed below and this README. Names say 1K/2K as vendors do; the pixels are 64–256 px.\n\n"
      << "| set | convention | exercises |\n| --- | --- | --- |\n";
    for (const SetDef& s : sets) o << "| `" << s.root << "` | " << s.family << " | " << s.exercises << " |\n";
    for (const SetDef& s : sets) {
        o << "\n## " << s.root << " (" << s.family << ")\n\n";
        for (const FileDef& f : s.files)
            o << "- `" << f.path << "` — " << map_description(f.map) << ", " << encoding_name(f) << "\n";
        for (const TextDef& t : s.texts) o << "- `" << t.path << "` — clutter: text sidecar, not an image\n";
    }
    return o.str();
}

// ---------------------------------------------------------------- output

bool write_text(const fs::path& path, const std::string& text, std::string& err) {
    std::ofstream f(path, std::ios::binary);
    f << text;
    if (!f) err = "cannot write " + path.string();
    return static_cast<bool>(f);
}

std::vector<unsigned char> read_bytes(const fs::path& path) {
    std::ifstream f(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

// Zips a staged folder: entries sorted by name, fixed DOS time and Unix mode, deflate level 9,
// so the archive's bytes depend on the content only.
bool write_zip(const fs::path& staged, const fs::path& zip_path, std::string& err) {
    std::vector<std::pair<std::string, std::vector<unsigned char>>> entries;
    for (const auto& e : fs::recursive_directory_iterator(staged))
        if (e.is_regular_file()) entries.emplace_back(fs::relative(e.path(), staged).generic_string(), read_bytes(e.path()));
    std::sort(entries.begin(), entries.end());
    int zerr = 0;
    zip_t* za = zip_open(zip_path.string().c_str(), ZIP_CREATE | ZIP_TRUNCATE, &zerr);
    if (!za) {
        err = "cannot create " + zip_path.string();
        return false;
    }
    constexpr zip_uint16_t kDosDate = ((2024 - 1980) << 9) | (1 << 5) | 1;  // 2024-01-01
    constexpr zip_uint16_t kDosTime = 12 << 11;                         // 12:00:00
    bool ok = true;
    for (const auto& [name, bytes] : entries) {
        zip_source_t* src = zip_source_buffer(za, bytes.data(), bytes.size(), 0);
        const zip_int64_t idx = src ? zip_file_add(za, name.c_str(), src, ZIP_FL_ENC_UTF_8) : -1;
        if (idx < 0) {
            if (src) zip_source_free(src);
            ok = false;
            break;
        }
        const auto u = static_cast<zip_uint64_t>(idx);
        ok = zip_set_file_compression(za, u, ZIP_CM_DEFLATE, 9) == 0 &&
             zip_file_set_dostime(za, u, kDosTime, kDosDate, 0) == 0 &&
             zip_file_set_external_attributes(za, u, 0, ZIP_OPSYS_UNIX, 0100644U << 16) == 0;
        if (!ok) break;
    }
    if (!ok) {
        err = zip_path.string() + ": " + zip_strerror(za);
        zip_discard(za);
        return false;
    }
    if (zip_close(za) != 0) {
        err = zip_path.string() + ": " + zip_strerror(za);
        zip_discard(za);
        return false;
    }
    return true;
}

// Writes one set's files under `dir`; bakes each resolution the set uses once.
bool write_set_files(const SetDef& set, const fs::path& dir, std::string& err) {
    std::map<int, Baked> bakes;
    auto baked = [&](int n) -> const Baked& {
        auto it = bakes.find(n);
        if (it == bakes.end()) it = bakes.emplace(n, bake(*set.material, n)).first;
        return it->second;
    };
    for (const FileDef& f : set.files) {
        const fs::path path = dir / f.path;
        fs::create_directories(path.parent_path());
        const Pixels px = f.map == Map::preview ? render_preview(baked(128), f.size) : extract(baked(f.size), f.map);
        if (!write_image(path, px, f.enc, is_color(f.map), err)) return false;
    }
    for (const TextDef& t : set.texts)
        if (!write_text(dir / t.path, text_content(set, t.kind), err)) return false;
    return true;
}

bool generate_set(const fs::path& out, const SetDef& set, std::string& err) {
    const fs::path target = out / set.root;
    fs::remove_all(target);
    if (target.extension() != ".zip") {
        fs::create_directories(target);
        return write_set_files(set, target, err);
    }
    const fs::path staged = out / (".staging-" + target.stem().string());
    fs::remove_all(staged);
    fs::create_directories(staged);
    const bool ok = write_set_files(set, staged, err) && write_zip(staged, target, err);
    fs::remove_all(staged);
    return ok;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
        std::cerr << "usage: gen_samples <out-dir>\n"
                     "Writes matforge's sample material sets and README.md into <out-dir>, replacing\n"
                     "only the set folders/archives it generates.\n";
        return 2;
    }
    const fs::path out = argv[1];
    try {
        fs::create_directories(out);
        const std::vector<SetDef> sets = sample_sets();
        for (const SetDef& set : sets) {
            std::string err;
            if (!generate_set(out, set, err)) {
                std::cerr << "gen_samples: " << set.root << ": " << err << "\n";
                return 1;
            }
            std::cout << "wrote " << (out / set.root).string() << "\n";
        }
        std::string err;
        if (!write_text(out / "README.md", readme(sets), err)) {
            std::cerr << "gen_samples: " << err << "\n";
            return 1;
        }
    } catch (const fs::filesystem_error& e) {
        std::cerr << "gen_samples: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
