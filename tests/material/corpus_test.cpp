// Every file of the real CC0 sets in the shared corpus (ambientCG, Poly Haven, 3dtextures.me),
// with the role its ground truth gives (ao = occlusion, packed = orm: all are Poly Haven ARM),
// copied here so the test does not depend on the corpus being present. A normal's convention is
// the one its name states (the truth's convention for the 3dtextures.me "_normal" maps comes from
// the pixels, which discovery does not read).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <optional>
#include <set>

#include "discovery_helpers.hpp"
#include "material/discovery.hpp"

namespace mf {
namespace {

using namespace discovery_test;
using NC = NormalConvention;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

struct CorpusFile {
    std::string file;
    std::optional<Role> role;  // nullopt: ignored (preview, sidecar, placeholder, mask)
    NC normal = NC::unknown;
};

struct CorpusSet {
    std::string folder;
    std::vector<CorpusFile> files;
};

const std::vector<CorpusSet> kCorpus{
    {"ambientcg_OfficeCeiling005_1K-JPG",
     {
         {"OfficeCeiling005.png", std::nullopt},
         {"OfficeCeiling005_1K-JPG.mtlx", std::nullopt},
         {"OfficeCeiling005_1K-JPG.usdc", std::nullopt},
         {"OfficeCeiling005_1K-JPG_AmbientOcclusion.jpg", Role::occlusion},
         {"OfficeCeiling005_1K-JPG_Color.jpg", Role::albedo},
         {"OfficeCeiling005_1K-JPG_Displacement.jpg", Role::height},
         {"OfficeCeiling005_1K-JPG_Emission.jpg", Role::emissive},
         {"OfficeCeiling005_1K-JPG_Metalness.jpg", Role::metalness},
         {"OfficeCeiling005_1K-JPG_NormalDX.jpg", Role::normal, NC::dx},
         {"OfficeCeiling005_1K-JPG_NormalGL.jpg", Role::normal, NC::gl},
         {"OfficeCeiling005_1K-JPG_Roughness.jpg", Role::roughness},
     }},
    {"ambientcg_WoodFloor040_1K-JPG",
     {
         {"WoodFloor040.png", std::nullopt},
         {"WoodFloor040_1K-JPG.mtlx", std::nullopt},
         {"WoodFloor040_1K-JPG.usdc", std::nullopt},
         {"WoodFloor040_1K-JPG_AmbientOcclusion.jpg", Role::occlusion},
         {"WoodFloor040_1K-JPG_Color.jpg", Role::albedo},
         {"WoodFloor040_1K-JPG_Displacement.jpg", Role::height},
         {"WoodFloor040_1K-JPG_NormalDX.jpg", Role::normal, NC::dx},
         {"WoodFloor040_1K-JPG_NormalGL.jpg", Role::normal, NC::gl},
         {"WoodFloor040_1K-JPG_Roughness.jpg", Role::roughness},
     }},
    {"ambientcg_Net004A_1K-JPG",
     {
         {"Net004A.png", std::nullopt},
         {"Net004A_1K-JPG.mtlx", std::nullopt},
         {"Net004A_1K-JPG.usdc", std::nullopt},
         {"Net004A_1K-JPG_Color.jpg", Role::albedo},
         {"Net004A_1K-JPG_Displacement.jpg", Role::height},
         {"Net004A_1K-JPG_NormalDX.jpg", Role::normal, NC::dx},
         {"Net004A_1K-JPG_NormalGL.jpg", Role::normal, NC::gl},
         {"Net004A_1K-JPG_Opacity.jpg", Role::opacity},
         {"Net004A_1K-JPG_Roughness.jpg", Role::roughness},
     }},
    {"flat_folder_two_sets",
     {
         {"Material_1586.jpg", std::nullopt},
         {"Rocks004_1K-JPG_AmbientOcclusion.jpg", Role::occlusion},
         {"Rocks004_1K-JPG_Color.jpg", Role::albedo},
         {"Rocks004_1K-JPG_Displacement.jpg", Role::height},
         {"Rocks004_1K-JPG_NormalDX.jpg", Role::normal, NC::dx},
         {"Rocks004_1K-JPG_NormalGL.jpg", Role::normal, NC::gl},
         {"Rocks004_1K-JPG_Roughness.jpg", Role::roughness},
         {"Surface_Imperfection_001_ambientOcclusion.jpg", Role::occlusion},
         {"Surface_Imperfection_001_basecolor.jpg", Role::albedo},
         {"Surface_Imperfection_001_height.png", Role::height},
         {"Surface_Imperfection_001_normal.jpg", Role::normal, NC::unknown},
         {"Surface_Imperfection_001_roughness.jpg", Role::roughness},
     }},
    {"polyhaven_rubberized_track_1k",
     {
         {"rubberized_track_ao_1k.jpg", Role::occlusion},
         {"rubberized_track_arm_1k.jpg", Role::orm},
         {"rubberized_track_diff_1k.jpg", Role::albedo},
         {"rubberized_track_disp_1k.png", Role::height},
         {"rubberized_track_nor_dx_1k.jpg", Role::normal, NC::dx},
         {"rubberized_track_nor_gl_1k.jpg", Role::normal, NC::gl},
         {"rubberized_track_rough_1k.jpg", Role::roughness},
     }},
    {"polyhaven_broken_wall_1k_jpg+webp",
     {
         {"broken_wall_arm_1k.jpg", Role::orm},
         {"broken_wall_arm_1k.webp", Role::orm},
         {"broken_wall_diff_1k.jpg", Role::albedo},
         {"broken_wall_diff_1k.webp", Role::albedo},
         {"broken_wall_nor_gl_1k.jpg", Role::normal, NC::gl},
         {"broken_wall_nor_gl_1k.webp", Role::normal, NC::gl},
     }},
    {"polyhaven_brown_planks_09_1k_jpg+webp",
     {
         {"brown_planks_09_arm_1k.jpg", Role::orm},
         {"brown_planks_09_arm_1k.webp", Role::orm},
         {"brown_planks_09_diff_1k.jpg", Role::albedo},
         {"brown_planks_09_diff_1k.webp", Role::albedo},
         {"brown_planks_09_nor_gl_1k.jpg", Role::normal, NC::gl},
         {"brown_planks_09_nor_gl_1k.webp", Role::normal, NC::gl},
     }},
    {"3dtextures_Crystal_003_SD",
     {
         {"Crystal_003_BLACK.jpg", std::nullopt},
         {"Crystal_003_COLOR.jpg", Role::albedo},
         {"Crystal_003_DISP.png", Role::height},
         {"Crystal_003_NORM.jpg", Role::normal, NC::unknown},
         {"Crystal_003_OCC.jpg", Role::occlusion},
         {"Crystal_003_ROUGH.jpg", Role::roughness},
     }},
    {"3dtextures_Fabric_polyester_003_SD",
     {
         {"Fabric_polyester_003_ambientOcclusion.jpg", Role::occlusion},
         {"Fabric_polyester_003_basecolor.jpg", Role::albedo},
         {"Fabric_polyester_003_black.jpg", std::nullopt},
         {"Fabric_polyester_003_height.png", Role::height},
         {"Fabric_polyester_003_normal.jpg", Role::normal, NC::unknown},
         {"Fabric_polyester_003_opacity.jpg", Role::opacity},
         {"Fabric_polyester_003_roughness.jpg", Role::roughness},
         {"Material_1639.jpg", std::nullopt},
     }},
    {"3dtextures_Metal_Damaged_001_SD",
     {
         {"Material_1957.jpg", std::nullopt},
         {"Metal_Damaged_001_ambientOcclusion.jpg", Role::occlusion},
         {"Metal_Damaged_001_basecolor.jpg", Role::albedo},
         {"Metal_Damaged_001_height.png", Role::height},
         {"Metal_Damaged_001_metallic.jpg", Role::metalness},
         {"Metal_Damaged_001_normal.jpg", Role::normal, NC::unknown},
         {"Metal_Damaged_001_roughness.jpg", Role::roughness},
     }},
    {"3dtextures_Obsidian_001",
     {
         {"Obsidian_001_ambientOcclusion.jpg", Role::occlusion},
         {"Obsidian_001_basecolor.jpg", Role::albedo},
         {"Obsidian_001_height.png", Role::height},
         {"Obsidian_001_metallic.jpg", Role::metalness},
         {"Obsidian_001_normal.jpg", Role::normal, NC::unknown},
         {"Obsidian_001_roughness.jpg", Role::roughness},
     }},
    {"3dtextures_Metal_Rusted_010",
     {
         {"Metal_Rusted_010_ambientOcclusion.jpg", Role::occlusion},
         {"Metal_Rusted_010_basecolor.jpg", Role::albedo},
         {"Metal_Rusted_010_height.png", Role::height},
         {"Metal_Rusted_010_metallic.jpg", Role::metalness},
         {"Metal_Rusted_010_normal.jpg", Role::normal, NC::unknown},
         {"Metal_Rusted_010_roughness.jpg", Role::roughness},
     }},
    {"3dtextures_Sci-Fi_Wall_014",
     {
         {"Sci-Fi_Wall_014_ambientOcclusion.jpg", Role::occlusion},
         {"Sci-Fi_Wall_014_basecolor.jpg", Role::albedo},
         {"Sci-Fi_Wall_014_height.png", Role::height},
         {"Sci-Fi_Wall_014_metallic.jpg", Role::metalness},
         {"Sci-Fi_Wall_014_normal.jpg", Role::normal, NC::unknown},
         {"Sci-Fi_Wall_014_opacity.jpg", Role::opacity},
         {"Sci-Fi_Wall_014_roughness.jpg", Role::roughness},
     }},
    {"3dtextures_Ground_Wet_002",
     {
         {"Ground_Wet_002_ambientOcclusion.jpg", Role::occlusion},
         {"Ground_Wet_002_basecolor.jpg", Role::albedo},
         {"Ground_Wet_002_height.png", Role::height},
         {"Ground_Wet_002_mask.jpg", std::nullopt},
         {"Ground_Wet_002_normal.jpg", Role::normal, NC::unknown},
         {"Ground_Wet_002_opacity.jpg", Role::opacity},
         {"Ground_Wet_002_roughness.jpg", Role::roughness},
     }},
};

std::vector<std::string> names(const CorpusSet& s) {
    std::vector<std::string> out;
    for (const auto& f : s.files) out.push_back(f.file);
    return out;
}

TEST(CorpusNames, EveryFileClassifiesToItsTrueRole) {
    size_t checked = 0;
    for (const auto& set : kCorpus)
        for (const auto& f : set.files) {
            SCOPED_TRACE(set.folder + "/" + f.file);
            const auto m = classify_name(f.file);
            ++checked;
            if (!f.role) {
                EXPECT_FALSE(m.has_value()) << role_name(m->role);
                continue;
            }
            ASSERT_TRUE(m.has_value());
            EXPECT_EQ(role_name(m->role), role_name(*f.role));
            EXPECT_EQ(convention_name(m->normal), convention_name(f.normal));
        }
    EXPECT_EQ(checked, 107u);
}

// The vendor's preview images of the corpus (truth.json's "preview" of each set): ambientCG's
// "<Id>.png" and 3dtextures.me's render in a folder of its own.
bool is_vendor_preview(const std::string& file) {
    static const std::set<std::string> kPreviews{"OfficeCeiling005.png", "WoodFloor040.png", "Net004A.png",
                                                 "Material_1639.jpg", "Material_1957.jpg"};
    return kPreviews.count(file) > 0;
}

TEST(CorpusNames, DiscoverSetUsesEveryMapAndExplainsEveryIgnoredFile) {
    for (const auto& set : kCorpus) {
        SCOPED_TRACE(set.folder);
        const auto groups = group_files(names(set), set.folder);
        std::vector<std::string> seen;
        for (const auto& g : groups) {
            ChoicePolicy policy;
            policy.shared_folder = g.shared;  // as lib/sets gives it
            const auto d = discover_set(g.files, nullptr, policy);
            for (const auto& file : g.files) {
                SCOPED_TRACE(file);
                seen.push_back(file);
                const auto& truth = *std::find_if(set.files.begin(), set.files.end(),
                                                  [&](const CorpusFile& c) { return c.file == file; });
                const auto reason = unrecognized_reason(d, file);
                if (truth.role) {
                    EXPECT_THAT(candidates(d, *truth.role), ::testing::Contains(file));
                    EXPECT_EQ(reason, "");
                    continue;
                }
                if (is_vendor_preview(file)) {  // the set's preview: no map, nothing to say
                    ASSERT_TRUE(d.preview.has_value());
                    EXPECT_EQ(d.preview->file, file);
                    EXPECT_EQ(reason, "");
                    continue;
                }
                EXPECT_NE(reason, "");  // ignored, and said so (info)
                EXPECT_NE(reason, "no role tag in the name");
            }
            for (const auto& f : d.findings) EXPECT_EQ(f.severity, Severity::info) << f.message;
        }
        EXPECT_EQ(seen.size(), set.files.size());  // every file in exactly one group
    }
}

TEST(CorpusNames, FlatFolderSplitsIntoItsTwoSets) {
    const auto& set = *std::find_if(kCorpus.begin(), kCorpus.end(),
                                    [](const CorpusSet& s) { return s.folder == "flat_folder_two_sets"; });
    const auto g = group_files(names(set), "flat_folder_two_sets");
    ASSERT_EQ(g.size(), 2u);
    EXPECT_EQ(g[0].name, "Rocks004");
    EXPECT_EQ(g[1].name, "Surface_Imperfection_001");
    // The 3dtextures.me preview render names no material: it joins the first group.
    EXPECT_THAT(g[0].files,
                ElementsAre("Material_1586.jpg", "Rocks004_1K-JPG_AmbientOcclusion.jpg", "Rocks004_1K-JPG_Color.jpg",
                            "Rocks004_1K-JPG_Displacement.jpg", "Rocks004_1K-JPG_NormalDX.jpg",
                            "Rocks004_1K-JPG_NormalGL.jpg", "Rocks004_1K-JPG_Roughness.jpg"));
    EXPECT_EQ(g[1].files.size(), 5u);
    EXPECT_FALSE(g[0].merge.has_value());
    EXPECT_FALSE(g[1].merge.has_value());
    EXPECT_TRUE(g[0].shared && g[1].shared);
    // In a shared folder the render that names no material is no set's preview (it is the other
    // set's, 3dtextures.me's Surface_Imperfection_001): unrecognized, with its reason.
    ChoicePolicy policy;
    policy.shared_folder = true;
    const auto d = discover_set(g[0].files, nullptr, policy);
    EXPECT_EQ(d.convention, "ambientcg");
    EXPECT_FALSE(d.preview.has_value());
    EXPECT_EQ(unrecognized_reason(d, "Material_1586.jpg"), "preview render (Material_NNNN)");
    // Alone with Rocks004's maps it would be taken for Rocks004's: what shared_folder prevents.
    EXPECT_EQ(discover_set(g[0].files, nullptr, ChoicePolicy{}).preview->file, "Material_1586.jpg");
}

TEST(CorpusNames, Crystal003OlderTagsMakeAFullSet) {
    const auto& set = *std::find_if(kCorpus.begin(), kCorpus.end(),
                                    [](const CorpusSet& s) { return s.folder == "3dtextures_Crystal_003_SD"; });
    const auto d = discover_set(names(set), nullptr, ChoicePolicy{});
    EXPECT_THAT(roles_of(d), ElementsAre("albedo", "normal", "roughness", "occlusion", "height"));
    EXPECT_THAT(keys(d), ElementsAre("UNRECOGNIZED_FILE  Crystal_003_BLACK.jpg"));
    EXPECT_THAT(d.findings[0].message, HasSubstr("all-black placeholder"));
}

}  // namespace
}  // namespace mf
