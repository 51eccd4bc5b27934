// A material's credit (manifest/attribution.hpp material_credit): the line the material files
// carry (glTF asset.copyright, the USD layer's customLayerData, the MaterialX material's doc),
// from provenances found as ingest finds them: ambientCG's CC0, a CC BY licence file's
// attribution, Poliigon's own licence, and none where the licence is unknown.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "manifest/attribution.hpp"
#include "material/discovery.hpp"
#include "material/provenance.hpp"

namespace mf::credit_test {

// The provenance of a set of `files` (discovered as plan does) with its licence files.
Provenance found(const std::vector<std::string>& files, const std::vector<SetText>& texts = {}) {
    const SetDiscovery d = discover_set(files, nullptr, ChoicePolicy{}, {});
    return find_provenance({files, d, {}, texts, false}).provenance;
}

// The licences `text` names, as matforge reads a sidecar's asset.copyright: a material file
// matforge wrote, ingested again, states the same licence.
std::vector<std::string> licences_of(const std::string& text) {
    std::vector<std::string> out;
    for (const auto& m : licences_named(text))
        out.emplace_back(m.licence->spdx.empty() ? m.licence->name : m.licence->spdx);
    return out;
}

}  // namespace mf::credit_test

namespace mf {

TEST(Credit, AmbientCgCc0NamesTheAssetItsPageAndTheLicence) {
    const Provenance p = credit_test::found({"Net004A.png", "Net004A_1K-JPG_Color.jpg", "Net004A_1K-JPG_NormalGL.jpg",
                                             "Net004A_1K-JPG_Roughness.jpg", "Net004A_1K-JPG_Opacity.jpg"});
    const auto c = manifest::material_credit(p);
    ASSERT_TRUE(c);
    EXPECT_EQ(c->author, "ambientCG");
    EXPECT_EQ(c->licence,
              "Creative Commons Zero v1.0 Universal (CC0-1.0, https://creativecommons.org/publicdomain/zero/1.0/)");
    EXPECT_EQ(c->url, "https://ambientcg.com/view?id=Net004A");
    EXPECT_EQ(c->source, "ambientCG asset Net004A (https://ambientcg.com/view?id=Net004A)");
    EXPECT_EQ(c->line,
              "ambientCG asset Net004A (https://ambientcg.com/view?id=Net004A); licensed under Creative Commons Zero "
              "v1.0 Universal (CC0-1.0, https://creativecommons.org/publicdomain/zero/1.0/)");
    EXPECT_EQ(credit_test::licences_of(c->line), std::vector<std::string>{"CC0-1.0"});
    EXPECT_EQ(credit_test::licences_of(c->licence), std::vector<std::string>{"CC0-1.0"});
}

TEST(Credit, CcByGivesTheAttributionTheLicenceAsksFor) {
    // The Godot demo's notice, its assets' part: the holder before the licence.
    const std::string licence = "All assets Copyright (c) 2018 Juan Linietsky, Fernando Miguel Calabr\xC3\xB3\n"
                                "Distributed under the terms of the Creative Commons Attribution License\n"
                                "version 3.0 (CC-BY 3.0) <https://creativecommons.org/licenses/by/3.0/legalcode>.\n";
    const Provenance p = credit_test::found({"LICENSE.md", "container1_albedo.png", "container1_normal.png",
                                             "container1_orm.png"},
                                            {{"LICENSE.md", licence, ""}});
    const auto c = manifest::material_credit(p);
    ASSERT_TRUE(c);
    const std::string attribution = "All assets Copyright (c) 2018 Juan Linietsky, Fernando Miguel Calabr\xC3\xB3; "
                                    "licensed under CC-BY-3.0 (https://creativecommons.org/licenses/by/3.0/)";
    EXPECT_EQ(p.attribution, attribution);
    EXPECT_EQ(c->author, attribution);
    EXPECT_EQ(c->licence,
              "Creative Commons Attribution 3.0 Unported (CC-BY-3.0, https://creativecommons.org/licenses/by/3.0/)");
    EXPECT_EQ(c->source, "");  // no vendor, no asset id, no page
    EXPECT_EQ(c->url, "");
    EXPECT_EQ(c->line, attribution);
    EXPECT_EQ(credit_test::licences_of(c->line), std::vector<std::string>{"CC-BY-3.0"});

    // A credit is one line of valid UTF-8, whatever the licence file held (a line break, a
    // Latin-1 byte): a viewer shows one line, a USD string cannot hold a break.
    Provenance odd = p;
    odd.attribution = "\xA9 2018 A\nB\tC; licensed under CC-BY-3.0";
    const auto o = manifest::material_credit(odd);
    ASSERT_TRUE(o);
    EXPECT_EQ(o->line, "\xEF\xBF\xBD 2018 A B C; licensed under CC-BY-3.0");
    EXPECT_EQ(o->author, o->line);
}

TEST(Credit, AVendorsOwnLicenceSaysItsTerms) {
    const Provenance p = credit_test::found({"Poliigon_GrassPatchyGround_4585_BaseColor.jpg",
                                             "Poliigon_GrassPatchyGround_4585_Normal.jpg",
                                             "Poliigon_GrassPatchyGround_4585_Roughness.jpg"});
    const auto c = manifest::material_credit(p);
    ASSERT_TRUE(c);
    EXPECT_EQ(c->author, "Poliigon");
    EXPECT_EQ(c->licence,
              "Poliigon EULA (https://www.poliigon.com/terms), the vendor's licence: no redistribution of the files");
    EXPECT_EQ(c->url, "");  // Poliigon's pages follow no certain scheme
    EXPECT_EQ(c->line,
              "Poliigon asset 4585; licensed under Poliigon EULA (https://www.poliigon.com/terms), the vendor's "
              "licence: no redistribution of the files");
    // ATTRIBUTION.md's row says the same terms.
    manifest::Material m;
    m.name = "GrassPatchyGround";
    m.provenance = p;
    EXPECT_NE(manifest::attribution_text({m}).find("| Poliigon EULA (" + std::string(manifest::kVendorLicenceTerms) +
                                                   ") |"),
              std::string::npos)
        << manifest::attribution_text({m});
}

TEST(Credit, NoneWhereTheLicenceIsUnknown) {
    // Hand-named maps: no vendor, no licence file, LICENCE_UNKNOWN.
    const Provenance p = credit_test::found({"crystal_color.jpg", "crystal_normal.jpg", "crystal_roughness.jpg"});
    EXPECT_FALSE(p.licence);
    EXPECT_FALSE(manifest::material_credit(p));
    // A vendor and an asset known without a licence claim none either.
    Provenance vendor_only;
    vendor_only.vendor = "ambientcg";
    vendor_only.vendor_name = "ambientCG";
    vendor_only.asset_id = "Net004A";
    vendor_only.url = "https://ambientcg.com/view?id=Net004A";
    EXPECT_FALSE(manifest::material_credit(vendor_only));
}

}  // namespace mf
