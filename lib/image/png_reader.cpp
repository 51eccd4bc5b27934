#include "image/png_reader.hpp"

#include "base/limits.hpp"
#include "image/exif.hpp"

#include <libdeflate.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
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
        case 3:  // the first pixel has no left neighbour (0): its own loop, none of it in the chain
            for (size_t i = 0; i < std::min(k, n); ++i) row[i] = static_cast<uint8_t>(row[i] + up[i] / 2);
            for (size_t i = k; i < n; ++i) row[i] = static_cast<uint8_t>(row[i] + (row[i - k] + up[i]) / 2);
            return true;
        case 4:
            switch (bpp) {  // bytes per pixel: 1-4 channels of 8 bits, or 1-4 of 16
                case 1: unpaeth<1>(row, up, width); return true;
                case 2: unpaeth<2>(row, up, width); return true;
                case 3: unpaeth<3>(row, up, width); return true;
                case 4: unpaeth<4>(row, up, width); return true;
                case 6: unpaeth<6>(row, up, width); return true;
                default: unpaeth<8>(row, up, width); return true;
            }
        default: return false;
    }
}

// One reduced image of the stream: its size and where its pixels go (column x0 + i dx, row y0 + j dy).
struct Pass {
    size_t width, height, x0, y0, dx, dy;
};

// The images of a width x height stream: the whole image, or Adam7's seven passes (PNG spec
// 8.2), the empty ones left out (they have no bytes in the stream).
std::vector<Pass> passes_of(size_t width, size_t height, bool interlaced) {
    if (!interlaced) return {{width, height, 0, 0, 1, 1}};
    static constexpr size_t kAdam7[7][4] = {{0, 0, 8, 8}, {4, 0, 8, 8}, {0, 4, 4, 8}, {2, 0, 4, 4},
                                            {0, 2, 2, 4}, {1, 0, 2, 2}, {0, 1, 1, 2}};
    std::vector<Pass> out;
    for (const auto& a : kAdam7) {
        const size_t w = width > a[0] ? (width - a[0] + a[2] - 1) / a[2] : 0;
        const size_t h = height > a[1] ? (height - a[1] + a[3] - 1) / a[3] : 0;
        if (w > 0 && h > 0) out.push_back({w, h, a[0], a[1], a[2], a[3]});
    }
    return out;
}

// The text of a text chunk (tEXt as it is, zTXt and a compressed iTXt inflated, at most 4 MiB);
// false when it cannot be had.
bool chunk_text(std::string_view type, const unsigned char* data, uint32_t len, std::string& out) {
    const auto* end = data + len;
    const auto* nul = std::find(data, end, 0);
    if (nul == end) return false;
    const unsigned char* p = nul + 1;
    bool compressed = type == "zTXt";
    if (type == "zTXt") ++p;  // compression method
    if (type == "iTXt") {     // compression flag, method, language tag\0, translated keyword\0
        if (end - p < 2) return false;
        compressed = p[0] != 0;
        p += 2;
        for (int field = 0; field < 2; ++field) {
            p = std::find(p, end, 0);
            if (p == end) return false;
            ++p;
        }
    }
    if (p > end) return false;
    if (!compressed) {
        out.assign(reinterpret_cast<const char*>(p), static_cast<size_t>(end - p));
        return true;
    }
    const std::unique_ptr<libdeflate_decompressor, decltype(&libdeflate_free_decompressor)> inflater(
        libdeflate_alloc_decompressor(), &libdeflate_free_decompressor);
    out.assign(size_t{4} << 20, '\0');
    size_t made = 0;
    if (!inflater || libdeflate_zlib_decompress(inflater.get(), p, static_cast<size_t>(end - p), out.data(), out.size(),
                                                &made) != LIBDEFLATE_SUCCESS)
        return false;
    out.resize(made);
    return true;
}

