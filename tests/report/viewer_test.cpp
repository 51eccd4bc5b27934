// `matforge report --viewer`: each card's interactive view (lib/report/viewer.cpp), opened from
// disk in headless Chromium (WebGL2 on SwiftShader) by tests/report/viewer_check.mjs, against the
// Vulkan previews of `matforge preview` (lavapipe, the default look-dev scene) of the sample
// materials: a textured metal, a cut-out (Net004A), a dielectric and a wood.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <sstream>

#include "render/shaders/interface.h"
#include "report/report.hpp"
#include "report_util.hpp"

using namespace mfr;

namespace mfviewer {

constexpr const char* kChromium = "/usr/bin/chromium";
constexpr int kSize = 256;  // the previews' size, hence the views'
const std::vector<std::string> kShapes = {"sphere", "plane", "shaderball"};
// The bounds a first frame must reach against the preview of its shape (PSNR over RGB, 8-bit),
// measured with SwiftShader against lavapipe at 256²:
//  - kMinPsnrDb: spheres 43.6 dB (Metal_Damaged_001) to 48.2 dB, planes and shaderballs 49 to
//    54 dB. The views of Metal_Damaged_001 broken on purpose (the test's variants) measured
//    22.4 dB (no tone mapping), 25.7 (the un-normalized Lambert), 26.6 (the normal map's green
//    read the other way) and 27.3 (the environment's ±Z faces swapped).
//  - kMinPsnrCutoutDb, for an alpha-tested material (Net004A): its hard edges flip where the
//    filtered opacity lies within a code of the cutoff, and the two software samplers filter
//    8-bit texels at different precision: 28.8 dB on the sphere (both sides seen), 37.2 on the
//    shaderball, 42.4 on the plane (1K maps in the view: the same 28.8). Broken on purpose: the
//    far side not drawn 20.3 dB, the mask ignored (opaque) 13.9.
constexpr double kMinPsnrDb = 35.0;
constexpr double kMinPsnrCutoutDb = 27.0;

double psnr_rgb(const mf::Image& a, const mf::Image& b) {
    if (a.width != b.width || a.height != b.height || a.channels < 3 || b.channels < 3) return 0.0;
    double se = 0.0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x)
            for (int c = 0; c < 3; ++c) {
                const double d = static_cast<double>(a.at(x, y, c)) - static_cast<double>(b.at(x, y, c));
                se += d * d;
            }
    const double mse = se / (3.0 * a.width * a.height);
    return mse > 0.0 ? 10.0 * std::log10(1.0 / mse) : 99.0;
}

// The JSON of a file the viewer writes: "prefix(ARGS);" with the data as its last argument.
nlohmann::json data_of(const std::string& js, const std::string& call) {
    const size_t at = js.rfind(call + "(");
    if (at == std::string::npos) return {};
    const size_t open = call == "mfViewer.material" ? js.find(", ", at) + 2 : at + call.size() + 1;
    const size_t close = js.rfind(");");
    return nlohmann::json::parse(js.substr(open, close - open), nullptr, false);
}

// The bytes a page says in its size note (id="viewer-sizes"): "this page is N bytes; the views'
// data M bytes ... (viewer/lookdev.js L bytes once ...; K bytes for n materials' maps)".
std::vector<uint64_t> numbers_in(const std::string& text) {
    std::vector<uint64_t> out;
    std::istringstream in(text);
    std::string word;
    while (in >> word)
        if (!word.empty() && std::isdigit(static_cast<unsigned char>(word[0])) && word.find('.') == std::string::npos)
            out.push_back(std::stoull(word));
    return out;
}

struct Previews {
    fs::path manifest, report;
    std::map<std::string, fs::path> by_shape;  // shape -> preview folder
};

