// A set's provenance (material/provenance.hpp): licences named in text, the vendors recognised by
// their names and sidecars, licence files and sidecar members before the vendor, LICENCE_UNKNOWN's
// reasons; the manifest's provenance read back as written, and ATTRIBUTION.md's text.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>

#include <nlohmann/json.hpp>

#include "findings/catalog.hpp"
#include "manifest/attribution.hpp"
#include "manifest/manifest.hpp"
#include "material/discovery.hpp"
#include "material/provenance.hpp"
#include "test_dirs.hpp"

namespace mf::provenance_test {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

// The licences a text names, as SPDX ids ("" for one without).
std::vector<std::string> named(std::string_view text) {
    std::vector<std::string> out;
    for (const auto& m : licences_named(text))
        out.emplace_back(m.licence->spdx.empty() ? m.licence->name : m.licence->spdx);
    return out;
}

// The provenance of a set of `files` (discovered as plan does), with its licence files and sidecars.
ProvenanceResult provenance_of(const std::vector<std::string>& files, const std::vector<SetText>& texts = {},
                               const std::vector<SidecarRoles>& sidecars = {}, bool shared = false) {
    ChoicePolicy policy;
    policy.shared_folder = shared;
    const SetDiscovery d = discover_set(files, nullptr, policy, sidecars);
    return find_provenance({files, d, sidecars, texts, shared});
}

// The Godot third-person demo's LICENSE.md (godotengine/tps-demo @ 117eca00206e), whose textures
// are the corpus's godot_tps-demo_* sets: CC-BY 3.0 for the assets, the MIT permission text (not
// named) for the code.
const std::string kTpsDemoLicence =
    "All assets Copyright (c) 2018 Juan Linietsky, Fernando Miguel Calabr\xC3\xB3 \\\n"
    "Distributed under the terms of the Creative Commons Attribution License\n"
    "version 3.0 (CC-BY 3.0) <https://creativecommons.org/licenses/by/3.0/legalcode>.\n\n"
    "************************************************************************\n\n"
    "Music Copyright (c) 2018 Christian Fernando Perucchi \\\n"
    "Distributed under the terms of the Creative Commons Attribution License\n"
    "version 3.0 (CC-BY 3.0) <https://creativecommons.org/licenses/by/3.0/legalcode>.\n\n"
    "************************************************************************\n\n"
    "Existing as derivatived work, many original Substance Painter materials\n"
    "used to create this scene were kindly provided by GameTextures.com\n\n"
    "************************************************************************\n\n"
    "All code Copyright (c) 2018-2020 Juan Linietsky, Godot Engine contributors.\n\n"
    "Permission is hereby granted, free of charge, to any person obtaining\n"
    "a copy of this software and associated documentation files (the\n"
    "\"Software\"), to deal in the Software without restriction, including\n";

const std::vector<std::string> kAmbientCg{"Bricks059.png", "Bricks059_1K-PNG_Color.png",
                                          "Bricks059_1K-PNG_NormalGL.png", "Bricks059_1K-PNG_Roughness.png",
                                          "Bricks059_1K-PNG.usdc"};

}  // namespace mf::provenance_test

