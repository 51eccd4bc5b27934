// matforge's JPEG reader (lib/image/jpeg_reader.hpp, reached through read_info and read_image)
// on files made here with libjpeg: grey and colour, baseline and progressive, EXIF orientations
// in both byte orders, and the files it must leave to OpenImageIO (two EXIF blocks, an XMP
// orientation, CMYK, a cut file, a JPEG under another name). Where it reads a file, every code
// and header fact must be OpenImageIO's; where it declines, matforge's readers say what
// OpenImageIO says.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <jpeglib.h>

#include "image/image.hpp"
#include "image/jpeg_reader.hpp"
#include "oiio_oracle.hpp"
#include "test_env.hpp"
#include "test_files.hpp"
#include "test_jpeg.hpp"

namespace {

using mf::testjpeg::make_jpeg;
using mf::testjpeg::Marker;

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
    const bool head_ok = end > 0 &&
                         mf::jpeg::read_plain(file.data(), static_cast<size_t>(end), true, 1u << 24, head, file.size());
    const bool ok = mf::jpeg::read_plain(file.data(), file.size(), false, 1u << 24, whole, file.size());
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
    EXPECT_FALSE(mf::jpeg::read_plain(cut.data(), cut.size(), false, 1u << 24, whole, cut.size()));
    mf::Decoded d;
    mf::ImageInfo info;
    std::string err;
    EXPECT_FALSE(mf::read_image(in_memory(cut, "cut.jpg"), d, info, err));
    EXPECT_NE(err.find("cut short"), std::string::npos) << err;
    EXPECT_FALSE(whole.refusal.empty()) << "a cut file is refused, not left to OpenImageIO";
    // Over the size bound; then a JPEG under another name (OpenImageIO's reader by that name
    // would state another colour space): both left to OpenImageIO, which reads them.
    EXPECT_FALSE(mf::jpeg::read_plain(good.data(), good.size(), false, 48 * 32 * 3 - 1, whole, good.size()));
    EXPECT_TRUE(whole.refusal.empty());
    EXPECT_TRUE(mf::jpeg::read_plain(good.data(), good.size(), false, 48 * 32 * 3, whole, good.size()));
    const auto misnamed = mf::read_info(in_memory(good, "albedo.png"), err);
    ASSERT_TRUE(misnamed) << err;
    EXPECT_EQ(misnamed->format, "jpeg");
}

