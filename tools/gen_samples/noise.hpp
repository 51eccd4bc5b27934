// Tileable noise from an integer hash: no tables, no random devices, identical everywhere.
#pragma once

#include <cstdint>

namespace gen {

uint32_t hash(int x, int y, uint32_t seed);
float hash01(int x, int y, uint32_t seed);  // [0, 1)

// Value noise on a px × py lattice that wraps at the tile border (so maps tile).
float value_noise(float u, float v, int px, int py, uint32_t seed);

// Fractal sum, normalised to [0,1]; periods double per octave so it stays tileable.
float fbm(float u, float v, int px, int py, int octaves, uint32_t seed);
float fbm(float u, float v, int period, int octaves, uint32_t seed);

// Tileable Worley noise: distances (in cell units) to the nearest and second feature points.
struct Cells {
    float f1 = 1e9f, f2 = 1e9f;
    uint32_t id = 0;
};
Cells worley(float u, float v, int period, uint32_t seed);

}  // namespace gen
