// `matforge report` end to end on sample_materials: ingest (gltf), preview (lavapipe), report;
// then the page is read back as files: a card per material, a row per finding, every picture a
// PNG of the size asked, the same bytes on a second run, nothing outside the report's folder.
#include <cstdio>
#include <map>
#include <set>

#include "color/srgb.hpp"
#include "core/files.hpp"
#include "report/html.hpp"
#include "report/images.hpp"
#include "report/report.hpp"
#include "report_util.hpp"

using namespace mfr;
using mf::report::escape;

namespace {

int code8(float v) { return static_cast<int>(mf::quantize8(v)); }

std::map<std::string, std::string> files_under(const fs::path& dir) {
    std::map<std::string, std::string> out;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        if (e.is_regular_file()) out[fs::relative(e.path(), dir).generic_string()] = read_text(e.path());
    return out;
}

}  // namespace

TEST_F(SampleReportTest, EveryMaterialHasItsCardAndEveryFindingItsRow) {
    const std::string html = read_text(r_.report / "index.html");
    ASSERT_EQ(manifest_["materials"].size(), 4u);
    size_t cards = 0;
    for (size_t at = html.find("<section class=\"card"); at != std::string::npos;
         at = html.find("<section class=\"card", at + 1))
        ++cards;
    EXPECT_EQ(cards, manifest_["materials"].size());
    size_t total = 0;
    for (const auto& m : manifest_["materials"]) {
        const std::string name = m["name"];
        const std::string card = card_of(html, escape(name));
        ASSERT_FALSE(card.empty()) << "no card for " << name;
        EXPECT_NE(card.find("<h2><a href=\"#m-" + name + "\">" + escape(name) + "</a>"), std::string::npos) << name;
        EXPECT_NE(card.find("src=\"" + name + "/preview.png\""), std::string::npos) << name << ": no preview";
        EXPECT_NE(html.find("<a class=\"tile"), std::string::npos);
        // The rows of this card, each matched to one finding of the manifest.
        std::vector<std::string> rows;
        for (size_t at = card.find("<tr class=\"finding"); at != std::string::npos;
             at = card.find("<tr class=\"finding", at + 1))
            rows.push_back(card.substr(at, card.find("</tr>", at) - at));
        EXPECT_EQ(rows.size(), m["findings"].size()) << name;
        for (const auto& f : m["findings"]) {
            const std::string code = f["code"], message = f["message"];
            const std::string link = "<a href=\"" + mf::report::rule_link(code) + "\">" + code + "</a>";
            const auto it = std::find_if(rows.begin(), rows.end(), [&](const std::string& r) {
                return r.find("data-code=\"" + code + "\"") != std::string::npos && r.find(link) != std::string::npos &&
                       r.find(escape(message)) != std::string::npos;
            });
            EXPECT_NE(it, rows.end()) << name << ": no row for " << code << " \"" << message << "\"";
            if (it != rows.end()) rows.erase(it);
            ++total;
        }
    }
    EXPECT_GE(total, 10u);  // the sample sets do have findings (ALBEDO_TOO_DARK, METALNESS_NOT_BINARY, ...)
    EXPECT_NE(html.find(std::to_string(manifest_["materials"].size()) + " materials · "), std::string::npos);
    // Every code the page links to has its row in rules.html.
    const std::string rules = read_text(r_.report / "rules.html");
    const std::string href = "href=\"rules.html#";
    size_t links = 0;
    for (size_t at = html.find(href); at != std::string::npos; at = html.find(href, at + 1), ++links) {
        const size_t start = at + href.size(), end = html.find('"', start);
        ASSERT_NE(end, std::string::npos);
        const std::string id = html.substr(start, end - start);
        EXPECT_NE(rules.find("<tr id=\"" + id + "\">"), std::string::npos) << "rules.html has no #" << id;
    }
    EXPECT_GE(links, total);
}