// Whether ImageMagick's raw profile "\n<name>\n<spaces><length>\n<hex>" states no orientation
// but 1: EXIF (optionally after "Exif\0\0") through exif::orientation, XMP by its
// tiff:Orientation. Anything this cannot read is left to OpenImageIO (false).
bool raw_profile_upright(std::string_view type, const std::string& key, const unsigned char* data, uint32_t len) {
    std::string text;
    if (!chunk_text(type, data, len, text)) return false;
    size_t at = text.find('\n', 1);  // after "\n<name>"
    if (text.empty() || text[0] != '\n' || at == std::string::npos) return false;
    at = text.find('\n', at + 1);  // after the length
    if (at == std::string::npos) return false;
    std::string bytes;
    auto nibble = [](char c) { return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1; };
    int high = -1;
    for (size_t i = at + 1; i < text.size(); ++i) {
        const char c = text[i] >= 'A' && text[i] <= 'F' ? static_cast<char>(text[i] - 'A' + 'a') : text[i];
        const int v = nibble(c);
        if (v < 0) continue;  // line breaks
        if (high < 0) high = v;
        else bytes += static_cast<char>(high * 16 + v), high = -1;
    }
    if (key == "raw profile type xmp") {
        const size_t o = bytes.find("Orientation");
        if (o == std::string::npos) return true;
        const size_t digit = bytes.find_first_of("0123456789", o);
        return digit != std::string::npos && digit < o + 24 && bytes[digit] == '1' &&
               (digit + 1 >= bytes.size() || !std::isdigit(static_cast<unsigned char>(bytes[digit + 1])));
    }
    size_t skip = bytes.compare(0, 6, std::string("Exif\0\0", 6)) == 0 ? 6 : 0;
    int orientation = 0;
    return exif::orientation(reinterpret_cast<const unsigned char*>(bytes.data()) + skip, bytes.size() - skip,
                             orientation) &&
           orientation == 1;
}

// Chunks that change no pixel OpenImageIO reads and no fact it states that matforge uses: text
// but an orientation, EXIF of orientation 1, time, pixel size, image offset (matforge reads no
// origin), and the colour chunks OpenImageIO 2.4 records as attributes without applying them
// (gAMA, sRGB, cHRM, iCCP; bKGD, a viewer's backdrop: OpenImageIO composites nothing).
// PngReader.LeavesEveryOtherPngToOpenImageIo and DirectCodecs.CorpusPngsReadAsOpenImageIoReadsThem
// hold this against OpenImageIO. Any other ancillary chunk (sBIT, tRNS, ...) sends the file to
// OpenImageIO.
bool inert(std::string_view type, const unsigned char* data, uint32_t len) {
    if (type == "tEXt" || type == "zTXt" || type == "iTXt") {
        // OpenImageIO makes each text chunk an attribute named by its keyword, reads an
        // "Orientation" one as the orientation it notes (ORIENTATION_IGNORED), and decodes
        // ImageMagick's raw profiles (hex-encoded EXIF or XMP, an orientation among them): a
        // file whose text states an orientation other than 1 is its.
        std::string_view key(reinterpret_cast<const char*>(data), std::min<uint32_t>(len, 80));
        key = key.substr(0, key.find('\0'));
        std::string lower(key);
        for (char& c : lower) c = c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c;
        if (lower == "orientation") return false;
        if (lower == "raw profile type exif" || lower == "raw profile type app1" || lower == "raw profile type xmp")
            return raw_profile_upright(type, lower, data, len);
        return true;
    }
    if (type == "eXIf") {  // inert when it states no orientation but 1 (image/exif.hpp)
        int orientation = 0;
        return exif::orientation(data, len, orientation) && orientation == 1;
    }
    return type == "tIME" || type == "pHYs" || type == "oFFs" || type == "gAMA" || type == "sRGB" || type == "cHRM" ||
           type == "iCCP" || type == "bKGD";
}

}  // namespace

bool plain_ihdr(const unsigned char* head, size_t max_bytes, Plain& out) {
    out = Plain{};
    if (std::memcmp(head, kSignature, 8) != 0 || be32(head + 8) != 13 || std::memcmp(head + 12, "IHDR", 4) != 0)
        return false;
    const unsigned char* data = head + 16;
    const uint32_t width = be32(data), height = be32(data + 4);
    static constexpr int kChannels[] = {1, 0, 3, 0, 2, 0, 4};  // by colour type
    const int channels = data[9] < 7 ? kChannels[data[9]] : 0;
    const int depth = data[8];
    // 8- or 16-bit samples, deflate, filter method 0, not interlaced or Adam7.
    if ((depth != 8 && depth != 16) || channels == 0 || data[10] != 0 || data[11] != 0 || data[12] > 1) return false;
    if (width == 0 || height == 0 || width > 0x7FFFFFFFu || height > 0x7FFFFFFFu ||
        uint64_t{width} * height * static_cast<uint64_t>(channels) * static_cast<uint64_t>(depth / 8) > max_bytes)
        return false;
    out.width = static_cast<int>(width);
    out.height = static_cast<int>(height);
    out.channels = channels;
    out.bit_depth = depth;
    out.interlaced = data[12] == 1;
    return true;
}

