// matforge's PNG reader (lib/image/png_reader.hpp) against OpenImageIO (libpng and zlib): files
// libpng wrote with each row filter, 16-bit and Adam7 files, declared sizes their data cannot
// hold, every kind of PNG it must leave to OpenImageIO, and chunk sequences libpng refuses.
#include <gtest/gtest.h>
#include <png.h>
#include <zlib.h>

#include <cmath>
#include <cstring>
#include <random>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <functional>

#include "image/image.hpp"
#include "image/png_reader.hpp"
#include "oiio_oracle.hpp"
#include "png_chunks.hpp"
#include "test_files.hpp"

namespace {

using namespace pngtest;  // NOLINT: the test files' own helpers
using mf::testfiles::in_memory;

constexpr size_t kLimit = size_t{1} << 30;

TEST(PngReader, ReadsEveryFilterAndLayoutExactly) {
    const int sizes[][2] = {{1, 1}, {7, 3}, {3, 7}, {33, 17}, {300, 2}};
    unsigned seed = 100;
    for (int channels = 1; channels <= 4; ++channels)
        for (const auto& wh : sizes)
            for (bool noise : {true, false})
                // libpng's NONE, SUB, UP, AVG, PAETH alone, its adaptive choice, and matforge's writer.
                for (int filter : {0x08, 0x10, 0x20, 0x40, 0x80, 0, -1}) {
                    const int w = wh[0], h = wh[1];
                    SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + "x" + std::to_string(channels) +
                                 (noise ? " noise" : " ramp") + " filter " + std::to_string(filter));
                    const auto s8 = samples<uint8_t>(w, h, channels, noise, seed++);
                    const std::vector<unsigned char> png = filter < 0 ? encode(w, h, channels, 8, {}, s8)
                                                                      : libpng_file(w, h, channels, s8, filter);
                    mf::png::Plain p;
                    std::vector<unsigned char> file = png;
                    ASSERT_TRUE(mf::png::read_plain(file, kLimit, p));
                    EXPECT_EQ(p.width, w);
                    EXPECT_EQ(p.height, h);
                    EXPECT_EQ(p.channels, channels);
                    EXPECT_EQ(p.pixels, s8);
                    // And through read_image, as codes and as floats (OpenImageIO's k / 255).
                    const mf::InputFile in = in_memory(png, "plain.png");
                    mf::Decoded d;
                    mf::ImageInfo info;
                    std::string err;
                    ASSERT_TRUE(mf::read_image(in, d, info, err)) << err;
                    ASSERT_TRUE(d.is_codes());
                    EXPECT_EQ(d.codes.pixels, s8);
                    EXPECT_EQ(info.format, "png");
                    EXPECT_EQ(info.bit_depth, 8);
                    mf::Image floats;
                    ASSERT_TRUE(mf::read_image(in, floats, info, err)) << err;
                    EXPECT_EQ(floats.pixels, mf::to_float(d.codes).pixels);
                }
}

// 16-bit samples: libpng's files with each filter (OpenImageIO writing) and matforge's, read here
// as host-order codes and, through read_image, as the floats OpenImageIO reads (k / 65535).
TEST(PngReader, Reads16BitAsOpenImageIoDoes) {
    unsigned seed = 900;
    for (int channels = 1; channels <= 4; ++channels)
        for (int filter : {0x08, 0x10, 0x20, 0x40, 0x80, 0, -1}) {
            const int w = 37, h = 11;
            SCOPED_TRACE(std::to_string(channels) + " channels, filter " + std::to_string(filter));
            const auto s16 = samples<uint16_t>(w, h, channels, (seed & 1) != 0, seed);
            ++seed;
            std::vector<unsigned char> png;
            if (filter < 0) {
                png = encode(w, h, channels, 16, s16, {});
            } else {
                OIIO::ImageSpec spec(w, h, channels, OIIO::TypeDesc::UINT16);
                spec.attribute("oiio:UnassociatedAlpha", 1);
                if (filter) spec.attribute("png:filter", filter);
                OIIO::Filesystem::IOVecOutput vec(png);
                auto out = OIIO::ImageOutput::create("x.png");
                ASSERT_TRUE(out && out->set_ioproxy(&vec) && out->open("x.png", spec) &&
                            out->write_image(OIIO::TypeDesc::UINT16, s16.data()) && out->close());
            }
            std::vector<unsigned char> file = png;
            mf::png::Plain p;
            ASSERT_TRUE(mf::png::read_plain(file, kLimit, p));
            EXPECT_EQ(p.bit_depth, 16);
            std::vector<uint16_t> codes(p.pixels.size() / 2);
            std::memcpy(codes.data(), p.pixels.data(), p.pixels.size());
            EXPECT_EQ(codes, s16);
            EXPECT_EQ(mf::testenv::expect_floats_as_openimageio(in_memory(png, "h16.png"), png, "png").bit_depth, 16);
        }
}