namespace mf {
using namespace provenance_test;

TEST(LicencesNamed, ByNameUrlOrSpdxId) {
    // ambientCG's own USD files state their licence so (customLayerData "copyright").
    EXPECT_THAT(named("CC0 1.0 Public Domain Dedication (https://creativecommons.org/publicdomain/zero/1.0/)"),
                ElementsAre("CC0-1.0"));
    EXPECT_THAT(named("Released as cc-0, no rights reserved"), ElementsAre("CC0-1.0"));
    EXPECT_THAT(named("Creative Commons Zero v1.0 Universal"), ElementsAre("CC0-1.0"));
    // Sketchfab's glTF asset.extras.license.
    EXPECT_THAT(named("CC-BY-4.0 (http://creativecommons.org/licenses/by/4.0/)"), ElementsAre("CC-BY-4.0"));
    EXPECT_THAT(named("Attribution-NonCommercial-ShareAlike: Creative Commons Attribution-NonCommercial-ShareAlike "
                      "4.0 International"),
                ElementsAre("CC-BY-NC-SA-4.0"));
    EXPECT_THAT(named("licensed CC BY-NC-ND 3.0"), ElementsAre("CC-BY-NC-ND-3.0"));
    EXPECT_THAT(named("see creativecommons.org/licenses/by-sa/2.0/"), ElementsAre("CC-BY-SA-2.0"));
    EXPECT_THAT(named("// SPDX-License-Identifier: MIT\n"), ElementsAre("MIT"));
    EXPECT_THAT(named("The MIT License (MIT)"), ElementsAre("MIT"));
    // No version: CC BY still (credit asked), without an SPDX id; a versioned mention wins.
    EXPECT_THAT(named("Licensed under CC-BY."), ElementsAre("Creative Commons Attribution (version not stated)"));
    EXPECT_THAT(named("CC-BY, that is CC BY 4.0"), ElementsAre("CC-BY-4.0"));
    // Two licences, in order of first mention.
    EXPECT_THAT(named("textures CC0; the model CC BY 4.0"), ElementsAre("CC0-1.0", "CC-BY-4.0"));
    // Not licences: "public domain" alone, a licence's text without its name, words that look alike.
    EXPECT_TRUE(named("public domain").empty());
    EXPECT_TRUE(named("Permission is hereby granted, free of charge, to any person obtaining a copy").empty());
    EXPECT_TRUE(named("licenses by region; cc by-sa-nd 4.0").empty());
    // The Godot demo's notice: CC-BY 3.0 twice (assets, music), the MIT text unnamed.
    const auto godot = licences_named(kTpsDemoLicence);
    ASSERT_EQ(godot.size(), 1u);
    EXPECT_EQ(godot[0].licence->spdx, "CC-BY-3.0");
    EXPECT_EQ(godot[0].licence->url, "https://creativecommons.org/licenses/by/3.0/");
    EXPECT_TRUE(godot[0].licence->attribution);
    EXPECT_EQ(kTpsDemoLicence.compare(godot[0].at, 8, "Creative"), 0);
}

TEST(LicencesNamed, TheTableHasOneEntryPerIdAndEveryUrlIsHttps) {
    std::set<std::string> ids;
    for (const auto& l : licence_table()) {
        EXPECT_TRUE(l.url.starts_with("https://")) << l.name;
        if (!l.spdx.empty()) {
            EXPECT_TRUE(ids.insert(std::string(l.spdx)).second) << l.spdx;
        }
        EXPECT_EQ(licence_by_spdx(l.spdx), l.spdx.empty() ? nullptr : &l);
    }
    EXPECT_EQ(ids.size(), 1u + 4 * 6 + 1);  // CC0, the CC BY family in 2.0/2.5/3.0/4.0, MIT
    EXPECT_EQ(licence_by_spdx("cc-by-4.0")->name, "Creative Commons Attribution 4.0 International");
    EXPECT_EQ(licence_by_spdx("CC-BY-NC-ND-3.0")->name,
              "Creative Commons Attribution-NonCommercial-NoDerivatives 3.0 Unported");
    for (const auto& v : vendor_table()) {  // every vendor's licence is in the table
        const bool found = licence_by_spdx(v.licence) != nullptr ||
                           std::any_of(licence_table().begin(), licence_table().end(),
                                       [&](const LicenceInfo& l) { return l.name == v.licence; });
        EXPECT_TRUE(found) << v.id;
    }
}

TEST(LicenceFiles, ByName) {
    for (const char* f : {"LICENSE", "License.txt", "LICENCE.md", "readme.txt", "README", "COPYING", "Credits.md",
                          "docs/ATTRIBUTION.txt", "license_cc0.txt"})
        EXPECT_TRUE(is_licence_file_name(f)) << f;
    for (const char* f : {"license.png", "readme.pdf", "Bricks059_License_Color.jpg", "my_license.txt", "LICENSE.json"})
        EXPECT_FALSE(is_licence_file_name(f)) << f;
}

TEST(Provenance, AmbientCgByItsNamesWithItsPage) {
    const auto r = provenance_of(kAmbientCg);
    const Provenance& p = r.provenance;
    EXPECT_EQ(p.vendor, "ambientcg");
    EXPECT_EQ(p.vendor_name, "ambientCG");
    EXPECT_EQ(p.asset_id, "Bricks059");
    EXPECT_EQ(p.asset_id_from, "name");
    EXPECT_EQ(p.url, "https://ambientcg.com/view?id=Bricks059");
    ASSERT_TRUE(p.licence);
    EXPECT_EQ(p.licence->spdx, "CC0-1.0");
    EXPECT_FALSE(p.licence->attribution_required);
    EXPECT_EQ(p.licence->evidence.how, "vendor");
    EXPECT_EQ(p.licence->evidence.file, "Bricks059_1K-PNG_Color.png");
    EXPECT_THAT(p.licence->evidence.detail, HasSubstr("ambientCG publishes every asset under CC0-1.0"));
    EXPECT_TRUE(p.attribution.empty());
    EXPECT_TRUE(r.unknown.empty());
    // ambientCG's tags without its "<res>-<FORMAT>" pair, or an id of another shape: no vendor.
    EXPECT_FALSE(provenance_of({"Bricks_Color.png", "Bricks_NormalGL.png", "Bricks_Roughness.png"}).provenance.licence);
    EXPECT_EQ(provenance_of({"MyBricks_1K-PNG_Color.png", "MyBricks_1K-PNG_Roughness.png"}).provenance.vendor, "");
}

TEST(Provenance, PolyHavenSlugAndPage) {
    const auto r = provenance_of({"brown_planks_09_diff_1k.jpg", "brown_planks_09_nor_gl_1k.jpg",
                                  "brown_planks_09_arm_1k.jpg", "brown_planks_09_diff_1k.webp"});
    EXPECT_EQ(r.provenance.vendor, "polyhaven");
    EXPECT_EQ(r.provenance.asset_id, "brown_planks_09");
    EXPECT_EQ(r.provenance.url, "https://polyhaven.com/a/brown_planks_09");
    ASSERT_TRUE(r.provenance.licence);
    EXPECT_EQ(r.provenance.licence->spdx, "CC0-1.0");
    EXPECT_EQ(r.provenance.licence->evidence.file, "brown_planks_09_arm_1k.jpg");
}

TEST(Provenance, ThreeDTexturesNeedsItsRenderInAFolderOfItsOwn) {
    const std::vector<std::string> files{"Metal_Damaged_001_basecolor.jpg", "Metal_Damaged_001_normal.jpg",
                                         "Metal_Damaged_001_roughness.jpg", "Metal_Damaged_001_height.png",
                                         "Material_1957.jpg"};
    const auto r = provenance_of(files);
    EXPECT_EQ(r.provenance.vendor, "3dtextures");
    EXPECT_EQ(r.provenance.asset_id, "Metal_Damaged_001");
    EXPECT_EQ(r.provenance.url, "");  // the site's pages are dated posts: no certain scheme
    ASSERT_TRUE(r.provenance.licence);
    EXPECT_EQ(r.provenance.licence->spdx, "CC0-1.0");
    // Substance Designer's names alone are anyone's export; in a shared folder the render is no one's.
    const std::vector<std::string> names_only(files.begin(), files.end() - 1);
    const auto bare = provenance_of(names_only);
    EXPECT_FALSE(bare.provenance.licence);
    EXPECT_THAT(bare.unknown, HasSubstr("naming: generic"));
    EXPECT_FALSE(provenance_of(files, {}, {}, true).provenance.licence);
}

// Poly Haven's tags without its scheme (Godot's demo textures: "rock_metal.jpg", no resolution)
// prove no vendor, and the reason says so rather than "follow no vendor's scheme".
TEST(Provenance, AVendorsTagsWithoutItsSchemeAreSaidSo) {
    const auto r = provenance_of({"rock_col.jpg", "rock_metal.jpg", "rock_rough.jpg"});
    EXPECT_FALSE(r.provenance.licence);
    EXPECT_EQ(r.provenance.vendor, "");
    EXPECT_THAT(r.unknown, HasSubstr("its names use Poly Haven's map tags (naming: polyhaven) but are not named the "
                                     "Poly Haven way (<slug>_<map>_<res>, in lower case), so no vendor is proven"));
}

TEST(Provenance, PoliigonIsTheVendorsOwnLicence) {
    const auto r = provenance_of({"Poliigon_GrassPatchyGround_4585_BaseColor.jpg",
                                  "Poliigon_GrassPatchyGround_4585_Normal.jpg",
                                  "Poliigon_GrassPatchyGround_4585_Roughness.jpg"});
    EXPECT_EQ(r.provenance.vendor, "poliigon");
    EXPECT_EQ(r.provenance.asset_id, "4585");
    ASSERT_TRUE(r.provenance.licence);
    EXPECT_EQ(r.provenance.licence->spdx, "");
    EXPECT_EQ(r.provenance.licence->name, "Poliigon EULA");
    EXPECT_TRUE(r.provenance.licence->vendor_licence);
    EXPECT_THAT(r.provenance.licence->evidence.detail, HasSubstr("no redistribution of the files"));
    // The older names Textures.com used too: no vendor, and the reason says so.
    const auto legacy = provenance_of({"WoodFine0012_COL_VAR1_3K.jpg", "WoodFine0012_NRM_3K.jpg",
                                       "WoodFine0012_GLOSS_3K.jpg"});
    EXPECT_FALSE(legacy.provenance.licence);
    EXPECT_THAT(legacy.unknown, HasSubstr("Textures.com / Poliigon legacy scheme"));
}

TEST(Provenance, MegascansFromItsAssetFile) {
    const std::string json = R"({"id": "sfjmafua", "name": "Mossy Rock",
      "maps": [{"type": "albedo", "uri": "rock_sfjmafua_2K_Albedo.jpg"}, {"type": "normal", "uri": "rock_sfjmafua_2K_Normal.jpg"}],
      "previews": {"images": [{"uri": "rock_sfjmafua_Preview.png"}]}})";
    const std::vector<SidecarRoles> sidecars{sidecar_roles("rock_sfjmafua.json", json)};
    const std::vector<std::string> files{"rock_sfjmafua.json", "rock_sfjmafua_2K_Albedo.jpg",
                                         "rock_sfjmafua_2K_Normal.jpg", "rock_sfjmafua_Preview.png"};
    const auto r = provenance_of(files, {}, sidecars);
    EXPECT_EQ(r.provenance.vendor, "megascans");
    EXPECT_EQ(r.provenance.asset_id, "sfjmafua");
    EXPECT_EQ(r.provenance.asset_id_from, "sidecar");
    ASSERT_TRUE(r.provenance.licence);
    EXPECT_EQ(r.provenance.licence->name, "Fab Standard License");
    EXPECT_TRUE(r.provenance.licence->vendor_licence);
    EXPECT_EQ(r.provenance.licence->evidence.file, "rock_sfjmafua.json");
    // Without its JSON the names are Megascans' layout, which others use: unknown, and said why.
    const auto bare = provenance_of({"rock_sfjmafua_2K_Albedo.jpg", "rock_sfjmafua_2K_Normal.jpg"});
    EXPECT_FALSE(bare.provenance.licence);
    EXPECT_THAT(bare.unknown, HasSubstr("no Megascans asset file"));
}

