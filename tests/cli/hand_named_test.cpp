// Folders someone named by hand (issue 26): real CC0 pixels from the corpus, renamed the way
// tutorials and hand-made game folders name them, through the binary.
#include <OpenImageIO/imageio.h>

#include <map>

#include "cli_util.hpp"
#include "core/text.hpp"

using namespace mft;

namespace {

// The manifest entry of the only material of an ingest of `set`.
nlohmann::json ingest_one(const fs::path& set, const fs::path& out) {
    const auto r = run("ingest " + q(set) + " -o " + q(out) + " --preset gltf --no-cache -q");
    EXPECT_LE(r.code, 1) << r.output;
    const nlohmann::json m = read_json(out / "manifest.json");
    EXPECT_EQ(m["materials"].size(), 1u) << m.dump(1);
    return m["materials"].empty() ? nlohmann::json() : m["materials"][0];
}

bool has_code(const nlohmann::json& mat, const std::string& code, const std::string& role = "") {
    for (const auto& f : mat["findings"])
        if (f["code"] == code && (role.empty() || f.value("role", "") == role)) return true;
    return false;
}

// The material's height output (channel R of the output holding it) is `height` (white = high),
// within a code, on every 7th texel.
void expect_height_output(const nlohmann::json& mat, const fs::path& out, const mf::Image& height) {
    const nlohmann::json* hout = output_with(mat, "R", "height");
    ASSERT_NE(hout, nullptr) << mat["outputs"].dump(1);
    const mf::Image written = read_pixels(out / (*hout)["file"].get<std::string>());
    ASSERT_EQ(written.width, height.width);
    double err = 0;
    for (int y = 0; y < height.height; y += 7)
        for (int x = 0; x < height.width; x += 7)
            err = std::max(err, std::abs(double{written.at(x, y, 0)} - height.at(x, y, 0)));
    EXPECT_LT(err, 1.0 / 255) << "the height output is white = high";
}

}  // namespace

// `Platform2.jpg` beside `PLatform2_Normal.jpg` and `Platform2_disp.png` (another letter case):
// the untagged file named as the set is its colour map, not an unrecognized file beside a grey
// constant albedo and a false MISSING_MAP.
TEST(HandNamed, UntaggedFileNamedAsTheSetIsItsColourMap) {
    const fs::path work = temp_dir("untagged");
    const fs::path src = corpus_set("3dtextures_Metal_Damaged_001_SD");
    const fs::path set = work / "Platform2";
    fs::create_directories(set);
    fs::copy_file(src / "Metal_Damaged_001_basecolor.jpg", set / "Platform2.jpg");
    fs::copy_file(src / "Metal_Damaged_001_normal.jpg", set / "PLatform2_Normal.jpg");
    fs::copy_file(src / "Metal_Damaged_001_height.png", set / "Platform2_disp.png");
    // Another untagged image, named otherwise, does not compete (Godot's demo: texture_bricks.jpg
    // beside an untagged texture_bricks_<word>.jpg lost its colour map).
    fs::copy_file(src / "Metal_Damaged_001_normal.jpg", set / "Platform2_sketch.jpg");
    const nlohmann::json mat = ingest_one(set, work / "out");
    EXPECT_EQ(mat["inputs"]["albedo"]["file"], "Platform2.jpg") << mat["inputs"].dump(1);
    EXPECT_EQ(mat["inputs"]["albedo"]["rule"], "untagged:the set's name, beside its tagged maps");
    EXPECT_FALSE(has_code(mat, "MISSING_MAP", "albedo")) << mat["findings"].dump(1);
    size_t unrecognized = 0;
    for (const auto& f : mat["findings"])
        if (f["code"] == "UNRECOGNIZED_FILE") {
            ++unrecognized;
            EXPECT_EQ(f["file"], "Platform2_sketch.jpg") << f.dump();
        }
    EXPECT_EQ(unrecognized, 1u) << mat["findings"].dump(1);
    EXPECT_FALSE(mat["constants"].contains("albedo"));
    // The base color holds the file's pixels, not a constant.
    const mf::Image base = read_pixels(work / "out" / mat["outputs"][0]["file"].get<std::string>());
    const mf::Image want = read_pixels(set / "Platform2.jpg");
    ASSERT_EQ(base.width, want.width);
    for (int x = 0; x < base.width; x += 97)
        EXPECT_NEAR(base.at(x, base.height / 2, 0), want.at(x, want.height / 2, 0), 1.5 / 255) << x;
}

