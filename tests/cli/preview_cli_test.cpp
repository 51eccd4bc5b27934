// The preview reads whatever layout a preset wrote: one source set, every shipped preset, the
// same image (issue: "previews to the same image within 1 code").
#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>

#include "cli_util.hpp"

using namespace mft;

TEST(PreviewCli, EveryPresetPreviewsTheSameImage) {
    const fs::path work = temp_dir("presets");
    // Metal_Damaged_001 (a real 3dtextures.me set): albedo, a GL normal map, roughness and a
    // graded metalness map, occlusion and height. Rendered under an environment it would use
    // occlusion too, so a key light and a fill light suffice to exercise albedo, normal (both
    // conventions), roughness (also as smoothness) and metalness.
    const std::vector<std::string> presets{"gltf", "unreal", "unity-hdrp", "unity-urp", "godot", "separate"};
    std::map<std::string, mf::Image> images;
    for (const auto& p : presets) {
        const fs::path out = work / p;
        auto r = run("ingest " + q(samples() / "Metal_Damaged_001_SD") + " -o " + q(out) + " --preset " + p);
        ASSERT_EQ(r.code, 0) << p << ": " << r.output;
        r = run("preview " + q(out / "manifest.json") + " -o " + q(out / "preview") +
                " --size 96 --device cpu --light dir:0.5,-0.6,-0.62:3 --light point:-2,1,2:12 --shading raster");
        ASSERT_EQ(r.code, 0) << p << ": " << r.output;
        images[p] = read_pixels(out / "preview" / "Metal_Damaged_001.png");
    }
    const mf::Image& ref = images["gltf"];
    ASSERT_EQ(ref.width, 96);
    int lit = 0;
    for (const float pixel : ref.pixels) lit += code8(pixel) > 8;
    EXPECT_GT(lit, 2000) << "the sphere is lit";
    for (const auto& p : presets) {
        const mf::Image& img = images[p];
        ASSERT_EQ(img.pixels.size(), ref.pixels.size()) << p;
        int worst = 0;
        for (size_t i = 0; i < ref.pixels.size(); ++i)
            worst = std::max(worst, std::abs(code8(img.pixels[i]) - code8(ref.pixels[i])));
        EXPECT_LE(worst, 1) << p << " previews differently from gltf";
    }
}

// The preview renders what a GPU preset wrote: the DDS/KTX2 blocks and mip chains as the files
// hold them (BCn sampled by the device, ASTC decoded on the CPU where the device lacks it, BC5
// normals with Z rebuilt in the shader). Against the PNG ingest's preview of the same set, what
// differs is the block-compression error and the file's own mips (Kaiser-filtered at ingest,
// where the renderer box-filters a PNG's): stated bound (docs/preview.md) mean <= 2.5 codes and
// 99.5th percentile <= 20 codes over the lit sphere. The GPU presets are run with their specular
// anti-aliasing off here: it widens the roughness mips on purpose, which the PNG's have not
// (with it: p99.5 31 codes on this 96-pixel sphere, where far mips are sampled). Measured:
// d3d11 0.90 / 11, vulkan-ktx2 0.89 / 12, vulkan-ktx2-astc 0.20 / 2 (BC1: 1.73 / 14, 2.00 / 17).
TEST(PreviewCli, GpuPresetsPreviewLikeThePngIngest) {
    const fs::path work = temp_dir("gpu");
    // The path pinned: the look-dev default (`auto`) could pick either from one run to the next.
    const std::string args =
        " --size 96 --device cpu --light dir:0.5,-0.6,-0.62:3 --light point:-2,1,2:12 --shading raster";
    auto render = [&](const std::string& preset) {
        const fs::path out = work / preset;
        std::string use = preset;
        if (preset != "gltf") {
            auto shown = run("presets show " + preset);
            nlohmann::json p = nlohmann::json::parse(shown.output.substr(shown.output.find('{')));
            p["toksvig"] = false;
            use = (work / (preset + ".json")).string();
            write_text(use, p.dump());
        }
        auto r = run("ingest " + q(samples() / "Metal_Damaged_001_SD") + " -o " + q(out) + " --preset " + q(use));
        EXPECT_EQ(r.code, 0) << preset << ": " << r.output;
        r = run("preview " + q(out / "manifest.json") + " -o " + q(out / "preview") + args);
        EXPECT_EQ(r.code, 0) << preset << ": " << r.output;
        return std::make_pair(read_pixels(out / "preview" / "Metal_Damaged_001.png"), r.output);
    };
    const auto [ref, ref_log] = render("gltf");
    ASSERT_EQ(ref.width, 96);
    for (const std::string preset : {"d3d11", "vulkan-ktx2", "vulkan-ktx2-astc"}) {
        const auto [img, log] = render(preset);
        ASSERT_EQ(img.pixels.size(), ref.pixels.size()) << preset;
        std::vector<int> diffs;
        for (size_t i = 0; i < ref.pixels.size(); ++i)
            if (code8(ref.pixels[i]) > 8 || code8(img.pixels[i]) > 8)
                diffs.push_back(std::abs(code8(img.pixels[i]) - code8(ref.pixels[i])));
        ASSERT_GT(diffs.size(), 2000u) << preset << ": the sphere is lit";
        std::sort(diffs.begin(), diffs.end());
        double mean = 0;
        for (int v : diffs) mean += v;
        mean /= static_cast<double>(diffs.size());
        const int p995 = diffs[diffs.size() * 995 / 1000];
        std::cout << preset << ": mean " << mean << ", p99.5 " << p995 << " codes\n";
        EXPECT_LE(mean, 2.5) << preset << " (p99.5 " << p995 << ", max " << diffs.back() << ")";
        EXPECT_LE(p995, 20) << preset << " (mean " << mean << ", max " << diffs.back() << ")";
        // A compressed preset previews differently from a PNG one, however little: the files
        // themselves were read (BC blocks, not a PNG twin).
        EXPECT_GT(diffs.back(), 0) << preset;
        if (preset == "vulkan-ktx2-astc")  // lavapipe samples BCn but not ASTC
            EXPECT_NE(log.find("decoded on the CPU"), std::string::npos) << log;
        else EXPECT_EQ(log.find("decoded on the CPU"), std::string::npos) << log;
    }
}

