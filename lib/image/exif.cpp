#include "image/exif.hpp"

#include <cstdint>

namespace mf::exif {
namespace {

uint16_t get16(const unsigned char* p, bool little) {
    return little ? static_cast<uint16_t>(p[0] | (p[1] << 8)) : static_cast<uint16_t>((p[0] << 8) | p[1]);
}
uint32_t get32(const unsigned char* p, bool little) {
    return little ? (uint32_t{p[0]} | (uint32_t{p[1]} << 8) | (uint32_t{p[2]} << 16) | (uint32_t{p[3]} << 24))
                  : ((uint32_t{p[0]} << 24) | (uint32_t{p[1]} << 16) | (uint32_t{p[2]} << 8) | uint32_t{p[3]});
}

constexpr uint16_t kOrientationTag = 0x0112, kExifIfdTag = 0x8769, kShort = 3;

}  // namespace

bool orientation(const unsigned char* tiff, size_t size, int& result) {
    if (size < 8) return false;
    const bool little = tiff[0] == 'I' && tiff[1] == 'I';
    if (!little && !(tiff[0] == 'M' && tiff[1] == 'M')) return false;
    if (get16(tiff + 2, little) != 42) return false;
    // Looks tag `tag` up in the IFD at `at`: 1 found (value set), 0 absent, -1 not walkable or unsure.
    auto find = [&](uint32_t at, uint16_t tag, uint32_t& value) {
        if (at < 8 || size < 2 || at > size - 2) return -1;
        const uint16_t count = get16(tiff + at, little);
        if (uint64_t{at} + 2 + uint64_t{count} * 12 > size) return -1;
        int found = 0;
        for (uint16_t i = 0; i < count; ++i) {
            const unsigned char* e = tiff + at + 2 + size_t{i} * 12;
            if (get16(e, little) != tag) continue;
            if (found) return -1;
            found = 1;
            const uint16_t type = get16(e + 2, little);
            const uint32_t n = get32(e + 4, little);
            if (tag == kOrientationTag) {
                if (type != kShort || n != 1) return -1;
                value = get16(e + 8, little);
            } else {
                value = get32(e + 8, little);  // the sub-IFD's offset
            }
        }
        return found;
    };
    const uint32_t ifd0 = get32(tiff + 4, little);
    uint32_t value = 1, sub = 0;
    const int o = find(ifd0, kOrientationTag, value);
    const int s = find(ifd0, kExifIfdTag, sub);
    if (o < 0 || s < 0) return false;
    if (s == 1) {
        uint32_t again = 0;
        if (find(sub, kOrientationTag, again) != 0) return false;
    }
    result = o == 1 ? static_cast<int>(value) : 1;
    return true;
}

}  // namespace mf::exif
