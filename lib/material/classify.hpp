// Internal to lib/material (not a public API): one file name analysed once, for the public
// classify_name / material_stem / is_clutter and for discover_set and group_files.
#pragma once
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "material/discovery.hpp"
#include "material/tokens.hpp"

namespace mf::naming {

enum class ClutterKind {
    preview,      // preview, thumbnail, swatch, icon, screenshot, render, sphere, cube…
    render,       // "Material_1639": 3dtextures.me's preview render
    mask,         // ID maps and masks with no PBR role ("_IdMap", "_mask", "_id")
    placeholder,  // an all-black file with no role ("_black", "_BLACK")
    billboard,    // Megascans billboard maps: a plant's far-LOD impostor, not the material
};
std::string_view clutter_reason(ClutterKind k);  // the UNRECOGNIZED_FILE reason

struct Clutter {
    size_t token = 0;  // where the clutter word starts
    ClutterKind kind = ClutterKind::preview;
};

// The role tag of a tokenized name.
struct RoleTag {
    size_t first_token = 0, last_token = 0;  // indices into the token list
    NameMatch match;
    std::vector<std::string_view> families;  // every family with a rule for this tag
    std::vector<std::string_view> fitting;   // those whose naming layout the name also follows
};

struct NameAnalysis {
    std::vector<Token> tokens;
    std::optional<RoleTag> tag;
    std::optional<Clutter> clutter;
    size_t name_end = 0;  // the material name part is tokens [0, name_end)
};

// Tokenize the stem of `filename`'s base name, find its role tag and clutter, and settle the
// bare numbers: a Kind::depth token before name_end becomes a word (part of the name), one
// after it becomes a format tag.
NameAnalysis analyse(std::string_view filename);

// Whether clutter is a picture of the material, and how plainly its name says so (smaller is
// plainer): 1 "preview", 2 a render ("render", "renders", 3dtextures.me's "Material_NNNN"),
// 3 "sphere", 4 "cube", 5 "flat", "plane", "cylinder", 6 a thumbnail, icon, swatch or
// screenshot. nullopt for names that are no clutter or clutter of another kind (masks,
// placeholders, billboards). 0 is left for a vendor's preview named by its id alone (ambientCG).
std::optional<int> preview_rank(const NameAnalysis& a);

// Material name tokens in [0, end), tags dropped, joined by '_' except across a camel-case
// boundary ("DamagedHelmet" stays one word).
std::string join_name(const std::vector<Token>& tokens, size_t end);

// The name part as written: the stem's text before the token at `end`, trailing separators
// dropped ("Bricks059_1K-PNG" of "Bricks059_1K-PNG_Color.png").
std::string name_spelling(std::string_view filename, const NameAnalysis& a);

// Bit depth a name states ("16bit", "_16" after the role, Poliigon's "NRM16"), 0 when none.
int name_bit_depth(const std::vector<Token>& tokens);

}  // namespace mf::naming
