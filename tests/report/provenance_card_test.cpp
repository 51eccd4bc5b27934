// The card of each material shows where it comes from and under what licence (the manifest's
// provenance, or LICENCE_UNKNOWN's reason), and the vendor's own preview beside matforge's render.
#include "core/text.hpp"
#include "report_util.hpp"

using namespace mfr;

namespace provenance_card {

size_t count_of(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

}  // namespace provenance_card

using provenance_card::count_of;

TEST_F(SampleReportTest, CardShowsTheVendorPreviewBesideTheRenderAndTheLicence) {
    const std::string html = read_text(r_.report / "index.html");
    const std::string net = card_of(html, "Net004A");
    ASSERT_FALSE(net.empty());
    // matforge's render, then the vendor's picture (ambientCG's Net004A.png), side by side.
    const size_t box = net.find("<div class=\"previews\">");
    ASSERT_NE(box, std::string::npos) << net;
    const size_t ours = net.find("src=\"Net004A/preview.png\"", box);
    const size_t theirs = net.find("<figure class=\"preview vendor-preview\"><img", box);
    const size_t end = net.find("</div>", box);
    EXPECT_LT(ours, theirs);
    EXPECT_LT(theirs, end);
    EXPECT_NE(net.find("src=\"Net004A/src-preview.png\" width=\"160\" height=\"160\"", theirs), std::string::npos);
    EXPECT_NE(net.find("the vendor's preview <code>Net004A.png</code>", theirs), std::string::npos);
    EXPECT_EQ(count_of(net, "Net004A/src-preview.png"), 1u);  // not again among the sources' before/after
    // Where it comes from: vendor, id, licence with its evidence, the asset's page (as text: the page
    // links nothing outside its folder).
    EXPECT_NE(net.find("vendor <b class=\"vendor\">ambientCG</b> · asset <code class=\"asset\">Net004A</code> · "
                       "licence <b class=\"licence\">CC0-1.0</b>"),
              std::string::npos)
        << net;
    EXPECT_NE(net.find("known from the vendor <code>Net004A_1K-JPG_Color.jpg</code>"), std::string::npos);
    EXPECT_NE(net.find("source <code>ambientcg.com/view?id=Net004A</code>"), std::string::npos);

    // 3dtextures.me's render, 600x800: its thumbnail keeps the shape.
    const std::string metal = card_of(html, "Metal_Damaged_001");
    EXPECT_NE(metal.find("src=\"Metal_Damaged_001/src-preview.png\" width=\"120\" height=\"160\""), std::string::npos)
        << metal;
    EXPECT_NE(metal.find("vendor <b class=\"vendor\">3dtextures.me</b>"), std::string::npos);

    // No licence found: "unknown", with LICENCE_UNKNOWN's reason; no vendor picture to show.
    const std::string crystal = card_of(html, "Crystal_003");
    ASSERT_FALSE(crystal.empty());
    EXPECT_NE(crystal.find("licence <b class=\"licence unknown\">unknown</b>"), std::string::npos) << crystal;
    std::string why;
    for (const auto& m : manifest_["materials"])
        if (m["name"] == "Crystal_003")
            for (const auto& f : m["findings"])
                if (f["code"] == "LICENCE_UNKNOWN") why = f["message"];
    ASSERT_FALSE(why.empty());
    EXPECT_NE(crystal.find(mf::markup_escape(why)), std::string::npos);
    EXPECT_EQ(crystal.find("vendor-preview"), std::string::npos);
    EXPECT_EQ(crystal.find("<div class=\"previews\">"), std::string::npos);
}