// The default scene is the look-dev studio: the metal's side away from the key light still
// reflects the environment (not black as under one light), the background is mid grey through
// PBR Neutral (0.18 linear -> code 105), and `--scene reference` is exactly the scene a scene file
// starts from (an empty scene file gives the same bytes), on black.
TEST(PreviewCli, DefaultIsLookDevAndReferenceIsExact) {
    const fs::path work = temp_dir("lookdev");
    ASSERT_EQ(run("ingest " + q(samples() / "Metal_Damaged_001_SD") + " -o " + q(work / "out")).code, 0);
    const std::string base = "preview " + q(work / "out/manifest.json") + " --size 64 --device cpu -o ";
    ASSERT_EQ(run(base + q(work / "lookdev")).code, 0);
    ASSERT_EQ(run(base + q(work / "reference") + " --scene reference").code, 0);
    write_text(work / "empty.json", "{}");
    ASSERT_EQ(run(base + q(work / "file") + " --scene " + q(work / "empty.json")).code, 0);
    const auto lookdev = read_pixels(work / "lookdev/Metal_Damaged_001.png");
    const auto reference = read_pixels(work / "reference/Metal_Damaged_001.png");
    EXPECT_EQ(bytes_of(work / "reference/Metal_Damaged_001.png"), bytes_of(work / "file/Metal_Damaged_001.png"));
    for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(code8(lookdev.at(0, 0, c)), 105) << "background, channel " << c;
        EXPECT_EQ(code8(reference.at(0, 0, c)), 0) << "background, channel " << c;
    }
    // The lower right of the sphere faces away from the key light (camera left, above).
    auto mean_at = [](const mf::Image& img, int x0, int y0) {
        double sum = 0;
        for (int y = y0; y < y0 + 6; ++y)
            for (int x = x0; x < x0 + 6; ++x)
                for (int c = 0; c < 3; ++c) sum += code8(img.at(x, y, c));
        return sum / 108.0;
    };
    EXPECT_LT(mean_at(reference, 40, 40), 3.0) << "one light: the far side is black";
    EXPECT_GT(mean_at(lookdev, 40, 40), 5.0) << "the studio lights the far side (a dark rusty metal: measured 7.5)";
}

