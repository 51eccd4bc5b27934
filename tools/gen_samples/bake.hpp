// Baking a shader on an n × n grid, and the maps derived from its height field (normals from
// the height, occlusion from its cavities), so every map of a set agrees with the others.
#pragma once

#include <cstddef>
#include <vector>

#include "shaders.hpp"

namespace gen {

// All shader samples of one n × n bake plus the maps derived from the height field.
struct Baked {
    int n = 0;
    std::vector<Sample> s;
    std::vector<Vec3> normal;  // tangent space, OpenGL (+Y) convention
    std::vector<float> ao;
};

// Index of texel (x, y), wrapping around the tile.
inline size_t at(int x, int y, int n) { return static_cast<size_t>(wrap(y, n)) * n + wrap(x, n); }

Baked bake(const Material& m, int n);

}  // namespace gen