// An Adam7-interlaced PNG made by libpng (OpenImageIO writes none): every pass, small images
// whose passes are partly empty among them, 8 and 16 bits, read as libpng's own reader and
// OpenImageIO read it.
std::vector<unsigned char> libpng_adam7(int w, int h, int channels, int depth, const void* samples) {
    std::vector<unsigned char> bytes;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        ADD_FAILURE() << "libpng failed";
        return {};
    }
    png_set_write_fn(
        png, &bytes,
        [](png_structp p, png_bytep data, png_size_t n) {
            auto* out = static_cast<std::vector<unsigned char>*>(png_get_io_ptr(p));
            for (png_size_t i = 0; i < n; ++i) out->push_back(data[i]);
        },
        nullptr);
    static constexpr int kType[] = {0, PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                                    PNG_COLOR_TYPE_RGBA};
    png_set_IHDR(png, info, static_cast<png_uint_32>(w), static_cast<png_uint_32>(h), depth, kType[channels],
                 PNG_INTERLACE_ADAM7, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    if (depth == 16) png_set_swap(png);  // host-order samples (little-endian hosts)
    const size_t row = static_cast<size_t>(w) * static_cast<size_t>(channels) * static_cast<size_t>(depth / 8);
    std::vector<png_bytep> rows(static_cast<size_t>(h));
    for (size_t y = 0; y < rows.size(); ++y)
        rows[y] = const_cast<png_bytep>(static_cast<const unsigned char*>(samples) + y * row);
    png_write_image(png, rows.data());
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return bytes;
}

TEST(PngReader, ReadsAdam7AsOpenImageIoDoes) {
    const int sizes[][2] = {{1, 1}, {2, 3}, {5, 1}, {9, 9}, {33, 17}};
    unsigned seed = 700;
    for (int depth : {8, 16})
        for (int channels = 1; channels <= 4; ++channels)
            for (const auto& wh : sizes) {
                const int w = wh[0], h = wh[1];
                SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + "x" + std::to_string(channels) + " " +
                             std::to_string(depth) + "-bit");
                const auto s8 = samples<uint8_t>(w, h, channels, true, seed);
                const auto s16 = samples<uint16_t>(w, h, channels, true, seed++);
                const std::vector<unsigned char> png = libpng_adam7(w, h, channels, depth,
                                                                    depth == 8 ? static_cast<const void*>(s8.data())
                                                                               : s16.data());
                std::vector<unsigned char> file = png;
                mf::png::Plain p;
                ASSERT_TRUE(mf::png::read_plain(file, kLimit, p));
                EXPECT_TRUE(p.interlaced);
                if (depth == 8) {
                    EXPECT_EQ(p.pixels, s8);
                } else {
                    ASSERT_EQ(p.pixels.size(), s16.size() * 2);
                    EXPECT_EQ(std::memcmp(p.pixels.data(), s16.data(), p.pixels.size()), 0);
                }
                mf::testenv::expect_floats_as_openimageio(in_memory(png, "adam7.png"), png, "png");
            }
}

