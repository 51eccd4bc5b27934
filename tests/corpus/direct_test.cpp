// The JPEGs, PNGs and WebPs matforge reads without OpenImageIO (lib/image/direct.hpp) against
// OpenImageIO itself, on every real file of the corpus: where the direct readers accept a file,
// its size, channels, depth, orientation, stated colour space and every code must be what
// OpenImageIO reads; and they must accept the everyday files (else the module loads anyway).
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <iterator>

#include "corpus.hpp"
#include "image/image.hpp"
#include "image/jpeg_reader.hpp"
#include "image/png_reader.hpp"
#include "image/webp_reader.hpp"
#include "oiio_oracle.hpp"

namespace {

std::vector<unsigned char> bytes_of(const corpus::fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

// `path` as an input file of matforge's readers.
mf::InputFile input_of(const corpus::fs::path& path) {
    mf::InputFile in;
    in.display = path.string();
    in.path = path;
    return in;
}

std::vector<corpus::fs::path> corpus_files(std::initializer_list<const char*> extensions) {
    std::vector<corpus::fs::path> out;
    for (const auto& e : corpus::fs::recursive_directory_iterator(corpus::dir() / "real")) {
        const std::string ext = e.path().extension().string();
        if (e.is_regular_file() && std::find(extensions.begin(), extensions.end(), ext) != extensions.end())
            out.push_back(e.path());
    }
    std::sort(out.begin(), out.end());
    return out;
}

TEST(DirectCodecs, CorpusJpegsReadAsOpenImageIoReadsThem) {
    size_t files = 0, accepted = 0, with_exif = 0;
    for (const auto& path : corpus_files({".jpg", ".jpeg"})) {
        SCOPED_TRACE(path.string());
        ++files;
        const std::vector<unsigned char> file = bytes_of(path);
        const uint64_t end = mf::jpeg::first_scan_header_end(file.size(), [&](uint64_t at, size_t n, unsigned char* o) {
            if (at + n > file.size()) return false;
            std::memcpy(o, file.data() + at, n);
            return true;
        });
        ASSERT_GT(end, 0u);
        mf::jpeg::Plain head, whole;
        const bool head_ok = mf::jpeg::read_plain(file.data(), static_cast<size_t>(end), true, uint64_t{1} << 30, head,
                                                  file.size());
        const bool whole_ok = mf::jpeg::read_plain(file.data(), file.size(), false, uint64_t{1} << 30, whole,
                                                   file.size());
        EXPECT_EQ(head_ok, whole_ok) << "the header read accepts what the decode accepts";
        if (!whole_ok) continue;
        ++accepted;
        const auto o = mf::testenv::oiio_read(file, "jpeg", OIIO::TypeDesc::UINT8);
        EXPECT_EQ(whole.width, o.spec.width);
        EXPECT_EQ(whole.height, o.spec.height);
        EXPECT_EQ(whole.channels, o.spec.nchannels);
        EXPECT_EQ(whole.orientation, o.spec.get_int_attribute("Orientation", 1));
        EXPECT_EQ(head.orientation, whole.orientation);
        EXPECT_EQ(o.spec.get_string_attribute("oiio:ColorSpace"), "sRGB") << "what direct::read_info states";
        EXPECT_TRUE(whole.pixels == o.pixels) << "every code as OpenImageIO decodes it";
        with_exif += o.spec.find_attribute("Exif:ColorSpace") || o.spec.find_attribute("ExposureTime") ||
                     o.spec.find_attribute("Exif:PixelXDimension");
        // And through matforge's readers, which take this path: the same codes and header.
        const mf::InputFile in = input_of(path);
        std::string err;
        const auto info = mf::read_info(in, err);
        ASSERT_TRUE(info) << err;
        EXPECT_EQ(info->format, "jpeg");
        EXPECT_EQ(info->notes.empty(), whole.orientation == 1);
        mf::Decoded d;
        mf::ImageInfo decoded;
        ASSERT_TRUE(mf::read_image(in, d, decoded, err)) << err;
        EXPECT_TRUE(d.codes.pixels == o.pixels);
        const auto stated = mf::stated_color_space(in);
        EXPECT_EQ(stated.color_space, "sRGB");
        EXPECT_EQ(stated.format, "jpeg");
    }
    EXPECT_GE(files, 80u);
    // Every corpus JPEG is an everyday one: 8-bit grey or YCbCr, EXIF from Photoshop or none.
    EXPECT_EQ(accepted, files);
    EXPECT_GE(with_exif, 10u) << "the corpus's EXIF blocks are walked, not only files without one";
}

TEST(DirectCodecs, CorpusPngsReadAsOpenImageIoReadsThem) {
    size_t files = 0, accepted = 0, palettes = 0;
    for (const auto& path : corpus_files({".png"})) {
        SCOPED_TRACE(path.string());
        ++files;
        std::vector<unsigned char> file = bytes_of(path);
        mf::png::Plain head, p;
        const bool head_ok = mf::png::read_plain_header(
            file.size(),
            [&](uint64_t at, size_t n, unsigned char* o) {
                if (at + n > file.size()) return false;
                std::memcpy(o, file.data() + at, n);
                return true;
            },
            size_t{1} << 30, head);
        const bool ok = mf::png::read_plain(file, size_t{1} << 30, p);
        EXPECT_EQ(head_ok, ok);
        // Colour type 3 (a palette: the tps-demo's emissive map) is left to OpenImageIO.
        const bool palette = file.size() > 25 && file[25] == 3;
        EXPECT_EQ(ok, !palette);
        if (palette) {
            ++palettes;
            mf::testenv::expect_floats_as_openimageio(input_of(path), bytes_of(path), "png");
        }
        if (!ok) continue;
        ++accepted;
        const auto o = mf::testenv::oiio_read(bytes_of(path), "png", OIIO::TypeDesc::FLOAT);
        EXPECT_EQ(p.width, o.spec.width);
        EXPECT_EQ(p.height, o.spec.height);
        EXPECT_EQ(p.channels, o.spec.nchannels);
        EXPECT_EQ(p.bit_depth, static_cast<int>(o.spec.format.size()) * 8);
        EXPECT_EQ(o.spec.get_int_attribute("Orientation", 1), 1);
        // Through matforge's reader: every float as OpenImageIO's.
        const mf::InputFile in = input_of(path);
        mf::testenv::expect_floats_as_openimageio(in, bytes_of(path), "png");
        std::string err;
        const auto header = mf::read_info(in, err);
        ASSERT_TRUE(header) << err;
        EXPECT_EQ(header->bit_depth, p.bit_depth);
        EXPECT_TRUE(header->notes.empty());
    }
    EXPECT_GE(files, 12u);
    // Every one is read here: interlaced files, a 16-bit height with an EXIF chunk, files with
    // gAMA, sRGB, cHRM, iCCP and bKGD chunks among them; the one palette file through OpenImageIO.
    EXPECT_EQ(palettes, 1u);
    EXPECT_EQ(accepted + palettes, files);
}

TEST(DirectCodecs, CorpusWebpsReadAsOpenImageIoReadsThem) {
    size_t files = 0, accepted = 0;
    for (const auto& path : corpus_files({".webp"})) {
        SCOPED_TRACE(path.string());
        ++files;
        const std::vector<unsigned char> file = bytes_of(path);
        mf::webp::Plain p;
        if (!mf::webp::read_plain(file.data(), file.size(), false, uint64_t{1} << 30, p)) continue;
        ++accepted;
        const auto o = mf::testenv::oiio_read(file, "webp", OIIO::TypeDesc::UINT8);
        EXPECT_EQ(p.width, o.spec.width);
        EXPECT_EQ(p.height, o.spec.height);
        EXPECT_EQ(o.spec.nchannels, 3);
        EXPECT_TRUE(p.pixels == o.pixels) << "every code as OpenImageIO decodes it";
    }
    EXPECT_GE(files, 6u);
    EXPECT_EQ(accepted, files) << "Poly Haven's WebP maps are still and opaque";
}

}  // namespace