bool read_plain_header(uint64_t size, const ReadAt& read, size_t max_bytes, Plain& out) {
    unsigned char head[kHeaderBytes];
    if (size < kHeaderBytes + 12 || !read(0, sizeof head, head) || !plain_ihdr(head, max_bytes, out)) return false;
    // Every chunk before the first IDAT, CRCs included (they are small: text, colour, times).
    std::vector<unsigned char> chunk;
    for (uint64_t at = 8;;) {
        unsigned char h[8];
        if (size - at < 12 || !read(at, 8, h)) break;
        const uint32_t len = be32(h);
        if (len > 0x7FFFFFFFu || size - at - 12 < len) break;
        const std::string_view type(reinterpret_cast<const char*>(h + 4), 4);
        if (type == "IDAT") return true;
        if (len > kMaxMetadataChunk) break;  // the module drops it before OpenImageIO reads the file
        chunk.resize(size_t{len} + 8);
        if (!read(at + 4, chunk.size(), chunk.data())) break;
        if (libdeflate_crc32(0, chunk.data(), len + 4) != be32(chunk.data() + 4 + len)) break;
        if (at != 8 && !inert(type, chunk.data() + 4, len)) break;
        at += 12 + uint64_t{len};
    }
    out = Plain{};
    return false;
}

bool read_plain(std::vector<unsigned char>& file, size_t max_bytes, Plain& out) {
    out = Plain{};
    unsigned char* bytes = file.data();
    const size_t size = file.size();
    Plain ihdr;
    if (size < kHeaderBytes || !plain_ihdr(bytes, max_bytes, ihdr)) return false;
    const auto width = static_cast<uint32_t>(ihdr.width), height = static_cast<uint32_t>(ihdr.height);
    const int bpp = ihdr.channels * ihdr.bit_depth / 8;  // bytes per pixel
    size_t stream = 0;                                   // the IDAT chunks' data, moved together to the front of `file`
    // The chunk order is kept in flags, never in views of `file`: the IDAT data moved to the
    // front overwrites the chunk headers already read (a first IDAT larger than what precedes it
    // overwrites its own type), so a view would read pixels instead of "IDAT".
    bool ended = false, in_idat_run = false, idat_run_over = false;
    for (size_t at = 8; !ended;) {
        if (size - at < 12) return false;
        const uint32_t len = be32(bytes + at);
        if (len > 0x7FFFFFFFu || size - at - 12 < len) return false;
        const std::string_view type(reinterpret_cast<const char*>(bytes + at + 4), 4);
        const unsigned char* data = bytes + at + 8;
        if (libdeflate_crc32(0, bytes + at + 4, len + 4) != be32(data + len)) return false;
        // Read before the memmove below, which may move pixels over this very header.
        const bool idat = at != 8 && type == "IDAT";
        if (at == 8) {  // IHDR, checked before the loop
        } else if (idat) {
            if (idat_run_over) return false;
            // Behind everything already read (stream <= at): moving it overwrites nothing unread.
            std::memmove(bytes + stream, data, len);
            stream += len;
        } else if (type == "IEND") {
            ended = true;
        } else if (!inert(type, data, len)) {
            return false;
        }
        at += 12 + len;
        if (in_idat_run && !idat) idat_run_over = true;
        in_idat_run = idat;
    }
    if (stream == 0) return false;

    // The stream holds one filtered image (interlace 0), or Adam7's seven reduced images (PNG spec
    // 8.2), each of its own rows with their filter bytes; an empty pass has no bytes at all.
    const std::vector<Pass> passes = passes_of(width, height, ihdr.interlaced);
    size_t raw_bytes = 0;
    for (const Pass& p : passes) raw_bytes += p.height * (p.width * static_cast<size_t>(bpp) + 1);
    std::vector<uint8_t> raw(raw_bytes);
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

    // Rows are reconstructed in place behind their filter bytes.
    const size_t row_bytes = size_t{width} * static_cast<size_t>(bpp);
    const std::vector<uint8_t> zeros(row_bytes, 0);
    size_t at = 0;
    for (const Pass& p : passes) {
        const size_t pass_row = p.width * static_cast<size_t>(bpp);
        for (size_t y = 0; y < p.height; ++y) {
            uint8_t* row = raw.data() + at + y * (pass_row + 1);
            const uint8_t* up = y ? row - pass_row : zeros.data();
            if (!unfilter(row[0], row + 1, up, p.width, bpp)) return false;
        }
        at += p.height * (pass_row + 1);
    }
    if (!ihdr.interlaced) {  // the rows moved together over their filter bytes
        for (size_t y = 0; y < height; ++y)
            std::memmove(raw.data() + y * row_bytes, raw.data() + y * (row_bytes + 1) + 1, row_bytes);
        raw.resize(row_bytes * height);
    } else {  // each pass's pixels to their places in the image
        std::vector<uint8_t> image(row_bytes * height);
        at = 0;
        for (const Pass& p : passes) {
            const size_t pass_row = p.width * static_cast<size_t>(bpp);
            for (size_t y = 0; y < p.height; ++y) {
                const uint8_t* src = raw.data() + at + y * (pass_row + 1) + 1;
                uint8_t* dst = image.data() + (p.y0 + y * p.dy) * row_bytes + p.x0 * static_cast<size_t>(bpp);
                for (size_t x = 0; x < p.width; ++x)
                    std::memcpy(dst + x * p.dx * static_cast<size_t>(bpp), src + x * static_cast<size_t>(bpp),
                                static_cast<size_t>(bpp));
            }
            at += p.height * (pass_row + 1);
        }
        raw = std::move(image);
    }
    if (ihdr.bit_depth == 16)  // PNG's samples are big-endian
        for (size_t i = 0; i + 1 < raw.size(); i += 2) {
            const auto v = static_cast<uint16_t>((raw[i] << 8) | raw[i + 1]);
            std::memcpy(raw.data() + i, &v, 2);
        }
    out = ihdr;
    out.pixels = std::move(raw);
    return true;
}

