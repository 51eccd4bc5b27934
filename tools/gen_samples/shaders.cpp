#include "shaders.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "noise.hpp"

namespace gen {

namespace {

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

}  // namespace

const Material kBricks{bricks, 0.02f, 2.5f};
const Material kTiles{glazed_tiles, 0.015f, 2.5f};
const Material kMetalPlates{metal_plates, 0.015f, 2.f};
const Material kRockyGround{rocky_ground, 0.025f, 2.5f};
const Material kWoodPlanks{wood_planks, 0.02f, 2.f};
const Material kMarbleTiles{marble_tiles, 0.02f, 2.5f};
const Material kIvyLeaves{ivy_leaves, 0.012f, 2.f};
const Material kScifiPanel{scifi_panel, 0.02f, 2.f};
const Material kWalnutInlay{walnut_inlay, 0.02f, 2.f};

}  // namespace gen
