// A reader for the plain PNGs matforge writes (png_writer.hpp), with libdeflate's inflate: the
// preview of a library of `gltf` outputs spent 38 % of its CPU in libpng and zlib decoding them
// (perf, 100 1K materials on lavapipe). Every other PNG, and any file this reader doubts, is left
// to OpenImageIO (libpng and zlib) by the caller.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace mf::png {

// Every PNG's first eight bytes (PNG spec 5.2).
inline constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
// The signature and the IHDR chunk: the bytes plain8_header looks at.
inline constexpr size_t kHeaderBytes = 8 + 12 + 13;

// A big-endian 32-bit field (PNG's lengths, sizes and CRCs).
inline uint32_t be32(const unsigned char* p) {
    return (uint32_t{p[0]} << 24) | (uint32_t{p[1]} << 16) | (uint32_t{p[2]} << 8) | uint32_t{p[3]};
}

// The channels of the plain 8-bit PNG whose first kHeaderBytes are `head` (signature, IHDR of 13
// bytes: 8-bit grey, grey+alpha, RGB or RGBA, not interlaced, a size of at most `max_bytes` of
// samples), else 0. The IHDR's CRC is not checked here: read_plain8 checks every chunk's. Lets a
// caller leave any other PNG to OpenImageIO before reading more than its head.
int plain8_header(const unsigned char* head, size_t max_bytes);

struct Plain8 {
    int width = 0, height = 0, channels = 0;
    std::vector<uint8_t> pixels;  // rows of width * channels codes
};

// Contract: decodes `file` when it is a plain 8-bit PNG: non-interlaced grey, grey+alpha, RGB or
// RGBA (alpha as stored), rows in any of the five filters, chunks IHDR, IDAT (one run), IEND and
// only the ancillary chunks that change no pixel or colour fact (tEXt, zTXt, iTXt, tIME, pHYs,
// oFFs), every CRC right, at most `max_bytes` of samples. Returns false, leaving `out` empty, for
// anything else (palette, transparency key, gamma or colour profile chunks, 16-bit, damage):
// never an error of its own, the caller reads such a file as before. `file` is used up (its
// image data moved together in place, then freed): at most the file and the samples are held at
// once, where libpng streams, hence the bound.
bool read_plain8(std::vector<unsigned char>& file, size_t max_bytes, Plain8& out);

}  // namespace mf::png