std::string size_refusal(uint64_t size, const ReadAt& read) {
    unsigned char head[kHeaderBytes];
    if (size < kHeaderBytes || !read(0, sizeof head, head) || std::memcmp(head, kSignature, 8) != 0 ||
        be32(head + 8) != 13 || std::memcmp(head + 12, "IHDR", 4) != 0)
        return {};
    const unsigned char* data = head + 16;
    const uint64_t width = be32(data), height = be32(data + 4);
    static constexpr int kChannels[] = {1, 0, 3, 1, 2, 0, 4};  // by colour type (3: palette index)
    const int channels = data[9] < 7 ? kChannels[data[9]] : 0;
    const uint64_t bits = uint64_t{data[8]} * static_cast<uint64_t>(channels);
    // Beyond kMaxImageSide² pixels the decoders' own limit refuses the file, in its words.
    if (width == 0 || height == 0 || bits == 0 || data[12] > 1 ||
        width * height > uint64_t{kMaxImageSide} * uint64_t{kMaxImageSide})
        return {};
    uint64_t rows = 0;  // the filtered rows' bytes: each row's samples, rounded up to bytes, and its filter byte
    for (const Pass& p : passes_of(static_cast<size_t>(width), static_cast<size_t>(height), data[12] == 1))
        rows += uint64_t{p.height} * ((uint64_t{p.width} * bits + 7) / 8 + 1);
    uint64_t idat = 0;
    for (uint64_t at = kHeaderBytes; at + 8 <= size;) {  // after IHDR and its CRC
        unsigned char chunk[8];
        if (!read(at, 8, chunk)) break;
        const uint64_t len = be32(chunk);
        if (std::memcmp(chunk + 4, "IDAT", 4) == 0) idat += len;
        if (std::memcmp(chunk + 4, "IEND", 4) == 0) break;
        at += 12 + len;
    }
    constexpr uint64_t kDeflateMaxRatio = 1032;
    const uint64_t most = kDeflateMaxRatio * idat + kDeflateMaxRatio;
    if (rows <= most) return {};
    return "its header declares " + std::to_string(width) + "x" + std::to_string(height) + " pixels (" +
           std::to_string(rows) + " bytes of rows), more than its " + std::to_string(idat) +
           " bytes of image data can inflate to (at most " + std::to_string(most) +
           "): the file is cut short or its header is damaged; not decoded";
}

}  // namespace mf::png