// Shape, camera and tiling from the command line: the shaderball, an orbit that moves the
// camera (another image), tiling that moves the texture (another image), and usage errors.
TEST(PreviewCli, ShapeOrbitAndTiling) {
    const fs::path work = temp_dir("controls");
    ASSERT_EQ(run("ingest " + q(samples() / "Net004A_1K-JPG") + " -o " + q(work / "out")).code, 0);
    const std::string base = "preview " + q(work / "out/manifest.json") +
                             " --size 48 --device cpu --shading raster -o ";
    auto image = [&](const std::string& name, const std::string& args) {
        const auto r = run(base + q(work / name) + " " + args);
        EXPECT_EQ(r.code, 0) << args << ": " << r.output;
        return bytes_of(work / name / "Net004A.png");
    };
    const std::string plain = image("plain", "");
    EXPECT_NE(image("ball", "--shape shaderball"), plain);
    EXPECT_NE(image("orbit", "--orbit 60,25"), plain);
    EXPECT_NE(image("tiled", "--uv-scale 3"), plain);
    EXPECT_EQ(image("same", "--orbit 0,0 --distance 4 --uv-scale 1 --uv-offset 0,0"), plain);
    for (const std::string bad :
         {"--orbit 10", "--uv-scale 0", "--distance 0", "--shape teapot", "--orbit 0,90", "--uv-aspect square"})
        EXPECT_EQ(run(base + q(work / "bad") + " " + bad).code, 2) << bad;
}

// Anti-aliasing and the texture path from the command line, on lavapipe under the validation
// layer: the look-dev default is `--aa msaa4 --textures fast`; multisampling leaves most of the
// inside of the sphere as one sample shades it (±1 code: the ray goes through the covered
// samples' centroid, the pixel centre when all are covered; a pixel an edge of the mesh's
// triangles crosses is shaded once per triangle) and moves the silhouette toward the 4×4
// supersampled picture; the fast texture path differs from the exact one by rounding only.
// tests/render's ReferenceTest measures both against the CPU reference; this checks the options.
TEST(PreviewCli, AntiAliasingAndTexturePath) {
    const fs::path work = temp_dir("aa");
    ASSERT_EQ(run("ingest " + q(samples() / "Metal_Damaged_001_SD") + " -o " + q(work / "out")).code, 0);
    const std::string base = "preview " + q(work / "out/manifest.json") +
                             " --size 64 --device cpu --vk-validation --shading raster -o ";
    auto render = [&](const std::string& name, const std::string& args) {
        const auto r = run(base + q(work / name) + " " + args);
        EXPECT_EQ(r.code, 0) << args << ": " << r.output;
        return work / name / "Metal_Damaged_001.png";
    };
    EXPECT_EQ(bytes_of(render("default", "")), bytes_of(render("explicit", "--aa msaa4 --textures fast")));
    const std::string ref = "--scene reference --textures exact ";
    const auto one = read_pixels(render("aa1", ref + "--aa 1"));
    const auto msaa = read_pixels(render("msaa4", ref + "--aa msaa4"));
    const auto ss4 = read_pixels(render("ss4", ref + "--aa 4"));
    ASSERT_EQ(one.width, 64);
    auto lit = [](const mf::Image& img, int x, int y) {
        return code8(img.at(x, y, 0)) + code8(img.at(x, y, 1)) + code8(img.at(x, y, 2)) > 0;
    };
    int inside = 0, edge = 0, inside_same = 0;
    double edge_msaa = 0, edge_one = 0;  // summed |Δ| against the 4×4 supersampled picture
    for (int y = 1; y < 63; ++y)
        for (int x = 1; x < 63; ++x) {
            bool all = true, any = false;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    all = all && lit(ss4, x + dx, y + dy);
                    any = any || lit(ss4, x + dx, y + dy);
                }
            int worst = 0;
            for (int c = 0; c < 3; ++c) {
                const int m = code8(msaa.at(x, y, c)), o = code8(one.at(x, y, c)), s = code8(ss4.at(x, y, c));
                worst = std::max(worst, std::abs(m - o));
                if (any && !all) {
                    edge_msaa += std::abs(m - s);
                    edge_one += std::abs(o - s);
                }
            }
            inside += all;
            inside_same += all && worst <= 1;
            edge += any && !all;
        }
    ASSERT_GT(inside, 1000);
    ASSERT_GT(edge, 100);
    // Measured on lavapipe: 1280 of 1665 inside pixels (77 %; the rest lie on the triangles' edges
    // at 64²), and msaa4 0.61 of one sample's error at the silhouette (texture detail included).
    EXPECT_GE(inside_same, inside * 2 / 3) << "multisampling shades the inside once a pixel";
    EXPECT_LT(edge_msaa, 0.75 * edge_one) << "the silhouette is anti-aliased (msaa4 " << edge_msaa << ", one sample "
                                          << edge_one << ", codes summed over " << edge << " edge pixels)";
    // Fast textures: level 0 as read, mips blitted in 8-bit sRGB; the exact path averages in float.
    const auto fast_png = render("fast", "--scene reference --aa 1 --textures fast");
    EXPECT_NE(bytes_of(fast_png), bytes_of(work / "aa1/Metal_Damaged_001.png")) << "--textures had no effect";
    const auto fast = read_pixels(fast_png);
    double sum = 0;
    int n = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
            for (int c = 0; c < 3 && lit(one, x, y); ++c, ++n)
                sum += std::abs(code8(fast.at(x, y, c)) - code8(one.at(x, y, c)));
    EXPECT_LE(sum / n, 1.0) << "fast textures differ from exact ones by rounding";
    for (const std::string bad : {"--aa msaa3", "--aa 5", "--aa msaa", "--aa 0", "--textures quick"})
        EXPECT_EQ(run(base + q(work / "bad") + " " + bad).code, 2) << bad;
}

