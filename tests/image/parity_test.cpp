// lib/image's direct readers (direct.hpp: JPEG, PNG, WebP without OpenImageIO) against
// OpenImageIO, one table: each row a file an independent encoder made (libjpeg, libpng through
// OpenImageIO, libwebp), which the direct readers take (not the module), and which image.hpp's
// read_info, read_image (codes and floats) and stated_color_space read exactly as OpenImageIO's
// own reader of that format does: the size, the channels, every code, every float bit for bit,
// the colour space it states. (The per-codec tests go further: what each leaves to OpenImageIO,
// damaged and lying files.)
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "image/direct.hpp"
#include "image/image.hpp"
#include "oiio_oracle.hpp"
#include "png_chunks.hpp"
#include "test_files.hpp"
#include "test_jpeg.hpp"
#include "test_webp.hpp"

namespace {

struct Row {
    std::string why;
    std::vector<unsigned char> file;
    std::string name;    // as the file is named (the readers go by content, then by name)
    std::string format;  // OpenImageIO's reader, and read_info's format
    bool codes = true;   // 8-bit: read_image keeps the codes
};

std::vector<Row> rows() {
    using mf::testjpeg::make_jpeg;
    using mf::testwebp::make_webp;
    auto png8 = [](int w, int h, int channels) {
        return pngtest::libpng_file(w, h, channels, pngtest::samples<uint8_t>(w, h, channels, true, 7), 0);
    };
    return {
        {"JPEG grey", make_jpeg(33, 17, 1, false), "a.jpg", "jpeg"},
        {"JPEG colour 4:2:0", make_jpeg(65, 31, 3, false), "a.jpg", "jpeg"},
        {"JPEG colour, progressive", make_jpeg(40, 41, 3, true), "a.jpeg", "jpeg"},
        {"PNG grey", png8(17, 9, 1), "a.png", "png"},
        {"PNG grey + alpha", png8(9, 17, 2), "a.png", "png"},
        {"PNG RGB", png8(31, 7, 3), "a.png", "png"},
        {"PNG RGBA", png8(7, 31, 4), "a.png", "png"},
        {"PNG RGB 16-bit", pngtest::encode(13, 5, 3, 16, pngtest::samples<uint16_t>(13, 5, 3, true, 9), {}), "a.png",
         "png", false},
        {"WebP lossy", make_webp(17, 5, 3, false), "a.webp", "webp"},
        {"WebP lossless", make_webp(64, 33, 3, true), "a.webp", "webp"},
    };
}

TEST(DirectReaders, EveryCodecReadsAsOpenImageIoReadsIt) {
    for (const Row& r : rows()) {
        SCOPED_TRACE(r.why);
        const mf::InputFile in = mf::testfiles::in_memory(r.file, r.name);
        // The direct readers take it: OpenImageIO is the oracle here, not the path.
        mf::ImageInfo direct_info;
        std::optional<mf::StatedColorSpace> stated;
        std::string refusal;
        ASSERT_TRUE(mf::direct::read_info(in, direct_info, stated, refusal)) << refusal;

        const auto o = mf::testenv::oiio_read(r.file, r.format, OIIO::TypeDesc::UINT8);
        ASSERT_TRUE(o.ok);
        std::string err;
        const auto info = mf::read_info(in, err);
        ASSERT_TRUE(info) << err;
        EXPECT_EQ(info->format, r.format);
        EXPECT_EQ(info->width, o.spec.width);
        EXPECT_EQ(info->height, o.spec.height);
        EXPECT_EQ(info->channels, o.spec.nchannels);
        EXPECT_EQ(info->bit_depth, r.codes ? 8 : 16);

        mf::Decoded d;
        mf::ImageInfo decoded;
        ASSERT_TRUE(mf::read_image(in, d, decoded, err)) << err;
        EXPECT_EQ(d.is_codes(), r.codes);
        if (r.codes) {
            EXPECT_TRUE(d.codes.pixels == o.pixels) << "every code as OpenImageIO decodes it";
        }
        mf::testenv::expect_floats_as_openimageio(in, r.file, r.format);
        EXPECT_EQ(mf::stated_color_space(in).color_space, o.spec.get_string_attribute("oiio:ColorSpace"));
    }
}

}  // namespace
