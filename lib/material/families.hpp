// Internal to lib/material (not a public API): the naming rules of each family, in one table per
// family (families.cpp). Matching them against a name is classify.cpp's job.
#pragma once
#include <array>
#include <span>
#include <string_view>

#include "material/roles.hpp"

namespace mf::naming {

// The rule id of a map named depth (Godot 3's parallax maps, white = deep): the planner reads it
// inverted unless the normal map's slopes show it holds height (lib/plan/plan.cpp).
inline constexpr std::string_view kDepthRule = "generic:depth";

enum class Case {
    any,
    lower,          // all letters lower case ("nor_gl")
    upper,          // all letters upper case ("COL", "NRM16")
    capital,        // first letter upper case ("NormalGL", "AO")
    lower_initial,  // first letter lower case ("baseColor", "normal")
};

// A condition on the whole name, for tags too short to trust anywhere.
enum class Need {
    none,
    // Megascans' Unreal export (Fab): "T_<id>_<res>_<tag>", the name starts with the token "T" and
    // a resolution tag stands right before the role tag ("T_tbdpec3r_4K_B-O"). Only there is a
    // lone "B" or "N" a role and not a variant letter ("Wall_B").
    unreal_texture,
    // A resolution tag right after the role tag (Poly Haven's "_alpha_1k"): for tags whose bare
    // form ("leaf_alpha") is left to the generic rules.
    res_after,
    // The role tag is the name's last word: only resolution, format or bit-depth tags and
    // variant numbers follow ("Rock_BC", "Rock_BC_2K", "T_Sand_BC_01"). For two-letter game
    // tags, which elsewhere in a name are ordinary words ("Ro", "Em").
    at_end,
    // An Unreal texture by the engine's naming convention: the name starts with the token "T"
    // and the role tag is its last word ("T_Rock_D", "T_Rock_ORM_2K"). Only there is a lone
    // letter (D, N, R, M, E, H, A, S) a role.
    unreal_suffix,
    // Glued to the word before it by a camel-case boundary, and at the end ("LampLights"): words
    // that with a separator are ordinary ("Street_Lights").
    glued_at_end,
};

struct Rule {
    std::string_view tokens;  // lower-case tokens separated by ' '
    Role role;
    NormalConvention normal;
    Case casing;
    bool joined;  // the tokens must form one camel-case word ("NormalGL", not "Normal_GL")
    std::string_view display;
    Need need = Need::none;
    bool opacity_in_alpha = false;             // the map's alpha channel is opacity ("_B-O": base color + opacity)
    NormalSpace space = NormalSpace::unknown;  // a normal map's name says tangent or object space
};

// How a name is laid out around its role tag; each family has a typical layout, used to
// attribute a rule several families share ("_Roughness").
struct Layout {
    bool res_format_pair = false;  // "1K-PNG": ambientCG
    bool res_before = false;       // "_2K_Albedo": Megascans
    bool res_after = false;        // "_COL_VAR1_2K", "_nor_gl_1k": Poliigon legacy, Poly Haven
    bool poliigon_prefix = false;  // "Poliigon_…": current Poliigon
    bool no_resolution = false;    // "Mat_BaseColor": Substance, glTF
    bool unreal_prefix = false;    // "T_…": Unreal's texture prefix
};

struct Family {
    std::string_view name;
    std::span<const Rule> rules;
    bool (*fits)(const Layout&);
};

// Priority order: also the tie-break when nothing else decides. The generic family is last.
extern const std::array<Family, 9> kFamilies;
inline constexpr size_t kGenericFamily = 8;

}  // namespace mf::naming
