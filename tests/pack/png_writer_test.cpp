// matforge's PNG writer (lib/image/oiio/png_writer.hpp, reached through encode_image) read back by
// two decoders that share no code with it or with each other: stb_image (its own inflate) and
// OpenImageIO (libpng and zlib). Every layout PNG outputs use, odd sizes, noise and smooth
// ramps; the file's chunk sequence and CRCs checked with zlib's crc32, its rows' filter bytes
// read from zlib's inflate.
#include <gtest/gtest.h>
#include <stb_image.h>
#include <zlib.h>

#include <cmath>
#include <cstring>
#include <random>

#include "image/image.hpp"

namespace {

struct Chunk {
    std::string type;
    std::vector<unsigned char> data;
};

uint32_t be32(const unsigned char* p) {
    return (uint32_t{p[0]} << 24) | (uint32_t{p[1]} << 16) | (uint32_t{p[2]} << 8) | uint32_t{p[3]};
}

// The chunks of `png`, each CRC checked; fails the test on a malformed file.
std::vector<Chunk> chunks_of(const std::vector<unsigned char>& png) {
    static const unsigned char kSignature[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    std::vector<Chunk> out;
    EXPECT_TRUE(png.size() >= 8 && std::memcmp(png.data(), kSignature, 8) == 0);
    size_t at = 8;
    while (at + 12 <= png.size()) {
        const uint32_t len = be32(&png[at]);
        if (at + 12 + len > png.size()) break;
        const uint32_t crc = static_cast<uint32_t>(crc32(0, &png[at + 4], 4 + len));
        EXPECT_EQ(crc, be32(&png[at + 8 + len])) << "chunk at " << at;
        out.push_back({std::string(reinterpret_cast<const char*>(&png[at + 4]), 4),
                       std::vector<unsigned char>(png.begin() + static_cast<long>(at) + 8,
                                                  png.begin() + static_cast<long>(at + 8 + len))});
        at += 12 + len;
    }
    EXPECT_EQ(at, png.size()) << "bytes after the last chunk";
    return out;
}

// Samples of a w x h image of `channels`: noise, or a smooth ramp (long runs after the filter).
template <class T>
std::vector<T> samples(int w, int h, int channels, bool noise, unsigned seed) {
    std::vector<T> v(static_cast<size_t>(w) * h * channels);
    std::mt19937 rng(seed);
    constexpr unsigned kMax = sizeof(T) == 1 ? 255u : 65535u;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < channels; ++c)
                v[(static_cast<size_t>(y) * w + x) * channels + c] =
                    static_cast<T>(noise ? rng() % (kMax + 1)
                                         : (static_cast<unsigned>(x * 3 + y * 5 + c * 40) * (kMax / 255)) % (kMax + 1));
    return v;
}

// Encodes through encode_image: 8-bit as codes, 16-bit as floats k / 65535 (quantized back to k).
std::vector<unsigned char> encode(int w, int h, int channels, int depth, const std::vector<uint16_t>& s16,
                                  const std::vector<uint8_t>& s8) {
    std::vector<unsigned char> png;
    std::string err;
    if (depth == 8) {
        mf::Image8 img(w, h, channels);
        img.pixels = s8;
        EXPECT_TRUE(mf::encode_image(img, {mf::FileFormat::png, 8}, png, err)) << err;
    } else {
        mf::Image img(w, h, channels);
        for (size_t i = 0; i < s16.size(); ++i) img.pixels[i] = static_cast<float>(s16[i]) / 65535.f;
        EXPECT_TRUE(mf::encode_image(img, {mf::FileFormat::png, 16}, png, err)) << err;
    }
    return png;
}

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
                    mf::InputFile in;
                    in.display = "written.png";
                    in.bytes = std::make_shared<const std::vector<unsigned char>>(png);
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