// Not when the name is someone else's, when two untagged files compete, when the set has its
// colour map, or in an ambientCG download (its untagged "<id>.png" is the vendor's preview).
TEST(HandNamed, UntaggedFilesStayUnrecognizedOtherwise) {
    const fs::path work = temp_dir("untagged-not");
    const fs::path src = corpus_set("3dtextures_Metal_Damaged_001_SD");
    auto make = [&](const std::string& name, const std::vector<std::pair<std::string, std::string>>& files) {
        const fs::path set = work / name;
        fs::create_directories(set);
        for (const auto& [from, to] : files) fs::copy_file(src / from, set / to);
        return set;
    };
    const std::string color = "Metal_Damaged_001_basecolor.jpg", normal = "Metal_Damaged_001_normal.jpg";
    for (const fs::path& set :
         {make("Other", {{color, "Crate.jpg"}, {normal, "Platform_Normal.jpg"}}),
          make("Two", {{color, "Platform.jpg"}, {color, "Platform.png"}, {normal, "Platform_Normal.jpg"}}),
          make("Has", {{color, "Platform.jpg"}, {color, "Platform_Color.jpg"}, {normal, "Platform_Normal.jpg"}})}) {
        const nlohmann::json mat = ingest_one(set, work / ("out-" + set.filename().string()));
        EXPECT_TRUE(has_code(mat, "UNRECOGNIZED_FILE")) << set << mat["findings"].dump(1);
        if (set.filename() == "Has") EXPECT_EQ(mat["inputs"]["albedo"]["file"], "Platform_Color.jpg");
        else EXPECT_FALSE(mat["inputs"].contains("albedo")) << set;
    }
    const fs::path ambient = work / "Net004A_1K-JPG";
    fs::create_directories(ambient);
    for (const char* f : {"Net004A.png", "Net004A_1K-JPG_NormalGL.jpg", "Net004A_1K-JPG_Roughness.jpg"})
        fs::copy_file(corpus_set("ambientcg_Net004A_1K-JPG") / f, ambient / f);
    const nlohmann::json mat = ingest_one(ambient, work / "out-ambient");
    EXPECT_FALSE(mat["inputs"].contains("albedo")) << mat["inputs"].dump(1);
    EXPECT_EQ(mat["inputs"]["preview"]["file"], "Net004A.png") << mat["inputs"].dump(1);  // the vendor's preview
}

// A folder holding Poly Haven's JPEGs and a WebP twin of each at the same size (someone's
// re-encoded copy: Poly Haven ships no WebP): the vendor's JPEG is chosen, and the choice says why.
TEST(HandNamed, VendorJpegBeatsItsWebpTwin) {
    const fs::path work = temp_dir("webp-twin");
    const fs::path src = corpus_set("polyhaven_brown_planks_09_1k_jpg+webp");
    const fs::path set = work / "brown_planks_09";
    fs::create_directories(set);
    for (const char* f : {"brown_planks_09_diff_1k", "brown_planks_09_nor_gl_1k", "brown_planks_09_arm_1k"}) {
        const fs::path jpg = set / (std::string(f) + ".jpg");
        fs::copy_file(src / jpg.filename(), jpg);
        const mf::Image img = read_pixels(jpg);
        std::vector<uint8_t> codes(img.pixels.size());
        for (size_t i = 0; i < codes.size(); ++i) codes[i] = mf::quantize8(img.pixels[i]);
        const fs::path webp = set / (std::string(f) + ".webp");
        auto out = OIIO::ImageOutput::create(webp.string());
        ASSERT_TRUE(out);
        const OIIO::ImageSpec spec(img.width, img.height, img.channels, OIIO::TypeDesc::UINT8);
        ASSERT_TRUE(out->open(webp.string(), spec) && out->write_image(OIIO::TypeDesc::UINT8, codes.data()) &&
                    out->close());
    }
    const nlohmann::json mat = ingest_one(set, work / "out");
    EXPECT_EQ(mat["inputs"]["albedo"]["file"], "brown_planks_09_diff_1k.jpg");
    EXPECT_EQ(mat["inputs"]["normal"]["file"], "brown_planks_09_nor_gl_1k.jpg");
    bool said = false;
    for (const auto& f : mat["findings"])
        if (f["code"] == "AMBIGUOUS_MAP" && f["role"] == "albedo")
            said = f["message"].get<std::string>().find("its format (jpg) ranks above webp (the vendor's own") !=
                   std::string::npos;
    EXPECT_TRUE(said) << mat["findings"].dump(1);
}

