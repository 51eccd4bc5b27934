// PNG's row filters reversed (lib/image/png_unfilter.hpp): every vector form byte for byte as
// the scalar one on random rows (every filter, pixel size, width; first rows; in place and moved
// over the bytes before it, as the reader moves each row over its filter byte), Paeth's for all
// 2^24 (left, above, upper left) triples as the spec's predictor, and real pictures, 8 and 16
// bits, written with each filter by libpng and by matforge's writer, read by read_plain as
// OpenImageIO reads them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>

#include "image/png_reader.hpp"
#include "image/png_unfilter.hpp"
#include "oiio_oracle.hpp"
#include "png_chunks.hpp"
#include "test_env.hpp"
#include "test_files.hpp"

namespace unfiltertest {

using mf::png::UnfilterIsa;

// The forms this build and CPU run besides the scalar one (SSE2 and SSE4.1 on x86-64): on a
// machine without them the test would compare nothing, so it says so.
std::vector<UnfilterIsa> vector_forms() {
    std::vector<UnfilterIsa> out;
    for (UnfilterIsa isa : {UnfilterIsa::sse2, UnfilterIsa::sse41})
        if (mf::png::can_unfilter_with(isa)) out.push_back(isa);
    return out;
}

const char* name_of(UnfilterIsa isa) {
    return isa == UnfilterIsa::sse41 ? "SSE4.1" : isa == UnfilterIsa::sse2 ? "SSE2" : "scalar";
}

// The spec's Paeth predictor (PNG spec 9.4), written out as it is there.
int paeth_predictor(int a, int b, int c) {
    const int p = a + b - c;
    const int pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
    if (pa <= pb && pa <= pc) return a;
    if (pb <= pc) return b;
    return c;
}

// Row contents: noise, bytes at the ends of the range, and the small residuals real rows have.
std::vector<uint8_t> row_of(size_t n, int kind, std::mt19937& rng) {
    std::vector<uint8_t> r(n);
    for (auto& v : r) {
        const auto x = static_cast<uint8_t>(rng());
        v = kind == 0 ? x : kind == 1 ? static_cast<uint8_t>((x & 1) ? 255 - (x >> 6) : (x >> 6)) : x % 5;
    }
    return r;
}

// An 8-bit PNG of `px` written by libpng (OpenImageIO) with filter mask `filter` (0: libpng's
// adaptive choice per row), or by matforge's writer (filter -1: Paeth, libdeflate).
std::vector<unsigned char> png8(int w, int h, int channels, const std::vector<uint8_t>& px, int filter) {
    return filter < 0 ? pngtest::encode(w, h, channels, 8, {}, px) : pngtest::libpng_file(w, h, channels, px, filter);
}

std::vector<unsigned char> png16(int w, int h, int channels, const std::vector<uint16_t>& px, int filter) {
    return filter < 0 ? pngtest::encode(w, h, channels, 16, px, {}) : pngtest::libpng_file(w, h, channels, px, filter);
}

// read_plain's samples of `png` equal OpenImageIO's (8-bit codes, or 16-bit in host order), and
// the `bytes` at `expected` where given.
void expect_read_as_openimageio(const std::vector<unsigned char>& png, const void* expected = nullptr,
                                size_t bytes = 0) {
    std::vector<unsigned char> file = png;
    mf::png::Plain p;
    ASSERT_TRUE(mf::png::read_plain(file, size_t{1} << 30, p));
    const auto o = mf::testenv::oiio_read(png, "png",
                                          p.bit_depth == 8 ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::UINT16);
    ASSERT_TRUE(o.ok);
    EXPECT_EQ(p.pixels, o.pixels);
    if (!expected) return;
    ASSERT_EQ(p.pixels.size(), bytes);
    EXPECT_EQ(std::memcmp(p.pixels.data(), expected, bytes), 0);
}

// Pictures, codes of real photographs: sample_materials' planks (colour), their normal map and
// their packed ARM map, as OpenImageIO decodes them.
struct Photo {
    int width = 0, height = 0;
    std::vector<uint8_t> rgb;
};
Photo photo(const std::string& file) {
    const std::filesystem::path path = mf::testenv::source_dir() / "sample_materials" / "flat_two_sets" / file;
    const auto o = mf::testenv::oiio_read(mf::testfiles::file_bytes(path), "jpeg", OIIO::TypeDesc::UINT8);
    EXPECT_TRUE(o.ok && o.spec.nchannels == 3) << path;
    return {o.spec.width, o.spec.height, o.pixels};
}

}  // namespace unfiltertest

using namespace unfiltertest;  // NOLINT: this file's helpers

