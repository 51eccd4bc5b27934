// The color space a file states about itself, when it states one explicitly.
//
// OpenImageIO reports "oiio:ColorSpace" = "sRGB" for every PNG and JPEG, tagged or not (a
// format default, not a statement), so PNG chunks are read here directly, in the precedence
// order of PNG 3rd edition §11.3.2.4 (cICP > iCCP > sRGB > gAMA). Other formats: the reader's
// "oiio:ColorSpace" counts only when it differs from that format's default (EXR "Linear",
// JPEG "sRGB").
#pragma once
#include <string>
#include <string_view>

#include "image/image.hpp"

namespace mf::validate {

enum class ColorTag { none, srgb, linear, other };

struct ColorTagInfo {
    ColorTag tag = ColorTag::none;
    std::string source;  // "png:cICP", "png:iCCP", "png:sRGB", "png:gAMA", "oiio:ColorSpace"
    std::string value;   // what the file says ("gamma 1.00", profile name, OIIO name, …)
};

std::string_view color_tag_name(ColorTag t);  // "none" | "srgb" | "linear" | "other"

// Never fails: an unreadable or untagged file gives ColorTag::none.
ColorTagInfo read_color_tag(const InputFile& in);

// PNG chunk parser over a whole file's bytes d[0, n) (exposed for tests).
ColorTagInfo png_color_tag(const unsigned char* d, size_t n);

}  // namespace mf::validate