TEST(Provenance, ALicenceFileBeatsTheVendorAndGivesTheCredit) {
    const std::vector<std::string> godot{"LICENSE.md", "container1_albedo.png", "container1_normal.png",
                                         "container1_orm.png"};
    const auto r = provenance_of(godot, {{"LICENSE.md", kTpsDemoLicence, ""}});
    const Provenance& p = r.provenance;
    EXPECT_EQ(p.vendor, "");
    ASSERT_TRUE(p.licence);
    EXPECT_EQ(p.licence->spdx, "CC-BY-3.0");
    EXPECT_TRUE(p.licence->attribution_required);
    EXPECT_EQ(p.licence->evidence.how, "file");
    EXPECT_EQ(p.licence->evidence.file, "LICENSE.md");
    // The holder named before the licence's first mention (the assets', not the music's or code's).
    EXPECT_EQ(p.attribution,
              "All assets Copyright (c) 2018 Juan Linietsky, Fernando Miguel Calabr\xC3\xB3; licensed under CC-BY-3.0 "
              "(https://creativecommons.org/licenses/by/3.0/)");
    // In an ambientCG download a readme's licence is the evidence, the vendor's page kept.
    std::vector<std::string> with_readme = kAmbientCg;
    with_readme.emplace_back("README.txt");
    const auto a = provenance_of(with_readme, {{"README.txt", "Textures: CC0 1.0 Universal", ""}});
    EXPECT_EQ(a.provenance.vendor, "ambientcg");
    EXPECT_EQ(a.provenance.url, "https://ambientcg.com/view?id=Bricks059");
    ASSERT_TRUE(a.provenance.licence);
    EXPECT_EQ(a.provenance.licence->evidence.how, "file");
    EXPECT_EQ(a.provenance.licence->evidence.file, "README.txt");
    // CC BY with nobody named: the credit line says so.
    const auto anon = provenance_of(godot, {{"LICENSE.md", "Licensed under CC BY 4.0.", ""}});
    EXPECT_EQ(anon.provenance.attribution,
              "the download names no author (LICENSE.md): find who to credit; licensed under CC-BY-4.0 "
              "(https://creativecommons.org/licenses/by/4.0/)");
}