// Every vector form equals the scalar one, byte for byte, for each filter and pixel size, widths
// around the vector widths (16 bytes, Paeth's blocks of 48), rows of noise, extremes and small
// residuals, first rows (zeros above), rows reconstructed in place and moved over 1 to 17 bytes
// before them (as read_plain moves each row over its filter byte and the rows before); nothing
// past the row is written, and an unknown filter type changes nothing.
TEST(PngUnfilter, VectorFormsEqualTheScalarOneOnRandomRows) {
    const std::vector<UnfilterIsa> forms = vector_forms();
#if defined(__x86_64__)
    ASSERT_FALSE(forms.empty()) << "x86-64 always has SSE2";
#endif
    // The scalar form moved too: it is read_plain's on other machines.
    std::vector<UnfilterIsa> moved_forms = forms;
    moved_forms.insert(moved_forms.begin(), UnfilterIsa::scalar);
    std::mt19937 rng(2024);
    size_t compared = 0;
    for (int bpp : {1, 2, 3, 4, 6, 8})
        for (size_t width : {1, 2, 3, 4, 5, 6, 15, 16, 17, 31, 32, 33, 47, 48, 49, 97, 1023})
            for (int kind = 0; kind < 3; ++kind)
                for (bool first : {false, true}) {
                    const size_t n = width * static_cast<size_t>(bpp);
                    const std::vector<uint8_t> in = row_of(n, kind, rng);
                    const std::vector<uint8_t> up = first ? std::vector<uint8_t>(n, 0) : row_of(n, (kind + 1) % 3, rng);
                    for (int type = 0; type <= 4; ++type) {
                        SCOPED_TRACE("bpp " + std::to_string(bpp) + ", width " + std::to_string(width) + ", kind " +
                                     std::to_string(kind) + (first ? ", first row" : "") + ", filter " +
                                     std::to_string(type));
                        std::vector<uint8_t> want = in;
                        ASSERT_TRUE(mf::png::unfilter_row(type, want.data(), want.data(), up.data(), width, bpp,
                                                          UnfilterIsa::scalar));
                        if (type == 0) {
                            EXPECT_EQ(want, in);
                        }
                        for (UnfilterIsa isa : moved_forms) {
                            for (size_t shift : {size_t{0}, size_t{1}, static_cast<size_t>(bpp), size_t{17}}) {
                                SCOPED_TRACE(std::string(name_of(isa)) + ", moved " + std::to_string(shift));
                                // The row at `shift`, then guard bytes; made at 0.
                                std::vector<uint8_t> buf(shift + n + 16, 0xA5);
                                std::copy(in.begin(), in.end(), buf.begin() + static_cast<std::ptrdiff_t>(shift));
                                ASSERT_TRUE(mf::png::unfilter_row(type, buf.data() + shift, buf.data(), up.data(),
                                                                  width, bpp, isa));
                                ASSERT_TRUE(std::equal(want.begin(), want.end(), buf.begin()));
                                for (size_t i = n; i < buf.size(); ++i)  // past the row: as it was
                                    ASSERT_EQ(buf[i], i >= shift && i < shift + n ? in[i - shift] : 0xA5)
                                        << "byte " << i;
                                ++compared;
                            }
                        }
                    }
                    for (UnfilterIsa isa : {UnfilterIsa::scalar, UnfilterIsa::sse2, UnfilterIsa::sse41}) {
                        if (!mf::png::can_unfilter_with(isa)) continue;
                        std::vector<uint8_t> row = in;
                        EXPECT_FALSE(mf::png::unfilter_row(5, row.data(), row.data(), up.data(), width, bpp, isa));
                        EXPECT_FALSE(mf::png::unfilter_row(255, row.data(), row.data(), up.data(), width, bpp, isa));
                        EXPECT_EQ(row, in);
                    }
                }
    EXPECT_EQ(compared, 6u * 17 * 3 * 2 * 5 * moved_forms.size() * 4);
}