::testing::AssertionResult make_viewer_report(const fs::path& work, Previews& r) {
    r.manifest = work / "out" / "manifest.json";
    r.report = work / "report";
    if (auto a = matforge({"ingest", samples().string(), "-o", (work / "out").string(), "--preset", "gltf", "-q"}); !a)
        return a;
    for (const std::string& shape : kShapes) {
        r.by_shape[shape] = work / ("preview-" + shape);
        if (auto a = matforge({"preview", r.manifest.string(), "-o", r.by_shape[shape].string(), "--device", "cpu",
                               "--size", std::to_string(kSize), "--shape", shape});
            !a)
            return a;
    }
    return matforge({"report", r.manifest.string(), "-o", r.report.string(), "--previews",
                     r.by_shape["sphere"].string(), "--viewer", "-q"});
}

// Runs a node script; `json` receives its one JSON line.
::testing::AssertionResult node_json(const std::vector<std::string>& args, nlohmann::json& json) {
    if (!fs::exists(kChromium))
        return ::testing::AssertionFailure() << kChromium << " is missing (Debian package `chromium`)";
    std::vector<std::string> argv{"node"};
    argv.insert(argv.end(), args.begin(), args.end());
    const auto p = mf::testbin::spawn(argv, 240);
    const size_t at = p.output.find("{\"");
    if (at == std::string::npos)
        return ::testing::AssertionFailure() << args[0] << " printed no JSON (exit " << p.code << "):\n" << p.output;
    json = nlohmann::json::parse(p.output.substr(at, p.output.find('\n', at) - at), nullptr, false);
    if (json.is_discarded() || p.code != 0 || json.value("ok", false) != true)
        return ::testing::AssertionFailure() << args[0] << " failed (exit " << p.code << "):\n" << p.output;
    return ::testing::AssertionSuccess();
}

class ViewerReportTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        work_ = fs::temp_directory_path() / ("matforge-viewer-" + std::to_string(::getpid()));
        fs::remove_all(work_);
        fs::create_directories(work_);
        made_ = make_viewer_report(work_, r_);
        if (made_) manifest_ = read_json(r_.manifest);
    }
    static void TearDownTestSuite() {
        std::error_code ec;
        fs::remove_all(work_, ec);
    }
    void SetUp() override { ASSERT_TRUE(made_) << made_.message(); }
    static std::vector<std::string> names() {
        std::vector<std::string> out;
        for (const auto& m : manifest_["materials"]) out.push_back(m["name"]);
        return out;
    }

    static inline fs::path work_;
    static inline Previews r_;
    static inline ::testing::AssertionResult made_ = ::testing::AssertionFailure();
    static inline nlohmann::json manifest_;
};

}  // namespace mfviewer

using mfviewer::ViewerReportTest;

