// The procedural material "shaders": each a function of tileable texture coordinates (u, v) in
// [0,1) giving what one point of the surface is (height, albedo, roughness, metalness...).
#pragma once

#include "math.hpp"

namespace gen {

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

extern const Material kBricks;       // running-bond bricks, mortar low and rough
extern const Material kTiles;        // glazed ceramic tiles, matte grout
extern const Material kMetalPlates;  // painted iron plates, chipped to bare iron, rivets
extern const Material kRockyGround;  // pebbles bedded in soil
extern const Material kWoodPlanks;   // worn boards, iron nail heads the only metal
extern const Material kMarbleTiles;  // polished veined marble, thin grout
extern const Material kIvyLeaves;    // cut-out leaf decal (opacity, translucency)
extern const Material kScifiPanel;   // hull panels, aluminium bolts, emissive strips
extern const Material kWalnutInlay;  // walnut with gold inlay and emissive gems

}  // namespace gen
