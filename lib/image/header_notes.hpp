// The notes a header read gives about facts matforge does not apply (ImageInfo::notes), typed
// once for both readers: image/direct.cpp's and the OpenImageIO module's.
#pragma once
#include <string>
#include <utility>

namespace mf {

// ORIENTATION_IGNORED for a file whose EXIF/TIFF orientation is `orientation` (not 1).
inline std::pair<std::string, std::string> orientation_note(const std::string& display, int orientation) {
    static constexpr const char* kMeaning[] = {"",
                                               "",
                                               "mirrored left-right",
                                               "rotated 180°",
                                               "mirrored top-bottom",
                                               "transposed",
                                               "rotated 90° clockwise",
                                               "transversed",
                                               "rotated 90° counter-clockwise"};
    return {
        "ORIENTATION_IGNORED",
        display + ": its EXIF/TIFF orientation is " + std::to_string(orientation) +
            (orientation >= 2 && orientation <= 8 ? std::string(" (") + kMeaning[orientation] + ")" : std::string()) +
            ", which is not applied: the map is used as stored, so that every map of the set lines up pixel for pixel"};
}

}  // namespace mf
