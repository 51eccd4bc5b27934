// matforge's PNG encoder: the chunks framed here (four kinds: IHDR, tEXt, IDAT, IEND; CRCs by
// libdeflate), libdeflate compresses the pixels. libpng, stb_image and zlib read its files back
// in the tests (tests/image/png_writer_test.cpp): independent decoders.
// image.cpp sends every PNG output here (encode_image); OpenImageIO writes the other formats.
//
// Why not libpng's own writer: it can only compress through zlib, whose deflate was a third of
// ingest's CPU time (perf, the corpus through gltf,unity-hdrp). On that run's 69 distinct 8-bit
// outputs, this writer encodes 1.9x faster than libpng with zlib's Z_RLE strategy (the earlier
// setting) into 1.2 % more bytes, decoded as fast (bench/throughput/png_tradeoff,
// docs/throughput/png_tradeoff.md); the run's 16-bit heights came out 18 % smaller. ISA-L
// compressed 2x faster again, but its output depends on the CPU's instruction set, and matforge
// promises the same bytes from the same inputs on any machine of a farm (docs/cluster.md).
#pragma once
#include <string>
#include <vector>

namespace mf::png {

// Contract: `samples` holds height rows of width * channels samples, uint8_t (bit_depth 8) or
// uint16_t in host order (bit_depth 16); channels 1 grey, 2 grey+alpha, 3 RGB, 4 RGBA (alpha
// unassociated, written as given). Appends nothing on failure: returns false with `error`.
// Every row uses the Paeth filter (PNG spec 9.4; the setting png_tradeoff.md chose), the file is
// one zlib stream of libdeflate level 1 in IDAT chunks of at most kIdatBytes, with one tEXt
// (Software=matforge) and no timestamp: the same pixels give the same bytes.
bool write(const void* samples, int width, int height, int channels, int bit_depth, std::vector<unsigned char>& bytes,
           std::string& error);

}  // namespace mf::png
