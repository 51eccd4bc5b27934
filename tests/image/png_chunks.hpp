// For the tests of lib/image's PNG writer and reader: a file taken apart into its chunks (each
// CRC checked with zlib's crc32) and put together again, so a test can build the files the
// reader must refuse; and the samples both write, PNG-encoded by matforge's writer.
#pragma once
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdint>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "image/image.hpp"

namespace pngtest {

struct Chunk {
    std::string type;
    std::vector<unsigned char> data;
};

inline uint32_t be32(const unsigned char* p) {
    return (uint32_t{p[0]} << 24) | (uint32_t{p[1]} << 16) | (uint32_t{p[2]} << 8) | uint32_t{p[3]};
}

// The chunks of `png`, each CRC checked; fails the test on a malformed file.
inline std::vector<Chunk> chunks_of(const std::vector<unsigned char>& png) {
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
// A chunk with its length and CRC (zlib's crc32), for building files the reader must refuse.
inline std::vector<unsigned char> chunk(const std::string& type, const std::vector<unsigned char>& data) {
    std::vector<unsigned char> c(4);
    const auto len = static_cast<uint32_t>(data.size());
    for (int k = 0; k < 4; ++k) c[static_cast<size_t>(k)] = static_cast<unsigned char>(len >> (24 - 8 * k));
    c.insert(c.end(), type.begin(), type.end());
    c.insert(c.end(), data.begin(), data.end());
    const auto crc = static_cast<uint32_t>(crc32(0, c.data() + 4, static_cast<uInt>(4 + data.size())));
    for (int k = 0; k < 4; ++k) c.push_back(static_cast<unsigned char>(crc >> (24 - 8 * k)));
    return c;
}

// `c` with `x` before its element `at` (a plain loop: GCC 12's -Warray-bounds misreads
// vector::insert of this struct).
inline void put(std::vector<Chunk>& c, size_t at, Chunk x) {
    std::vector<Chunk> out;
    out.reserve(c.size() + 1);
    for (size_t i = 0; i <= c.size(); ++i) {
        if (i == at) out.push_back(x);
        if (i < c.size()) out.push_back(std::move(c[i]));
    }
    c = std::move(out);
}

inline std::vector<unsigned char> file_of(const std::vector<Chunk>& chunks) {
    std::vector<unsigned char> f = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    for (const Chunk& c : chunks) {
        const auto bytes = chunk(c.type, c.data);
        f.insert(f.end(), bytes.begin(), bytes.end());
    }
    return f;
}

template <class T>
inline std::vector<T> samples(int w, int h, int channels, bool noise, unsigned seed) {
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
inline std::vector<unsigned char> encode(int w, int h, int channels, int depth, const std::vector<uint16_t>& s16,
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

// 8-bit (uint8_t) or 16-bit (uint16_t, host order) samples written by OpenImageIO (libpng, zlib)
// with libpng filter mask `filter` (0: its adaptive default, which picks among all five per row).
template <class T>
std::vector<unsigned char> libpng_file(int w, int h, int channels, const std::vector<T>& samples, int filter) {
    static_assert(std::is_same_v<T, uint8_t> || std::is_same_v<T, uint16_t>);
    const OIIO::TypeDesc type = sizeof(T) == 1 ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::UINT16;
    OIIO::ImageSpec spec(w, h, channels, type);
    spec.attribute("oiio:UnassociatedAlpha", 1);
    if (filter) spec.attribute("png:filter", filter);
    std::vector<unsigned char> bytes;
    OIIO::Filesystem::IOVecOutput vec(bytes);
    auto out = OIIO::ImageOutput::create("x.png");
    EXPECT_TRUE(out && out->set_ioproxy(&vec) && out->open("x.png", spec) && out->write_image(type, samples.data()) &&
                out->close());
    return bytes;
}

}  // namespace pngtest
