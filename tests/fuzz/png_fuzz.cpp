// Plain-PNG reader (lib/image/oiio/png_reader.hpp): any bytes as a PNG. Whatever it accepts must
// come back as exactly width x height x channels samples; anything else is refused (false), never
// a crash, an overread or an unbounded allocation.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include <libdeflate.h>

#include "image/oiio/png_reader.hpp"

namespace {

// Mutated chunks get their CRCs right (as far as their lengths walk), so the fuzzer reaches the
// header checks, the inflate and the row filters instead of stopping at the first CRC.
void fix_crcs(std::vector<unsigned char>& f) {
    auto be32 = [&](size_t at) {
        return (uint32_t{f[at]} << 24) | (uint32_t{f[at + 1]} << 16) | (uint32_t{f[at + 2]} << 8) | f[at + 3];
    };
    for (size_t at = 8; at + 12 <= f.size();) {
        const uint32_t len = be32(at);
        if (len > f.size() - at - 12) return;
        const uint32_t crc = libdeflate_crc32(0, f.data() + at + 4, len + 4);
        for (int k = 0; k < 4; ++k)
            f[at + 8 + len + static_cast<size_t>(k)] = static_cast<unsigned char>(crc >> (24 - 8 * k));
        at += 12 + len;
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::vector<unsigned char> file(data, data + size);
    if (size > 0 && (data[0] & 1)) fix_crcs(file);  // half the inputs as they come
    mf::png::Plain8 p;
    if (!mf::png::read_plain8(file, size_t{1} << 24, p)) {
        if (!p.pixels.empty()) std::abort();  // a refusal leaves nothing
        return 0;
    }
    if (p.width <= 0 || p.height <= 0 || p.channels < 1 || p.channels > 4 ||
        p.pixels.size() !=
            static_cast<size_t>(p.width) * static_cast<size_t>(p.height) * static_cast<size_t>(p.channels))
        std::abort();
    return 0;
}