TEST(Provenance, WhatLeavesItUnknownIsSaid) {
    const std::vector<std::string> godot{"LICENSE.md", "README.md", "container1_albedo.png", "container1_normal.png"};
    // Two files, two licences: which covers the maps is not said.
    const auto two = provenance_of(godot, {{"LICENSE.md", "CC BY 4.0", ""}, {"README.md", "MIT License", ""}});
    EXPECT_FALSE(two.provenance.licence);
    EXPECT_EQ(two.unknown, "the set's licence files name several licences (CC-BY-4.0, MIT): which one covers these "
                           "maps is not said");
    EXPECT_EQ(two.unknown_file, "LICENSE.md");
    EXPECT_EQ(figure_text(two.figures.at("licences")), R"(["CC-BY-4.0","MIT"])");
    // A readme naming no licence, one that could not be read.
    const auto silent = provenance_of(godot, {{"LICENSE.md", "", "permission denied"}, {"README.md", "Have fun!", ""}});
    EXPECT_EQ(silent.unknown, "no licence found: README.md names no licence matforge recognises, could not read "
                              "LICENSE.md (permission denied), no sidecar states one, and its names (naming: generic) "
                              "follow no vendor's scheme with a known licence");
    EXPECT_EQ(silent.unknown_file, "README.md");
    // Nothing at all.
    const auto none = provenance_of({"crystal.jpg", "crystal_NM.jpg", "crystal_RO.jpg"});
    EXPECT_EQ(none.unknown, "no licence found: no licence or readme file in the set, no sidecar states one, and its "
                            "names (naming: generic) follow no vendor's scheme with a known licence");
    EXPECT_EQ(figure_string(none.figures, "naming"), "generic");
}

