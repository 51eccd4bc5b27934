// matforge's JPEG reader (lib/image/jpeg_reader.hpp, reached through read_info and read_image)
// on files made here with libjpeg: grey and colour, baseline and progressive, EXIF orientations
// in both byte orders, and the files it must leave to OpenImageIO (two EXIF blocks, an XMP
// orientation, CMYK, a cut file, a JPEG under another name). Where it reads a file, every code
// and header fact must be OpenImageIO's; where it declines, matforge's readers say what
// OpenImageIO says.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <jpeglib.h>

#include "image/image.hpp"
#include "image/jpeg_reader.hpp"
#include "oiio_oracle.hpp"
#include "test_files.hpp"

namespace {

struct Marker {
    int code;  // JPEG_APP0 + n
    std::vector<unsigned char> data;
};

// A w x h JPEG of `components` (1 grey, 3 RGB as YCbCr, 4 CMYK) of smooth noise, with `markers`
// written after the JFIF header.
std::vector<unsigned char> make_jpeg(int w, int h, int components, bool progressive,
                                     const std::vector<Marker>& markers = {}) {
    jpeg_compress_struct c{};
    jpeg_error_mgr err{};
    c.err = jpeg_std_error(&err);
    jpeg_create_compress(&c);
    unsigned char* out = nullptr;
    unsigned long size = 0;
    jpeg_mem_dest(&c, &out, &size);
    c.image_width = static_cast<JDIMENSION>(w);
    c.image_height = static_cast<JDIMENSION>(h);
    c.input_components = components;
    c.in_color_space = components == 1 ? JCS_GRAYSCALE : components == 3 ? JCS_RGB : JCS_CMYK;
    jpeg_set_defaults(&c);
    jpeg_set_quality(&c, 90, TRUE);
    if (progressive) jpeg_simple_progression(&c);
    jpeg_start_compress(&c, TRUE);
    for (const Marker& m : markers)
        jpeg_write_marker(&c, m.code, m.data.data(), static_cast<unsigned int>(m.data.size()));
    std::mt19937 rng(static_cast<unsigned>(w * 31 + h * 7 + components));
    std::vector<unsigned char> row(static_cast<size_t>(w) * static_cast<size_t>(components));
    while (c.next_scanline < c.image_height) {
        for (size_t i = 0; i < row.size(); ++i)
            row[i] = static_cast<unsigned char>((i * 3 + c.next_scanline * 5 + (rng() & 15)) & 0xFF);
        JSAMPROW r[1] = {row.data()};
        jpeg_write_scanlines(&c, r, 1);
    }
    jpeg_finish_compress(&c);
    std::vector<unsigned char> bytes(out, out + size);
    jpeg_destroy_compress(&c);
    std::free(out);
    return bytes;
}

// An EXIF APP1 block ("Exif\0\0" and a TIFF structure) whose IFD0 holds `orientation` (0: none)
// and, when `sub_ifd`, a pointer to an EXIF sub-IFD holding ColorSpace 1 and, when
// `sub_orientation`, an orientation too; then an IFD1 (a thumbnail's, with its own orientation 8,
// which OpenImageIO does not read).
Marker exif(bool little, int orientation, bool sub_ifd = false, int sub_orientation = 0) {
    std::vector<unsigned char> t;
    // push_back, not insert: GCC 12's -Warray-bounds misreads vector::insert into small vectors.
    auto u16 = [&](unsigned v) {
        t.push_back(static_cast<unsigned char>(little ? v : v >> 8));
        t.push_back(static_cast<unsigned char>(little ? v >> 8 : v));
    };
    auto u32 = [&](uint32_t v) {
        if (little) {
            u16(v & 0xFFFF);
            u16(v >> 16);
        } else {
            u16(v >> 16);
            u16(v & 0xFFFF);
        }
    };
    auto entry = [&](unsigned tag, unsigned type, uint32_t count, uint32_t value) {
        u16(tag);
        u16(type);
        u32(count);
        if (type == 3) {
            u16(value);
            u16(0);
        } else {
            u32(value);
        }
    };
    t.push_back(little ? 'I' : 'M');
    t.push_back(little ? 'I' : 'M');
    u16(42);
    u32(8);                                                                  // IFD0 right after the header
    const unsigned n0 = (orientation ? 1u : 0u) + (sub_ifd ? 1u : 0u) + 1u;  // + XResolution-like filler
    const uint32_t ifd0_end = 8 + 2 + n0 * 12 + 4;
    const uint32_t sub_at = ifd0_end;
    const unsigned n_sub = 1u + (sub_orientation ? 1u : 0u);
    const uint32_t ifd1_at = sub_ifd ? sub_at + 2 + n_sub * 12 + 4 : ifd0_end;
    u16(n0);
    entry(0x0100, 3, 1, 64);  // ImageWidth
    if (orientation) entry(0x0112, 3, 1, static_cast<uint32_t>(orientation));
    if (sub_ifd) entry(0x8769, 4, 1, sub_at);
    u32(ifd1_at);
    if (sub_ifd) {
        u16(n_sub);
        if (sub_orientation) entry(0x0112, 3, 1, static_cast<uint32_t>(sub_orientation));
        entry(0xA001, 3, 1, 1);  // ColorSpace: sRGB
        u32(0);
    }
    u16(1);
    entry(0x0112, 3, 1, 8);  // IFD1's
    u32(0);
    Marker m{JPEG_APP0 + 1, {'E', 'x', 'i', 'f', 0, 0}};
    for (unsigned char b : t) m.data.push_back(b);
    return m;
}

Marker xmp(const std::string& body) {
    const std::string s = std::string("http://ns.adobe.com/xap/1.0/") + '\0' + body;
    return {JPEG_APP0 + 1, {s.begin(), s.end()}};
}

using mf::testfiles::in_memory;

mf::testenv::OiioRead oiio_read(const std::vector<unsigned char>& bytes) {
    return mf::testenv::oiio_read(bytes, "jpeg", OIIO::TypeDesc::UINT8);
}

// jpeg::read_plain over the whole file and over its markers alone.
bool direct(const std::vector<unsigned char>& file, mf::jpeg::Plain& whole, mf::jpeg::Plain& head) {
    const uint64_t end = mf::jpeg::first_scan_header_end(file.size(), [&](uint64_t at, size_t n, unsigned char* o) {
        if (at + n > file.size()) return false;
        std::memcpy(o, file.data() + at, n);
        return true;
    });
    const bool head_ok = end > 0 && mf::jpeg::read_plain(file.data(), static_cast<size_t>(end), true, 1u << 24, head);
    const bool ok = mf::jpeg::read_plain(file.data(), file.size(), false, 1u << 24, whole);
    EXPECT_EQ(head_ok, ok);
    return ok;
}

// matforge's readers on `file` named `name` state OpenImageIO's facts and codes.
void expect_as_openimageio(const std::vector<unsigned char>& file, const std::string& name) {
    const auto o = oiio_read(file);
    ASSERT_TRUE(o.ok);
    const mf::InputFile in = in_memory(file, name);
    std::string err;
    const auto info = mf::read_info(in, err);
    ASSERT_TRUE(info) << err;
    EXPECT_EQ(info->width, o.spec.width);
    EXPECT_EQ(info->height, o.spec.height);
    EXPECT_EQ(info->channels, o.spec.nchannels);
    EXPECT_EQ(info->format, "jpeg");
    const int orientation = o.spec.get_int_attribute("Orientation", 1);
    ASSERT_EQ(info->notes.size(), orientation != 1 ? 1u : 0u);
    if (orientation != 1) {
        EXPECT_EQ(info->notes[0].first, "ORIENTATION_IGNORED");
        EXPECT_NE(info->notes[0].second.find("orientation is " + std::to_string(orientation)), std::string::npos);
    }
    mf::Decoded d;
    mf::ImageInfo decoded;
    ASSERT_TRUE(mf::read_image(in, d, decoded, err)) << err;
    EXPECT_EQ(decoded.notes, info->notes);
    EXPECT_TRUE(d.codes.pixels == o.pixels);
    mf::Image floats;
    ASSERT_TRUE(mf::read_image(in, floats, decoded, err)) << err;
    EXPECT_EQ(floats.pixels, mf::to_float(d.codes).pixels);
    EXPECT_EQ(mf::stated_color_space(in).color_space, o.spec.get_string_attribute("oiio:ColorSpace"));
}

TEST(JpegReader, ReadsEverydayJpegsAsOpenImageIoDoes) {
    struct Case {
        std::string why;
        std::vector<unsigned char> file;
        int orientation;
    };
    const std::vector<Case> cases = {
        {"grey", make_jpeg(33, 17, 1, false), 1},
        {"colour 4:2:0", make_jpeg(65, 31, 3, false), 1},
        {"colour, progressive", make_jpeg(40, 41, 3, true), 1},
        {"grey, progressive", make_jpeg(9, 70, 1, true), 1},
        {"EXIF, little-endian, rotated 90° clockwise", make_jpeg(24, 16, 3, false, {exif(true, 6)}), 6},
        {"EXIF, big-endian, rotated 180°", make_jpeg(24, 16, 3, true, {exif(false, 3)}), 3},
        {"EXIF with a sub-IFD and no orientation", make_jpeg(16, 16, 3, false, {exif(true, 0, true)}), 1},
        {"EXIF orientation 1 and a sub-IFD", make_jpeg(16, 16, 1, false, {exif(false, 1, true)}), 1},
        {"XMP without an orientation", make_jpeg(16, 8, 3, false, {xmp("<x:xmpmeta><dc:title/></x:xmpmeta>")}), 1},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.why);
        mf::jpeg::Plain whole, head;
        ASSERT_TRUE(direct(c.file, whole, head));
        const auto o = oiio_read(c.file);
        ASSERT_TRUE(o.ok);
        EXPECT_EQ(whole.orientation, c.orientation);
        EXPECT_EQ(o.spec.get_int_attribute("Orientation", 1), c.orientation);
        EXPECT_EQ(head.orientation, c.orientation);
        EXPECT_TRUE(head.pixels.empty());
        EXPECT_TRUE(whole.pixels == o.pixels);
        expect_as_openimageio(c.file, "made.jpg");
    }
}