// A displacement map stored as depth (white = deep) beside a normal map whose name says nothing:
// the GL/DX test reads the pair through the relative sign of its two correlations, so a DirectX
// normal map is still found DirectX (and converted), a GL one GL; the height is recorded as
// depth and written white = high. Real pixels: 3dtextures.me's Metal_Damaged_001 (GL normal,
// height map), the green flipped for DX and the height inverted for depth.
TEST(HandNamed, DepthMapBesideADxOrGlNormalMap) {
    const fs::path work = temp_dir("depth");
    const fs::path src = corpus_set("3dtextures_Metal_Damaged_001_SD");
    const mf::Image height = read_pixels(src / "Metal_Damaged_001_height.png");
    mf::Image depth = height;
    for (float& v : depth.pixels) v = 1.f - v;
    for (const std::string conv : {"dx", "gl"}) {
        SCOPED_TRACE(conv);
        const fs::path set = work / conv / "Plate";
        fs::create_directories(set);
        fs::copy_file(src / "Metal_Damaged_001_basecolor.jpg", set / "Plate_Diffuse.jpg");
        mf::Image normal = read_pixels(src / "Metal_Damaged_001_normal.jpg");
        if (conv == "dx")
            for (size_t i = 1; i < normal.pixels.size(); i += 3) normal.pixels[i] = 1.f - normal.pixels[i];
        write_png(set / "Plate_nrm.png", normal);
        write_png(set / "Plate_disp.png", depth, 16);
        const fs::path out = work / conv / "out";
        const auto r = run("ingest " + q(set) + " -o " + q(out) + " --preset unity-hdrp --no-cache -q");
        ASSERT_LE(r.code, 1) << r.output;
        const nlohmann::json m = read_json(out / "manifest.json");
        ASSERT_EQ(m["materials"].size(), 1u);
        const nlohmann::json& mat = m["materials"][0];
        const nlohmann::json& in = mat["inputs"]["normal"];
        EXPECT_EQ(in["normal_convention"], conv) << mat["findings"].dump(1);
        EXPECT_EQ(in["normal_convention_source"], "content");
        EXPECT_GE(in["normal_convention_confidence"].get<double>(), 0.6);
        EXPECT_EQ(mat["inputs"]["height"]["stored_as_depth"], true) << mat["inputs"].dump(1);
        EXPECT_TRUE(has_code(mat, "HEIGHT_STORED_AS_DEPTH", "height")) << mat["findings"].dump(1);
        EXPECT_FALSE(has_code(mat, "NORMAL_CONVENTION_UNKNOWN")) << mat["findings"].dump(1);
        EXPECT_FALSE(has_code(mat, "GLOSS_INVERTED"));
        // The normal output is the preset's GL, converted from DX where the input was DX; the
        // height output holds the original height (white = high), not the depth.
        const nlohmann::json* nout = output_with(mat, "RGB", "normal");
        ASSERT_NE(nout, nullptr);
        EXPECT_EQ(nout->contains("normal_converted_from"), conv == "dx") << nout->dump();
        expect_height_output(mat, out, height);
    }
    // The same set with the height stored white = high: no depth, no finding.
    const fs::path set = work / "height" / "Plate";
    fs::create_directories(set);
    fs::copy_file(src / "Metal_Damaged_001_basecolor.jpg", set / "Plate_Diffuse.jpg");
    fs::copy_file(src / "Metal_Damaged_001_normal.jpg", set / "Plate_nrm.jpg");
    fs::copy_file(src / "Metal_Damaged_001_height.png", set / "Plate_disp.png");
    const nlohmann::json mat = ingest_one(set, work / "height" / "out");
    EXPECT_EQ(mat["inputs"]["normal"]["normal_convention"], "gl");
    EXPECT_FALSE(mat["inputs"]["height"].contains("stored_as_depth"));
    EXPECT_FALSE(has_code(mat, "HEIGHT_STORED_AS_DEPTH"));
}