// The shading path from the command line (tests/render's ComputeShadingTest compares the paths
// closely): compute and raster give the same picture of a textured material inside the
// silhouette; the shaderball falls back to raster with a note; auto is raster on a CPU device.
TEST(PreviewCli, ShadingPath) {
    const fs::path work = temp_dir("shading");
    ASSERT_EQ(run("ingest " + q(samples() / "Metal_Damaged_001_SD") + " -o " + q(work / "out")).code, 0);
    const std::string base = "preview " + q(work / "out/manifest.json") + " --size 64 --device cpu --vk-validation -o ";
    auto render = [&](const std::string& name, const std::string& args) {
        const auto r = run(base + q(work / name) + " " + args);
        EXPECT_EQ(r.code, 0) << args << ": " << r.output;
        return r.output;
    };
    const std::string ref = "--scene reference --aa 1 ";
    EXPECT_EQ(render("raster", ref + "--shading raster").find("note:"), std::string::npos);
    EXPECT_EQ(render("compute", ref + "--shading compute").find("note:"), std::string::npos);
    const auto raster = read_pixels(work / "raster/Metal_Damaged_001.png");
    const auto compute = read_pixels(work / "compute/Metal_Damaged_001.png");
    auto lit = [](const mf::Image& img, int x, int y) {
        return code8(img.at(x, y, 0)) + code8(img.at(x, y, 1)) + code8(img.at(x, y, 2)) > 0;
    };
    int inside = 0, worst = 0;
    double sum = 0;
    for (int y = 1; y < 63; ++y)
        for (int x = 1; x < 63; ++x) {
            bool all = true;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) all = all && lit(raster, x + dx, y + dy);
            if (!all) continue;
            ++inside;
            for (int c = 0; c < 3; ++c) {
                const int d = std::abs(code8(raster.at(x, y, c)) - code8(compute.at(x, y, c)));
                worst = std::max(worst, d);
                sum += d;
            }
        }
    ASSERT_GT(inside, 1000);
    std::printf("  compute vs raster, 64², 1K maps: max |Δcode| %d, mean %.3f over %d inside pixels\n", worst,
                sum / (3.0 * inside), inside);
    // 1K maps at 64²: minified 16×, where the mip level comes from each path's derivatives (the
    // raster path's per 2×2 quad, compute's per pixel). Measured on lavapipe: mean 0.05, at most
    // 3 codes in a few pixels.
    EXPECT_LE(sum / (3.0 * inside), 0.25);
    EXPECT_LE(worst, 4) << "mip selection from analytic derivatives against the raster path's";

    const std::string ball = render("ball", "--shape shaderball --shading compute");
    EXPECT_NE(ball.find("note: compute shading covers the sphere, cube and plane, not the shaderball"),
              std::string::npos)
        << ball;
    // On lavapipe auto is raster, unmeasured: the same bytes as --shading raster, nothing said.
    const std::string automatic = render("auto", ref + "--shading auto");
    EXPECT_EQ(automatic.find("note:"), std::string::npos) << automatic;
    EXPECT_EQ(bytes_of(work / "auto/Metal_Damaged_001.png"), bytes_of(work / "raster/Metal_Damaged_001.png"));
    for (const std::string bad : {"--shading gpu", "--shading", "--shading Compute"})
        EXPECT_EQ(run(base + q(work / "bad") + " " + bad).code, 2) << bad;
}