TEST_F(SampleReportTest, EveryPictureIsAPngOfTheThumbSize) {
    // All sample maps are larger than the thumbnails: every picture is reduced to exactly
    // kThumb on its long side (packed channels to a quarter of it).
    for (const auto& m : manifest_["materials"]) {
        for (const auto& o : m["outputs"]) ASSERT_GE(std::max(o["width"].get<int>(), o["height"].get<int>()), kThumb);
        for (const auto& i : m["inputs"]) ASSERT_GE(std::max(i["width"].get<int>(), i["height"].get<int>()), kThumb);
    }
    const std::string html = read_text(r_.report / "index.html");
    const auto imgs = images_of(html);
    std::set<std::string> shown;
    for (const Img& i : imgs) {
        SCOPED_TRACE(i.src);
        shown.insert(i.src);
        const fs::path file = r_.report / i.src;
        ASSERT_TRUE(fs::is_regular_file(file));
        EXPECT_EQ(read_text(file).substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
        const mf::Image px = read_pixels(file);
        EXPECT_EQ(px.width, i.width);
        EXPECT_EQ(px.height, i.height);
        EXPECT_EQ(std::max(px.width, px.height), i.cls == "chan" ? kThumb / 4 : kThumb);
    }
    // Each material: a preview, the albedo range overlay, its outputs.
    for (const auto& m : manifest_["materials"]) {
        const std::string name = m["name"];
        EXPECT_TRUE(shown.count(name + "/preview.png")) << name;
        EXPECT_TRUE(shown.count(name + "/albedo-range.png")) << name;
    }
    EXPECT_TRUE(shown.count("Metal_Damaged_001/metalness.png"));  // the one set with a metalness map
    // Nothing written that the page does not show.
    std::set<std::string> on_disk;
    for (const auto& [rel, bytes] : files_under(r_.report))
        if (rel.ends_with(".png")) on_disk.insert(rel);
    EXPECT_EQ(on_disk, shown);
    EXPECT_GT(shown.size(), 30u);
}

TEST_F(SampleReportTest, NothingOutsideTheReportFolder) {
    const std::string html = read_text(r_.report / "index.html");
    for (const char* s : {"http:", "https:", "//", "file:/", "src=\"/", "href=\"/"})
        EXPECT_EQ(html.find(s), std::string::npos) << s;
    EXPECT_EQ(html.find(r_.previews.string()), std::string::npos) << "an absolute path of the previews";
    // Every link and picture is an anchor of the page, or a file of the report's folder.
    std::vector<std::string> values;  // every src="..." and href="..."
    for (const std::string key : {" src=\"", " href=\""})
        for (size_t at = html.find(key); at != std::string::npos; at = html.find(key, at + 1)) {
            const size_t start = at + key.size(), end = html.find('"', start);
            if (end != std::string::npos) values.push_back(html.substr(start, end - start));
        }
    size_t n = 0;
    for (const std::string& v : values) {
        ++n;
        if (v.rfind('#', 0) == 0) {
            EXPECT_NE(html.find("id=\"" + v.substr(1) + "\""), std::string::npos) << v;
            continue;
        }
        EXPECT_TRUE(fs::is_regular_file(r_.report / v.substr(0, v.find('#')))) << v;
    }
    EXPECT_GT(n, 50u);
}

TEST_F(SampleReportTest, ASecondRunWritesTheSameBytesAndRewritesNothing) {
    const fs::path again = work_ / "report-again";
    ASSERT_TRUE(matforge({"report", r_.manifest.string(), "-o", again.string(), "--previews", r_.previews.string(),
                          "--thumb-size", std::to_string(kThumb), "-q", "-j", "1"}));
    const auto first = files_under(r_.report), second = files_under(again);
    ASSERT_EQ(first.size(), second.size());
    for (const auto& [rel, bytes] : first) {
        ASSERT_TRUE(second.count(rel)) << rel;
        EXPECT_TRUE(second.at(rel) == bytes) << rel << " differs between two runs";
    }
    // Into the same folder: no file is rewritten.
    std::map<std::string, fs::file_time_type> times;
    for (const auto& e : fs::recursive_directory_iterator(again))
        if (e.is_regular_file()) times[e.path().string()] = e.last_write_time();
    ASSERT_TRUE(matforge({"report", r_.manifest.string(), "-o", again.string(), "--previews", r_.previews.string(),
                          "--thumb-size", std::to_string(kThumb), "-q"}));
    for (const auto& [p, t] : times) EXPECT_EQ(fs::last_write_time(p), t) << p << " was rewritten";
}

TEST_F(SampleReportTest, AlbedoOverlayMarksTooDarkPixelsRed) {
    // Net004A: a dark net on a cut-out (ALBEDO_TOO_DARK, opacity in the albedo's alpha, no
    // metalness map: all dielectric). A thumbnail pixel whose whole box of source pixels is
    // visible, dielectric and darker than 50 sRGB is exactly red; one whose box is in range is grey.
    const auto* mat = [&]() -> const nlohmann::json* {
        for (const auto& m : manifest_["materials"])
            if (m["name"] == "Net004A") return &m;
        return nullptr;
    }();
    ASSERT_NE(mat, nullptr);
    ASSERT_TRUE(std::any_of((*mat)["findings"].begin(), (*mat)["findings"].end(),
                            [](const auto& f) { return f["code"] == "ALBEDO_TOO_DARK"; }));
    const fs::path dir = r_.manifest.parent_path();
    const mf::Image albedo = read_pixels(dir / "Net004A/Net004A_basecolor.png");
    const mf::Image orm = read_pixels(dir / "Net004A/Net004A_orm.png");
    const mf::Image overlay = read_pixels(r_.report / "Net004A/albedo-range.png");
    ASSERT_EQ(albedo.channels, 4);
    ASSERT_EQ(orm.width, albedo.width);
    ASSERT_EQ(std::max(overlay.width, overlay.height), kThumb);
    ASSERT_EQ(overlay.channels, 3);
    const int w = albedo.width, h = albedo.height, ow = overlay.width, oh = overlay.height;
    // The box of each thumbnail pixel, as lib/report/images.cpp reduces: column x goes to
    // x * ow / w, rows [oy * h / oh, (oy + 1) * h / oh) to row oy.
    std::vector<int> row_of(static_cast<size_t>(h));
    for (int oy = 0; oy < oh; ++oy)
        for (int y = oy * h / oh; y < std::max(oy * h / oh + 1, (oy + 1) * h / oh); ++y)
            row_of[static_cast<size_t>(y)] = oy;
    // Per box: does any source pixel fail to be dark (resp. in range)?
    std::vector<char> not_dark(static_cast<size_t>(ow * oh)), not_in_range(static_cast<size_t>(ow * oh));
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            double lin = 0;
            const double k[3] = {0.2126, 0.7152, 0.0722};
            for (int c = 0; c < 3; ++c) lin += k[c] * mf::srgb_to_linear(static_cast<double>(albedo.at(x, y, c)));
            const double s = mf::linear_to_srgb(lin) * 255.0;
            const bool ok = albedo.at(x, y, 3) >= 0.55f && orm.at(x, y, 2) <= 0.05f;  // visible, dielectric
            const auto box = static_cast<size_t>(row_of[static_cast<size_t>(y)] * ow + x * ow / w);
            if (!(ok && s < 45)) not_dark[box] = 1;
            if (!(ok && s > 55 && s < 238)) not_in_range[box] = 1;
        }
    }
    int dark_boxes = 0, grey_boxes = 0;
    for (int oy = 0; oy < oh; ++oy) {
        for (int ox = 0; ox < ow; ++ox) {
            const auto box = static_cast<size_t>(oy * ow + ox);
            const int r = code8(overlay.at(ox, oy, 0)), g = code8(overlay.at(ox, oy, 1)),
                      b = code8(overlay.at(ox, oy, 2));
            if (!not_dark[box]) {
                ++dark_boxes;
                EXPECT_EQ(r, code8(mf::report::kTooDark[0])) << ox << "," << oy;
                EXPECT_EQ(g, code8(mf::report::kTooDark[1])) << ox << "," << oy;
                EXPECT_EQ(b, code8(mf::report::kTooDark[2])) << ox << "," << oy;
            } else if (!not_in_range[box]) {
                ++grey_boxes;
                EXPECT_TRUE(r == g && g == b && r > 50) << ox << "," << oy << ": " << r << " " << g << " " << b;
            }
        }
    }
    EXPECT_GT(dark_boxes, 100) << "Net004A has a dark net: many wholly dark boxes";
    std::printf("Net004A overlay: %d wholly dark boxes red, %d wholly in-range boxes grey\n", dark_boxes, grey_boxes);
    // The legend names the red.
    const std::string card = card_of(read_text(r_.report / "index.html"), "Net004A");
    EXPECT_NE(card.find("<span class=\"key dark\"></span> too dark: "), std::string::npos);
}

