// The command end to end: files, exit codes, contact sheet.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "preview/preview.hpp"
#include "vulkan_fixture.hpp"

namespace mf::preview {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("matforge_preview_cmd_" + name);
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

fs::path write_scene(const fs::path& dir, const std::string& text) {
    const fs::path f = dir / "gold.json";
    std::ofstream(f) << text;
    return f;
}

const char* kGold = R"({"image": {"width": 48, "height": 32}, "background": [0.1, 0.1, 0.1],
  "material": {"albedo": [1.0, 0.766, 0.336], "roughness": 0.3, "metalness": 1.0}})";

class Command : public ::testing::Test {
protected:
    void SetUp() override {
        test::use_lavapipe_only();
    }
    Options options(const fs::path& dir) {
        Options o;
        o.out_dir = dir / "out";
        o.device = "cpu";
        o.validation = true;  // any validation message makes run() return 1
        o.quiet = true;
        return o;
    }
};

TEST_F(Command, SceneMaterialWithoutManifestWritesSceneNamedPng) {
    const fs::path dir = temp_dir("png");
    Options o = options(dir);
    o.scene = write_scene(dir, kGold);
    std::ostringstream log;
    EXPECT_EQ(run(o, log), 0) << log.str();
    auto in = OIIO::ImageInput::open((dir / "out/gold.png").string());
    ASSERT_TRUE(in) << log.str();
    EXPECT_EQ(in->spec().width, 48);
    EXPECT_EQ(in->spec().height, 32);
    EXPECT_EQ(in->spec().nchannels, 3);
    EXPECT_EQ(in->spec().format, OIIO::TypeDesc::UINT8);
}

TEST_F(Command, ExrIsLinearRadianceAndSizeOverrides) {
    const fs::path dir = temp_dir("exr");
    Options o = options(dir);
    o.scene = write_scene(dir, kGold);
    o.format = "exr";
    o.size = 24;
    o.contact_sheet = dir / "sheet.png";
    std::ostringstream log;
    EXPECT_EQ(run(o, log), 0) << log.str();
    auto in = OIIO::ImageInput::open((dir / "out/gold.exr").string());
    ASSERT_TRUE(in) << log.str();
    EXPECT_EQ(in->spec().width, 24);
    std::vector<float> px(24 * 24 * 3);
    ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, px.data()));
    EXPECT_NEAR(px[0], 0.1f, 1e-6f);  // background corner: the linear value itself
    EXPECT_TRUE(fs::exists(dir / "sheet.png"));
}

TEST_F(Command, ExitCodes) {
    const fs::path dir = temp_dir("codes");
    std::ostringstream log;
    Options none = options(dir);
    EXPECT_EQ(run(none, log), 2);  // nothing to render
    Options bad_manifest = options(dir);
    bad_manifest.manifest = dir / "missing.json";
    EXPECT_EQ(run(bad_manifest, log), 2);
    Options bad_light = options(dir);
    bad_light.scene = write_scene(dir, kGold);
    bad_light.lights = {"sun"};
    EXPECT_EQ(run(bad_light, log), 2);
    // A manifest whose texture is missing: that material fails (1), the run goes on.
    std::ofstream(dir / "manifest.json") << R"({"manifest_version": 1, "materials": [
        {"name": "Gone", "outputs": [{"file": "gone.png", "color_space": "sRGB", "channels": {"RGB": "albedo"}}]},
        {"name": "Plain", "outputs": [], "constants": {"albedo": [0.5, 0.5, 0.5]}}]})";
    Options partial = options(dir);
    partial.manifest = dir / "manifest.json";
    partial.size = 16;
    EXPECT_EQ(run(partial, log), 1);
    EXPECT_TRUE(fs::exists(dir / "out/Plain.png"));
    EXPECT_FALSE(fs::exists(dir / "out/Gone.png"));
}

TEST_F(Command, NoVulkanDriverIsAConfigurationErrorNamingThePackage) {
    const fs::path dir = temp_dir("nodriver");
    Options o = options(dir);
    o.validation = false;
    o.scene = write_scene(dir, kGold);
    // The loader finds no driver manifest: as on a machine without mesa-vulkan-drivers.
    setenv("VK_ICD_FILENAMES", (dir / "none.json").c_str(), 1);
    setenv("VK_DRIVER_FILES", (dir / "none.json").c_str(), 1);
    std::ostringstream log;
    const int rc = run(o, log);
    unsetenv("VK_ICD_FILENAMES");
    unsetenv("VK_DRIVER_FILES");
    EXPECT_EQ(rc, 2);
    EXPECT_NE(log.str().find("mesa-vulkan-drivers"), std::string::npos) << log.str();
}

TEST(ContactSheet, TilesAndLabels) {
    std::vector<SheetTile> tiles;
    for (const char* name : {"Bricks059", "MetalPlates013", "a_very_long_material_name_that_overflows"})
        tiles.push_back({name, 64, 64, std::vector<uint8_t>(64 * 64 * 4, 255)});
    uint32_t w = 0, h = 0;
    std::vector<uint8_t> sheet;
    compose_contact_sheet(tiles, w, h, sheet);
    EXPECT_EQ(w, 2 * 64 + 3 * 8u);  // 2 columns for 3 tiles
    EXPECT_EQ(h % 2, 0u);
    // Some label pixels are lit below the first tile.
    size_t lit = 0;
    for (uint32_t y = 8 + 64; y < 8 + 64 + 16; ++y)
        for (uint32_t x = 8; x < 8 + 64; ++x) lit += sheet[(size_t{y} * w + x) * 4] > 200;
    EXPECT_GT(lit, 20u);
    EXPECT_EQ(text_width("abc", 2), 36);
}

}  // namespace
}  // namespace mf::preview
