// Two-channel normal maps (X and Y stored; blue empty or absent, as BC5 exports leave them): Z is
// reconstructed as sqrt(1 - x² - y²), said by NORMAL_Z_RECONSTRUCTED, never NORMAL_INVALID.
#include <cmath>

#include "cli_util.hpp"

using namespace mft;

namespace {

// A bumpy unit-vector field; `blue`: what channel 3 holds (-1: no third channel).
mf::Image xy_normals(int size, float blue) {
    mf::Image img(size, size, blue < 0 ? 2 : 3);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const float nx = 0.4f * std::sin(0.3f * static_cast<float>(x)),
                        ny = 0.3f * std::cos(0.2f * static_cast<float>(y));
            img.at(x, y, 0) = 0.5f * nx + 0.5f;
            img.at(x, y, 1) = 0.5f * ny + 0.5f;
            if (blue >= 0) img.at(x, y, 2) = blue;
        }
    return img;
}

}  // namespace

TEST(TwoChannelNormal, EmptyBlueOrTwoChannelsRebuildZ) {
    const fs::path work = temp_dir("bc5");
    for (const auto& [name, blue] : {std::pair{"Zero", 0.f}, std::pair{"Half", 0.5f}, std::pair{"TwoCh", -1.f}}) {
        const fs::path set = work / "in" / name;
        write_png(set / (std::string(name) + "_Color.png"), mf::Image(32, 32, 3, 0.5f));
        write_png(set / (std::string(name) + "_NormalGL.png"), xy_normals(32, blue));
    }
    const auto r = run("ingest " + q(work / "in") + " -o " + q(work / "out") + " -q");
    ASSERT_EQ(r.code, 0) << r.output;
    const auto manifest = read_json(work / "out/manifest.json");
    for (const char* name : {"Zero", "Half", "TwoCh"}) {
        const auto* m = material(manifest, name);
        ASSERT_TRUE(m) << name;
        EXPECT_TRUE(has_finding(*m, "NORMAL_Z_RECONSTRUCTED", "normal")) << name << m->dump(2);
        EXPECT_FALSE(has_finding(*m, "NORMAL_INVALID")) << name << m->dump(2);
        const auto* out = output_with(*m, "RGB", "normal");
        ASSERT_TRUE(out) << name;
        const mf::Image n = read_pixels(work / "out" / (*out)["file"].get<std::string>());
        // Every texel: z = sqrt(1 - x² - y²) of the stored x, y (within 8-bit quantization).
        double worst = 0;
        for (int y = 0; y < n.height; ++y)
            for (int x = 0; x < n.width; ++x) {
                const double nx = 2.0 * n.at(x, y, 0) - 1, ny = 2.0 * n.at(x, y, 1) - 1, nz = 2.0 * n.at(x, y, 2) - 1;
                worst = std::max(worst, std::abs(nz - std::sqrt(std::max(0.0, 1 - nx * nx - ny * ny))));
                EXPECT_NEAR(nx, 0.4 * std::sin(0.3 * x), 0.02) << name;
            }
        EXPECT_LT(worst, 0.02) << name;
    }
    // A real three-channel map keeps its blue: no reconstruction claimed.
    const auto v = run("validate " + q(samples()) + " --report json");
    EXPECT_EQ(v.output.find("NORMAL_Z_RECONSTRUCTED"), std::string::npos);
}
