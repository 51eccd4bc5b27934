// The preview reads whatever layout a preset wrote: one source set, every shipped preset, the
// same image (issue: "previews to the same image within 1 code").
#include "cli_util.hpp"

using namespace mft;

TEST(PreviewCli, EveryPresetPreviewsTheSameImage) {
    const fs::path work = temp_dir("presets");
    // WalnutInlay: glTF metallicRoughness, occlusion, emissive and a GL normal map; rendered
    // under an environment too would use occlusion, so a key light and a fill light suffice to
    // exercise albedo, normal (both conventions), roughness (also as smoothness) and metalness.
    const std::vector<std::string> presets{"gltf", "unreal", "unity-hdrp", "unity-urp", "godot", "separate"};
    std::map<std::string, mf::Image> images;
    for (const auto& p : presets) {
        const fs::path out = work / p;
        auto r = run("ingest " + q(samples() / "WalnutInlay") + " -o " + q(out) + " --preset " + p);
        ASSERT_EQ(r.code, 0) << p << ": " << r.output;
        r = run("preview " + q(out / "manifest.json") + " -o " + q(out / "preview") +
                " --size 96 --device cpu --light dir:0.5,-0.6,-0.62:3 --light point:-2,1,2:12");
        ASSERT_EQ(r.code, 0) << p << ": " << r.output;
        images[p] = read_pixels(out / "preview" / "WalnutInlay.png");
    }
    const mf::Image& ref = images["gltf"];
    ASSERT_EQ(ref.width, 96);
    int lit = 0;
    for (size_t i = 0; i < ref.pixels.size(); ++i) lit += code8(ref.pixels[i]) > 8;
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

TEST(PreviewCli, ContactSheetAndMissingManifest) {
    const fs::path work = temp_dir("sheet");
    ASSERT_EQ(run("ingest " + q(samples()) + " -o " + q(work)).code, 0);
    const auto r = run("preview " + q(work / "manifest.json") + " -o " + q(work / "p") +
                       " --size 48 --device cpu --contact-sheet " + q(work / "sheet.png"));
    ASSERT_EQ(r.code, 0) << r.output;
    const auto manifest = read_json(work / "manifest.json");  // a named object: the loop borrows it
    for (const auto& m : manifest["materials"])
        EXPECT_TRUE(fs::exists(work / "p" / (m["name"].get<std::string>() + ".png"))) << m["name"];
    const auto sheet = read_pixels(work / "sheet.png");
    EXPECT_GT(sheet.width, 3 * 48);
    EXPECT_GT(sheet.height, 3 * 48);
    EXPECT_EQ(run("preview " + q(work / "nope.json") + " -o " + q(work / "x")).code, 2);
}
