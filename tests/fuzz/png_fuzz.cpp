// Plain-PNG reader (lib/image/png_reader.hpp): any bytes as a PNG. Whatever it accepts must
// come back as exactly width x height x channels samples of its depth, as its header read states
// them; anything else is refused (false), never a crash, an overread or an unbounded allocation.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include <libdeflate.h>

#include "image/png_reader.hpp"

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
    // The header read first, as image/direct.cpp does: over the same bytes it may accept what
    // the decode then refuses (damage after the first IDAT), never the other way round.
    mf::png::Plain head;
    const bool head_ok = mf::png::read_plain_header(
        file.size(),
        [&](uint64_t at, size_t n, unsigned char* out) {
            if (at > file.size() || n > file.size() - at) return false;
            std::copy_n(file.data() + at, n, out);
            return true;
        },
        size_t{1} << 24, head);
    // The size check walks any PNG's chunk headers; it never doubts one the decode reads whole.
    const std::string doubt = mf::png::size_refusal(file.size(), [&](uint64_t at, size_t n, unsigned char* out) {
        if (at > file.size() || n > file.size() - at) return false;
        std::copy_n(file.data() + at, n, out);
        return true;
    });
    mf::png::Plain p;
    if (!mf::png::read_plain(file, size_t{1} << 24, p)) {
        if (!p.pixels.empty()) std::abort();  // a refusal leaves nothing
        return 0;
    }
    const size_t bytes = p.bit_depth == 16 ? 2 : 1;
    if (p.width <= 0 || p.height <= 0 || p.channels < 1 || p.channels > 4 || (p.bit_depth != 8 && p.bit_depth != 16) ||
        p.pixels.size() !=
            static_cast<size_t>(p.width) * static_cast<size_t>(p.height) * static_cast<size_t>(p.channels) * bytes)
        std::abort();
    if (!doubt.empty()) std::abort();
    if (!head_ok || head.width != p.width || head.height != p.height || head.channels != p.channels ||
        head.bit_depth != p.bit_depth)
        std::abort();  // what the decode reads, the header read states
    return 0;
}