// The first frame of every view, on every shape, against the Vulkan preview of that shape; the
// views of the first material broken on purpose fail the same bound; nothing but the report's
// own files is requested.
TEST_F(ViewerReportTest, FirstFramesMatchThePreviewsAndBrokenViewsDoNot) {
    namespace gpu = mf::render::gpu;
    const std::vector<std::string> materials = names();
    ASSERT_EQ(materials.size(), 4u);
    // A material's shipped variant (its sphere's): whether its normal map is read green-down and
    // whether it is alpha-tested.
    auto constant = [&](const std::string& name, int id) {
        const nlohmann::json d = mfviewer::data_of(read_text(r_.report / name / "viewer.js"), "mfViewer.material");
        for (const auto& c : d["shapes"]["sphere"]["constants"])
            if (c[0] == id) return c[1].get<int>();
        return -1;
    };
    const std::string metal = "Metal_Damaged_001", cutout = "Net004A";
    ASSERT_EQ(constant(cutout, gpu::kSpecAlphaMode), gpu::kAlphaMask);
    ASSERT_EQ(constant(cutout, gpu::kSpecDoubleSided), 1);
    auto broken = [](const std::string& material, int id, int value) {
        return nlohmann::json{{"material", material},
                              {"options", {{"debug", {{"constants", {{std::to_string(id), value}}}}}}}};
    };
    // What each broken view gets wrong: the un-normalized Lambert (a wrong BRDF), no tone mapping,
    // the normal map's green read the other way (a flipped normal), the environment's +Z and −Z
    // faces swapped (a wrongly oriented environment); the cut-out's far side not drawn, its mask
    // ignored.
    const nlohmann::json variants = {
        {"brdf", broken(metal, gpu::kSpecBrdfModel, gpu::kBrdfUnnormalizedDiffuse)},
        {"tonemap",
         {{"material", metal},
          {"options", {{"output", {{"exposure", 1}, {"srgb", 1}, {"tonemap", gpu::kTonemapNone}}}}}}},
        {"normal", broken(metal, gpu::kSpecNormalGreenDown, constant(metal, gpu::kSpecNormalGreenDown) ? 0 : 1)},
        {"env", {{"material", metal}, {"options", {{"debug", {{"swapZ", true}}}}}}},
        {"single-sided", broken(cutout, gpu::kSpecDoubleSided, 0)},
        {"unmasked", broken(cutout, gpu::kSpecAlphaMode, gpu::kAlphaOpaque)},
    };
    const fs::path shots = work_ / "shots";
    fs::create_directories(shots);
    nlohmann::json j;
    ASSERT_TRUE(mfviewer::node_json({(mf::testenv::source_dir() / "tests/report/viewer_check.mjs").string(), "--page",
                                     (r_.report / "index.html").string(), "--out", shots.string(), "--materials",
                                     nlohmann::json(materials).dump(), "--shapes",
                                     nlohmann::json(mfviewer::kShapes).dump(), "--variants", variants.dump()},
                                    j));
    auto bound = [&](const std::string& name) {
        return name == cutout ? mfviewer::kMinPsnrCutoutDb : mfviewer::kMinPsnrDb;
    };
    auto psnr_against = [&](const std::string& png, const std::string& name, const std::string& shape) {
        const auto preview = mf::report::preview_file(r_.by_shape[shape], name);
        EXPECT_TRUE(preview) << name;
        return preview ? mfviewer::psnr_rgb(read_pixels(png), read_pixels(*preview)) : 0.0;
    };
    ASSERT_EQ(j["frames"].size(), materials.size() * mfviewer::kShapes.size());
    for (const auto& f : j["frames"]) {
        const std::string name = f["material"], shape = f["shape"];
        const double db = psnr_against(f["png"], name, shape);
        std::cout << name << " " << shape << ": " << db << " dB\n";
        EXPECT_GE(db, bound(name)) << name << " on the " << shape;
        if (shape == "sphere") {
            EXPECT_EQ(f["width"], mfviewer::kSize);
            EXPECT_EQ(f["samples"], 4) << "the look-dev scene's 4x MSAA";
            EXPECT_LE(f["camera_diff"].get<double>(), 1e-6) << "the script's camera against the renderer's";
        }
    }
    ASSERT_EQ(j["variants"].size(), variants.size());
    for (const auto& v : j["variants"]) {
        const std::string name = v["material"];
        const double db = psnr_against(v["png"], name, "sphere");
        std::cout << name << " broken (" << v["name"].get<std::string>() << "): " << db << " dB\n";
        EXPECT_LT(db, bound(name)) << v["name"];
    }
    // The page, the views' scripts and the pictures: all files of the report's folder.
    const std::string folder = "file://" + fs::canonical(r_.report).string() + "/";
    ASSERT_FALSE(j["requests"].empty());
    for (const auto& u : j["requests"]) EXPECT_EQ(u.get<std::string>().rfind(folder, 0), 0u) << u;
    EXPECT_TRUE(std::any_of(j["requests"].begin(), j["requests"].end(), [&](const auto& u) {
        return u.template get<std::string>() == folder + "viewer/lookdev.js";
    }));
}

// The page with views still passes the reader's checks: every card and finding, no console
// error, no network, every card without JavaScript.
TEST_F(ViewerReportTest, BrowserCheckPassesWithTheViews) {
    nlohmann::json j;
    ASSERT_TRUE(mfviewer::node_json({(mf::testenv::source_dir() / "scripts/browser-check.mjs").string(), "--page",
                                     (r_.report / "index.html").string(), "--manifest", r_.manifest.string()},
                                    j));
    EXPECT_EQ(j["cards"], manifest_["materials"].size());
    EXPECT_EQ(j["cards_without_js"], manifest_["materials"].size());
}

