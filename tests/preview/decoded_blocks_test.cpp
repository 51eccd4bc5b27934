// GPU texture files on a CPU device: lavapipe decodes blocks on every fetch, so the preview
// decodes BC7 levels once on the CPU (BlockUse::decoded) and uploads them as 8-bit RGBA with the
// file's own chain. BC7's decoding is integer arithmetic in its specification: the picture is
// within a code of the one lavapipe draws from the blocks themselves (its filtering of 8-bit
// texels is fixed point), every level is the file's, and only a device that lacks the format
// says so in a note.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "core/files.hpp"
#include "preset/texture_fields.hpp"
#include "preview/preview.hpp"
#include "test_dirs.hpp"
#include "texture/texture.hpp"
#include "vulkan_fixture.hpp"

namespace mf::preview::decoded_blocks_test {
namespace fs = std::filesystem;

// A level of smooth colour with fine detail (a sum of waves and a hash), `channels` codes a texel.
Image8 detail(int w, int h, int channels, int seed) {
    Image8 img(w, h, channels);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < channels; ++c) {
                const double s = (x + 0.5) / w, t = (y + 0.5) / h;
                const unsigned hash = (static_cast<unsigned>(x) * 73856093u) ^ (static_cast<unsigned>(y) * 19349663u) ^
                                      (static_cast<unsigned>(c + seed) * 83492791u);
                const double v = 0.5 + 0.3 * std::sin(6.283 * (3 + c + seed) * s) * std::cos(6.283 * (2 + c) * t) +
                                 0.08 * ((hash % 1000) / 1000.0 - 0.5);
                img.at(x, y, c) = static_cast<uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255));
            }
    return img;
}

// A BC7 KTX2 of `size`² with a full chain (each level a 2x2 box of the one above), written to `file`.
void write_bc7(const fs::path& file, int size, bool srgb, int seed) {
    texture::GpuTexture gt;
    gt.format = block_format_info("bc7");
    ASSERT_NE(gt.format, nullptr);
    gt.srgb = srgb;
    Image8 level = detail(size, size, 4, seed);
    for (int w = size;; w /= 2) {
        texture::CodecOptions o;
        o.format = gt.format;
        o.srgb = srgb;
        o.effort = Effort::fast;
        texture::Level l{w, w, {}};
        std::string err;
        ASSERT_TRUE(texture::encode_level(level, o, l.data, err)) << err;
        gt.levels.push_back(std::move(l));
        if (w == 1) break;
        Image8 half(w / 2, w / 2, 4);
        for (int y = 0; y < w / 2; ++y)
            for (int x = 0; x < w / 2; ++x)
                for (int c = 0; c < 4; ++c)
                    half.at(x, y, c) = static_cast<uint8_t>((level.at(2 * x, 2 * y, c) + level.at(2 * x + 1, 2 * y, c) +
                                                             level.at(2 * x, 2 * y + 1, c) +
                                                             level.at(2 * x + 1, 2 * y + 1, c) + 2) /
                                                            4);
        level = std::move(half);
    }
    std::vector<uint8_t> bytes;
    std::string err;
    ASSERT_TRUE(texture::write_ktx2(gt, {}, bytes, err)) << err;
    ASSERT_TRUE(write_file_atomic(file, bytes, err)) << err;
}

class DecodedBlocks : public test::VulkanTest {};

TEST_F(DecodedBlocks, Bc7LevelsDrawAsLavapipeDrawsTheBlocks) {
    const fs::path dir = mf::testdirs::fresh_for_test("matforge-preview-test-", "ktx2");
    write_bc7(dir / "color.ktx2", 128, true, 0);
    write_bc7(dir / "orm.ktx2", 128, false, 5);
    auto read = [&](const std::string& name, BlockUse use, std::vector<std::string>& notes) {
        std::string err;
        auto t = read_gpu_texture(
            dir / name, [use](uint32_t) { return use; }, notes, err);
        EXPECT_TRUE(t) << err;
        return t ? *t : render::Texture{};
    };
    std::vector<std::string> notes;
    const render::Texture blocks = read("color.ktx2", BlockUse::as_written, notes);
    const render::Texture decoded = read("color.ktx2", BlockUse::decoded, notes);
    EXPECT_TRUE(notes.empty()) << notes.front();
    ASSERT_EQ(decoded.block_format, render::kDecodedLevels);
    ASSERT_EQ(decoded.block_levels.size(), 8u) << "128 down to 1: the file's chain";
    for (size_t i = 0; i < decoded.block_levels.size(); ++i) {
        const size_t side = size_t{128} >> i;
        EXPECT_EQ(decoded.block_levels[i].size(), side * side * 4) << "level " << i;
    }
    read("color.ktx2", BlockUse::decoded_absent, notes);
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_NE(notes[0].find("does not sample bc7"), std::string::npos) << notes[0];

    // The colour map on a sphere, roughness and metalness from the ORM map, one key light: drawn
    // from the blocks and from the decoded levels, at two sizes (level 0 and the far levels).
    for (const uint32_t size : {256u, 48u}) {
        render::Scene scene;
        scene.width = scene.height = size;
        render::Renderer renderer(context(), scene);
        std::array<render::Frame, 2> frames;
        for (const BlockUse use : {BlockUse::as_written, BlockUse::decoded}) {
            std::vector<std::string> unused;
            render::Material m;
            m.name = "bc7";
            m.textures = {read("color.ktx2", use, unused), read("orm.ktx2", use, unused)};
            m.textures[0].srgb = true;
            m.albedo.texture = 0;
            m.roughness = {1, render::Channel::G, false, 0.f};
            m.metalness = {1, render::Channel::B, false, 0.f};
            frames[use == BlockUse::decoded] = renderer.render(renderer.upload(m));
        }
        int worst = 0, lit = 0;
        for (size_t k = 0; k < frames[0].rgba8.size(); ++k) {
            worst = std::max(worst, std::abs(int(frames[0].rgba8[k]) - int(frames[1].rgba8[k])));
            lit += k % 4 != 3 && frames[0].rgba8[k] > 16;
        }
        EXPECT_GT(lit, int(size * size / 4)) << "the sphere is lit";
        EXPECT_LE(worst, 1) << size << "x" << size;
    }
}

}  // namespace mf::preview::decoded_blocks_test