TEST(PreviewCli, ContactSheetAndMissingManifest) {
    const fs::path work = temp_dir("sheet");
    ASSERT_EQ(run("ingest " + q(samples()) + " -o " + q(work)).code, 0);
    const auto r = run("preview " + q(work / "manifest.json") + " -o " + q(work / "p") +
                       " --size 48 --device cpu --contact-sheet " + q(work / "sheet.png"));
    ASSERT_EQ(r.code, 0) << r.output;
    const auto manifest = read_json(work / "manifest.json");  // a named object: the loop borrows it
    ASSERT_EQ(manifest["materials"].size(), 4u);
    // Four tiles: two columns, two rows of 48 px tiles with a 16 px label under each, 8 px gaps.
    const auto sheet = read_pixels(work / "sheet.png");
    EXPECT_EQ(sheet.width, 2 * 48 + 3 * 8);
    EXPECT_EQ(sheet.height, 2 * (48 + 16) + 3 * 8);
    // Each material's own preview is its tile, in manifest order.
    for (size_t i = 0; i < manifest["materials"].size(); ++i) {
        const std::string name = manifest["materials"][i]["name"];
        ASSERT_TRUE(fs::exists(work / "p" / (name + ".png"))) << name;
        const auto tile = read_pixels(work / "p" / (name + ".png"));
        ASSERT_EQ(tile.width, 48) << name;
        const int x0 = 8 + static_cast<int>(i % 2) * (48 + 8), y0 = 8 + static_cast<int>(i / 2) * (48 + 16 + 8);
        int worst = 0;
        for (int y = 0; y < 48; ++y)
            for (int x = 0; x < 48; ++x)
                for (int c = 0; c < 3; ++c)
                    worst = std::max(worst, std::abs(code8(sheet.at(x0 + x, y0 + y, c)) - code8(tile.at(x, y, c))));
        EXPECT_EQ(worst, 0) << name << " is not tile " << i;
    }
    EXPECT_EQ(run("preview " + q(work / "nope.json") + " -o " + q(work / "x")).code, 2);
}

// ---- the command end to end: files, exit codes

namespace {

const char* kGold = R"({"image": {"width": 48, "height": 32}, "background": [0.1, 0.1, 0.1],
  "material": {"albedo": [1.0, 0.766, 0.336], "roughness": 0.3, "metalness": 1.0}})";

// A preview on lavapipe under the validation layer: any validation message makes it exit 1.
RunResult preview(const std::string& args) { return run("preview --device cpu --vk-validation " + args); }

}  // namespace

TEST(PreviewCli, SceneMaterialWithoutManifestWritesSceneNamedPng) {
    const fs::path dir = temp_dir("png");
    write_text(dir / "gold.json", kGold);
    const auto r = preview("--scene " + q(dir / "gold.json") + " -o " + q(dir / "out"));
    ASSERT_EQ(r.code, 0) << r.output;
    mf::ImageInfo info;
    mf::InputFile in;
    in.path = dir / "out/gold.png";
    in.display = in.path.string();
    std::string err;
    const auto header = mf::read_info(in, err);
    ASSERT_TRUE(header) << err;
    EXPECT_EQ(header->width, 48);
    EXPECT_EQ(header->height, 32);
    EXPECT_EQ(header->channels, 3);
    EXPECT_EQ(header->bit_depth, 8);
}

TEST(PreviewCli, ExrIsLinearRadianceAndSizeOverrides) {
    const fs::path dir = temp_dir("exr");
    write_text(dir / "gold.json", kGold);
    const auto r = preview("--scene " + q(dir / "gold.json") + " -o " + q(dir / "out") + " --format exr --size 24" +
                           " --contact-sheet " + q(dir / "sheet.png"));
    ASSERT_EQ(r.code, 0) << r.output;
    const mf::Image px = read_pixels(dir / "out/gold.exr");
    ASSERT_EQ(px.width, 24);
    EXPECT_NEAR(px.pixels[0], 0.1f, 1e-6f);  // background corner: the linear value itself
    EXPECT_TRUE(fs::exists(dir / "sheet.png"));
}

TEST(PreviewCli, ExitCodes) {
    const fs::path dir = temp_dir("codes");
    write_text(dir / "gold.json", kGold);
    EXPECT_EQ(preview("-o " + q(dir / "out")).code, 2);  // nothing to render
    EXPECT_EQ(preview(q(dir / "missing.json") + " -o " + q(dir / "out")).code, 2);
    const auto bad_light = preview("--scene " + q(dir / "gold.json") + " -o " + q(dir / "out") + " --light sun");
    EXPECT_EQ(bad_light.code, 2);
    EXPECT_NE(bad_light.output.find("matforge preview: --light"), std::string::npos) << bad_light.output;
    write_text(dir / "bad.json", R"({"material": {"metalness": 7}})");
    const auto bad_scene = preview("--scene " + q(dir / "bad.json") + " -o " + q(dir / "out"));
    EXPECT_EQ(bad_scene.code, 2);
    EXPECT_NE(bad_scene.output.find("material.metalness"), std::string::npos) << bad_scene.output;
    // A manifest whose texture is missing: that material fails (1), the run goes on.
    write_text(dir / "manifest.json", R"({"manifest_version": 1, "materials": [
        {"name": "Gone", "outputs": [{"file": "gone.png", "color_space": "sRGB", "channels": {"RGB": "albedo"}}]},
        {"name": "Plain", "outputs": [], "constants": {"albedo": [0.5, 0.5, 0.5]}}]})");
    const auto partial = preview(q(dir / "manifest.json") + " -o " + q(dir / "out") + " --size 16");
    EXPECT_EQ(partial.code, 1) << partial.output;
    EXPECT_NE(partial.output.find("matforge preview: Gone: "), std::string::npos) << partial.output;
    EXPECT_TRUE(fs::exists(dir / "out/Plain.png"));
    EXPECT_FALSE(fs::exists(dir / "out/Gone.png"));
}