// Damaged JPEGs (issue 45): libjpeg decodes them "successfully" with warnings and grey or
// garbage rows. Every warning that means lost data makes the file unreadable, in the direct
// reader and, for a JPEG it declines (here: under another name, and CMYK), before OpenImageIO
// decodes it — the same rule, the same words. A frame header declaring more blocks than the
// file can code is refused on the header. A few padding bytes before the end marker, which real
// encoders leave, are no damage.
TEST(JpegReader, DamagedJpegsAreUnreadableInBothReaders) {
    const std::vector<unsigned char> real = mf::testfiles::file_bytes(
        mf::testenv::source_dir() / "sample_materials/Net004A_1K-JPG/Net004A_1K-JPG_Color.jpg");
    ASSERT_GT(real.size(), 100000u);
    const size_t mid = real.size() / 2;
    std::vector<std::pair<std::string, std::vector<unsigned char>>> damaged;
    {  // cut in half, an end marker appended
        std::vector<unsigned char> b(real.begin(), real.begin() + static_cast<long>(mid));
        b.insert(b.end(), {0xFF, 0xD9});
        damaged.emplace_back("cut in half with an end marker", b);
    }
    {  // 4 KiB zeroed
        std::vector<unsigned char> b = real;
        std::fill(b.begin() + static_cast<long>(mid), b.begin() + static_cast<long>(mid + 4096), 0);
        damaged.emplace_back("4 KiB zeroed", b);
    }
    {  // 256 bytes garbled (no 0xFF: no marker made)
        std::vector<unsigned char> b = real;
        std::mt19937 rng(45);
        for (size_t i = mid; i < mid + 256; ++i) b[i] = static_cast<unsigned char>(rng() % 255);
        damaged.emplace_back("256 bytes garbled", b);
    }
    {  // a hole: 1 KiB of entropy data gone
        std::vector<unsigned char> b = real;
        b.erase(b.begin() + static_cast<long>(mid), b.begin() + static_cast<long>(mid + 1024));
        damaged.emplace_back("a hole in the entropy data", b);
    }
    {  // a CMYK file (declined by the direct reader) cut in half
        const std::vector<unsigned char> cmyk = make_jpeg(256, 256, 4, true);
        std::vector<unsigned char> b(cmyk.begin(), cmyk.begin() + static_cast<long>(cmyk.size() / 2));
        b.insert(b.end(), {0xFF, 0xD9});
        damaged.emplace_back("a progressive CMYK file cut in half", b);
    }
    for (const auto& [what, bytes] : damaged)
        for (const std::string name : {"damaged.jpg", "damaged.png"}) {
            SCOPED_TRACE(what + " as " + name);
            mf::Decoded d;
            mf::ImageInfo info;
            std::string err;
            EXPECT_FALSE(mf::read_image(in_memory(bytes, name), d, info, err));
            EXPECT_TRUE(err.find("libjpeg reports lost data") != std::string::npos ||
                        err.find("cut short") != std::string::npos)
                << err;
            int bands = 0;
            err.clear();
            EXPECT_FALSE(mf::read_bands(in_memory(bytes, name), 64, info, err,
                                        [&](int, int, const float*) { ++bands; }));
            EXPECT_EQ(bands, 0) << "no band of a damaged file is handed on";
            EXPECT_FALSE(err.empty());
        }
    // A 64x64 JPEG whose frame header claims 16384x16384: refused on the header read.
    std::vector<unsigned char> forged = make_jpeg(64, 64, 3, false);
    bool patched = false;
    for (size_t i = 2; i + 9 < forged.size() && !patched; ++i)
        if (forged[i] == 0xFF && forged[i + 1] == 0xC0) {  // SOF0: length(2) precision(1) height(2) width(2)
            forged[i + 5] = 0x40, forged[i + 6] = 0x00, forged[i + 7] = 0x40, forged[i + 8] = 0x00;
            patched = true;
        }
    ASSERT_TRUE(patched);
    for (const std::string name : {"forged.jpg", "forged.tif"}) {
        std::string err;
        EXPECT_FALSE(mf::read_info(in_memory(forged, name), err)) << name;
        EXPECT_NE(err.find("declares 16384x16384 pixels"), std::string::npos) << err;
    }
    // Stray bytes between header segments, before any pixel is decoded: no data lost, read.
    std::vector<unsigned char> stray = real;
    size_t dqt = 2;
    while (dqt + 1 < stray.size() && !(stray[dqt] == 0xFF && stray[dqt + 1] == 0xDB)) ++dqt;
    ASSERT_LT(dqt + 1, stray.size());
    stray.insert(stray.begin() + static_cast<long>(dqt), {0x12, 0x34, 0x56, 0x78, 0x9A});
    {
        mf::Decoded d;
        mf::ImageInfo info;
        std::string err;
        EXPECT_TRUE(mf::read_image(in_memory(stray, "stray.jpg"), d, info, err)) << err;
        EXPECT_EQ(mf::jpeg::check(stray.data(), stray.size(), false, 1u << 24, stray.size()), "");
    }
    // Padding before the end marker: read, as OpenImageIO reads it.
    std::vector<unsigned char> padded = real;
    ASSERT_EQ(padded[padded.size() - 2], 0xFF);
    padded.insert(padded.end() - 2, {0x12, 0x34, 0x56});
    mf::jpeg::Plain whole, head;
    EXPECT_TRUE(direct(padded, whole, head));
    EXPECT_EQ(mf::jpeg::check(padded.data(), padded.size(), false, 1u << 24, padded.size()), "");
}

}  // namespace
