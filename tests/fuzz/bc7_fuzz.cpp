// BC7 (lib/texture/bc7.hpp), its source compiled in: any 16 bytes decode (every first byte, the
// reserved mode included) without reading past the block; any 4x4 texels encode, under any level
// and any set of allowed modes, to a block of an allowed mode, the same bytes twice, that decodes
// opaque where alpha is data and every alpha was 255. Input: an options byte, a modes byte, 64
// texel bytes (RGBA), then any number of blocks to decode.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include "texture/bc7.hpp"

namespace bc7 = mf::texture::bc7;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 66) return 0;
    bc7::Options opt;
    opt.level = data[0] % 3;
    opt.alpha_data = (data[0] & 4) != 0;
    opt.modes = data[1] ? data[1] : 0xff;
    uint8_t texels[64];
    std::memcpy(texels, data + 2, 64);
    uint8_t block[16], again[16], rgba[64];
    bc7::encode_block(texels, opt, block);
    bc7::encode_block(texels, opt, again);
    if (std::memcmp(block, again, 16) != 0) std::abort();
    const int mode = bc7::block_mode(block);
    if (mode > 7 || !((opt.modes >> mode) & 1)) std::abort();
    bc7::decode_block(block, rgba);
    bool opaque = true;
    for (int t = 0; t < 16; ++t) opaque = opaque && texels[t * 4 + 3] == 255;
    if (opt.alpha_data && opaque)
        for (int t = 0; t < 16; ++t)
            if (rgba[t * 4 + 3] != 255) std::abort();
    for (size_t at = 66; at + 16 <= size; at += 16) bc7::decode_block(data + at, rgba);
    return 0;
}