// A made-up set: the left half of its albedo far too dark (sRGB 20), the right half mid-grey.
TEST(ReportCli, DarkHalfOfAnAlbedoIsRedInTheOverlay) {
    const fs::path work = temp_dir("dark");
    mf::Image albedo(64, 32, 3);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 64; ++x)
            for (int c = 0; c < 3; ++c) albedo.at(x, y, c) = (x < 32 ? 20.f : 128.f) / 255.f;
    mf::Image rough(64, 32, 1);
    for (float& v : rough.pixels) v = 0.5f;
    for (const auto& [file, img] :
         {std::pair{"Dark_basecolor.png", &albedo}, std::pair{"Dark_roughness.png", &rough}}) {
        std::vector<unsigned char> bytes;
        std::string err;
        ASSERT_TRUE(mf::encode_image(*img, mf::EncodeOptions{"png", 8}, bytes, err)) << err;
        fs::create_directories(work / "src/Dark");
        ASSERT_TRUE(mf::write_file_atomic(work / "src/Dark" / file, bytes, err)) << err;
    }
    ASSERT_TRUE(matforge({"ingest", (work / "src").string(), "-o", (work / "out").string(), "-q"}));
    const auto manifest = read_json(work / "out/manifest.json");
    ASSERT_EQ(manifest["materials"].size(), 1u);
    ASSERT_EQ(manifest["materials"][0]["name"], "Dark");
    ASSERT_TRUE(matforge({"report", (work / "out/manifest.json").string(), "-o", (work / "report").string(), "-q"}));
    const mf::Image overlay = read_pixels(work / "report/Dark/albedo-range.png");
    ASSERT_EQ(overlay.width, 64);  // never enlarged, never reduced below the thumb size
    ASSERT_EQ(overlay.height, 32);
    for (const int x : {0, 17, 31}) {
        EXPECT_EQ(code8(overlay.at(x, 5, 0)), 219) << x;  // kTooDark = (0.86, 0.12, 0.12)
        EXPECT_EQ(code8(overlay.at(x, 5, 1)), 31) << x;
        EXPECT_EQ(code8(overlay.at(x, 5, 2)), 31) << x;
    }
    for (const int x : {32, 63}) {
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(code8(overlay.at(x, 5, c)), 128, 1) << x;
    }
    const std::string html = read_text(work / "report/index.html");
    EXPECT_NE(html.find("<span class=\"key dark\"></span> too dark: 50.0 %"), std::string::npos);
    EXPECT_NE(html.find("data-code=\"ALBEDO_TOO_DARK\""), std::string::npos);
}

TEST(ReportCli, UnreadableManifestIsAUsageError) {
    const fs::path work = temp_dir("usage");
    EXPECT_TRUE(matforge({"report", (work / "none.json").string(), "-o", (work / "r").string()}, 2));
    EXPECT_FALSE(fs::exists(work / "r/index.html"));
    EXPECT_TRUE(matforge({"report", (work / "none.json").string(), "-o", (work / "r").string(), "--previews",
                          (work / "missing").string()},
                         2));
}