TEST(Provenance, AGltfStoreListingStatesLicenceAndCredit) {
    const std::string gltf = R"json({"asset": {"version": "2.0", "extras": {
        "author": "Jane (https://sketchfab.com/jane)", "license": "CC-BY-4.0 (http://creativecommons.org/licenses/by/4.0/)",
        "source": "https://sketchfab.com/3d-models/old-crate-123", "title": "Old Crate"}},
      "images": [{"uri": "crate_albedo.png"}], "textures": [{"source": 0}],
      "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]})json";
    const std::vector<SidecarRoles> sidecars{sidecar_roles("scene.gltf", gltf)};
    const auto r = provenance_of({"scene.gltf", "crate_albedo.png", "crate_normal.png"}, {}, sidecars);
    ASSERT_TRUE(r.provenance.licence);
    EXPECT_EQ(r.provenance.licence->spdx, "CC-BY-4.0");
    EXPECT_EQ(r.provenance.licence->evidence.how, "sidecar");
    EXPECT_EQ(r.provenance.licence->evidence.file, "scene.gltf");
    EXPECT_EQ(r.provenance.licence->evidence.field, "asset.extras.license");
    EXPECT_EQ(r.provenance.attribution,
              "\"Old Crate\" by Jane (https://sketchfab.com/jane) (https://sketchfab.com/3d-models/old-crate-123); "
              "licensed under CC-BY-4.0 (https://creativecommons.org/licenses/by/4.0/)");
    // glTF 2.0's asset.copyright alone: the licence it names, the message as the credit.
    const auto c = sidecar_roles("m.gltf", R"({"asset": {"version": "2.0", "copyright": "2019 Ann Lee, CC BY 4.0"}})");
    const auto rc = provenance_of({"m.gltf", "m_basecolor.png"}, {}, {c});
    ASSERT_TRUE(rc.provenance.licence);
    EXPECT_EQ(rc.provenance.licence->evidence.field, "asset.copyright");
    EXPECT_EQ(rc.provenance.attribution,
              "2019 Ann Lee, CC BY 4.0; licensed under CC-BY-4.0 (https://creativecommons.org/licenses/by/4.0/)");
}

