// matforge's PNG writer (lib/image/png_writer.hpp, reached through encode_image) read back by
// two decoders that share no code with it or with each other: stb_image (its own inflate) and
// OpenImageIO (libpng and zlib). Every layout PNG outputs use, odd sizes, noise and smooth
// ramps; the file's chunk sequence and CRCs checked with zlib's crc32, its rows' filter bytes
// read from zlib's inflate. (The reader: png_reader_test.cpp.)
#include <gtest/gtest.h>
#include <stb_image.h>
#include <zlib.h>

#include <cmath>
#include <cstring>
#include <random>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "image/image.hpp"
#include "oiio_oracle.hpp"
#include "png_chunks.hpp"
#include "test_files.hpp"

namespace {

using namespace pngtest;  // NOLINT: the test files' own helpers

using mf::testfiles::in_memory;

TEST(PngWriter, EveryLayoutReadsBackExactlyInTwoIndependentDecoders) {
    const int sizes[][2] = {{1, 1}, {7, 3}, {3, 7}, {33, 17}, {300, 2}, {2, 300}};
    unsigned seed = 1;
    for (int depth : {8, 16})
        for (int channels = 1; channels <= 4; ++channels)
            for (const auto& wh : sizes)
                for (bool noise : {true, false}) {
                    const int w = wh[0], h = wh[1];
                    SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + "x" + std::to_string(channels) + " " +
                                 std::to_string(depth) + "-bit " + (noise ? "noise" : "ramp"));
                    const auto s8 = samples<uint8_t>(w, h, channels, noise, seed);
                    const auto s16 = samples<uint16_t>(w, h, channels, noise, seed++);
                    const std::vector<unsigned char> png = encode(w, h, channels, depth, s16, s8);
                    ASSERT_FALSE(png.empty());

                    // stb_image: its own PNG parser and inflate.
                    int sw = 0, sh = 0, sc = 0;
                    const auto size = static_cast<int>(png.size());
                    if (depth == 8) {
                        stbi_uc* d = stbi_load_from_memory(png.data(), size, &sw, &sh, &sc, 0);
                        ASSERT_NE(d, nullptr) << stbi_failure_reason();
                        EXPECT_EQ(std::vector<uint8_t>(d, d + s8.size()), s8);
                        stbi_image_free(d);
                    } else {
                        stbi_us* d = stbi_load_16_from_memory(png.data(), size, &sw, &sh, &sc, 0);
                        ASSERT_NE(d, nullptr) << stbi_failure_reason();
                        EXPECT_EQ(std::vector<uint16_t>(d, d + s16.size()), s16);
                        stbi_image_free(d);
                    }
                    EXPECT_EQ(sw, w);
                    EXPECT_EQ(sh, h);
                    EXPECT_EQ(sc, channels);

                    // OpenImageIO: libpng and zlib.
                    const mf::InputFile in = in_memory(png, "written.png");
                    mf::Decoded decoded;
                    mf::ImageInfo info;
                    std::string err;
                    ASSERT_TRUE(mf::read_image(in, decoded, info, err)) << err;
                    EXPECT_EQ(info.width, w);
                    EXPECT_EQ(info.height, h);
                    EXPECT_EQ(info.channels, channels);
                    EXPECT_EQ(info.bit_depth, depth);
                    if (depth == 8) {
                        ASSERT_TRUE(decoded.is_codes());
                        EXPECT_EQ(decoded.codes.pixels, s8);
                    } else {
                        ASSERT_EQ(decoded.floats.pixels.size(), s16.size());
                        for (size_t i = 0; i < s16.size(); ++i)  // OpenImageIO scales by 1/65535: to the code
                            ASSERT_EQ(std::lround(decoded.floats.pixels[i] * 65535.f), s16[i]) << i;
                    }
                }
}

TEST(PngWriter, ChunksFilterBytesAndTheSameBytesAgain) {
    // 3.6 MB of noise: more than one IDAT chunk (at most 1 MiB each).
    const int w = 1100, h = 1100, channels = 3;
    const auto s8 = samples<uint8_t>(w, h, channels, true, 7);
    const std::vector<unsigned char> png = encode(w, h, channels, 8, {}, s8);
    EXPECT_EQ(encode(w, h, channels, 8, {}, s8), png) << "the same pixels must give the same bytes";

    const std::vector<Chunk> chunks = chunks_of(png);
    ASSERT_GE(chunks.size(), 5u);
    EXPECT_EQ(chunks.front().type, "IHDR");
    EXPECT_EQ(chunks.back().type, "IEND");
    std::vector<unsigned char> stream;
    size_t idats = 0, texts = 0;
    for (const Chunk& c : chunks) {
        EXPECT_NE(c.type, "tIME") << "no timestamp";
        if (c.type == "tEXt") {
            ++texts;
            EXPECT_EQ(std::string(c.data.begin(), c.data.end()), std::string("Software\0matforge", 17));
        }
        if (c.type != "IDAT") continue;
        ++idats;
        EXPECT_LE(c.data.size(), size_t{1} << 20);
        stream.insert(stream.end(), c.data.begin(), c.data.end());
    }
    EXPECT_EQ(texts, 1u);
    EXPECT_GE(idats, 3u);
    const std::vector<unsigned char>& ihdr = chunks.front().data;
    ASSERT_EQ(ihdr.size(), 13u);
    EXPECT_EQ(be32(&ihdr[0]), static_cast<uint32_t>(w));
    EXPECT_EQ(be32(&ihdr[4]), static_cast<uint32_t>(h));
    EXPECT_EQ(ihdr[8], 8);   // bit depth
    EXPECT_EQ(ihdr[9], 2);   // RGB
    EXPECT_EQ(ihdr[12], 0);  // not interlaced

    // zlib inflates the IDAT stream into every row behind filter type 4 (Paeth).
    const size_t row = static_cast<size_t>(w) * channels + 1;
    std::vector<unsigned char> rows(row * h);
    uLongf got = static_cast<uLongf>(rows.size());
    ASSERT_EQ(uncompress(rows.data(), &got, stream.data(), static_cast<uLong>(stream.size())), Z_OK);
    ASSERT_EQ(got, rows.size());
    for (int y = 0; y < h; ++y) ASSERT_EQ(rows[static_cast<size_t>(y) * row], 4) << "row " << y;
}

}  // namespace