// Paeth in every form, for every (a, b, c) of bytes, against the spec's predictor: a row of two
// pixels per triple (the first pixel's reconstruction is a, the row above holds c then b), in
// pixels of 1 byte and of 3 (the triples spread over the channels: the wide loads and stores of
// 3-byte pixels). Their filtered bytes come from the spec's forward filter of known pixels.
TEST(PngUnfilter, PaethTakesEveryTripleAsTheSpecDoes) {
    std::vector<UnfilterIsa> forms = vector_forms();
    forms.insert(forms.begin(), UnfilterIsa::scalar);
    for (int bpp : {1, 3}) {
        const auto b = static_cast<size_t>(bpp);
        const size_t triples = size_t{1} << 24, pairs = (triples + b - 1) / b, width = 2 * pairs, n = width * b;
        std::vector<uint8_t> up(n), pixels(n), filtered(n);
        std::mt19937 rng(static_cast<unsigned>(bpp));
        for (auto& v : pixels) v = static_cast<uint8_t>(rng());
        for (size_t t = 0; t < triples; ++t) {
            const size_t at = 2 * (t / b) * b + t % b;  // the pair's first pixel, the triple's channel
            pixels[at] = static_cast<uint8_t>(t);       // a
            up[at + b] = static_cast<uint8_t>(t >> 8);  // b
            up[at] = static_cast<uint8_t>(t >> 16);     // c
        }
        for (size_t i = 0; i < n; ++i) {
            const int a = i >= b ? pixels[i - b] : 0, c = i >= b ? up[i - b] : 0;
            filtered[i] = static_cast<uint8_t>(pixels[i] - paeth_predictor(a, up[i], c));
        }
        for (UnfilterIsa isa : forms) {
            std::vector<uint8_t> row = filtered;
            ASSERT_TRUE(mf::png::unfilter_row(4, row.data(), row.data(), up.data(), width, bpp, isa));
            size_t wrong = 0;
            for (size_t i = 0; i < n; ++i) wrong += row[i] != pixels[i];
            EXPECT_EQ(wrong, 0u) << name_of(isa) << ", " << bpp << "-byte pixels";
        }
    }
}

// Real pictures (crops of photographs) of 1 to 4 channels, 8 and 16 bits, at widths around the
// vector widths, written by libpng with each of the five filters alone and with its adaptive
// choice, and by matforge's writer (Paeth, as ingest writes its outputs): read_plain reads every
// sample as OpenImageIO (libpng) does. The plain reader takes the fastest form this CPU has.
TEST(PngUnfilter, RealPicturesWithEveryFilterReadAsOpenImageIoReadsThem) {
    const Photo colour = photo("brown_planks_09_diff_1k.jpg"), normal = photo("brown_planks_09_nor_gl_1k.jpg");
    ASSERT_GE(colour.width, 1023);
    ASSERT_EQ(normal.width, colour.width);
    const int widths[] = {1, 2, 3, 5, 15, 16, 17, 33, 1023};
    int files = 0;
    for (int w : widths)
        for (int channels = 1; channels <= 4; ++channels) {
            const int h = w < 64 ? 11 : 6;
            const int x0 = (colour.width - w) / 3, y0 = 200 + channels * 40;
            // Channels: the colour's R, G, B, the normal's G as a 4th (alpha, or grey+alpha's).
            std::vector<uint8_t> s8;
            std::vector<uint16_t> s16;
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    const size_t at = (static_cast<size_t>(y0 + y) * static_cast<size_t>(colour.width) +
                                       static_cast<size_t>(x0 + x)) *
                                      3;
                    const uint8_t rgba[4] = {colour.rgb[at], colour.rgb[at + 1], colour.rgb[at + 2],
                                             normal.rgb[at + 1]};
                    for (int c = 0; c < channels; ++c) {
                        const uint8_t v = rgba[channels == 2 && c == 1 ? 3 : c];
                        s8.push_back(v);
                        // 16 bits: the code, and the normal's B as the low byte (real, not smooth).
                        s16.push_back(static_cast<uint16_t>(v << 8 | normal.rgb[at + 2]));
                    }
                }
            for (int filter : {0x08, 0x10, 0x20, 0x40, 0x80, 0, -1}) {
                SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + "x" + std::to_string(channels) +
                             ", filter " + std::to_string(filter));
                expect_read_as_openimageio(png8(w, h, channels, s8, filter), s8.data(), s8.size());
                expect_read_as_openimageio(png16(w, h, channels, s16, filter), s16.data(), s16.size() * 2);
                files += 2;
            }
        }
    EXPECT_EQ(files, 9 * 4 * 7 * 2);
}

// The PNGs of sample_materials (vendors' height maps and a preview, 1024 x 1024 RGBA, written
// with libpng's choice per row: one mostly Average rows, one Paeth, one all five filters):
// read_plain reads them as OpenImageIO does.
TEST(PngUnfilter, SampleMaterialsPngsReadAsOpenImageIoReadsThem) {
    int files = 0;
    for (const auto& e :
         std::filesystem::recursive_directory_iterator(mf::testenv::source_dir() / "sample_materials")) {
        if (e.path().extension() != ".png") continue;
        SCOPED_TRACE(e.path().string());
        expect_read_as_openimageio(mf::testfiles::file_bytes(e.path()));
        ++files;
    }
    EXPECT_GE(files, 3);
}