TEST(GroupFiles, ALicenceFileSpeaksForEverySetOfItsFolder) {
    const auto g = group_files({"LICENSE.txt", "Rocks004_1K-JPG_Color.jpg", "Rocks004_1K-JPG_Roughness.jpg",
                                "Surface_Imperfection_001_basecolor.jpg", "Surface_Imperfection_001_normal.jpg",
                                "Material_1586.jpg", "Rocks004_readme.txt"},
                               "flat");
    ASSERT_EQ(g.size(), 2u);
    EXPECT_TRUE(g[0].shared && g[1].shared);
    EXPECT_THAT(g[0].files, ElementsAre("LICENSE.txt", "Material_1586.jpg", "Rocks004_1K-JPG_Color.jpg",
                                        "Rocks004_1K-JPG_Roughness.jpg", "Rocks004_readme.txt"));
    EXPECT_THAT(g[1].files, ElementsAre("LICENSE.txt", "Surface_Imperfection_001_basecolor.jpg",
                                        "Surface_Imperfection_001_normal.jpg"));
    EXPECT_FALSE(group_files({"a_Color.png", "LICENSE"}, "x")[0].shared);
}

TEST(ManifestProvenance, ReadBackAsWritten) {
    manifest::Material m;
    m.name = "container1";
    m.source = "in/container1";
    Provenance p;
    p.licence = Provenance::Licence{"CC-BY-3.0",
                                    "Creative Commons Attribution 3.0 Unported",
                                    "https://creativecommons.org/licenses/by/3.0/",
                                    true,
                                    false,
                                    {"file", "LICENSE.md", "", "LICENSE.md names it"}};
    p.attribution = "All assets Copyright (c) 2018 A, B; licensed under CC-BY-3.0";
    m.provenance = p;
    manifest::Input preview;
    preview.role = Role::preview;
    preview.file = "Net004A.png";
    preview.color_space = "sRGB";
    m.inputs.push_back(preview);
    const nlohmann::json j = manifest::to_json(m);
    EXPECT_EQ(j.at("provenance").at("licence").at("spdx"), "CC-BY-3.0");
    EXPECT_FALSE(j.at("provenance").contains("vendor"));  // unknown fields are not written
    EXPECT_TRUE(j.at("inputs").contains("preview"));
    std::string error;
    const auto back = manifest::material_from_json(j, "materials[0]", error);
    ASSERT_TRUE(back) << error;
    ASSERT_TRUE(back->provenance);
    EXPECT_EQ(*back->provenance, p);
    EXPECT_EQ(back->inputs.at(0).role, Role::preview);
    EXPECT_EQ(manifest::to_json(*back), j);
    // A typo is an error naming the member, never a default.
    nlohmann::json bad = j;
    bad["provenance"]["licence"]["evidence"]["how"] = "guess";
    EXPECT_FALSE(manifest::material_from_json(bad, "materials[0]", error));
    EXPECT_THAT(error, HasSubstr("\"how\" must be"));
}