// Godot 3's parallax maps are named depth ("rock_depth.jpg", godotengine/godot-demo-projects
// 3d/material_testers): white = deep. Read as the height, inverted, and said: by the normal map's
// slopes where there is one, by the name where there is none; a map named depth whose slopes
// show height stays as it is. They were unrecognized files before, the sets without height.
TEST(HandNamed, MapsNamedDepthAreHeightStoredAsDepth) {
    const fs::path work = temp_dir("named-depth");
    const fs::path src = corpus_set("3dtextures_Metal_Damaged_001_SD");
    const mf::Image height = read_pixels(src / "Metal_Damaged_001_height.png");
    mf::Image depth = height;
    for (float& v : depth.pixels) v = 1.f - v;
    struct Case {
        std::string name;
        bool normal, stored_depth, inverted;
        std::string why;
    };
    for (const Case& c :
         {Case{"slopes", true, true, true, "its slopes run against the normal map's"},
          Case{"name", false, true, true, "its name says so"}, Case{"height", true, false, false, ""}}) {
        SCOPED_TRACE(c.name);
        const fs::path set = work / c.name / "rock";
        fs::create_directories(set);
        fs::copy_file(src / "Metal_Damaged_001_basecolor.jpg", set / "rock_albedo.jpg");
        if (c.normal) fs::copy_file(src / "Metal_Damaged_001_normal.jpg", set / "rock_normal.jpg");
        write_png(set / "rock_depth.png", c.stored_depth ? depth : height, 16);
        const fs::path out = work / c.name / "out";
        const auto r = run("ingest " + q(set) + " -o " + q(out) + " --preset unity-hdrp --no-cache -q");
        ASSERT_LE(r.code, 1) << r.output;
        const nlohmann::json mat = read_json(out / "manifest.json")["materials"][0];
        EXPECT_EQ(mat["inputs"]["height"]["file"], "rock_depth.png") << mat["inputs"].dump(1);
        EXPECT_EQ(mat["inputs"]["height"]["rule"], "generic:depth");
        EXPECT_EQ(mat["inputs"]["height"].value("stored_as_depth", false), c.inverted);
        bool said = false;
        for (const auto& f : mat["findings"])
            if (f["code"] == "HEIGHT_STORED_AS_DEPTH")
                said = f["message"].get<std::string>().find(c.why) != std::string::npos;
        EXPECT_EQ(said, c.inverted) << mat["findings"].dump(1);
        expect_height_output(mat, out, height);
    }
}

