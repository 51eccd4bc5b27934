// Names found on real downloads that discovery used to miss or misread: 3dtextures.me's older
// tags and clutter, Megascans' Unreal-export plant atlases and billboards, Poly Haven's
// translucent/alpha maps, dashes and dots between name and tag, bare numbers in material names,
// camel-case words that start like a format, and JPEG originals beside smaller WebP re-encodes.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "discovery_helpers.hpp"
#include "material/discovery.hpp"
#include "material/routing.hpp"

namespace mf {
namespace {

using namespace discovery_test;
using NC = NormalConvention;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;

struct Expect {
    std::string file;
    Role role;
    std::string rule;  // "" = not checked
    NC normal = NC::unknown;
    bool opacity_in_alpha = false;
};

void check(const std::vector<Expect>& rows) {
    for (const auto& r : rows) {
        SCOPED_TRACE(r.file);
        const auto m = classify_name(r.file);
        ASSERT_TRUE(m.has_value());
        EXPECT_EQ(role_name(m->role), role_name(r.role));
        EXPECT_EQ(convention_name(m->normal), convention_name(r.normal));
        EXPECT_EQ(m->opacity_in_alpha, r.opacity_in_alpha);
        EXPECT_TRUE(m->unused.empty());
        EXPECT_TRUE(m->sidecar.empty());
        if (!r.rule.empty()) {
            EXPECT_EQ(m->rule, r.rule);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// 3dtextures.me

TEST(NamingGaps, ThreeDTexturesOlderTags) {
    check({
        {"Crystal_003_COLOR.jpg", Role::albedo, ""},
        {"Crystal_003_NORM.jpg", Role::normal, "generic:norm"},
        {"Crystal_003_OCC.jpg", Role::occlusion, "generic:occ"},
        {"Crystal_003_ROUGH.jpg", Role::roughness, "generic:rough"},
        {"Crystal_003_DISP.png", Role::height, ""},
        {"Rock_occ.png", Role::occlusion, "generic:occ"},
    });
    EXPECT_EQ(material_stem("Crystal_003_OCC.jpg"), "Crystal_003");
}

// A 3dtextures.me set renamed by hand in a three.js project (fl-martin/threejs-hello-mars,
// src/Images/): "basecolor" and "heightmap" were read, the five other maps dropped unread.
TEST(NamingGaps, OneWordMapNames) {
    check({
        {"normalmap.jpg", Role::normal, "generic:normalmap"},
        {"roughnessmap.jpg", Role::roughness, "generic:roughnessmap"},
        {"metallicmap.jpg", Role::metalness, "generic:metallicmap"},
        {"aomap.jpg", Role::occlusion, "generic:aomap"},
        {"opacitymap.jpg", Role::opacity, "generic:opacitymap"},
        {"Rock_alphaMap.png", Role::opacity, ""},
        {"Rock_displacementMap.png", Role::height, ""},
        {"Rock_emissiveMap.png", Role::emissive, ""},
        {"DancingGirl_normals.png", Role::normal, "generic:normals"},
    });
}

TEST(NamingGaps, ThreeDTexturesClutterHasItsOwnReason) {
    // Files of several sets in one folder: the render names no material, so it is no one's preview.
    ChoicePolicy shared;
    shared.shared_folder = true;
    const auto d = discover_set({"Crystal_003_BLACK.jpg", "Crystal_003_COLOR.jpg", "Fabric_polyester_003_black.jpg",
                                 "Material_1639.jpg", "Ground_Wet_002_mask.jpg", "Leaf_OpacityMask.png"},
                                nullptr, shared);
    EXPECT_FALSE(d.preview.has_value());
    EXPECT_THAT(roles_of(d), ElementsAre("albedo", "opacity"));
    EXPECT_EQ(chosen_file(d, Role::opacity), "Leaf_OpacityMask.png");  // "mask" after "opacity" is no clutter
    EXPECT_EQ(unrecognized_reason(d, "Crystal_003_BLACK.jpg"), "all-black placeholder (_black) with no PBR role");
    EXPECT_EQ(unrecognized_reason(d, "Fabric_polyester_003_black.jpg"),
              "all-black placeholder (_black) with no PBR role");
    EXPECT_EQ(unrecognized_reason(d, "Material_1639.jpg"), "preview render (Material_NNNN)");
    EXPECT_EQ(unrecognized_reason(d, "Ground_Wet_002_mask.jpg"), "ID or mask image with no PBR role");
    for (const auto& f : d.findings) EXPECT_EQ(f.severity, Severity::info) << f.message;
    for (const std::string file :
         {"Crystal_003_BLACK.jpg", "Material_1957.jpg", "Ground_Wet_002_mask.jpg", "Material.001.png"}) {
        EXPECT_TRUE(is_clutter(file)) << file;
        EXPECT_FALSE(classify_name(file).has_value()) << file;
    }
    // HDRP's "_MaskMap" is a packed map (R metallic, G occlusion, B detail mask, A smoothness).
    EXPECT_EQ(classify_name("Mat_MaskMap.png")->role, Role::mask_map);
    // Ordinary words stay words away from the tag's place, and a material named "Material" is fine.
    for (const std::string file :
         {"Black_Marble_2K_Albedo.jpg", "Mask_Factory_Color.png", "Material_001_BaseColor.png"})
        EXPECT_FALSE(is_clutter(file)) << file;
    EXPECT_EQ(material_stem("Material_001_BaseColor.png"), "Material_001");
    EXPECT_EQ(material_stem("Crystal_003_BLACK.jpg"), "Crystal_003");
}

// ---------------------------------------------------------------------------------------------
// Megascans Unreal export (Fab): T_<id>_<res>_<tag>

TEST(NamingGaps, MegascansUnrealExportTags) {
    check({
        {"T_tbdpec3r_4K_B-O.png", Role::albedo, "megascans:_B-O", NC::unknown, true},
        {"T_tbdpec3r_4K_B.png", Role::albedo, "megascans:_B"},
        {"T_tbdpec3r_4K_N.png", Role::normal, "megascans:_N"},
        {"T_tbdpec3r_4K_ORT.png", Role::ort, "megascans:_ORT"},
        {"T_rh0ribp0_1K_ORM.jpg", Role::orm, "megascans:_ORM"},
        {"Bracken_Fern_okdr22_4K_BaseColor.jpg", Role::albedo, "megascans:_BaseColor"},
    });
    // A lone letter is a role only in that layout (or Unreal's own, "T_Foo_N": ClassifyName.GameAndHandNamed):
    // a variant letter elsewhere.
    for (const std::string file : {"Wall_B.png", "Brick_2K_N.png", "T_Foo_B.tga", "t_x_1K_B.png", "T_x_1K_b.png"})
        EXPECT_FALSE(classify_name(file).has_value()) << file;
    EXPECT_EQ(material_stem("T_tbdpec3r_4K_B-O.png"), "T_tbdpec3r");
}

TEST(NamingGaps, MegascansPlantAtlasWithBillboards) {
    const std::vector<std::string> files{
        "Textures/T_tbdpec3r_4K_B-O.png",
        "Textures/T_tbdpec3r_4K_B.png",
        "Textures/T_tbdpec3r_4K_N.png",
        "Textures/T_tbdpec3r_4K_ORT.png",
        "Textures/T_tbdpec3r_4K_Billboard_B-O.png",
        "Textures/T_tbdpec3r_4K_Billboard_N-T.png",
        "Textures/Billboard/Billboard_2K_Albedo.jpg",
    };
    const auto d = discover_set(files, nullptr, ChoicePolicy{});
    EXPECT_EQ(d.convention, "megascans");
    EXPECT_THAT(roles_of(d), ElementsAre("albedo", "normal", "ort"));
    // Same size and format: by name, and the one carrying opacity sorts first ('-' < '.').
    EXPECT_THAT(candidates(d, Role::albedo),
                ElementsAre("Textures/T_tbdpec3r_4K_B-O.png", "Textures/T_tbdpec3r_4K_B.png"));
    EXPECT_TRUE(find_choice(d, Role::albedo)->chosen.match.opacity_in_alpha);
    EXPECT_FALSE(find_choice(d, Role::albedo)->rejected[0].match.opacity_in_alpha);
    for (const std::string f : {"Textures/T_tbdpec3r_4K_Billboard_B-O.png", "Textures/T_tbdpec3r_4K_Billboard_N-T.png",
                                "Textures/Billboard/Billboard_2K_Albedo.jpg"})
        EXPECT_THAT(unrecognized_reason(d, f), HasSubstr("billboard map")) << f;
    for (const auto& f : d.findings) EXPECT_EQ(f.severity, Severity::info) << f.message;
}

// ---------------------------------------------------------------------------------------------
// Poly Haven translucent / alpha

TEST(NamingGaps, PolyHavenTranslucentAndAlpha) {
    check({
        {"fern_02_translucent_1k.jpg", Role::translucency, "polyhaven:_translucent_"},
        {"fern_02_alpha_1k.png", Role::opacity, "polyhaven:_alpha_"},
        {"fern_02_alpha_4k.exr", Role::opacity, "polyhaven:_alpha_"},
        {"leaf_translucent.png", Role::translucency, "generic:translucent"},
        {"leaf_alpha.png", Role::opacity, "generic:alpha"},
    });
    const auto d = discover_set({"fern_02_diff_1k.jpg", "fern_02_nor_gl_1k.jpg", "fern_02_arm_1k.jpg",
                                 "fern_02_translucent_1k.jpg", "fern_02_alpha_1k.png"},
                                nullptr, ChoicePolicy{});
    EXPECT_EQ(d.convention, "polyhaven");
    EXPECT_THAT(roles_of(d), ElementsAre("albedo", "normal", "opacity", "orm", "translucency"));
    EXPECT_THAT(keys(d), IsEmpty());  // no "no role tag", nothing ambiguous
}

// ---------------------------------------------------------------------------------------------
// Separators

TEST(NamingGaps, DashesAndDotsBetweenNameAndTag) {
    const std::string en = "\xE2\x80\x93", em = "\xE2\x80\x94", dot = "\xC2\xB7", nbsp = "\xC2\xA0";
    const std::vector<std::string> files{"Old Wood " + en + " Color.png", "Old Wood" + em + "Normal_GL.png",
                                         "Old Wood " + dot + " Roughness.png", "Old" + nbsp + "Wood_Height.png"};
    check({
        {files[0], Role::albedo, ""},
        {files[1], Role::normal, "", NC::gl},
        {files[2], Role::roughness, ""},
        {files[3], Role::height, ""},
    });
    for (const auto& f : files) EXPECT_EQ(material_stem(f), "Old_Wood") << f;
    const auto g = group_files(files, "x");
    ASSERT_EQ(g.size(), 1u);
    EXPECT_EQ(g[0].name, "Old_Wood");
    EXPECT_EQ(g[0].files.size(), 4u);
    // "Old Wood" and "Old·Wood" spell the name with different separators: reported, not hidden.
    ASSERT_TRUE(g[0].merge.has_value());
    EXPECT_TRUE(g[0].merge->spelling_differs);
    EXPECT_FALSE(g[0].merge->tags_differ);
    EXPECT_THAT(g[0].merge->spellings, ElementsAre("Old Wood", "Old" + nbsp + "Wood"));
    // Other non-ASCII bytes are letters: they stay inside their token.
    EXPECT_EQ(material_stem("Caf\xC3\xA9_Tiles_Color.png"), "Caf\xC3\xA9_Tiles");
    // Stems that differ only in the case of a non-ASCII letter are one material, the
    // difference reported as a spelling.
    const auto brick = group_files({"Br\xC3\xAF"
                                    "ck Wall 01 " +
                                        en + " BASECOLOR.PNG",
                                    "BR\xC3\x8F"
                                    "CK WALL 01 " +
                                        en + " Roughness.png"},
                                   "x");
    ASSERT_EQ(brick.size(), 1u);
    EXPECT_EQ(brick[0].files.size(), 2u);
    ASSERT_TRUE(brick[0].merge.has_value());
    EXPECT_TRUE(brick[0].merge->spelling_differs);
}

// ---------------------------------------------------------------------------------------------
// Numbers and camel-case words in material names

TEST(NamingGaps, BareNumbersBeforeTheRoleTagBelongToTheName) {
    const std::vector<std::pair<std::string, std::string>> stems{
        {"Metal_16_Color.png", "Metal_16"},
        {"Metal_32_Color.png", "Metal_32"},
        {"Metal_16_Roughness.png", "Metal_16"},
        {"Rock_Height_16.png", "Rock"},  // after the tag: a bit-depth tag
        {"Rock_Normal_32_2K.exr", "Rock"},
        {"Bricks_2048_Color.png", "Bricks"},  // a known resolution is a tag anywhere
        {"Bricks_2K_Color.png", "Bricks"},
        {"Metal_600_Color.png", "Metal_600"},
        {"Steel_16.png", "Steel_16"},  // no role tag: all name
        {"Steel_16_Preview.png", "Steel_16"},
        {"Metal_16.png", ""},  // "metal" is the role tag here (a 16-bit metalness map)
    };
    for (const auto& [file, stem] : stems) EXPECT_EQ(material_stem(file), stem) << file;
    EXPECT_EQ(classify_name("Rock_Normal_32_2K.exr")->role, Role::normal);
    EXPECT_EQ(classify_name("Metal_16.png")->role, Role::metalness);
    EXPECT_EQ(resolution_hint("Rock_Normal_32_2K.exr"), 2048);

    const auto g = group_files({"Metal_16_Color.png", "Metal_16_Roughness.png", "Metal_32_Color.png",
                                "Metal_32_Roughness.png"},
                               "x");
    ASSERT_EQ(g.size(), 2u);
    EXPECT_EQ(g[0].name, "Metal_16");
    EXPECT_THAT(g[0].files, ElementsAre("Metal_16_Color.png", "Metal_16_Roughness.png"));
    EXPECT_EQ(g[1].name, "Metal_32");
    EXPECT_FALSE(g[0].merge.has_value());
    EXPECT_FALSE(g[1].merge.has_value());
}

TEST(NamingGaps, BitDepthAfterTheTagStillRanks) {
    const auto d = discover_set({"Rock_Height.png", "Rock_Height_16.png"}, nullptr, ChoicePolicy{});
    EXPECT_EQ(chosen_file(d, Role::height), "Rock_Height_16.png");
    const auto* f = find_finding(d, code::ambiguous_map, "height");
    ASSERT_NE(f, nullptr);
    EXPECT_THAT(f->message, HasSubstr("higher bit depth (16 vs 0)"));
    // Before the tag the number names another material: no bit depth, one candidate each.
    const auto g = group_files({"Rock_16_Height.png", "Rock_Height.png"}, "x");
    ASSERT_EQ(g.size(), 2u);
    EXPECT_EQ(g[0].name, "Rock");
    EXPECT_EQ(g[1].name, "Rock_16");
}

TEST(NamingGaps, CamelCaseWordsAreNeverFormatTags) {
    EXPECT_EQ(material_stem("TgaRle_Color.png"), "TgaRle");
    EXPECT_EQ(material_stem("PngLogo_Albedo.png"), "PngLogo");
    EXPECT_EQ(material_stem("HdrPanel_2K_Albedo.jpg"), "HdrPanel");
    EXPECT_EQ(material_stem("Rle_Color.png"), "Rle");
    const auto g = group_files({"TgaRle_Color.png", "Rle_Color.png"}, "x");
    ASSERT_EQ(g.size(), 2u);
    EXPECT_EQ(g[0].name, "Rle");
    EXPECT_EQ(g[1].name, "TgaRle");
    // Separated, a format word is still a tag ("1K-PNG").
    EXPECT_EQ(material_stem("Tga_Color.png"), "");
    EXPECT_EQ(material_stem("Bricks059_1K-PNG_Color.png"), "Bricks059");
}

// ---------------------------------------------------------------------------------------------
// group_files reports names that reduced to one

TEST(GroupFilesMerge, ResolutionAndFormatVariantsAreReportedAsTags) {
    const auto g = group_files({"Bricks059_1K-JPG_Color.jpg", "Bricks059_1K-PNG_Color.png",
                                "Bricks059_2K-PNG_Color.png", "Bricks059_2K-PNG_NormalGL.png"},
                               "x");
    ASSERT_EQ(g.size(), 1u);
    ASSERT_TRUE(g[0].merge.has_value());
    const auto& m = *g[0].merge;
    EXPECT_THAT(m.spellings, ElementsAre("Bricks059_1K-JPG", "Bricks059_1K-PNG", "Bricks059_2K-PNG"));
    EXPECT_THAT(m.files,
                ElementsAre("Bricks059_1K-JPG_Color.jpg", "Bricks059_1K-PNG_Color.png", "Bricks059_2K-PNG_Color.png"));
    EXPECT_TRUE(m.tags_differ);
    EXPECT_FALSE(m.spelling_differs);
    EXPECT_THAT(m.message, HasSubstr("3 spellings of a material name were grouped as 'Bricks059'"));
    EXPECT_THAT(m.message, HasSubstr("Bricks059_2K-PNG (Bricks059_2K-PNG_Color.png)"));
    EXPECT_THAT(m.message, HasSubstr("resolution/format tags"));
}

TEST(GroupFilesMerge, CaseAndSeparatorDifferencesAreReported) {
    const auto g = group_files({"Wood_Color.png", "wood_Normal.png", "WOOD_Roughness.png", "Wood-Planks_Color.png",
                                "Wood_Planks_Roughness.png", "Stone_Color.png", "Stone_Normal.png"},
                               "x");
    ASSERT_EQ(g.size(), 3u);
    EXPECT_FALSE(g[0].merge.has_value());  // Stone: one spelling
    ASSERT_TRUE(g[1].merge.has_value());
    EXPECT_THAT(g[1].merge->spellings, ElementsAre("WOOD", "Wood", "wood"));
    EXPECT_TRUE(g[1].merge->spelling_differs);
    EXPECT_FALSE(g[1].merge->tags_differ);
    EXPECT_THAT(g[1].merge->message, HasSubstr("letter case or separators"));
    ASSERT_TRUE(g[2].merge.has_value());
    EXPECT_THAT(g[2].merge->spellings, ElementsAre("Wood-Planks", "Wood_Planks"));
    EXPECT_TRUE(g[2].merge->spelling_differs);
    // Both at once.
    const auto both = group_files({"Rock_1K_Color.png", "rock_2K_Normal.png"}, "x");
    ASSERT_EQ(both.size(), 1u);
    ASSERT_TRUE(both[0].merge.has_value());
    EXPECT_TRUE(both[0].merge->tags_differ);
    EXPECT_TRUE(both[0].merge->spelling_differs);
    EXPECT_THAT(both[0].merge->message, HasSubstr("resolution/format tags and letter case or separators"));
}

// ---------------------------------------------------------------------------------------------
// JPEG originals beside smaller WebP re-encodes (real sizes of two Poly Haven downloads)

TEST(NamingGaps, LargerJpegOriginalBeatsSmallerWebp) {
    struct Case {
        std::string set;
        int webp_size;
    };
    for (const auto& c : {Case{"broken_wall", 800}, Case{"brown_planks_09", 512}}) {
        SCOPED_TRACE(c.set);
        std::vector<std::string> files;
        HeaderMap h;
        for (const std::string tag : {"arm", "diff", "nor_gl"}) {
            const auto base = c.set + "_" + tag + "_1k";
            files.push_back(base + ".jpg");
            files.push_back(base + ".webp");
            h[base + ".jpg"] = square(1024);
            h[base + ".webp"] = square(c.webp_size);
        }
        for (const int limit : {0, 2048}) {
            const auto d = discover_set(files, headers(h), ChoicePolicy{NC::gl, limit});
            EXPECT_THAT(roles_of(d), ElementsAre("albedo", "normal", "orm"));
            for (const auto& [role, tag] :
                 {std::pair{Role::albedo, "diff"}, std::pair{Role::normal, "nor_gl"}, std::pair{Role::orm, "arm"}}) {
                EXPECT_EQ(chosen_file(d, role), c.set + "_" + tag + "_1k.jpg");
                const auto* f = find_finding(d, code::ambiguous_map, role_name(role));
                ASSERT_NE(f, nullptr);
                EXPECT_THAT(f->message,
                            HasSubstr("it is the largest (1024 px vs " + std::to_string(c.webp_size) + " px)"));
            }
        }
        // Without headers the names are equal: the vendor's JPEG ranks above its WebP twin.
        const auto blind = discover_set(files, nullptr, ChoicePolicy{});
        EXPECT_EQ(chosen_file(blind, Role::albedo), c.set + "_diff_1k.jpg");
        const auto* f = find_finding(blind, code::ambiguous_map, role_name(Role::albedo));
        ASSERT_NE(f, nullptr);
        EXPECT_THAT(f->message, HasSubstr("its format (jpg) ranks above webp (the vendor's own"));
    }
}

}  // namespace
}  // namespace mf

namespace mf {
namespace {

using namespace discovery_test;

// ---------------------------------------------------------------------------------------------
// Engine exports (issue 44): Unity's packed maps, names stating their channel order, a normal
// map's space, Unreal-style letters decided by the pixels.

TEST(EngineNames, UnityAndStatedOrderPackings) {
    check({
        {"Crate_MetallicSmoothness.png", Role::metallic_smoothness, "unity:_MetallicSmoothness"},
        {"Crate_MetallicGlossMap.png", Role::metallic_smoothness, "unity:_MetallicGlossMap"},
        {"Crate_SpecularSmoothness.png", Role::specular_smoothness, "unity:_SpecularSmoothness"},
        {"Crate_MaskMap.tga", Role::mask_map, "unity:_MaskMap"},
        {"Crate_AlbedoTransparency.png", Role::albedo, "unity:_AlbedoTransparency", NormalConvention::unknown, true},
        {"Rock_MRA.png", Role::mra, "generic:_MRA"},
        {"rock-mrao.png", Role::mra, "generic:_MRAO"},
        {"Rock_RMA_2K.png", Role::rma, "generic:_RMA"},
        {"Rock_Metallic_Roughness_AO.png", Role::mra, ""},
        {"Rock_RoughnessMetallic.png", Role::rm, ""},
        {"Rock_OcclusionRoughnessMetallic.png", Role::orm, ""},
        {"Rock_metallicRoughness.png", Role::metallic_roughness, ""},  // glTF's: G roughness, B metal
        {"T_Rock_O.png", Role::opacity, "megascans:_O"},
        {"T_Rock_T.png", Role::translucency, "megascans:_T"},
    });
    // Every channel of a packing, smoothness inverted; the detail mask and the specular colour unread.
    EXPECT_EQ(packing_channels(Role::mask_map), (std::vector<std::pair<std::string, std::string>>{
                                                    {"R", "metalness"}, {"G", "occlusion"}, {"A", "smoothness"}}));
    EXPECT_EQ(packing_channels(Role::specular_smoothness),
              (std::vector<std::pair<std::string, std::string>>{{"A", "smoothness"}}));
    EXPECT_TRUE(packed_layout(Role::metallic_smoothness)[3]->invert);
    EXPECT_FALSE(packed_layout(Role::rma)[0]->invert);
    // Words that merely contain the letters stay words.
    EXPECT_FALSE(classify_name("Rma_Stone_Color.png")->role == Role::rma);
}

TEST(EngineNames, SmoothnessRoutesInvertedAndADedicatedMapWins) {
    auto channels = [](std::map<Role, int> have) {
        return [have](Role r) {
            const auto it = have.find(r);
            return it == have.end() ? 0 : it->second;
        };
    };
    Routes r = route_roles(channels({{Role::metallic_smoothness, 4}}));
    ASSERT_TRUE(r.count(Role::roughness));
    EXPECT_EQ(r.at(Role::roughness).from, Role::metallic_smoothness);
    EXPECT_EQ(r.at(Role::roughness).channel, 3);
    EXPECT_TRUE(r.at(Role::roughness).invert);
    EXPECT_EQ(r.at(Role::metalness).channel, 0);
    // Saved without alpha: no smoothness to read, the metal still is.
    r = route_roles(channels({{Role::metallic_smoothness, 3}}));
    EXPECT_FALSE(r.count(Role::roughness));
    EXPECT_EQ(r.at(Role::metalness).from, Role::metallic_smoothness);
    // A roughness map beats the packed smoothness, which beats a gloss map.
    r = route_roles(channels({{Role::mask_map, 4}, {Role::roughness, 1}, {Role::gloss, 1}}));
    EXPECT_EQ(r.at(Role::roughness).from, Role::roughness);
    r = route_roles(channels({{Role::mask_map, 4}, {Role::gloss, 1}}));
    EXPECT_EQ(r.at(Role::roughness).from, Role::mask_map);
    EXPECT_EQ(r.at(Role::occlusion).channel, 1);
}

TEST(EngineNames, ObjectSpaceNormalsNeverTakeTheNormalSlot) {
    const auto d = discover_set({"rock_diffuse.png", "rock_nm.tga", "rock_nm_tangent.tga"}, nullptr, ChoicePolicy{});
    EXPECT_EQ(chosen_file(d, Role::normal), "rock_nm_tangent.tga");
    EXPECT_THAT(unrecognized_reason(d, "rock_nm.tga"), ::testing::HasSubstr("object-space"));
    const auto os = discover_set({"rock_diffuse.png", "rock_normal_os.png"}, nullptr, ChoicePolicy{});
    EXPECT_EQ(discovery_test::find_choice(os, Role::normal), nullptr);
    EXPECT_THAT(unrecognized_reason(os, "rock_normal_os.png"), ::testing::HasSubstr("object-space"));
}

TEST(EngineNames, UnrealLettersByThePixels) {
    const std::vector<std::string> files{"T_Rock_A.jpg", "T_Rock_D.png", "T_Rock_N.jpg", "T_Rock_R.jpg"};
    // Megascans: a colour _A, a grey _D.
    auto mega = discover_set(files, nullptr, ChoicePolicy{}, {},
                             [](const std::string& f) -> std::optional<bool> { return f == "T_Rock_A.jpg"; });
    EXPECT_EQ(chosen_file(mega, Role::albedo), "T_Rock_A.jpg");
    EXPECT_EQ(chosen_file(mega, Role::height), "T_Rock_D.png");
    EXPECT_EQ(discovery_test::find_choice(mega, Role::opacity), nullptr);
    // Epic's style: a colour _D, a grey _A mask.
    auto epic = discover_set(files, nullptr, ChoicePolicy{}, {},
                             [](const std::string& f) -> std::optional<bool> { return f == "T_Rock_D.png"; });
    EXPECT_EQ(chosen_file(epic, Role::albedo), "T_Rock_D.png");
    EXPECT_EQ(chosen_file(epic, Role::opacity), "T_Rock_A.jpg");
    // Pixels unknown: the names as Epic's style guide has them.
    auto plain = discover_set(files, nullptr, ChoicePolicy{});
    EXPECT_EQ(chosen_file(plain, Role::opacity), "T_Rock_A.jpg");
}

TEST(EngineNames, BillboardFoldersAndLoneMaps) {
    EXPECT_TRUE(billboards_only({"Fern_Billboard_2K_Albedo.jpg", "Fern_Billboard_2K_Normal.jpg", "notes.txt"}));
    EXPECT_FALSE(billboards_only({"Fern_2K_Albedo.jpg", "Fern_Billboard_2K_Albedo.jpg"}));
    const auto d = discover_set({"Fern_Billboard_2K_Albedo.jpg", "Fern_Billboard_2K_Normal.jpg"}, nullptr,
                                ChoicePolicy{});
    EXPECT_EQ(chosen_file(d, Role::albedo), "Fern_Billboard_2K_Albedo.jpg");
    EXPECT_EQ(group_files({"Fern_Billboard_2K_Albedo.jpg", "Fern_Billboard_2K_Normal.jpg"}, "x").size(), 1u);
}

}  // namespace
}  // namespace mf
