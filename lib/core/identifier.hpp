// Names and numbers for scene-description files (MaterialX, USD): one spelling for both.
#pragma once
#include <string>
#include <string_view>

namespace mf {

// `name` as an identifier that MaterialX element names and USD prim names both accept: ASCII
// letters, digits and '_' (every other byte becomes '_'), never empty nor starting with a digit
// ("M_" is put in front). Distinct names may meet ("a-b", "a_b"): a document holds one material.
std::string scene_identifier(std::string_view name);

// A float as the shortest text of at most 6 significant digits ("%.6g": 0.5, 1, 2.25).
std::string scene_number(float v);

}  // namespace mf
