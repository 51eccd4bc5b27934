// The one EXIF fact matforge reads itself: the orientation, as OpenImageIO 2.4's decode_exif
// reads it, for the JPEGs and PNGs image/direct.hpp reads without OpenImageIO.
#pragma once
#include <cstddef>

namespace mf::exif {

// The orientation an EXIF block's TIFF structure (after a JPEG's "Exif\0\0", or a PNG's eXIf
// chunk) states: tag 0x0112 of IFD0, 1 when absent (IFD1 describes the thumbnail and is not
// read). False for a block this function cannot walk, or an orientation it could not be sure
// of (not one SHORT, twice in IFD0, or again in the EXIF sub-IFD, whose tags OpenImageIO reads
// into the same names): the caller leaves such a file to OpenImageIO.
bool orientation(const unsigned char* tiff, size_t size, int& result);

}  // namespace mf::exif
