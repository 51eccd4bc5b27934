#include "image/webp_reader.hpp"

#include <webp/decode.h>

#include <cstring>

namespace mf::webp {

bool read_plain(const unsigned char* data, size_t size, bool header_only, uint64_t max_samples, Plain& out) {
    out = Plain{};
    // RIFF container (WebP container spec): "RIFF" size "WEBP", then the first chunk. An
    // extended file's VP8X chunk states in its flags byte what else it holds.
    if (size < 30 || std::memcmp(data, "RIFF", 4) != 0 || std::memcmp(data + 8, "WEBP", 4) != 0) return false;
    if (std::memcmp(data + 12, "VP8X", 4) == 0) {
        // Alpha (0x10) is read here: libwebp's RGBA mode gives the stored, unassociated values, where
        // OpenImageIO's reader associates them and back (up to 44 codes off under low alpha).
        constexpr unsigned char kIcc = 0x20, kExif = 0x08, kXmp = 0x04, kAnimation = 0x02;
        if (data[20] & (kIcc | kExif | kXmp | kAnimation)) return false;
    } else if (std::memcmp(data + 12, "VP8 ", 4) != 0 && std::memcmp(data + 12, "VP8L", 4) != 0) {
        return false;
    }
    WebPBitstreamFeatures f{};
    if (WebPGetFeatures(data, size, &f) != VP8_STATUS_OK || f.has_animation || f.width <= 0 || f.height <= 0 ||
        uint64_t{static_cast<uint32_t>(f.width)} * static_cast<uint32_t>(f.height) * (f.has_alpha ? 4U : 3U) >
            max_samples)
        return false;
    out.width = f.width;
    out.height = f.height;
    out.channels = f.has_alpha ? 4 : 3;
    if (header_only) return true;
    const size_t stride = static_cast<size_t>(f.width) * static_cast<size_t>(out.channels);
    out.pixels.resize(stride * static_cast<size_t>(f.height));
    const bool decoded = f.has_alpha ? WebPDecodeRGBAInto(data, size, out.pixels.data(), out.pixels.size(),
                                                          static_cast<int>(stride))
                                     : WebPDecodeRGBInto(data, size, out.pixels.data(), out.pixels.size(),
                                                         static_cast<int>(stride));
    if (!decoded) {
        out = Plain{};
        return false;
    }
    return true;
}

}  // namespace mf::webp
