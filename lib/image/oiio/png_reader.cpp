#include "image/oiio/png_reader.hpp"

#include <libdeflate.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string_view>

namespace mf::png {
namespace {

// Reverses the Paeth filter (PNG spec 9.4) of one row in place (`row` holds the filtered bytes,
// `up` the row above, reconstructed, or zeros). Each pixel depends on the one before it; its
// channels are independent chains, which the processor overlaps. (Per-pixel vector forms ran no
// faster here: the chain from one pixel to the next sets the pace.)
template <int Bpp>
void unpaeth(uint8_t* row, const uint8_t* up, size_t width) {
    int a[Bpp] = {}, c[Bpp] = {};
    for (size_t x = 0; x < width; ++x) {
        uint8_t* px = row + x * Bpp;
        const uint8_t* above = up + x * Bpp;
        for (int k = 0; k < Bpp; ++k) {
            const int b = above[k];
            const int pa = std::abs(b - c[k]), pb = std::abs(a[k] - c[k]), pc = std::abs(a[k] + b - 2 * c[k]);
            const int by_b = pb <= pc ? b : c[k];
            const int pred = (pa <= pb && pa <= pc) ? a[k] : by_b;
            a[k] = (px[k] + pred) & 0xFF;
            px[k] = static_cast<uint8_t>(a[k]);
            c[k] = b;
        }
    }
}

// Reverses row filter `type` (PNG spec 9.2) in place; false for an unknown type.
bool unfilter(int type, uint8_t* row, const uint8_t* up, size_t width, int bpp) {
    const size_t n = width * static_cast<size_t>(bpp);
    const auto k = static_cast<size_t>(bpp);
    switch (type) {
        case 0: return true;
        case 1:
            for (size_t i = k; i < n; ++i) row[i] = static_cast<uint8_t>(row[i] + row[i - k]);
            return true;
        case 2:
            for (size_t i = 0; i < n; ++i) row[i] = static_cast<uint8_t>(row[i] + up[i]);
            return true;
        case 3:
            for (size_t i = 0; i < n; ++i)
                row[i] = static_cast<uint8_t>(row[i] + ((i >= k ? row[i - k] : 0) + up[i]) / 2);
            return true;
        case 4:
            switch (bpp) {
                case 1: unpaeth<1>(row, up, width); return true;
                case 2: unpaeth<2>(row, up, width); return true;
                case 3: unpaeth<3>(row, up, width); return true;
                default: unpaeth<4>(row, up, width); return true;
            }
        default: return false;
    }
}

// Chunks that change no pixel and no colour fact OpenImageIO would state for the file: text but
// an orientation, time, pixel size, image offset (matforge reads no origin). Any other ancillary chunk (gAMA, sRGB,
// iCCP, cHRM, sBIT, tRNS, eXIf, ...) sends the file to OpenImageIO.
bool inert(std::string_view type, const unsigned char* data, uint32_t len) {
    if (type == "tEXt" || type == "zTXt" || type == "iTXt") {
        // OpenImageIO makes each text chunk an attribute named by its keyword, and reads an
        // "Orientation" one as the orientation it notes (ORIENTATION_IGNORED): such a file is its.
        std::string_view key(reinterpret_cast<const char*>(data), std::min<uint32_t>(len, 80));
        key = key.substr(0, key.find('\0'));
        static constexpr std::string_view kOrientation = "orientation";
        return !(key.size() == kOrientation.size() &&
                 std::equal(key.begin(), key.end(), kOrientation.begin(),
                            [](char a, char b) { return (a >= 'A' && a <= 'Z' ? a - 'A' + 'a' : a) == b; }));
    }
    return type == "tIME" || type == "pHYs" || type == "oFFs";
}

}  // namespace

int plain8_header(const unsigned char* head, size_t max_bytes) {
    if (std::memcmp(head, kSignature, 8) != 0 || be32(head + 8) != 13 || std::memcmp(head + 12, "IHDR", 4) != 0)
        return 0;
    const unsigned char* data = head + 16;
    const uint32_t width = be32(data), height = be32(data + 4);
    static constexpr int kChannels[] = {1, 0, 3, 0, 2, 0, 4};  // by colour type
    const int channels = data[9] < 7 ? kChannels[data[9]] : 0;
    // 8-bit samples, deflate, filter method 0, not interlaced.
    if (data[8] != 8 || channels == 0 || data[10] != 0 || data[11] != 0 || data[12] != 0) return 0;
    if (width == 0 || height == 0 || width > 0x7FFFFFFFu || height > 0x7FFFFFFFu ||
        uint64_t{width} * height * static_cast<uint64_t>(channels) > max_bytes)
        return 0;
    return channels;
}

bool read_plain8(std::vector<unsigned char>& file, size_t max_bytes, Plain8& out) {
    out = Plain8{};
    unsigned char* bytes = file.data();
    const size_t size = file.size();
    if (size < kHeaderBytes) return false;
    const int channels = plain8_header(bytes, max_bytes);
    if (channels == 0) return false;
    uint32_t width = 0, height = 0;
    size_t stream = 0;  // the IDAT chunks' data, moved together to the front of `file`
    bool ended = false, idat_run_over = false;
    std::string_view last;
    for (size_t at = 8; !ended;) {
        if (size - at < 12) return false;
        const uint32_t len = be32(bytes + at);
        if (len > 0x7FFFFFFFu || size - at - 12 < len) return false;
        const std::string_view type(reinterpret_cast<const char*>(bytes + at + 4), 4);
        const unsigned char* data = bytes + at + 8;
        if (libdeflate_crc32(0, bytes + at + 4, len + 4) != be32(data + len)) return false;
        if (at == 8) {  // IHDR, checked before the loop
            width = be32(data);
            height = be32(data + 4);
        } else if (type == "IDAT") {
            if (idat_run_over) return false;
            // Behind everything already read (stream <= at): moving it overwrites nothing unread.
            std::memmove(bytes + stream, data, len);
            stream += len;
        } else if (type == "IEND") {
            ended = true;
        } else if (!inert(type, data, len)) {
            return false;
        }
        if (last == "IDAT" && type != "IDAT") idat_run_over = true;
        last = type;
        at += 12 + len;
    }
    if (stream == 0) return false;

    const size_t row_bytes = size_t{width} * static_cast<size_t>(channels);
    std::vector<uint8_t> raw((row_bytes + 1) * height);
    const std::unique_ptr<libdeflate_decompressor, decltype(&libdeflate_free_decompressor)> inflater(
        libdeflate_alloc_decompressor(), &libdeflate_free_decompressor);
    size_t used = 0, made = 0;
    // The whole stream, exactly the rows' bytes: anything short, long or damaged is not plain.
    if (!inflater ||
        libdeflate_zlib_decompress_ex(inflater.get(), bytes, stream, raw.data(), raw.size(), &used, &made) !=
            LIBDEFLATE_SUCCESS ||
        used != stream || made != raw.size())
        return false;
    std::vector<unsigned char>().swap(file);

    // Rows are reconstructed in place behind their filter bytes, then moved together over them.
    const std::vector<uint8_t> zeros(row_bytes, 0);
    for (size_t y = 0; y < height; ++y) {
        uint8_t* row = raw.data() + y * (row_bytes + 1);
        const uint8_t* up = y ? raw.data() + (y - 1) * (row_bytes + 1) + 1 : zeros.data();
        if (!unfilter(row[0], row + 1, up, width, channels)) return false;
    }
    for (size_t y = 0; y < height; ++y)
        std::memmove(raw.data() + y * row_bytes, raw.data() + y * (row_bytes + 1) + 1, row_bytes);
    raw.resize(row_bytes * height);
    out.pixels = std::move(raw);
    out.width = static_cast<int>(width);
    out.height = static_cast<int>(height);
    out.channels = channels;
    return true;
}

}  // namespace mf::png