TEST(PreviewCli, NamesThatMeetOnOneFileGetDistinctFiles) {
    const fs::path dir = temp_dir("stems");
    write_text(dir / "manifest.json", R"({"manifest_version": 1, "materials": [
        {"name": "Rock", "outputs": [], "constants": {"albedo": [0.5, 0.5, 0.5]}},
        {"name": "rock", "outputs": [], "constants": {"albedo": [0.2, 0.2, 0.2]}},
        {"name": "a/b", "outputs": [], "constants": {"albedo": [0.1, 0.1, 0.1]}},
        {"name": "a_b", "outputs": [], "constants": {"albedo": [0.9, 0.9, 0.9]}}]})");
    const auto r = preview(q(dir / "manifest.json") + " -o " + q(dir / "out") + " --size 8");
    ASSERT_EQ(r.code, 0) << r.output;
    for (const char* f : {"Rock.png", "rock_2.png", "a_b.png", "a_b_2.png"})
        EXPECT_TRUE(fs::exists(dir / "out" / f)) << f;
    // Each file holds its own material: the brighter albedo renders brighter.
    auto sum = [](const mf::Image& img) {
        double t = 0;
        for (float v : img.pixels) t += v;
        return t;
    };
    EXPECT_GT(sum(read_pixels(dir / "out/Rock.png")), sum(read_pixels(dir / "out/rock_2.png")));
    EXPECT_GT(sum(read_pixels(dir / "out/a_b_2.png")), sum(read_pixels(dir / "out/a_b.png")));
}

TEST(PreviewCli, AFifoNamedInAManifestIsRefusedNotWaitedFor) {
    const fs::path dir = temp_dir("fifo");
    ASSERT_EQ(::mkfifo((dir / "albedo.png").c_str(), 0600), 0);
    write_text(dir / "manifest.json", R"({"manifest_version": 1, "materials": [
        {"name": "F", "outputs": [{"file": "albedo.png", "color_space": "sRGB", "channels": {"RGB": "albedo"}}]}]})");
    const auto r = preview(q(dir / "manifest.json") + " -o " + q(dir / "out") + " --size 8");
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("not a regular file (a FIFO)"), std::string::npos) << r.output;
    ASSERT_EQ(::mkfifo((dir / "scene.json").c_str(), 0600), 0);
    EXPECT_EQ(preview("--scene " + q(dir / "scene.json") + " -o " + q(dir / "out")).code, 2);
}

TEST(PreviewCli, NoVulkanDriverIsAConfigurationErrorNamingThePackage) {
    const fs::path dir = temp_dir("nodriver");
    write_text(dir / "gold.json", kGold);
    // The loader finds no driver manifest: as on a machine without mesa-vulkan-drivers.
    const std::string none = q(dir / "none.json");
    const auto r = run_env("VK_ICD_FILENAMES=" + none + " VK_DRIVER_FILES=" + none,
                           "preview --device cpu --scene " + q(dir / "gold.json") + " -o " + q(dir / "out"));
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.output.find("mesa-vulkan-drivers"), std::string::npos) << r.output;
}