// A lying header (issue 45): a 177-byte PNG declaring 16384x16384 RGBA 16-bit is refused on its
// header, by name or not, before anything is allocated (OpenImageIO would allocate 2 GiB, then
// fail for want of data); a real image whose data compresses far (a flat 4096x4096 grey: 1000
// rows' worth a kilobyte) is not.
TEST(PngReader, ADeclaredSizeItsDataCannotHoldIsRefused) {
    std::vector<unsigned char> ihdr = {0, 0, 0x40, 0, 0, 0, 0x40, 0, 16, 6, 0, 0, 0};
    std::vector<unsigned char> z(64);
    uLongf zn = z.size();
    const std::vector<unsigned char> row(64, 0);
    ASSERT_EQ(compress(z.data(), &zn, row.data(), static_cast<uLong>(row.size())), Z_OK);
    z.resize(zn);
    std::vector<unsigned char> lie = file_of({Chunk{"IHDR", ihdr}, Chunk{"IDAT", z}, Chunk{"IEND", {}}});
    for (const std::string name : {"lie.png", "lie.tif"}) {
        std::string err;
        EXPECT_FALSE(mf::read_info(mf::testfiles::in_memory(lie, name), err)) << name;
        EXPECT_NE(err.find("declares 16384x16384 pixels"), std::string::npos) << err;
        mf::Decoded d;
        mf::ImageInfo info;
        err.clear();
        EXPECT_FALSE(mf::read_image(mf::testfiles::in_memory(lie, name), d, info, err));
        EXPECT_NE(err.find("more than its"), std::string::npos) << err;
    }
    // A flat 4096x4096 grey PNG compresses over 500:1 (deflate's limit: 1032:1) and is read.
    const int n = 4096;
    const std::vector<uint8_t> flat(static_cast<size_t>(n) * n, 77);
    const std::vector<unsigned char> file = encode(n, n, 1, 8, {}, flat);
    ASSERT_LT(file.size() * 500, static_cast<size_t>(n) * n) << "the test needs a file that compresses over 500:1";
    std::string err;
    const auto info = mf::read_info(mf::testfiles::in_memory(file, "flat.png"), err);
    ASSERT_TRUE(info) << err;
    EXPECT_EQ(info->width, n);
}

