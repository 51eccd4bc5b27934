// BC7 (BPTC UNORM): one 4x4 block of RGBA codes to 16 bytes and back.
//
// Debian packages no BC7 encoder, so this is matforge's own, written from the format's
// definition (Khronos Data Format Specification 1.3, section "BPTC Compressed Texture Image
// Formats"; Microsoft, "BC7 Format" and "BC7 Format Mode Reference"). Its decoded texels are
// checked bit for bit against an independent decoder (PyPI texture2ddecoder) and Mesa's lavapipe
// (tests/texture/bc7_test.cpp); bench/texture/bc7_vs_bc7e.sh measures it beside bc7e.
//
// Contract:
//  - encode_block writes a valid block for any input (no reserved mode), deterministically: the
//    same texels and options give the same bytes on any thread;
//  - where alpha is data (Options::alpha_data), a block whose 16 alphas are 255 decodes to alpha
//    255 everywhere (opaque stays opaque);
//  - the error minimised is the sum of squared differences of the 8-bit codes over R, G, B, A
//    (each weighted 1): what the PSNR of every output's level records;
//  - decode_block follows the specification exactly (what a GPU returns before sRGB decoding);
//    the reserved mode (a zero first byte) decodes to 0 in every channel, as Direct3D defines.
#pragma once
#include <cstdint>

namespace mf::texture::bc7 {

// Bumped whenever the encoder may write other blocks for the same input: the ingest cache's key
// (encoder_versions) must then miss.
constexpr int kEncoderVersion = 1;

struct Options {
    // 0 (fast): mode 6, and mode 1 on the best partition where mode 6 fits badly;
    // 1 (normal): modes 6, 1 and 3, flat blocks' endpoints nudged (about bc7e -u2);
    // 2 (thorough): every mode, more partitions, rotations and refinements. Blocks with alpha try
    // modes 4, 5, 6 and 7 at every level. bc7.cpp's search_of has the figures; codec.cpp maps
    // Effort here.
    int level = 1;
    uint8_t modes = 0xff;  // bit m: mode m may be chosen (tests force each mode; at least one set)
    // False for an output without alpha (RGB): alpha is then not fitted, and mode 6's p-bits buy
    // RGB precision at the price of alphas of 254 (bc7e does the same); true: alpha is data and an
    // opaque block decodes to 255 exactly.
    bool alpha_data = true;
};

void encode_block(const uint8_t rgba[64], const Options& opt, uint8_t out[16]);
void decode_block(const uint8_t in[16], uint8_t rgba[64]);

// The mode a block was written in (0..7; 8 for the reserved mode).
int block_mode(const uint8_t in[16]);

}  // namespace mf::texture::bc7
