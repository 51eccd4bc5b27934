// WebP files made by libwebp for the tests of lib/image's WebP reader: noise-and-ramp pixels
// of w x h with 3 or 4 channels, lossy (quality 80) or lossless. Needs libwebp's encoder.
#pragma once
#include <webp/encode.h>

#include <cstdint>
#include <random>
#include <vector>

namespace mf::testwebp {

inline std::vector<unsigned char> make_webp(int w, int h, int channels, bool lossless) {
    std::vector<uint8_t> px(static_cast<size_t>(w) * static_cast<size_t>(h) * static_cast<size_t>(channels));
    std::mt19937 rng(static_cast<unsigned>(w * 13 + h + channels));
    for (size_t i = 0; i < px.size(); ++i) px[i] = static_cast<uint8_t>((i * 7 + (rng() & 31)) & 0xFF);
    uint8_t* out = nullptr;
    const int stride = w * channels;
    const size_t n = channels == 3 ? (lossless ? WebPEncodeLosslessRGB(px.data(), w, h, stride, &out)
                                               : WebPEncodeRGB(px.data(), w, h, stride, 80.f, &out))
                                   : (lossless ? WebPEncodeLosslessRGBA(px.data(), w, h, stride, &out)
                                               : WebPEncodeRGBA(px.data(), w, h, stride, 80.f, &out));
    std::vector<unsigned char> bytes(out, out + n);
    WebPFree(out);
    return bytes;
}

}  // namespace mf::testwebp
