// lib/report's pieces on their own: the materials' folder names, the preview a card shows, the
// links of findings into rules.html, and the albedo / metalness overlays pixel by pixel.
#include <gmock/gmock.h>

#include <algorithm>
#include <cctype>
#include <set>

#include "core/text.hpp"
#include "findings/rules.hpp"
#include "report/html.hpp"
#include "report/images.hpp"
#include "report/report.hpp"
#include "report_util.hpp"

using namespace mfr;
using mf::report::material_stems;
using ::testing::ElementsAre;

namespace {

std::string lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

}  // namespace

// ---- material_stems

TEST(MaterialStems, UniqueWithoutCaseInManifestOrder) {
    EXPECT_THAT(material_stems({"Rock", "rock", "ROCK", "Rock"}), ElementsAre("Rock", "rock_2", "ROCK_3", "Rock_4"));
    // A generated suffix never meets a name of the manifest, in either order.
    EXPECT_THAT(material_stems({"a_2", "a", "A"}), ElementsAre("a_2", "a", "A_3"));
    EXPECT_THAT(material_stems({"a", "A", "a_2"}), ElementsAre("a", "A_2", "a_2_2"));
}

TEST(MaterialStems, UnsafeCharactersBecomeUnderscores) {
    // Every byte outside [A-Za-z0-9._-] is one '_' (é is two bytes in UTF-8).
    EXPECT_THAT(material_stems({"wood planks:\xc3\xa9", "a/b", "a_b", "c\\d", "e\"<f>|?*", "ok-1.2_x"}),
                ElementsAre("wood_planks___", "a_b", "a_b_2", "c_d", "e__f____", "ok-1.2_x"));
    // No hidden folder, no path out of the report, never empty.
    EXPECT_THAT(material_stems({".hidden", "..", ".", ""}), ElementsAre("_hidden", "_.", "_", "material"));
}

TEST(MaterialStems, NeverTheReportsOwnFiles) {
    const auto s = material_stems({"index.html", "INDEX.HTML", "rules.html", "Rules.Html", "index"});
    EXPECT_THAT(s, ElementsAre("index.html_2", "INDEX.HTML_3", "rules.html_2", "Rules.Html_3", "index"));
}

TEST(MaterialStems, CappedAt96BytesStillUnique) {
    const std::string a100(100, 'a');
    std::vector<std::string> names;
    for (int i = 0; i < 12; ++i) names.push_back(a100 + std::to_string(i));  // equal in their first 96 bytes
    names.push_back(std::string(96, 'b'));
    const auto s = material_stems(names);
    ASSERT_EQ(s.size(), names.size());
    EXPECT_EQ(s[0], std::string(96, 'a'));
    EXPECT_EQ(s[1], std::string(94, 'a') + "_2");
    EXPECT_EQ(s[9], std::string(93, 'a') + "_10");
    EXPECT_EQ(s[12], std::string(96, 'b'));
    std::set<std::string> seen;
    for (const auto& x : s) {
        EXPECT_LE(x.size(), 96u) << x;
        EXPECT_TRUE(seen.insert(lower(x)).second) << "two materials in " << x;
    }
}

// ---- preview_file

TEST(PreviewFile, FindsTheFileMatforgePreviewNamed) {
    const fs::path d = temp_dir("previews");
    for (const char* f : {"a_b.png", "x_y______.png", "material.png", "Plain.png"}) std::ofstream(d / f) << "png";
    fs::create_directories(d / "Dir.png");
    using mf::report::preview_file;
    EXPECT_EQ(preview_file(d, "Plain"), d / "Plain.png");
    EXPECT_EQ(preview_file(d, "a/b"), d / "a_b.png");
    EXPECT_EQ(preview_file(d, "a\\b"), d / "a_b.png");
    EXPECT_EQ(preview_file(d, "x:y*?\"<>|"), d / "x_y______.png");
    EXPECT_EQ(preview_file(d, ".."), d / "material.png");
    EXPECT_EQ(preview_file(d, ""), d / "material.png");
    EXPECT_EQ(preview_file(d, "plain"), std::nullopt);  // file names keep their case
    EXPECT_EQ(preview_file(d, "Missing"), std::nullopt);
    EXPECT_EQ(preview_file(d, "Dir"), std::nullopt);  // a folder is no picture
}

// ---- rule_link / rules_page

namespace {

// The <tr> whose id is `id` in `page` (empty when there is none, or when the id is on another element).
std::string row_with_id(const std::string& page, const std::string& id) {
    const size_t at = page.find("<tr id=\"" + id + "\">");
    if (at == std::string::npos) return {};
    return page.substr(at, page.find("</tr>", at) - at);
}

size_t count(const std::string& s, const std::string& what) {
    size_t n = 0;
    for (size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + 1)) ++n;
    return n;
}

}  // namespace

TEST(RulesPage, EveryCatalogCodeLinksToItsOwnRow) {
    const std::string page = mf::report::rules_page({});
    ASSERT_GT(mf::finding_catalog().size(), 10u);
    for (const auto& r : mf::finding_catalog()) {
        const std::string code(r.code);
        const std::string link = mf::report::rule_link(code);
        ASSERT_EQ(link.rfind("rules.html#", 0), 0u) << link;
        const std::string id = link.substr(11);
        EXPECT_EQ(id, std::string(r.anchor)) << code;
        const std::string row = row_with_id(page, id);
        EXPECT_NE(row.find("<code>" + code + "</code>"), std::string::npos) << code << ": no row #" << id;
        EXPECT_EQ(count(page, "id=\"" + id + "\""), 1u) << "#" << id << " is not unique";
    }
}

