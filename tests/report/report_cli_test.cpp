// `matforge report` end to end on sample_materials: ingest (gltf), preview (lavapipe), report;
// then the page is read back as files: a card per material, a row per finding, every picture a
// PNG of the size asked, the same bytes on a second run, nothing outside the report's folder.
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "base/srgb.hpp"
#include "core/files.hpp"
#include "core/text.hpp"
#include "report/html.hpp"
#include "report/images.hpp"
#include "report/report.hpp"
#include "report_util.hpp"

using namespace mfr;
using mf::markup_escape;

namespace {

int code8(float v) { return static_cast<int>(mf::quantize8(v)); }

using mf::testfiles::files_under;

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
        const std::string card = card_of(html, markup_escape(name));
        ASSERT_FALSE(card.empty()) << "no card for " << name;
        EXPECT_NE(card.find("<h2><a href=\"#m-" + name + "\">" + markup_escape(name) + "</a>"), std::string::npos)
            << name;
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
                       r.find(markup_escape(message)) != std::string::npos;
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

// Each card lists the material files written for its set (issue 27), each file with its format
// and the line on how to open it; gltf writes four per set.
TEST_F(SampleReportTest, EveryCardListsItsMaterialFiles) {
    const std::string html = read_text(r_.report / "index.html");
    for (const auto& m : manifest_["materials"]) {
        const std::string name = m["name"];
        const std::string card = card_of(html, markup_escape(name));
        const size_t table = card.find("<table class=\"material-files\">");
        ASSERT_NE(table, std::string::npos) << name;
        const std::string rows = card.substr(table, card.find("</table>", table) - table);
        ASSERT_EQ(m["material_files"].size(), 4u) << name;
        for (const auto& f : m["material_files"]) {
            const std::string row = "<tr data-format=\"" + f["format"].get<std::string>() + "\"><td><code>" +
                                    markup_escape(f["file"].get<std::string>()) + "</code>";
            EXPECT_NE(rows.find(row), std::string::npos) << name << ": " << f["file"];
        }
        EXPECT_NE(rows.find("three.js GLTFLoader"), std::string::npos) << name;
        EXPECT_NE(rows.find("a USD host"), std::string::npos) << name;
    }
}

// A Unity preset's .meta files beside the textures are one row with their count; the .mat its own.
TEST(ReportCli, EngineMaterialFilesAreListedWithHowToOpenThem) {
    const fs::path work = temp_dir("unity");
    ASSERT_TRUE(matforge({"ingest", (mf::testenv::source_dir() / "sample_materials/Net004A_1K-JPG").string(), "-o",
                          (work / "out").string(), "--preset", "unity-urp", "-q", "--fail-on", "never"}));
    ASSERT_TRUE(matforge({"report", (work / "out/manifest.json").string(), "-o", (work / "report").string(), "-q"}));
    const std::string html = read_text(work / "report/index.html");
    EXPECT_NE(html.find("<tr data-format=\"mat\"><td><code>Net004A/Net004A.mat</code></td><td>mat</td><td>Unity: "),
              std::string::npos)
        << html.substr(html.find("material-files") == std::string::npos ? 0 : html.find("material-files"), 800);
    EXPECT_NE(html.find("<td>4 <code>.meta</code> beside the textures</td>"), std::string::npos);
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
    // visible, dielectric and darker than 30 sRGB (the rule's bound) is exactly red; one whose box
    // is in range is grey.
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
            if (!(ok && s < 28)) not_dark[box] = 1;
            if (!(ok && s > 32 && s < 238)) not_in_range[box] = 1;
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
    // 51 % of the visible net is darker than 30 sRGB, but a box of the thin net mostly holds a
    // hole or a lighter pixel too: few boxes are wholly dark.
    EXPECT_GE(dark_boxes, 5) << "Net004A has a dark net: some wholly dark boxes";
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
        ASSERT_TRUE(mf::encode_image(*img, mf::EncodeOptions{mf::FileFormat::png, 8}, bytes, err)) << err;
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
    EXPECT_NE(html.find("<span class=\"key dark\"></span> too dark: dielectric <span class=\"share\" "
                        "data-code=\"ALBEDO_TOO_DARK\">50.0 %</span>"),
              std::string::npos);
    EXPECT_NE(html.find("data-code=\"ALBEDO_TOO_DARK\""), std::string::npos);
}

// The overlay's shares are the findings' (issue 25): on every set of the real corpus, each share
// the legend gives under a rule's code is that finding's surface_share, as the finding's message
// writes it; where the rule raised nothing, the share is within its max_share.
TEST(ReportCli, OverlaySharesAreTheFindingsOnTheRealCorpus) {
    const fs::path work = temp_dir("corpus");
    const fs::path corpus = mf::testenv::corpus_dir() / "real";
    ASSERT_TRUE(matforge({"ingest", corpus.string(), "-o", (work / "out").string(), "--fail-on", "never", "-q"}));
    ASSERT_TRUE(matforge({"report", (work / "out/manifest.json").string(), "-o", (work / "report").string(),
                          "--no-sources", "-q"}));
    const auto manifest = read_json(work / "out/manifest.json");
    const std::string html = read_text(work / "report/index.html");
    const double max_share = manifest["thresholds"]["ALBEDO_TOO_DARK"]["max_share"];
    int compared = 0, raised = 0;
    for (const auto& m : manifest["materials"]) {
        const std::string name = m["name"];
        const std::string card = card_of(html, markup_escape(name));
        ASSERT_FALSE(card.empty()) << name;
        for (const std::string code : {"ALBEDO_TOO_DARK", "ALBEDO_TOO_BRIGHT", "METAL_ALBEDO_TOO_DARK"}) {
            const std::string key = "data-code=\"" + code + "\">";
            const size_t at = card.find(key);
            if (at == std::string::npos) continue;  // no albedo map: no overlay
            const std::string shown = card.substr(at + key.size(), card.find("</span>", at) - at - key.size());
            const auto f = std::find_if(m["findings"].begin(), m["findings"].end(),
                                        [&](const auto& x) { return x["code"] == code; });
            if (f != m["findings"].end()) {
                EXPECT_EQ(shown, mf::percent((*f)["figures"]["surface_share"].get<double>())) << name << " " << code;
                EXPECT_NE((*f)["message"].get<std::string>().find(shown), std::string::npos) << name << " " << code;
                ++raised;
            } else if (shown != "—") {  // "—": no pixel visible (OPACITY_ALL_TRANSPARENT), nothing judged
                EXPECT_LE(std::stod(shown), 100.0 * max_share + 0.05) << name << " " << code;
            }
            ++compared;
        }
    }
    EXPECT_GE(compared, 3 * 14);
    EXPECT_GE(raised, 2) << "the corpus has dark albedos (Metal_Rusted_010, Net004A)";
}

// "written as dx (green flipped)" is a fact of the output (normal_converted_from), not read out
// of a finding a rules file can switch off.
TEST(ReportCli, AFlippedGreenChannelIsReportedWithItsFindingOff) {
    const fs::path work = temp_dir("flipped");
    const fs::path set = mf::testenv::corpus_dir() / "real/polyhaven_brown_planks_09_1k_jpg+webp";
    std::ofstream(work / "rules.json") << R"({"rules": {"NORMAL_CONVENTION_CONVERTED": "off"}})";
    ASSERT_TRUE(matforge({"ingest", set.string(), "-o", (work / "out").string(), "--normal-convention", "dx", "--rules",
                          (work / "rules.json").string(), "-q"}));
    const auto manifest = read_json(work / "out/manifest.json");
    ASSERT_EQ(manifest["materials"].size(), 1u);
    const auto& mat = manifest["materials"][0];
    for (const auto& f : mat["findings"]) EXPECT_NE(f["code"], "NORMAL_CONVENTION_CONVERTED");
    int flipped = 0;
    for (const auto& o : mat["outputs"])
        if (o.contains("normal_converted_from")) {
            EXPECT_EQ(o["normal_converted_from"], "gl");
            EXPECT_EQ(o["normal_convention"], "dx");
            ++flipped;
        }
    EXPECT_EQ(flipped, 1);
    ASSERT_TRUE(matforge({"report", (work / "out/manifest.json").string(), "-o", (work / "report").string(), "-q"}));
    const std::string html = read_text(work / "report/index.html");
    EXPECT_NE(html.find("; written as <b>dx</b> (green flipped)"), std::string::npos);
    // The same set kept in its own convention says so.
    ASSERT_TRUE(matforge({"ingest", set.string(), "-o", (work / "kept").string(), "-q"}));
    const auto kept = read_json(work / "kept/manifest.json");  // held: a loop over a temporary's member dangles
    for (const auto& o : kept["materials"][0]["outputs"]) EXPECT_FALSE(o.contains("normal_converted_from"));
    ASSERT_TRUE(matforge({"report", (work / "kept/manifest.json").string(), "-o", (work / "kept-report").string(),
                          "-q"}));
    EXPECT_NE(read_text(work / "kept-report/index.html").find("; written as <b>gl</b> (green kept)"),
              std::string::npos);
}

TEST(ReportCli, UnreadableManifestIsAUsageError) {
    const fs::path work = temp_dir("usage");
    EXPECT_TRUE(matforge({"report", (work / "none.json").string(), "-o", (work / "r").string()}, 2));
    EXPECT_FALSE(fs::exists(work / "r/index.html"));
    EXPECT_TRUE(matforge({"report", (work / "none.json").string(), "-o", (work / "r").string(), "--previews",
                          (work / "missing").string()},
                         2));
}

// The report writes only inside -o, never through a link there: a link named like one of its
// files (or folders) pointing outside is refused, the target untouched. A folder that holds
// anything a report did not write is refused before anything is written (exit 2).
TEST(ReportCli, NeverWritesThroughALinkInItsFolder) {
    const fs::path work = temp_dir("links");
    const fs::path set = samples() / "Metal_Damaged_001_SD";
    ASSERT_TRUE(matforge({"ingest", set.string(), "-o", (work / "out").string(), "-q"}));
    const std::string manifest = (work / "out/manifest.json").string();
    std::ofstream(work / "victim.html") << "the user's page";
    fs::create_directories(work / "victims");
    fs::create_directories(work / "report");
    fs::create_symlink(work / "victim.html", work / "report/index.html");
    EXPECT_TRUE(matforge({"report", manifest, "-o", (work / "report").string(), "-q"}, 2));
    EXPECT_EQ(read_text(work / "victim.html"), "the user's page");
    EXPECT_EQ(fs::directory_iterator(work / "report")->path().filename(), "index.html") << "nothing written";
    // A folder an earlier report wrote, whose material folder became a link: refused there.
    fs::remove(work / "report/index.html");
    ASSERT_TRUE(matforge({"report", manifest, "-o", (work / "report").string(), "-q"}));
    fs::remove_all(work / "report/Metal_Damaged_001");
    fs::create_symlink(work / "victims", work / "report/Metal_Damaged_001");
    EXPECT_TRUE(matforge({"report", manifest, "-o", (work / "report").string(), "-q"}, 1));
    EXPECT_TRUE(fs::is_empty(work / "victims"));
    // A user's folder with a file of theirs: refused, untouched.
    fs::create_directories(work / "docs");
    std::ofstream(work / "docs/index.html") << "<html>the user's own page</html>";
    EXPECT_TRUE(matforge({"report", manifest, "-o", (work / "docs").string(), "-q"}, 2));
    EXPECT_EQ(read_text(work / "docs/index.html"), "<html>the user's own page</html>");
}

// The report's folder is its own: not the ingest output folder (which holds what the manifest
// lists), not inside a material's source set (the next ingest would read its pictures as maps).
TEST(ReportCli, ReportFolderIsNeverInASetOrTheOutputFolder) {
    const fs::path work = temp_dir("placement");
    fs::create_directories(work / "lib");
    fs::copy(samples() / "Net004A_1K-JPG", work / "lib/Net004A_1K-JPG", fs::copy_options::recursive);
    ASSERT_TRUE(matforge({"ingest", (work / "lib").string(), "-o", (work / "out").string(), "-q"}));
    const fs::path manifest = work / "out/manifest.json";
    for (const fs::path& bad : {work / "lib/Net004A_1K-JPG", work / "lib/Net004A_1K-JPG/report", work / "out"}) {
        EXPECT_TRUE(matforge({"report", manifest.string(), "-o", bad.string(), "-q"}, 2)) << bad;
        EXPECT_FALSE(fs::exists(bad / "index.html")) << bad;
    }
    EXPECT_TRUE(matforge({"report", manifest.string(), "-o", (work / "out/report").string(), "-q"}));
    EXPECT_TRUE(matforge({"report", manifest.string(), "-o", (work / "lib/report").string(), "-q"}));
}

// Memory is bounded by what a material needs as it is written: an 8-bit picture is held as its
// codes, thumbnails and overlays are reduced row by row, materials lease from a budget as
// ingest's sets do. A 4096² material (RGBA albedo, ORM): the report's peak stays far below the
// 910 MB that float pictures and their full-size copies took (issue 24's measurement).
TEST(ReportCli, MemoryIsBoundedByTheMaterialsCodes) {
    const fs::path work = temp_dir("memory");
    const int n = 4096;
    mf::Image8 albedo(n, n, 4), rough(n, n, 1), metal(n, n, 1);
    uint32_t s = 7;
    for (auto* img : {&albedo, &rough, &metal})
        for (uint8_t& v : img->pixels) v = static_cast<uint8_t>((s = s * 1664525u + 1013904223u) >> 24);
    for (size_t p = 3; p < albedo.pixels.size(); p += 4) albedo.pixels[p] = 255;
    fs::create_directories(work / "src/Big");
    for (const auto& [file, img] : {std::pair{"Big_Color.png", &albedo}, std::pair{"Big_Roughness.png", &rough},
                                    std::pair{"Big_Metalness.png", &metal}}) {
        std::vector<unsigned char> bytes;
        std::string err;
        ASSERT_TRUE(mf::encode_image(*img, mf::EncodeOptions{mf::FileFormat::png, 8}, bytes, err)) << err;
        ASSERT_TRUE(mf::write_file_atomic(work / "src/Big" / file, bytes, err)) << err;
    }
    ASSERT_TRUE(matforge({"ingest", (work / "src").string(), "-o", (work / "out").string(), "-q", "--no-cache"}));
    const auto p = mf::testbin::spawn({mf::testenv::bin(), "report", (work / "out/manifest.json").string(), "-o",
                                       (work / "report").string(), "-q", "--jobs", "2"});
    ASSERT_EQ(p.code, 0) << p.output;
    EXPECT_LT(p.maxrss_kb, 400 * 1024) << "peak resident memory of the report";
    EXPECT_TRUE(fs::exists(work / "report/Big/albedo-range.png"));
}

// validate writes the same page (its manifest has no outputs): each set's card with its
// findings, and the albedo overlay judged on the source maps, its shares the findings'.
TEST(ReportCli, ValidateWritesThePageWithTheFindingsShares) {
    const fs::path work = temp_dir("validate-html");
    const fs::path corpus = mf::testenv::corpus_dir() / "real";
    const fs::path sets[] = {corpus / "3dtextures_Metal_Rusted_010", corpus / "ambientcg_Net004A_1K-JPG",
                             corpus / "polyhaven_brown_planks_09_1k_jpg+webp"};
    std::vector<std::string> args{"validate"};
    for (const auto& s : sets) args.push_back(s.string());
    for (const std::string& a : std::vector<std::string>{"--report", "json", "--report-file",
                                                         (work / "v.json").string(), "--fail-on", "never"})
        args.push_back(a);
    ASSERT_TRUE(matforge(args));
    args.erase(args.end() - 5, args.end());
    for (const std::string& a :
         std::vector<std::string>{"html", "--report-file", (work / "page").string(), "--fail-on", "never"})
        args.push_back(a);
    ASSERT_TRUE(matforge(args));
    const auto report = read_json(work / "v.json");
    const std::string html = read_text(work / "page/index.html");
    EXPECT_NE(html.find("<title>matforge report — matforge validate</title>"), std::string::npos);
    ASSERT_EQ(report["materials"].size(), 3u);
    int raised = 0;
    for (const auto& m : report["materials"]) {
        const std::string card = card_of(html, markup_escape(m["name"].get<std::string>()));
        ASSERT_FALSE(card.empty()) << m["name"];
        EXPECT_NE(card.find("albedo luminance of the source map"), std::string::npos) << m["name"];
        for (const auto& f : m["findings"]) {
            EXPECT_NE(card.find("data-code=\"" + f["code"].get<std::string>() + "\""), std::string::npos)
                << m["name"] << " " << f["code"];
            if (!f["figures"].contains("surface_share")) continue;
            const std::string key = "class=\"share\" data-code=\"" + f["code"].get<std::string>() + "\">";
            const size_t at = card.find(key);
            ASSERT_NE(at, std::string::npos) << m["name"] << " " << f["code"];
            EXPECT_EQ(card.substr(at + key.size(), card.find("</span>", at) - at - key.size()),
                      mf::percent(f["figures"]["surface_share"].get<double>()))
                << m["name"] << " " << f["code"];
            ++raised;
        }
    }
    EXPECT_GE(raised, 2) << "Metal_Rusted_010 and Net004A have dark albedos";
    // The page needs a folder: without --report-file it is a usage error, and nothing is read.
    EXPECT_TRUE(matforge({"validate", sets[0].string(), "--report", "html"}, 2));
    // Never in a set's folder (the next run would read its pictures as maps).
    EXPECT_TRUE(matforge({"validate", sets[0].string(), "--report", "html", "--report-file",
                          (work / "copy").string()}));
    fs::create_directories(work / "lib");
    fs::copy(sets[0], work / "lib/set", fs::copy_options::recursive);
    EXPECT_TRUE(matforge({"validate", (work / "lib").string(), "--report", "html", "--report-file",
                          (work / "lib/set/page").string()},
                         2));
    EXPECT_FALSE(fs::exists(work / "lib/set/page"));
}

// The GPU presets' outputs (.dds, .ktx2) are shown as the engine samples them: level 0 decoded
// by the codec that wrote it (BC1/BC3 colour, BC4 scalars, BC5 normals with Z rebuilt, ASTC), close to
// the same map's PNG output of the gltf preset, with nothing "not shown" and no error line.
TEST(ReportCli, BlockCompressedOutputsAreShownAsTheEngineSamplesThem) {
    const fs::path work = temp_dir("gpu");
    ASSERT_TRUE(matforge({"ingest", samples().string(), "-o", (work / "out").string(), "--preset",
                          "gltf,d3d11,vulkan-ktx2,vulkan-ktx2-astc", "-q", "--fail-on", "never"}));
    // The thumbnail of each material's albedo and normal output in a preset's report.
    auto thumbs = [&](const std::string& preset) {
        const auto report = work / ("report-" + preset);
        const auto p = mf::testbin::spawn({mf::testenv::bin(), "report",
                                           (work / "out" / preset / "manifest.json").string(), "-o", report.string(),
                                           "--thumb-size", "128"},
                                          300);
        EXPECT_EQ(p.code, 0) << p.output;
        EXPECT_EQ(p.output.find(".dds:"), std::string::npos) << p.output;
        EXPECT_EQ(p.output.find(".ktx2:"), std::string::npos) << p.output;
        EXPECT_EQ(read_text(report / "index.html").find("not shown"), std::string::npos) << preset;
        // "<material>/albedo" | "<material>/normal" -> the thumbnail and the normal's convention
        std::map<std::string, std::pair<fs::path, std::string>> found;
        const nlohmann::json manifest = read_json(work / "out" / preset / "manifest.json");
        for (const auto& m : manifest["materials"])
            for (const auto& o : m["outputs"]) {
                const auto rgb = o["channels"].value("RGB", std::string());
                if (rgb != "albedo" && rgb != "normal") continue;
                const fs::path file = o["file"].get<std::string>();
                found[m["name"].get<std::string>() + "/" + rgb] = {report / file.parent_path() /
                                                                       ("out-" + file.stem().string() + ".png"),
                                                                   o.value("normal_convention", std::string())};
            }
        return found;
    };
    const auto png = thumbs("gltf");
    ASSERT_EQ(png.size(), 8u);  // four sets, an albedo and a normal each
    for (const std::string preset : {"d3d11", "vulkan-ktx2", "vulkan-ktx2-astc"}) {
        const auto gpu = thumbs(preset);
        ASSERT_EQ(gpu.size(), 8u) << preset;
        for (const auto& [what, thumb] : gpu) {
            SCOPED_TRACE(preset + " " + what);
            const mf::Image a = read_pixels(png.at(what).first);
            mf::Image b = read_pixels(thumb.first);
            // d3d11 writes DirectX normals, gltf OpenGL ones: the same surface with green flipped.
            if (thumb.second != png.at(what).second)
                for (size_t i = 1; i < b.pixels.size(); i += 3) b.pixels[i] = 1.f - b.pixels[i];
            ASSERT_EQ(a.width, b.width);
            ASSERT_EQ(a.height, b.height);
            ASSERT_EQ(a.channels, b.channels);  // a grey blue channel would make the normal one channel
            double se = 0;
            for (size_t i = 0; i < a.pixels.size(); ++i) se += std::pow(double(a.pixels[i]) - double(b.pixels[i]), 2);
            const double psnr = 10 * std::log10(double(a.pixels.size()) / std::max(se, 1e-12));
            // A thumbnail averages blocks' errors away: BC1 level 0 is 37-46 dB here, its
            // thumbnail well above; a normal without its Z (blue 0) would be under 10 dB.
            EXPECT_GT(psnr, 36.0);
            std::cout << preset << " " << what << ": thumbnail " << psnr << " dB\n";
        }
    }
}
