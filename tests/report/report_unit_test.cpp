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

// ---- thumbnails of 8-bit codes (summed exactly as integers) against the float pictures

namespace report_unit_codes {

// Codes of a w x h picture of `channels`, from a fixed pseudo-random sequence (the full range:
// 0 and 255 included, so the sums see the sRGB curve's two ends).
mf::Image8 codes_picture(int w, int h, int channels, uint32_t seed) {
    mf::Image8 img(w, h, channels);
    for (uint8_t& v : img.pixels) {
        seed = seed * 1664525u + 1013904223u;
        v = static_cast<uint8_t>(seed >> 24);
    }
    return img;
}

// Every value of both pictures equal, bit for bit.
void expect_same(const mf::Image& a, const mf::Image& b) {
    ASSERT_EQ(a.width, b.width);
    ASSERT_EQ(a.height, b.height);
    ASSERT_EQ(a.channels, b.channels);
    size_t differ = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) differ += a.pixels[i] != b.pixels[i] ? 1 : 0;
    EXPECT_EQ(differ, 0u) << "of " << a.pixels.size() << " values";
}

}  // namespace report_unit_codes

TEST(ReportThumbnail, CodesGiveTheFloatPicturesThumbnailBitForBit) {
    using namespace report_unit_codes;
    // Sizes that do not divide (boxes of 2 and 3 columns, rows alike), one that does, a picture
    // no larger than the thumbnail (kept as it is) and a strip (one output row).
    const int sizes[][3] = {{37, 23, 16}, {64, 64, 16}, {12, 9, 16}, {301, 5, 40}};
    for (const auto& s : sizes)
        for (int channels = 1; channels <= 4; ++channels)
            for (const bool srgb : {true, false}) {
                SCOPED_TRACE(std::to_string(s[0]) + "x" + std::to_string(s[1]) + " to " + std::to_string(s[2]) +
                             ", channels " + std::to_string(channels) + (srgb ? ", sRGB" : ", data"));
                const mf::Image8 codes = codes_picture(s[0], s[1], channels,
                                                       static_cast<uint32_t>(channels * 7 + srgb));
                const mf::Image floats = mf::to_float(codes);
                expect_same(mf::report::thumbnail(codes, s[2], srgb), mf::report::thumbnail(floats, s[2], srgb));
                for (int ch = 0; ch < channels; ++ch)
                    expect_same(mf::report::channel_thumbnail(codes, ch, s[2] / 4),
                                mf::report::channel_thumbnail(floats, ch, s[2] / 4));
            }
}

TEST(ReportThumbnail, EachPixelIsTheMeanOfTheSourcePixelsItCovers) {
    // 10 x 7 to at most 4: 4 x 3 (7 * 0.4 = 2.8 rounds to 3). Source column x goes to output
    // column x * 4 / 10 (columns 0-2, 3-4, 5-7, 8-9); output row oy holds the source rows
    // [oy * 7 / 3, (oy + 1) * 7 / 3) (rows 0-1, 2-3, 4-6).
    const mf::Image8 codes = report_unit_codes::codes_picture(10, 7, 1, 5);
    const mf::Image t = mf::report::thumbnail(codes, 4, false);
    ASSERT_EQ(t.width, 4);
    ASSERT_EQ(t.height, 3);
    const int col0[5] = {0, 3, 5, 8, 10}, row0[4] = {0, 2, 4, 7};
    for (int oy = 0; oy < 3; ++oy)
        for (int ox = 0; ox < 4; ++ox) {
            double sum = 0;
            for (int y = row0[oy]; y < row0[oy + 1]; ++y)
                for (int x = col0[ox]; x < col0[ox + 1]; ++x) sum += codes.at(x, y) / 255.0;
            const double mean = sum / ((col0[ox + 1] - col0[ox]) * (row0[oy + 1] - row0[oy]));
            EXPECT_NEAR(t.at(ox, oy, 0), mean, 1e-6) << ox << "," << oy;
            EXPECT_EQ(t.at(ox, oy, 1), t.at(ox, oy, 0));  // grey
        }
}

TEST(ReportThumbnail, TheLargestExactBoxAndOneBeyondItAgreeWithTheFloats) {
    using namespace report_unit_codes;
    // 8192 x 512 to 16: boxes of 512 x 512 = 2^18 pixels, the most whose integer sums are taken
    // (in units of 2^-35: up to 2^53); 8192 x 513 boxes one row more, which the double sums make.
    for (const int h : {512, 513}) {
        SCOPED_TRACE(h);
        mf::Image8 codes = codes_picture(8192, h, 1, 11);
        std::fill_n(codes.pixels.begin(), 8192 * 16, uint8_t{255});  // a run of the largest value
        const mf::Image floats = mf::to_float(codes);
        const mf::Image a = mf::report::thumbnail(codes, 16, true), b = mf::report::thumbnail(floats, 16, true);
        ASSERT_EQ(a.width, 16);
        expect_same(a, b);
    }
}

TEST(ReportOverlays, CodesAndFloatsGiveTheSamePicturesAndCounts) {
    using namespace report_unit_codes;
    // A 3-channel albedo of 29 x 17 over a smaller metalness (5 x 4, stored inverted) and an
    // opacity of 2 x 2, sampled by nearest neighbour: the same overlays and counts from codes
    // and from floats, and the counts those of Scalar::at pixel by pixel.
    const mf::Image8 albedo = codes_picture(29, 17, 3, 3), metal = codes_picture(5, 4, 2, 4),
                     alpha = codes_picture(2, 2, 1, 9);
    const mf::Image albedo_f = mf::to_float(albedo), metal_f = mf::to_float(metal), alpha_f = mf::to_float(alpha);
    mf::report::Scalar m8, o8, mf_, of;
    m8.codes = &metal;
    mf_.image = &metal_f;
    m8.channel = mf_.channel = 1;
    m8.invert = mf_.invert = true;
    o8.codes = &alpha;
    of.image = &alpha_f;
    const mf::rules::Thresholds t;
    for (const int size : {0, 8}) {
        SCOPED_TRACE(size);
        mf::report::AlbedoStats s8, sf;
        expect_same(mf::report::albedo_overlay(albedo, true, m8, o8, t, s8, size),
                    mf::report::albedo_overlay(albedo_f, true, mf_, of, t, sf, size));
        EXPECT_EQ(s8.pixels, 29u * 17u);
        EXPECT_EQ(s8.counts.visible, sf.counts.visible);
        EXPECT_EQ(s8.counts.metal_dark, sf.counts.metal_dark);
        EXPECT_EQ(s8.counts.dielectric_dark, sf.counts.dielectric_dark);
        mf::report::MetalnessStats n8, nf;
        expect_same(mf::report::metalness_overlay(m8, 29, 17, t, n8, size),
                    mf::report::metalness_overlay(mf_, 29, 17, t, nf, size));
        size_t visible = 0, zero = 0, between = 0;
        for (int y = 0; y < 17; ++y)
            for (int x = 0; x < 29; ++x) {
                visible += of.at(x, y, 29, 17) >= t.opacity_visible ? 1 : 0;
                const float v = m8.at(x, y, 29, 17);
                zero += v < 0.5f / 255.f ? 1 : 0;
                between += v > t.dielectric_max && v < t.metal_min ? 1 : 0;
            }
        EXPECT_EQ(s8.counts.visible, static_cast<long long>(visible));
        EXPECT_EQ(n8.zero, zero);
        EXPECT_EQ(n8.between, between);
        EXPECT_EQ(nf.between, between);
    }
}
