// The table of synthetic sets: for each, the vendor family it imitates, its files (names,
// sizes, formats, packing) and its clutter, and what it exercises.
#pragma once

#include <string>
#include <vector>

#include "maps.hpp"

namespace gen {

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

std::vector<SetDef> sample_sets();

}  // namespace gen