// Issue 49: the batch at the device's pace (lanes drawing at once, workers reading ahead and
// writing) gives the pictures, the contact sheet and the messages of one lane and one worker,
// byte for byte: the corpus's sets (a cut-out, a packed ORM, JPEG and WebP sources) ingested once,
// previewed with 1 lane / 1 worker and with 3 lanes / 4 workers, materials failing among them
// (an output deleted) reported in manifest order while the others render.
TEST(PreviewCli, LanesAndWorkersChangeNoPictureNorMessage) {
    const fs::path work = temp_dir("lanes");
    auto r = run("ingest " + q(mf::testenv::corpus_dir() / "real") + " -o " + q(work / "out") + " --fail-on never");
    ASSERT_EQ(r.code, 0) << r.output;
    const nlohmann::json manifest = read_json(work / "out" / "manifest.json");
    ASSERT_GE(manifest["materials"].size(), 12u);
    // Two materials lose a texture: each is reported, in its place, and the rest still render.
    for (const size_t i : {size_t{1}, size_t{6}})
        fs::remove(work / "out" / manifest["materials"][i]["outputs"][0]["file"].get<std::string>());
    std::map<std::string, std::string> pictures[2];
    std::string said[2];
    for (int k = 0; k < 2; ++k) {
        const fs::path dir = work / ("p" + std::to_string(k));
        r = run("preview " + q(work / "out" / "manifest.json") + " -o " + q(dir) +
                " --size 64 --device cpu --shading raster --contact-sheet " +
                q(work / ("sheet" + std::to_string(k) + ".png")) + (k == 0 ? " --lanes 1 -j 1" : " --lanes 3 -j 4"));
        EXPECT_EQ(r.code, 1) << r.output;  // the two materials without their texture
        pictures[k] = mf::testfiles::files_under(dir);
        said[k] = r.output.substr(0, r.output.rfind("matforge preview:"));  // the last line names the time
    }
    EXPECT_EQ(pictures[0].size(), manifest["materials"].size() - 2);
    EXPECT_TRUE(pictures[0] == pictures[1]) << "the same pictures, byte for byte";
    EXPECT_EQ(said[0], said[1]);
    EXPECT_NE(said[0].find(manifest["materials"][1]["name"].get<std::string>()), std::string::npos) << said[0];
    EXPECT_EQ(mf::testfiles::file_bytes(work / "sheet0.png"), mf::testfiles::file_bytes(work / "sheet1.png"));
}