TEST(JpegReader, LeavesOtherJpegsToOpenImageIo) {
    const std::vector<unsigned char> good = make_jpeg(48, 32, 3, false);
    struct Case {
        std::string why;
        std::vector<unsigned char> file;
    };
    const std::vector<Case> declined = {
        {"two EXIF blocks", make_jpeg(16, 16, 3, false, {exif(true, 6), exif(true, 3)})},
        {"an orientation in the EXIF sub-IFD", make_jpeg(16, 16, 3, false, {exif(true, 1, true, 6)})},
        {"an XMP orientation",
         make_jpeg(16, 16, 3, false, {xmp("<x:xmpmeta><rdf:Description tiff:Orientation=\"6\"/></x:xmpmeta>")})},
        {"CMYK", make_jpeg(16, 16, 4, false)},
        {"an EXIF block that is not TIFF",
         make_jpeg(16, 16, 3, false, {Marker{JPEG_APP0 + 1, {'E', 'x', 'i', 'f', 0, 0, 'X', 'Y'}}})},
    };
    for (const Case& c : declined) {
        SCOPED_TRACE(c.why);
        mf::jpeg::Plain whole, head;
        EXPECT_FALSE(direct(c.file, whole, head));
        EXPECT_TRUE(whole.pixels.empty());
        // OpenImageIO reads them, and matforge's readers say what it says.
        expect_as_openimageio(c.file, "made.jpg");
    }
    // A cut file: libjpeg would fill the rest with grey; OpenImageIO's read fails, and so does matforge's.
    const std::vector<unsigned char> cut(good.begin(), good.begin() + static_cast<long>(good.size() * 6 / 10));
    mf::jpeg::Plain whole, head;
    EXPECT_FALSE(mf::jpeg::read_plain(cut.data(), cut.size(), false, 1u << 24, whole));
    mf::Decoded d;
    mf::ImageInfo info;
    std::string err;
    EXPECT_FALSE(mf::read_image(in_memory(cut, "cut.jpg"), d, info, err));
    EXPECT_NE(err.find("ends before its last pixel"), std::string::npos) << err;
    // Over the size bound; then a JPEG under another name (OpenImageIO's reader by that name
    // would state another colour space): both left to OpenImageIO, which reads them.
    EXPECT_FALSE(mf::jpeg::read_plain(good.data(), good.size(), false, 48 * 32 * 3 - 1, whole));
    EXPECT_TRUE(mf::jpeg::read_plain(good.data(), good.size(), false, 48 * 32 * 3, whole));
    const auto misnamed = mf::read_info(in_memory(good, "albedo.png"), err);
    ASSERT_TRUE(misnamed) << err;
    EXPECT_EQ(misnamed->format, "jpeg");
}

}  // namespace