TEST(PngReader, LeavesEveryOtherPngToOpenImageIo) {
    const int w = 9, h = 5, channels = 3;
    const auto s8 = samples<uint8_t>(w, h, channels, true, 5);
    const std::vector<unsigned char> good = encode(w, h, channels, 8, {}, s8);
    mf::png::Plain p;
    auto plain = [&p](std::vector<unsigned char> file, size_t limit = kLimit) {
        return mf::png::read_plain(file, limit, p);
    };
    ASSERT_TRUE(plain(good));
    const std::vector<Chunk> chunks = chunks_of(good);  // IHDR, tEXt, IDAT, IEND

    auto with = [&](const std::function<void(std::vector<Chunk>&)>& change) {
        std::vector<Chunk> c = chunks;
        change(c);
        return file_of(c);
    };
    auto ihdr_byte = [&](size_t at, unsigned char v) {
        return with([&](std::vector<Chunk>& c) { c[0].data[at] = v; });
    };
    // ImageMagick keeps EXIF as hex text in a zTXt chunk "Raw profile type exif"; OpenImageIO reads
    // the orientation in it (here 6), so the file is its, and matforge says ORIENTATION_IGNORED.
    const std::vector<unsigned char> imagemagick_exif = with([](auto& c) {
        const unsigned char exif[] = {'E',  'x', 'i', 'f', 0, 0, 'M', 'M', 0, 42, 0, 0, 0, 8, 0, 1, 0x01,
                                      0x12, 0,   3,   0,   0, 0, 1,   0,   6, 0,  0, 0, 0, 0, 0, 0, 0};
        std::string text = "\nexif\n      " + std::to_string(sizeof exif) + "\n";
        static const char* hex = "0123456789abcdef";
        for (unsigned char b : exif) text += {hex[b >> 4], hex[b & 15]};
        text += "\n";
        uLongf n = compressBound(static_cast<uLong>(text.size()));
        std::vector<unsigned char> z(n);
        compress(z.data(), &n, reinterpret_cast<const Bytef*>(text.data()), static_cast<uLong>(text.size()));
        z.resize(n);
        const std::string key = "Raw profile type exif";
        std::vector<unsigned char> data(key.begin(), key.end());
        data.push_back(0);
        data.push_back(0);  // compression method: deflate
        data.insert(data.end(), z.begin(), z.end());
        put(c, 1, Chunk{"zTXt", data});
    });
    {
        std::string err;
        const auto info = mf::read_info(in_memory(imagemagick_exif, "magick.png"), err);
        ASSERT_TRUE(info) << err;
        bool noted = false;
        for (const auto& n : info->notes) noted = noted || n.first == "ORIENTATION_IGNORED";
        EXPECT_TRUE(noted) << "the orientation OpenImageIO reads is said, as for any other PNG it reads";
    }
    const std::pair<std::string, std::vector<unsigned char>> refused[] = {
        {"2-bit samples", ihdr_byte(8, 2)},
        {"palette", ihdr_byte(9, 3)},
        {"an unknown interlace method", ihdr_byte(12, 2)},
        {"sBIT (significant bits)", with([](auto& c) {
             put(c, 1, Chunk{"sBIT", {5, 6, 5}});
         })},
        {"eXIf with orientation 6", with([](auto& c) {
             put(c, 1, Chunk{"eXIf", {'M', 'M', 0, 42, 0, 0, 0, 8, 0, 1, 0x01, 0x12, 0,
                                      3,   0,   0, 0,  1, 0, 6, 0, 0, 0, 0,    0,    0}});
         })},
        {"tRNS", with([](auto& c) {
             put(c, 1, Chunk{"tRNS", {0, 0, 0, 0, 0, 0}});
         })},
        {"an unknown chunk", with([](auto& c) {
             put(c, 1, Chunk{"abCd", {1, 2}});
         })},
        {"an orientation in text", with([](auto& c) {
             put(c, 1, Chunk{"tEXt", {'O', 'r', 'i', 'e', 'n', 't', 'a', 't', 'i', 'o', 'n', 0, '6'}});
         })},
        {"ImageMagick's raw EXIF profile in zTXt", imagemagick_exif},
        {"IDAT split by another chunk", with([](auto& c) {
             Chunk second{"IDAT", {c[2].data.begin() + 4, c[2].data.end()}};
             c[2].data.resize(4);
             put(c, 3, Chunk{"tEXt", {'a', 0, 'b'}});
             put(c, 4, second);
         })},
        {"no IEND", with([](auto& c) { c.pop_back(); })},
        {"a bad filter type", with([&](auto& c) {
             std::vector<unsigned char> rows(static_cast<size_t>(w * channels + 1) * h, 0);
             rows[0] = 5;
             uLongf n = compressBound(static_cast<uLong>(rows.size()));
             c[2].data.assign(n, 0);
             compress(c[2].data.data(), &n, rows.data(), static_cast<uLong>(rows.size()));
             c[2].data.resize(n);
         })},
    };
    EXPECT_TRUE(plain(with([](auto& c) {
        put(c, 1, Chunk{"tEXt", {'O', 'r', 'i', 'e', 'n', 't', 0, '6'}});
    }))) << "other text is inert";
    // Colour chunks OpenImageIO records and never applies, and EXIF that states no orientation:
    // read here, each value as OpenImageIO reads it (its floats, bit for bit).
    const std::pair<std::string, std::vector<unsigned char>> colour[] = {
        {"gAMA", with([](auto& c) {
             put(c, 1, Chunk{"gAMA", {0, 0, 0xB1, 0x8F}});
         })},
        {"sRGB", with([](auto& c) {
             put(c, 1, Chunk{"sRGB", {0}});
         })},
        {"cHRM", with([](auto& c) {
             put(c, 1, Chunk{"cHRM", {0, 0, 0x7A, 0x26, 0, 0, 0x80, 0x84, 0, 0, 0xFA, 0,    0, 0, 0x80, 0xE8,
                                      0, 0, 0x75, 0x30, 0, 0, 0xEA, 0x60, 0, 0, 0x3A, 0x98, 0, 0, 0x17, 0x70}});
         })},
        {"bKGD", with([](auto& c) {
             put(c, 1, Chunk{"bKGD", {0, 255, 0, 0, 0, 255}});
         })},
        {"eXIf without an orientation", with([](auto& c) {
             put(c, 1, Chunk{"eXIf", {'M', 'M', 0, 42, 0, 0, 0, 8, 0, 0, 0, 0, 0, 0}});
         })},
    };
    for (const auto& [why, bytes] : colour) {
        SCOPED_TRACE(why);
        EXPECT_TRUE(plain(bytes));
        EXPECT_EQ(p.pixels, s8);
        mf::testenv::expect_floats_as_openimageio(in_memory(bytes, "colour.png"), bytes, "png");
    }
    for (const auto& [why, bytes] : refused) {
        SCOPED_TRACE(why);
        EXPECT_FALSE(plain(bytes));
        EXPECT_TRUE(p.pixels.empty());
    }
    // Damage: a flipped bit in the pixels' CRC, a cut file, a size over the limit.
    std::vector<unsigned char> bad_crc = good;
    bad_crc[bad_crc.size() - 13] ^= 1;  // the IDAT chunk's CRC
    EXPECT_FALSE(plain(bad_crc));
    for (size_t cut : {size_t{8}, size_t{40}, good.size() - 12, good.size() - 1})
        EXPECT_FALSE(plain({good.begin(), good.begin() + static_cast<long>(cut)})) << cut;
    EXPECT_FALSE(plain(good, w * h * channels - 1));
    EXPECT_TRUE(plain(good, w * h * channels));
    // What OpenImageIO then says about the file with an sBIT chunk: its pixels, as before.
    const mf::InputFile in = in_memory(refused[3].second, "sbit.png");
    mf::Decoded d;
    mf::ImageInfo info;
    std::string err;
    ASSERT_TRUE(mf::read_image(in, d, info, err)) << err;
    EXPECT_EQ(d.codes.pixels, s8);
}

