// A reader for still WebP files with libwebp alone: the library OpenImageIO's WebP
// reader calls. Polyhaven ships every map as JPEG and WebP; each WebP decoded through
// OpenImageIO loaded its module (261 libraries) for a run of JPEG sets. Every file this reader
// doubts (animation, EXIF/XMP/ICC chunks, damage) is left to OpenImageIO by the caller
// (image/direct.hpp).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace mf::webp {

struct Plain {
    int width = 0, height = 0;
    int channels = 3;             // 3 (RGB) or 4 (RGBA, alpha unassociated: the stored values)
    std::vector<uint8_t> pixels;  // rows of width * channels codes; empty after a header read
};

// Contract: reads `data` (a whole file; for header_only its first 30 bytes suffice) when it is a
// still WebP without metadata chunks (a simple lossy or lossless file, or an extended one whose
// VP8X flags name none but alpha), no larger than `max_samples`, decoded by libwebp as RGB, or
// as RGBA with the stored (unassociated) alpha when the file has alpha. Returns false, leaving `out` empty, for
// anything else: never an error of its own, the caller reads such a file as before.
bool read_plain(const unsigned char* data, size_t size, bool header_only, uint64_t max_samples, Plain& out);

}  // namespace mf::webp
