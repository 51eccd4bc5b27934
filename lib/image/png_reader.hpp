// A reader for plain PNGs (those matforge writes, png_writer.hpp, and vendors' height and
// texture maps), with libdeflate's inflate and vector row filters (png_unfilter.hpp): the preview
// of a library of `gltf` outputs spent 38 % of its CPU in libpng and zlib decoding them (perf, 100
// 1K materials on lavapipe), and a run that decodes none of its files through OpenImageIO never
// loads it (image/direct.hpp). Every other PNG, and any file this reader doubts, is left to
// OpenImageIO (libpng and zlib) by the caller.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "image/read_at.hpp"

namespace mf::png {

// Every PNG's first eight bytes (PNG spec 5.2).
inline constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
// The signature and the IHDR chunk: the bytes plain8_header looks at.
inline constexpr size_t kHeaderBytes = 8 + 12 + 13;

// PNG metadata matforge does not use can be huge (a 200 MB tEXt chunk: OpenImageIO keeps every
// text chunk as an attribute, ~1 GB at peak). The module drops ancillary chunks larger than this
// before OpenImageIO sees the file (oiio_module.cpp); a header read here leaves such a file to it.
inline constexpr uint32_t kMaxMetadataChunk = 1u << 20;

// A big-endian 32-bit field (PNG's lengths, sizes and CRCs).
inline uint32_t be32(const unsigned char* p) {
    return (uint32_t{p[0]} << 24) | (uint32_t{p[1]} << 16) | (uint32_t{p[2]} << 8) | uint32_t{p[3]};
}

struct Plain {
    int width = 0, height = 0, channels = 0;
    int bit_depth = 0;            // 8 or 16
    bool interlaced = false;      // Adam7 in the file (pixels are always the whole image's rows)
    std::vector<uint8_t> pixels;  // rows of width * channels samples: 8-bit codes, or uint16_t in host order
};

// The plain PNG whose first kHeaderBytes are `head` (signature, IHDR of 13 bytes: 8- or 16-bit
// grey, grey+alpha, RGB or RGBA, not interlaced or Adam7, a size of at most `max_bytes` of samples): its
// size, channels and bit depth in `out` (no pixels), else false. The IHDR's CRC is not checked
// here (read_plain and read_plain_header check every chunk's). Lets a caller leave any other PNG
// to OpenImageIO before reading more than its head.
bool plain_ihdr(const unsigned char* head, size_t max_bytes, Plain& out);

// A header read of a file of `size` bytes: plain_ihdr's facts when the chunks up to the first
// IDAT are ones read_plain accepts, each with its CRC right (what OpenImageIO's header read
// would state: the size, channels and depth, no orientation). False for anything else.
bool read_plain_header(uint64_t size, const ReadAt& read, size_t max_bytes, Plain& out);

// Contract: decodes `file` when it is a plain PNG: 8- or 16-bit grey, grey+alpha, RGB or RGBA
// (alpha as stored), not interlaced or Adam7, rows in any of the five filters, chunks IHDR, IDAT
// (one run), IEND and only ancillary chunks that change no pixel OpenImageIO reads nor any fact
// it states that matforge uses: text (not an orientation), eXIf of orientation 1, tIME, pHYs,
// oFFs, and the colour chunks gAMA,
// sRGB, cHRM, iCCP and bKGD, which OpenImageIO records and never applies (matforge reads a PNG's
// colour chunks itself: validate/color_tag.cpp). Every CRC right, at most `max_bytes` of samples.
// Returns false, leaving `out` empty, for anything else (palette, transparency key, significant
// bits, another orientation, damage): never an error of its own, the caller reads such a file as
// before. `file` is used up (its image data moved together in place, then freed): at most the
// file and the samples are held at once, where libpng streams, hence the bound.
bool read_plain(std::vector<unsigned char>& file, size_t max_bytes, Plain& out);

// Why a PNG of `size` bytes (any: palette, any depth, interlaced) cannot hold the image its IHDR
// declares, or empty: the filtered rows it states (PNG spec 7.2, Adam7's passes included) are
// more than its IDAT chunks' data can inflate to. Deflate's best ratio is 1032:1 (a 258-byte
// match in at most 2 bits, RFC 1951 §3.2.5), so N bytes of IDAT hold at most 1032 N + 1032
// bytes. Walks the chunk headers only (8 bytes each): a 177-byte file declaring 16384² RGBA
// 16-bit is refused before anything is allocated, where OpenImageIO would allocate 2 GiB for
// it. Empty too for a file that is not a PNG or whose chunks do not walk (the reader says why).
std::string size_refusal(uint64_t size, const ReadAt& read);

}  // namespace mf::png
