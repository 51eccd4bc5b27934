// matforge's WebP reader (lib/image/webp_reader.hpp, reached through read_info and read_image)
// on files libwebp's encoder makes here: lossy and lossless, odd sizes. Where it reads a file,
// every code and header fact must be OpenImageIO's; files with alpha are left to OpenImageIO,
// and matforge's readers then say what it says.
#include <gtest/gtest.h>

#include <webp/decode.h>
#include <webp/encode.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "image/image.hpp"
#include "image/webp_reader.hpp"
#include "oiio_oracle.hpp"
#include "test_files.hpp"
#include "test_webp.hpp"

namespace {

using mf::testwebp::make_webp;

using mf::testfiles::in_memory;

TEST(WebpReader, ReadsOpaqueWebpAsOpenImageIoDoes) {
    for (bool lossless : {false, true})
        for (const auto& wh : {std::pair{1, 1}, {17, 5}, {64, 33}}) {
            SCOPED_TRACE(std::to_string(wh.first) + "x" + std::to_string(wh.second) +
                         (lossless ? " lossless" : " lossy"));
            const std::vector<unsigned char> file = make_webp(wh.first, wh.second, 3, lossless);
            mf::webp::Plain head, whole;
            ASSERT_TRUE(mf::webp::read_plain(file.data(), file.size(), true, 1u << 24, head));
            ASSERT_TRUE(mf::webp::read_plain(file.data(), file.size(), false, 1u << 24, whole));
            EXPECT_EQ(head.width, wh.first);
            EXPECT_EQ(whole.height, wh.second);
            const auto o = mf::testenv::oiio_read(file, "webp", OIIO::TypeDesc::UINT8);
            ASSERT_TRUE(o.ok);
            EXPECT_EQ(o.spec.nchannels, 3);
            EXPECT_TRUE(whole.pixels == o.pixels) << "every code as OpenImageIO decodes it";
            const mf::InputFile in = in_memory(file, "made.webp");
            std::string err;
            const auto info = mf::read_info(in, err);
            ASSERT_TRUE(info) << err;
            EXPECT_EQ(info->format, "webp");
            EXPECT_EQ(info->channels, 3);
            mf::Decoded d;
            mf::ImageInfo decoded;
            ASSERT_TRUE(mf::read_image(in, d, decoded, err)) << err;
            EXPECT_TRUE(d.codes.pixels == o.pixels);
            EXPECT_EQ(mf::stated_color_space(in).color_space, o.spec.get_string_attribute("oiio:ColorSpace"));
        }
}

// A WebP with alpha is read here too, as libwebp's RGBA: the stored (unassociated) values. A
// lossless file gives back the very pixels encoded; OpenImageIO's reader associates alpha and
// back, which moves colours under low alpha (issue 44: up to 44 codes), so it is not the oracle.
TEST(WebpReader, ReadsWebpWithAlphaAsItsStoredValues) {
    for (bool lossless : {false, true}) {
        SCOPED_TRACE(lossless ? "lossless" : "lossy");
        const std::vector<unsigned char> file = make_webp(20, 12, 4, lossless);
        mf::webp::Plain p;
        ASSERT_TRUE(mf::webp::read_plain(file.data(), file.size(), false, 1u << 24, p));
        EXPECT_EQ(p.channels, 4);
        int w = 0, h = 0;
        uint8_t* stored = WebPDecodeRGBA(file.data(), file.size(), &w, &h);
        ASSERT_TRUE(stored);
        EXPECT_TRUE(std::equal(p.pixels.begin(), p.pixels.end(), stored));
        WebPFree(stored);
        if (lossless) {  // the encoded pixels themselves (where alpha > 0: libwebp may drop a clear texel's RGB)
            std::vector<uint8_t> px(20 * 12 * 4);
            std::mt19937 rng(static_cast<unsigned>(20 * 13 + 12 + 4));
            for (size_t i = 0; i < px.size(); ++i) px[i] = static_cast<uint8_t>((i * 7 + (rng() & 31)) & 0xFF);
            ASSERT_EQ(p.pixels.size(), px.size());
            size_t differing = 0, seen = 0;
            for (size_t i = 0; i < px.size(); i += 4) {
                if (px[i + 3] == 0) continue;
                ++seen;
                differing += !std::equal(px.begin() + static_cast<long>(i), px.begin() + static_cast<long>(i) + 4,
                                         p.pixels.begin() + static_cast<long>(i));
            }
            EXPECT_GT(seen, 200u);
            EXPECT_EQ(differing, 0u);
        }
        std::string err;
        mf::Decoded d;
        mf::ImageInfo info;
        ASSERT_TRUE(mf::read_image(in_memory(file, "alpha.webp"), d, info, err)) << err;
        EXPECT_EQ(info.channels, 4);
        EXPECT_TRUE(d.codes.pixels == p.pixels);
    }
    // Cut files and a size over the bound are left alone too.
    const std::vector<unsigned char> good = make_webp(40, 40, 3, false);
    mf::webp::Plain p;
    EXPECT_FALSE(mf::webp::read_plain(good.data(), good.size() / 2, false, 1u << 24, p));
    EXPECT_FALSE(mf::webp::read_plain(good.data(), good.size(), false, 40 * 40 * 3 - 1, p));
    EXPECT_TRUE(mf::webp::read_plain(good.data(), good.size(), false, 40 * 40 * 3, p));
}

}  // namespace