TEST(Attribution, EveryMaterialWithItsSourceAndLicence) {
    manifest::Material a, b, c;
    a.name = "Net004A";
    Provenance pa;
    pa.vendor = "ambientcg";
    pa.vendor_name = "ambientCG";
    pa.asset_id = "Net004A";
    pa.url = "https://ambientcg.com/view?id=Net004A";
    pa.licence = Provenance::Licence{"CC0-1.0", "Creative Commons Zero v1.0 Universal",
                                     "",        false,
                                     false,     {"vendor", "Net004A_1K-JPG_Color.jpg", "", "named the ambientCG way"}};
    a.provenance = pa;
    b.name = "container1";
    Provenance pb;
    pb.licence = Provenance::Licence{"CC-BY-3.0", "Creative Commons Attribution 3.0 Unported",      "", true,
                                     false,       {"file", "LICENSE.md", "", "LICENSE.md names it"}};
    pb.attribution = "A | B; licensed under CC-BY-3.0";
    b.provenance = pb;
    c.name = "crystal";
    c.findings.push_back(finding(code::licence_unknown, "", "", "no licence found: nothing"));
    const std::string text = manifest::attribution_text({a, b, c});
    EXPECT_TRUE(text.starts_with("# Attribution\n")) << text;
    EXPECT_THAT(text, HasSubstr("| Net004A | ambientCG | Net004A | CC0-1.0 | vendor (Net004A_1K-JPG_Color.jpg): named "
                                "the ambientCG way | not required | https://ambientcg.com/view?id=Net004A |\n"));
    EXPECT_THAT(text, HasSubstr("| container1 | — | — | CC-BY-3.0 | file (LICENSE.md): LICENSE.md names it | A \\| B; "
                                "licensed under CC-BY-3.0 | — |\n"));
    EXPECT_THAT(text, HasSubstr("| crystal | — | — | unknown | no licence found: nothing | — | — |\n"));
    EXPECT_TRUE(text.ends_with("\n3 materials: CC-BY-3.0 1, CC0-1.0 1, unknown 1.\n")) << text;

    // From a run's spool, read back one material at a time: the same bytes.
    const auto dir = testdirs::fresh("matforge-attribution-", "spool");
    std::string error;
    auto spool = manifest::MaterialSpool::open(dir, error);
    ASSERT_TRUE(spool) << error;
    for (const auto* m : {&c, &a, &b}) ASSERT_TRUE(spool->add(*m, error)) << error;
    ASSERT_FALSE(spool->sort());
    std::string spooled;
    ASSERT_TRUE(manifest::attribution_text(
        *spool,
        [&](std::string_view piece) {
            spooled += piece;
            return true;
        },
        error))
        << error;
    EXPECT_EQ(spooled, text);
}

}  // namespace mf