// A normal map under a scalar role's name (Godot's demo material_testers: "rock_metal.jpg" is the
// normal_texture of its rock.tres) in a set without a normal map is the normal map, said as a
// warning; a grey metalness map is never taken for one, nor is any map where a normal map is named.
TEST(HandNamed, ANormalMapNamedMetalIsTheNormalMap) {
    const fs::path work = temp_dir("named-metal");
    const fs::path src = corpus_set("3dtextures_Metal_Damaged_001_SD");
    const fs::path set = work / "rock";
    fs::create_directories(set);
    fs::copy_file(src / "Metal_Damaged_001_basecolor.jpg", set / "rock_albedo.jpg");
    fs::copy_file(src / "Metal_Damaged_001_normal.jpg", set / "rock_metal.jpg");
    fs::copy_file(src / "Metal_Damaged_001_roughness.jpg", set / "rock_rough.jpg");
    nlohmann::json mat = ingest_one(set, work / "out");
    EXPECT_EQ(mat["inputs"]["normal"]["file"], "rock_metal.jpg") << mat["inputs"].dump(1);
    EXPECT_FALSE(mat["inputs"].contains("metalness"));
    EXPECT_EQ(mat["inputs"]["normal"]["normal_convention"], "gl") << "its pixels decide its convention too";
    size_t said = 0;
    for (const auto& f : mat["findings"])
        if (f["code"] == "ROLE_FROM_PIXELS") {
            ++said;
            EXPECT_EQ(f["severity"], "warning");
            EXPECT_EQ(f["file"], "rock_metal.jpg");
            EXPECT_EQ(f["figures"]["named"], "metalness");
        }
    EXPECT_EQ(said, 1u) << mat["findings"].dump(1);
    // A grey map named metal stays metalness; beside a named normal map, nothing is looked at.
    for (const std::string which : {"grey", "beside"}) {
        SCOPED_TRACE(which);
        const fs::path other = work / which / "rock";
        fs::create_directories(other);
        fs::copy_file(src / "Metal_Damaged_001_basecolor.jpg", other / "rock_albedo.jpg");
        fs::copy_file(src / (which == "grey" ? "Metal_Damaged_001_metallic.jpg" : "Metal_Damaged_001_normal.jpg"),
                      other / "rock_metal.jpg");
        if (which == "beside") fs::copy_file(src / "Metal_Damaged_001_normal.jpg", other / "rock_normal.jpg");
        mat = ingest_one(other, work / which / "out");
        EXPECT_EQ(mat["inputs"]["metalness"]["file"], "rock_metal.jpg") << mat["inputs"].dump(1);
        EXPECT_FALSE(has_code(mat, "ROLE_FROM_PIXELS")) << mat["findings"].dump(1);
    }
}