TEST(RulesPage, CodesOfOtherStagesGetARowToo) {
    const std::set<std::string> codes{"MISSING_MAP", "UNRECOGNIZED_FILE", "AMBIGUOUS_MAP", "ZZ_NEW_CODE"};
    const std::string page = mf::report::rules_page(codes);
    for (const auto& code : codes) {
        const std::string id = mf::report::rule_link(code).substr(11);
        EXPECT_NE(row_with_id(page, id).find("<code>" + code + "</code>"), std::string::npos) << code << " #" << id;
        EXPECT_EQ(count(page, "id=\"" + id + "\""), 1u) << id;
    }
    EXPECT_EQ(mf::report::rule_link("ZZ_NEW_CODE"), "rules.html#zz_new_code");
    // A code that is no rule of the catalog is not in the page until a manifest has it.
    EXPECT_EQ(mf::report::rules_page({}).find("ZZ_NEW_CODE"), std::string::npos);
}

TEST(Html, EscapesAndUrlPaths) {
    EXPECT_EQ(mf::markup_escape("<a href=\"x\">&'</a>"), "&lt;a href=&quot;x&quot;&gt;&amp;&#39;&lt;/a&gt;");
    EXPECT_EQ(mf::markup_escape("bad \xff byte"), "bad \xef\xbf\xbd byte");
    EXPECT_EQ(mf::percent_encode_path("a b/c#d?.png"), "a%20b/c%23d%3F.png");
}

// ---- overlays

TEST(AlbedoOverlay, ClassifiesEachPixelByMetalnessAndLuminance) {
    // sRGB-encoded greys (luminance = the code): 20 (dielectric: too dark), 128 (in range),
    // 250 (too bright), 100 with metalness 1 (metal: too dark), 200 metal (in range),
    // 128 with metalness 0.5 (half metal: too dark for a metal, in range for a dielectric), 128
    // with opacity 0.2 (not visible).
    const float grey[7] = {20, 128, 250, 100, 200, 128, 128};
    const float metal[7] = {0, 0, 0, 1, 1, 0.5f, 0};
    const float alpha[7] = {1, 1, 1, 1, 1, 1, 0.2f};
    mf::Image albedo(7, 1, 3), metalness(7, 1, 1), opacity(7, 1, 1);
    for (int x = 0; x < 7; ++x) {
        for (int c = 0; c < 3; ++c) albedo.at(x, 0, c) = grey[x] / 255.f;
        metalness.at(x, 0) = metal[x];
        opacity.at(x, 0) = alpha[x];
    }
    mf::report::Scalar m, o;
    m.image = &metalness;
    o.image = &opacity;
    mf::report::AlbedoStats st;
    const mf::Image out = mf::report::albedo_overlay(albedo, true, m, o, mf::rules::Thresholds{}, st);
    ASSERT_EQ(out.width, 7);
    auto is = [&](int x, const float* rgb) {
        return out.at(x, 0, 0) == rgb[0] && out.at(x, 0, 1) == rgb[1] && out.at(x, 0, 2) == rgb[2];
    };
    EXPECT_TRUE(is(0, mf::report::kTooDark));
    EXPECT_NEAR(out.at(1, 0, 0), 128 / 255.f, 1e-3f);  // in range: its luminance, grey
    EXPECT_EQ(out.at(1, 0, 0), out.at(1, 0, 2));
    EXPECT_TRUE(is(2, mf::report::kTooBright));
    EXPECT_TRUE(is(3, mf::report::kTooDark));
    EXPECT_NEAR(out.at(4, 0, 1), 200 / 255.f, 1e-3f);
    // Half of it too dark: half red, half its grey.
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(out.at(5, 0, c), 0.5f * mf::report::kTooDark[c] + 0.5f * out.at(1, 0, c), 1e-6f);
    EXPECT_EQ(out.at(6, 0, 0), out.at(6, 0, 1));  // checkerboard grey
    EXPECT_EQ(st.pixels, 7u);
    // Weighted sums in units of 1/kWeightUnit of a pixel: the half-metal pixel counts half to each.
    constexpr long long u = mf::validate::kWeightUnit;
    const auto& n = st.counts;
    EXPECT_EQ(n.visible, 6);
    EXPECT_EQ(n.blend, 1);
    EXPECT_EQ(n.dielectric, 3 * u + u / 2);
    EXPECT_EQ(n.dielectric_dark, u);
    EXPECT_EQ(n.dielectric_bright, u);
    EXPECT_EQ(n.metal, 2 * u + u / 2);
    EXPECT_EQ(n.metal_dark, u + u / 2);
    EXPECT_DOUBLE_EQ(n.surface_share(n.metal_dark), 0.25);
}

TEST(Thumbnail, BoxFilterInLinearLightAndNeverEnlarged) {
    // Black and white columns: the mean in linear light is 0.5, which sRGB encodes as ~188.
    mf::Image src(4, 2, 3);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x)
            for (int c = 0; c < 3; ++c) src.at(x, y, c) = static_cast<float>(x % 2);
    const mf::Image t = mf::report::thumbnail(src, 2, true);
    ASSERT_EQ(t.width, 2);
    ASSERT_EQ(t.height, 1);
    EXPECT_NEAR(t.at(0, 0, 0) * 255.f, 187.5f, 1.f);
    const mf::Image data = mf::report::thumbnail(src, 2, false);  // data: averaged as stored
    EXPECT_NEAR(data.at(1, 0, 1), 0.5f, 1e-6f);
    EXPECT_EQ(mf::report::thumbnail(src, 64, true).width, 4);
}
