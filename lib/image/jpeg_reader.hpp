// A reader for everyday JPEGs with libjpeg-turbo alone: the library OpenImageIO's JPEG reader
// calls, with the same settings (its defaults), so the same codes. Loading OpenImageIO's module
// (261 libraries) cost a run of JPEG sets 0.2-0.3 s in which no other work could start, and its
// reader opened a progressive JPEG by entropy-decoding every scan. Every file this reader doubts
// is left to OpenImageIO by the caller (image/direct.hpp).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "image/read_at.hpp"

namespace mf::jpeg {

// The length of a JPEG's markers up to and including its first scan's header (SOS), which hold
// everything a header read states (size, components, EXIF/XMP); 0 when the markers do not walk
// to a scan from the SOI at 0 (a damaged file: the decoder then reads the file as it is).
// Inline: the OpenImageIO module, which links no matforge library, uses it too.
inline uint64_t first_scan_header_end(uint64_t size, const ReadAt& read) {
    unsigned char m[4];
    if (size < 4 || !read(0, 2, m) || m[0] != 0xFF || m[1] != 0xD8) return 0;
    uint64_t at = 2;  // after SOI
    while (at + 4 <= size) {
        if (!read(at, 4, m) || m[0] != 0xFF) return 0;
        if (m[1] == 0xFF) {  // fill byte before a marker
            ++at;
            continue;
        }
        if (m[1] == 0x01 || (m[1] >= 0xD0 && m[1] <= 0xD9)) return 0;  // no segment before a scan is bare
        const uint64_t end = at + 2 + ((uint64_t{m[2]} << 8) | m[3]);
        if (end > size) return 0;
        if (m[1] == 0xDA) return end;
        at = end;
    }
    return 0;
}

struct Plain {
    int width = 0, height = 0, channels = 0;
    int orientation = 1;          // EXIF's Orientation (tag 0x0112 of IFD0); 1 when there is none
    std::vector<uint8_t> pixels;  // rows of width * channels codes; empty after a header read
    // Set when read_plain declines because the file is damaged (check() below says when): the
    // caller reports it (UNREADABLE_FILE) instead of reading the file another way.
    std::string refusal;
};

// Contract: reads `data` (a whole file, or for header_only at least its first_scan_header_end
// bytes of a file of `file_size` bytes) when it is an 8-bit JPEG of one (grey) or
// three (YCbCr or RGB: decoded to RGB) components, no larger than `max_samples`, whose only
// orientation is in one well-formed EXIF block, and which libjpeg reads without a warning of
// lost data. Returns false, leaving `out` empty, for anything else (CMYK/YCCK, 12-bit, an XMP
// orientation, two EXIF blocks, an error): never an error of its own, the caller reads such a
// file as before — except a damaged one, for which `out.refusal` says why.
bool read_plain(const unsigned char* data, size_t size, bool header_only, uint64_t max_samples, Plain& out,
                uint64_t file_size);

// Why a JPEG read another way must not be trusted (empty: no reason), from libjpeg's reading of
// it: its frame header declares more 8x8 blocks than its `file_size` bytes can code (refused on
// the header, before anything is allocated), or, unless header_only, a decode of every row (at
// most `max_samples`, into one row's buffer) raises a libjpeg warning that means lost data — a
// segment cut short or garbled, data out of step, the file ending early ("Corrupt JPEG data:
// ...", "Premature end of JPEG file"). The same rule read_plain applies, for the files it
// declines (CMYK, XMP orientations, misnamed JPEGs) before OpenImageIO decodes them.
std::string check(const unsigned char* data, size_t size, bool header_only, uint64_t max_samples, uint64_t file_size);

}  // namespace mf::jpeg
