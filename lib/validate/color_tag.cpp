#include "validate/color_tag.hpp"
#include "core/text.hpp"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <vector>

namespace mf::validate {
namespace {

uint32_t be32(const unsigned char* p) {
    return (uint32_t{p[0]} << 24) | (uint32_t{p[1]} << 16) | (uint32_t{p[2]} << 8) | uint32_t{p[3]};
}

ColorTag classify_name(const std::string& name) {
    const std::string l = ascii_lower(name);
    if (l.find("srgb") != std::string::npos) return ColorTag::srgb;
    if (l.find("linear") != std::string::npos || l == "raw" || l.find("scene_linear") != std::string::npos)
        return ColorTag::linear;
    return ColorTag::other;
}

}  // namespace

std::string_view color_tag_name(ColorTag t) {
    switch (t) {
        case ColorTag::srgb: return "srgb";
        case ColorTag::linear: return "linear";
        case ColorTag::other: return "other";
        case ColorTag::none: break;
    }
    return "none";
}

ColorTagInfo png_color_tag(const unsigned char* d, size_t n) {
    static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (n < 8 || !std::equal(sig, sig + 8, d)) return {};
    ColorTagInfo cicp, iccp, srgb, gama;
    size_t off = 8;
    while (off + 12 <= n) {
        const uint32_t len = be32(d + off);
        const std::string type(reinterpret_cast<const char*>(d + off + 4), 4);
        const unsigned char* data = d + off + 8;
        if (len > n - off - 12) break;                // truncated: keep what was found
        if (type == "IDAT" || type == "IEND") break;  // colour chunks precede image data
        if (type == "cICP" && len >= 4) {
            // ITU-T H.273 transfer characteristics: 13 = sRGB (IEC 61966-2-1), 8 = linear.
            const int tc = data[1];
            cicp.source = "png:cICP";
            cicp.value = "transfer " + std::to_string(tc);
            cicp.tag = tc == 13 ? ColorTag::srgb : (tc == 8 ? ColorTag::linear : ColorTag::other);
        } else if (type == "iCCP" && len >= 2) {
            const auto* end = std::find(data, data + std::min<uint32_t>(len, 80), 0);
            iccp.source = "png:iCCP";
            iccp.value.assign(reinterpret_cast<const char*>(data), reinterpret_cast<const char*>(end));
            iccp.tag = classify_name(iccp.value);
        } else if (type == "sRGB") {
            srgb.source = "png:sRGB";
            srgb.value = "sRGB";
            srgb.tag = ColorTag::srgb;
        } else if (type == "gAMA" && len >= 4) {
            // gAMA stores 100000 × the encoding exponent (1/2.2 → 45455; linear → 100000).
            const double g = be32(data) / 100000.0;
            gama.source = "png:gAMA";
            gama.value = "gamma " + std::to_string(g > 0 ? 1.0 / g : 0.0);
            gama.tag = std::abs(g - 1.0) < 0.02         ? ColorTag::linear
                       : std::abs(g - 1.0 / 2.2) < 0.02 ? ColorTag::srgb
                                                        : ColorTag::other;
        }
        off += size_t{len} + 12;
    }
    for (const ColorTagInfo* t : {&cicp, &iccp, &srgb, &gama})
        if (!t->source.empty()) return *t;
    return {};
}

ColorTagInfo read_color_tag(const InputFile& in) {
    const std::string ext = in.extension();
    if (ext == "png") {
        if (in.bytes) return png_color_tag(in.bytes->data(), in.bytes->size());
        std::ifstream f(in.path, std::ios::binary);
        // Colour chunks come before IDAT; 1 MiB holds any sane iCCP.
        std::vector<unsigned char> head(1 << 20);
        f.read(reinterpret_cast<char*>(head.data()), static_cast<std::streamsize>(head.size()));
        head.resize(static_cast<size_t>(f.gcount()));
        return png_color_tag(head.data(), head.size());
    }
    const auto [cs, fmt] = stated_color_space(in);
    if (cs.empty()) return {};
    // Readers that state a color space for every file (EXR: linear; JPEG and WebP: sRGB, the
    // format's assumption, not a tag the file carries) say nothing about this file.
    if ((fmt == "openexr" && ascii_lower(cs) == "linear") ||
        ((fmt == "jpeg" || fmt == "webp") && ascii_lower(cs) == "srgb"))
        return {};
    return {classify_name(cs), "oiio:ColorSpace", cs};
}

}  // namespace mf::validate
