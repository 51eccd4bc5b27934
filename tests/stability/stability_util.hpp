// Shared helpers of the stability suite.
#pragma once
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "color/color.hpp"
#include "image/image.hpp"
#include "test_color.hpp"

namespace mf::stability {

using testcolor::color_context;

// Encodes `img` to file bytes and decodes them again: what a consumer of the output reads.
inline Image encode_and_read(const Image& img, const EncodeOptions& opt) {
    std::vector<unsigned char> bytes;
    std::string err;
    if (!encode_image(img, opt, bytes, err)) {
        ADD_FAILURE() << "encode " << mf::word(opt.format) << "/" << opt.bit_depth << ": " << err;
        return {};
    }
    InputFile in;
    in.display = "roundtrip." + std::string(mf::word(opt.format));
    in.bytes = std::make_shared<const std::vector<unsigned char>>(std::move(bytes));
    Image out;
    ImageInfo info;
    if (!read_image(in, out, info, err)) ADD_FAILURE() << "read back " << mf::word(opt.format) << ": " << err;
    return out;
}

}  // namespace mf::stability