// IDAT chunks must be consecutive (PNG spec 5.6); libpng refuses IDAT, tEXt, IDAT. The reader
// moves each IDAT's data to the front of the file as it goes: a first IDAT large enough to cover
// its own chunk header must not erase what the reader knows of the chunk order.
TEST(PngReader, AnIdatRunBrokenByAnotherChunkIsRefusedWhateverItsSize) {
    const int w = 64, h = 64, channels = 3;
    const std::vector<unsigned char> good = encode(w, h, channels, 8, {}, samples<uint8_t>(w, h, channels, true, 9));
    std::vector<Chunk> c = chunks_of(good);  // IHDR, tEXt, IDAT, IEND
    ASSERT_EQ(c[2].type, "IDAT");
    ASSERT_GT(c[2].data.size(), 1000u);  // noise: the first part covers everything before it
    Chunk tail{"IDAT", {c[2].data.end() - 4, c[2].data.end()}};
    c[2].data.resize(c[2].data.size() - 4);
    put(c, 3, Chunk{"tEXt", {'a', 0, 'b'}});
    put(c, 4, tail);
    std::vector<unsigned char> split = file_of(c);
    mf::png::Plain p;
    std::vector<unsigned char> copy = split;
    EXPECT_FALSE(mf::png::read_plain(copy, kLimit, p));
    EXPECT_TRUE(p.pixels.empty());
    // Left to OpenImageIO, whose libpng refuses it: an error naming the file, no pixels.
    mf::Decoded d;
    mf::ImageInfo info;
    std::string err;
    EXPECT_FALSE(mf::read_image(in_memory(split, "split.png"), d, info, err));
    EXPECT_NE(err.find("split.png"), std::string::npos) << err;
}

}  // namespace
