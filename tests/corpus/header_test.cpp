// read_info opens a JPEG over its headers alone (lib/image/oiio: the markers through the first
// scan's header): on every real JPEG of the corpus, from its file and from memory, it must state
// what decoding the whole file states, and each file must still decode.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "corpus.hpp"
#include "image/image.hpp"

namespace {

void expect_same_header(const mf::ImageInfo& header, const mf::ImageInfo& decoded) {
    EXPECT_EQ(header.width, decoded.width);
    EXPECT_EQ(header.height, decoded.height);
    EXPECT_EQ(header.channels, decoded.channels);
    EXPECT_EQ(header.bit_depth, decoded.bit_depth);
    EXPECT_EQ(header.is_float, decoded.is_float);
    EXPECT_EQ(header.format, decoded.format);
    EXPECT_EQ(header.notes, decoded.notes);
}

TEST(CorpusHeaders, JpegHeaderReadStatesWhatTheDecodeStates) {
    size_t jpegs = 0, progressive = 0;
    for (const auto& e : corpus::fs::recursive_directory_iterator(corpus::dir() / "real")) {
        const std::string ext = e.path().extension().string();
        if (!e.is_regular_file() || (ext != ".jpg" && ext != ".jpeg")) continue;
        SCOPED_TRACE(e.path().string());
        ++jpegs;
        std::ifstream f(e.path(), std::ios::binary);
        auto bytes = std::make_shared<const std::vector<unsigned char>>(std::istreambuf_iterator<char>(f),
                                                                        std::istreambuf_iterator<char>());
        // SOF2: a progressive JPEG, the kind whose full open decodes every scan.
        for (size_t i = 0; i + 1 < bytes->size(); ++i)
            if ((*bytes)[i] == 0xFF && (*bytes)[i + 1] == 0xC2) {
                ++progressive;
                break;
            }
        mf::InputFile on_disk;
        on_disk.display = e.path().string();
        on_disk.path = e.path();
        mf::InputFile in_memory;
        in_memory.display = e.path().string();
        in_memory.bytes = bytes;
        for (const mf::InputFile* in : {&on_disk, &in_memory}) {
            std::string err;
            const auto header = mf::read_info(*in, err);
            ASSERT_TRUE(header) << err;
            mf::Decoded decoded;
            mf::ImageInfo info;
            ASSERT_TRUE(mf::read_image(*in, decoded, info, err)) << err;
            expect_same_header(*header, info);
            EXPECT_EQ(decoded.width(), header->width);
        }
    }
    EXPECT_GE(jpegs, 80u);
    EXPECT_GE(progressive, 40u) << "the corpus's 3dtextures.me maps are progressive";
}

}  // namespace
