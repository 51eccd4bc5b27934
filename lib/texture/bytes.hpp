// Little-endian integers in byte buffers: the DDS and KTX2 containers (texture/dds.cpp,
// texture/ktx2.cpp) are little-endian whatever the host is. Internal to lib/texture.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace mf::texture::bytes {

inline void put32(std::vector<uint8_t>& out, uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
}
inline void set64(std::vector<uint8_t>& out, size_t at, uint64_t v) {
    for (size_t i = 0; i < 8; ++i) out[at + i] = static_cast<uint8_t>(v >> (8 * i));
}
// The caller has checked that `b` holds [at, at + 4) (or + 8).
inline uint32_t get32(std::span<const uint8_t> b, size_t at) {
    uint32_t v = 0;
    for (size_t i = 0; i < 4; ++i) v |= static_cast<uint32_t>(b[at + i]) << (8 * i);
    return v;
}
inline uint64_t get64(std::span<const uint8_t> b, size_t at) {
    uint64_t v = 0;
    for (size_t i = 0; i < 8; ++i) v |= static_cast<uint64_t>(b[at + i]) << (8 * i);
    return v;
}

}  // namespace mf::texture::bytes