// The page says its own size and the views' data's, and they are the files' sizes; each card
// says its material's.
TEST_F(ViewerReportTest, PageStatesItsSizeAndTheViewsData) {
    const std::string html = read_text(r_.report / "index.html");
    const size_t at = html.find("id=\"viewer-sizes\">");
    ASSERT_NE(at, std::string::npos);
    const std::string note = html.substr(at, html.find("</p>", at) - at);
    const std::vector<uint64_t> n = mfviewer::numbers_in(note);
    ASSERT_GE(n.size(), 5u) << note;
    uint64_t materials_bytes = 0;
    const std::vector<std::string> all = names(), stems = mf::report::material_stems(all);
    for (size_t i = 0; i < all.size(); ++i) {
        const uint64_t bytes = fs::file_size(r_.report / stems[i] / "viewer.js");
        materials_bytes += bytes;
        EXPECT_NE(card_of(html, all[i]).find(std::to_string((bytes + 512) / 1024) + " KB of maps"), std::string::npos)
            << all[i];
    }
    EXPECT_EQ(n[0], fs::file_size(r_.report / "index.html")) << note;
    EXPECT_EQ(n[2], fs::file_size(r_.report / "viewer" / "lookdev.js")) << note;
    EXPECT_EQ(n[3], materials_bytes) << note;
    EXPECT_EQ(n[4], names().size()) << note;
    EXPECT_EQ(n[1], n[2] + n[3]) << note;
}

// Maps at most 512 on a side, in each material's own file, none of it in index.html; a card's
// button names its file and is hidden until the page's script shows it.
TEST_F(ViewerReportTest, MapsAreBoundedAndLoadedOnlyWithTheirCard) {
    const std::string html = read_text(r_.report / "index.html");
    EXPECT_EQ(html.find("mfViewer.material("), std::string::npos);
    EXPECT_EQ(html.find(";base64,"), std::string::npos);
    EXPECT_NE(html.find("script-src 'unsafe-inline' file:"), std::string::npos);
    const std::vector<std::string> all = names(), stems = mf::report::material_stems(all);
    for (size_t i = 0; i < all.size(); ++i) {
        const std::string card = card_of(html, all[i]);
        EXPECT_NE(card.find("<div class=\"viewer\" hidden data-stem=\"" + stems[i] + "\" data-src=\"" + stems[i] +
                            "/viewer.js\""),
                  std::string::npos)
            << all[i];
        const nlohmann::json d = mfviewer::data_of(read_text(r_.report / stems[i] / "viewer.js"), "mfViewer.material");
        ASSERT_TRUE(d.is_object()) << stems[i];
        int maps = 0;
        for (const auto& t : d["textures"]) {
            if (t.is_null()) continue;
            ++maps;
            EXPECT_LE(std::max(t["width"].get<int>(), t["height"].get<int>()), 512) << stems[i];
            // The sample maps are 1K: each is its 512 mip.
            EXPECT_EQ(std::max(t["width"].get<int>(), t["height"].get<int>()), 512) << stems[i];
        }
        EXPECT_GE(maps, 2) << stems[i] << ": albedo, normal, and the packed ORM";
        EXPECT_EQ(d["shapes"].size(), mfviewer::kShapes.size());
    }
}

// Without --viewer the page is as it was: no view, no script from a file allowed.
TEST_F(ViewerReportTest, WithoutTheFlagThereIsNoView) {
    const fs::path plain = work_ / "report-plain";
    ASSERT_TRUE(matforge({"report", r_.manifest.string(), "-o", plain.string(), "--previews",
                          r_.by_shape["sphere"].string(), "-q"}));
    const std::string html = read_text(plain / "index.html");
    EXPECT_EQ(html.find("class=\"viewer\""), std::string::npos);
    EXPECT_EQ(html.find("viewer-sizes"), std::string::npos);
    EXPECT_NE(html.find("script-src 'unsafe-inline'\""), std::string::npos);
    EXPECT_FALSE(fs::exists(plain / "viewer"));
}
