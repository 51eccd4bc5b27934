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
        constexpr unsigned char kIcc = 0x20, kAlpha = 0x10, kExif = 0x08, kXmp = 0x04, kAnimation = 0x02;
        if (data[20] & (kIcc | kAlpha | kExif | kXmp | kAnimation)) return false;
    } else if (std::memcmp(data + 12, "VP8 ", 4) != 0 && std::memcmp(data + 12, "VP8L", 4) != 0) {
        return false;
    }
    WebPBitstreamFeatures f{};
    if (WebPGetFeatures(data, size, &f) != VP8_STATUS_OK || f.has_alpha || f.has_animation || f.width <= 0 ||
        f.height <= 0 || uint64_t{static_cast<uint32_t>(f.width)} * static_cast<uint32_t>(f.height) * 3 > max_samples)
        return false;
    out.width = f.width;
    out.height = f.height;
    if (header_only) return true;
    const size_t stride = static_cast<size_t>(f.width) * 3;
    out.pixels.resize(stride * static_cast<size_t>(f.height));
    if (!WebPDecodeRGBInto(data, size, out.pixels.data(), out.pixels.size(), static_cast<int>(stride))) {
        out = Plain{};
        return false;
    }
    return true;
}

}  // namespace mf::webp