// --rules excludes a file by name: 3dtextures.me's all-black opacity placeholder is left out
// (an unrecognized file saying why), so the material has no opacity at all; ingest and
// validate alike.
TEST(HandNamed, RulesExcludeAFileByName) {
    const fs::path work = temp_dir("exclude");
    const fs::path set = corpus_set("3dtextures_Fabric_polyester_003_SD");
    write_text(work / "rules.json",
               R"({"exclude": [{"file": "*_opacity.jpg", "reason": "the vendor's all-black placeholder"}]})");
    const auto r = run("ingest " + q(set) + " -o " + q(work / "out") + " --rules " + q(work / "rules.json") +
                       " --no-cache -q");
    ASSERT_EQ(r.code, 0) << r.output;
    const nlohmann::json mat = read_json(work / "out/manifest.json")["materials"][0];
    EXPECT_FALSE(mat["inputs"].contains("opacity")) << mat["inputs"].dump(1);
    EXPECT_FALSE(has_code(mat, "OPACITY_ALL_TRANSPARENT"));
    bool said = false;
    for (const auto& f : mat["findings"])
        said = said || (f["code"] == "UNRECOGNIZED_FILE" && f["file"] == "Fabric_polyester_003_opacity.jpg" &&
                        f["message"].get<std::string>().find("excluded by the rules (\"*_opacity.jpg\": the vendor's "
                                                             "all-black placeholder)") != std::string::npos);
    EXPECT_TRUE(said) << mat["findings"].dump(1);
    const auto v = run("validate " + q(set) + " --rules " + q(work / "rules.json") + " --report json --report-file " +
                       q(work / "v.json"));
    EXPECT_EQ(v.code, 0) << v.output;
    auto codes = [](const nlohmann::json& findings) {
        std::vector<std::string> list;
        for (const auto& f : findings) list.push_back(f["code"].get<std::string>() + " " + f.value("file", ""));
        return list;
    };
    EXPECT_EQ(codes(read_json(work / "v.json")["materials"][0]["findings"]), codes(mat["findings"]));
}

// Metalness painted between the classes (issue 26 item 5), on real albedos: each pixel counts
// toward the metal and the dielectric checks by its metalness ((m - 0.1) / 0.8, so 0.8 is 7/8
// metal), where it used to count toward neither. Poly Haven's brown planks (all below 180 sRGB)
// painted 0.8 are a dark metal on 7/8 of the surface; 3dtextures.me's obsidian (all below
// 30 sRGB) painted 0.5 is half a dark dielectric and half a dark metal; the planks at metalness
// 0 stay an ordinary dielectric. validate's HTML page shows the findings' own shares.
TEST(HandNamed, HalfMetalMapsMeetTheMetalChecks) {
    const fs::path work = temp_dir("half-metal");
    auto make = [&](const std::string& name, const fs::path& albedo, float metalness) {
        const fs::path set = work / "lib" / name;
        fs::create_directories(set);
        fs::copy_file(albedo, set / (name + "_basecolor.jpg"));
        const mf::Image a = read_pixels(albedo);
        mf::Image m(a.width, a.height, 1);
        for (float& v : m.pixels) v = metalness;
        write_png(set / (name + "_metallic.png"), m);
    };
    make("Planks08", corpus_set("polyhaven_brown_planks_09_1k_jpg+webp") / "brown_planks_09_diff_1k.jpg", 204 / 255.f);
    make("Obsidian05", corpus_set("3dtextures_Obsidian_001") / "Obsidian_001_basecolor.jpg", 128 / 255.f);
    make("Wood0", corpus_set("polyhaven_brown_planks_09_1k_jpg+webp") / "brown_planks_09_diff_1k.jpg", 0.f);
    const auto v = run("validate " + q(work / "lib") + " --report json --report-file " + q(work / "v.json") +
                       " --fail-on never");
    ASSERT_EQ(v.code, 0) << v.output;
    const auto h = run("validate " + q(work / "lib") + " --report html --report-file " + q(work / "page") +
                       " --fail-on never");
    ASSERT_EQ(h.code, 0) << h.output;
    const nlohmann::json report = read_json(work / "v.json");
    const std::string html = bytes_of(work / "page/index.html");
    auto share = [&](const nlohmann::json& mat, const std::string& code) -> double {
        for (const auto& f : mat["findings"])
            if (f["code"] == code) return f["figures"]["surface_share"].get<double>();
        return -1;
    };
    std::map<std::string, nlohmann::json> by_name;
    for (const auto& m : report["materials"]) by_name[m["name"].get<std::string>()] = m;
    ASSERT_EQ(by_name.size(), 3u) << report.dump(1);
    // 204/255 = 0.8: weight (0.8 - 0.1) / 0.8 = 0.875 on every pixel; 99.4 % of them darker than 180.
    const double planks = share(by_name["Planks08"], "METAL_ALBEDO_TOO_DARK");
    EXPECT_GT(planks, 0.85) << by_name["Planks08"].dump(1);
    EXPECT_LE(planks, 0.875);
    EXPECT_LT(share(by_name["Planks08"], "ALBEDO_TOO_DARK"), 0);
    // 128/255 = 0.502: weight 0.5025 metal, 0.4975 dielectric; obsidian is darker than 30 almost everywhere.
    EXPECT_NEAR(share(by_name["Obsidian05"], "METAL_ALBEDO_TOO_DARK"), 0.5025, 0.01);
    EXPECT_NEAR(share(by_name["Obsidian05"], "ALBEDO_TOO_DARK"), 0.4975, 0.03);
    EXPECT_LT(share(by_name["Wood0"], "METAL_ALBEDO_TOO_DARK"), 0);
    EXPECT_LT(share(by_name["Wood0"], "ALBEDO_TOO_DARK"), 0) << by_name["Wood0"].dump(1);
    for (const auto& [name, mat] : by_name) {
        for (const auto& f : mat["findings"]) {
            if (!f["figures"].contains("surface_share")) continue;
            const size_t from = html.find("data-material=\"" + name + "\"");
            ASSERT_NE(from, std::string::npos) << name;
            const std::string card = html.substr(from, html.find("</section>", from) - from);
            const std::string key = "data-code=\"" + f["code"].get<std::string>() + "\">";
            const size_t at = card.find(key);
            ASSERT_NE(at, std::string::npos) << name << " " << f["code"];
            EXPECT_EQ(card.substr(at + key.size(), card.find("</span>", at) - at - key.size()),
                      mf::percent(f["figures"]["surface_share"].get<double>()))
                << name << " " << f["code"];
        }
    }
}