// --timings says where the batch's time went: the points in order (the device, then the
// renderers, the first image, the end) within the command's own wall clock, the lanes and
// workers asked for, and time spent reading, drawing and writing. Without it, no such line.
TEST(PreviewCli, TimingsSayWhereTheTimeWent) {
    const fs::path work = temp_dir("timings");
    auto r = run("ingest " + q(samples() / "Metal_Damaged_001_SD") + " -o " + q(work / "out"));
    ASSERT_EQ(r.code, 0) << r.output;
    const std::string args = "preview " + q(work / "out" / "manifest.json") + " -o " + q(work / "p") +
                             " --size 48 --device cpu";
    r = run(args);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(r.output.find("timings:"), std::string::npos) << r.output;

    const auto began = std::chrono::steady_clock::now();
    r = run(args + " --timings --lanes 2 -j 3");
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
    ASSERT_EQ(r.code, 0) << r.output;
    double device = -1, renderers = -1, first = -1, total = -1, read = -1, write = -1, upload = -1, draw = -1;
    unsigned lanes = 0, workers = 0;
    const size_t at = r.output.find("timings: device made");
    ASSERT_NE(at, std::string::npos) << r.output;
    ASSERT_EQ(std::sscanf(r.output.c_str() + at,
                          "timings: device made %lf s, %u renderer(s) %lf s, first image %lf s, all %lf s", &device,
                          &lanes, &renderers, &first, &total),
              5)
        << r.output;
    const size_t at2 = r.output.find("timings: read");
    ASSERT_NE(at2, std::string::npos) << r.output;
    double read_wait = -1;
    ASSERT_EQ(std::sscanf(r.output.c_str() + at2,
                          "timings: read %lf s (%lf s of it waiting for the device or the renderers) and write %lf s "
                          "on %u worker(s), upload %lf s and draw %lf s",
                          &read, &read_wait, &write, &workers, &upload, &draw),
              6)
        << r.output;
    double made = -1, made_shading = -1, made_load = -1;
    const size_t at_made = r.output.find("timings: renderers made in");
    ASSERT_NE(at_made, std::string::npos) << r.output;
    ASSERT_EQ(std::sscanf(r.output.c_str() + at_made,
                          "timings: renderers made in %lf s (load-time uploads and passes %lf s, then waiting for "
                          "the shading choice %lf s",
                          &made, &made_load, &made_shading),
              3)
        << r.output;
    double pipelines = -1, images = -1, staging = -1, rest = -1, retire = -1, submit = -1, rest_device = -1, wait = -1,
           wait_device = -1, readback = -1;
    const size_t at3 = r.output.find("timings: upload: pipelines");
    ASSERT_NE(at3, std::string::npos) << r.output;
    ASSERT_EQ(std::sscanf(r.output.c_str() + at3,
                          "timings: upload: pipelines %lf s, images %lf s, staging copies %lf s, submission and the "
                          "rest %lf s (waiting for the lane's previous upload %lf s, submitting %lf s; on the device "
                          "%lf s); draw: submitted and waited for %lf s (on the device %lf s), read back %lf s",
                          &pipelines, &images, &staging, &rest, &retire, &submit, &rest_device, &wait, &wait_device,
                          &readback),
              10)
        << r.output;
    // The device timed the copies and the draw (lavapipe has timestamps), in seconds: within the
    // command (the copies run while the lane goes on to the draw, which then waits for them);
    // the renderer's construction within the time to make the renderers, its parts within it;
    // the workers' waits within their reading (the first material waits for the device).
    EXPECT_GT(rest_device, 0.0) << r.output;
    EXPECT_GT(wait_device, 0.0) << r.output;
    EXPECT_LE(rest_device + wait_device, total) << r.output;
    EXPECT_GT(made, 0.0) << r.output;
    EXPECT_LE(made, renderers + 0.002) << r.output;
    EXPECT_GT(made_load, 0.0) << r.output;
    EXPECT_LE(made_shading + made_load, made + 0.002) << r.output;
    EXPECT_GE(read_wait, 0.0) << r.output;
    EXPECT_LE(read_wait, read + 0.002) << r.output;
    // The lane's parts lie within what the batch timed around upload and draw (printed rounded
    // to the millisecond). Its pipeline is compiled by the worker that read the material or by
    // the lane, whichever comes first; lavapipe's images take host memory in microseconds, and
    // the submission records the copies and submits them without waiting: those may print 0.
    for (const double t : {pipelines, images, staging, rest, wait, readback}) EXPECT_GE(t, 0.0) << r.output;
    // The submission's parts lie within it (a submission on lavapipe takes microseconds: it may
    // print 0).
    EXPECT_GE(retire, 0.0) << r.output;
    EXPECT_GE(submit, 0.0) << r.output;
    EXPECT_LE(retire + submit, rest + 0.002) << r.output;
    EXPECT_LE(pipelines + images + staging + rest, upload + 0.004) << r.output;
    EXPECT_LE(wait + readback, draw + 0.002) << r.output;
    // What the memory budget counted: the one material's textures (a few MiB), within the budget.
    double held = -1, budget = -1;
    const size_t at4 = r.output.find("timings: held at most");
    ASSERT_NE(at4, std::string::npos) << r.output;
    ASSERT_EQ(std::sscanf(r.output.c_str() + at4,
                          "timings: held at most %lf MiB of prepared textures and images at once (the budget: %lf MiB)",
                          &held, &budget),
              2)
        << r.output;
    EXPECT_GT(held, 0.5) << r.output;
    EXPECT_EQ(budget, 1024.0) << r.output;
    EXPECT_LT(held, budget) << r.output;
    // The process around the batch: its start before (within the command's wall clock, which the
    // test measured from before the process existed, to the kernel's tick of 10 ms) and the
    // renderers' and the device's destruction after.
    double before = -1, teardown = -1;
    const size_t at5 = r.output.find("timings: the process:");
    ASSERT_NE(at5, std::string::npos) << r.output;
    ASSERT_EQ(std::sscanf(r.output.c_str() + at5,
                          "timings: the process: %lf s before the start (%*[^)]), %lf s after all", &before, &teardown),
              2)
        << r.output;
    EXPECT_GE(before, 0.0) << r.output;
    EXPECT_GE(teardown, 0.0) << r.output;
    EXPECT_LE(before + total + teardown, wall + 0.011) << r.output;
    EXPECT_EQ(lanes, 1u) << "one material: one lane, whatever --lanes asks";
    EXPECT_EQ(workers, 3u);
    EXPECT_GE(device, 0.0);  // made while the manifest was read: it may be ready when the batch starts
    EXPECT_LE(device, renderers);
    EXPECT_LE(renderers, first);
    EXPECT_LE(first, total);
    EXPECT_LE(total, wall);
    // Each stage ran (a 1K set's decode, its upload and a lavapipe draw take milliseconds; a
    // 48-pixel picture's write may take under the millisecond printed) and none took longer than
    // the whole on its threads.
    for (const double t : {read, upload, draw}) EXPECT_GT(t, 0.0) << r.output;
    for (const double t : {read, write, upload, draw}) {
        EXPECT_GE(t, 0.0) << r.output;
        EXPECT_LE(t, total * 3) << r.output;
    }
}
