#include "image/png_reader.hpp"

#include "base/limits.hpp"
#include "image/exif.hpp"
#include "image/png_unfilter.hpp"

#include <libdeflate.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>
#include <utility>

namespace mf::png {
namespace {

// PNG's big-endian 16-bit samples in the host's order: on a little-endian host each sample's two
// bytes swapped, 8 samples a step (GCC vectorizes neither a byte loop nor a rotate of each).
void to_host_order16(std::vector<uint8_t>& samples) {
    if constexpr (std::endian::native == std::endian::big) return;
    using U16x8 = uint16_t __attribute__((vector_size(16)));
    uint8_t* p = samples.data();
    const size_t n = samples.size() & ~size_t{1};
    size_t i = 0;
    for (; i + 16 <= n; i += 16) {
        U16x8 v;
        std::memcpy(&v, p + i, 16);
        v = (v << 8) | (v >> 8);
        std::memcpy(p + i, &v, 16);
    }
    for (; i < n; i += 2) std::swap(p[i], p[i + 1]);
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
    // The IDAT chunks' data, `stream` bytes at `stream_at`: the first chunk's where it is, each
    // later one moved back over the 12 bytes of CRC and header between them (a copy of the
    // chunks after the first, not of the whole stream).
    size_t stream_at = 0, stream = 0;
    // The chunk order is kept in flags, never in views of `file`: the IDAT data moved back
    // overwrites the chunk headers already read (its own length and type), so a view would read
    // pixels instead of "IDAT".
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
            // Behind everything already read (stream_at + stream <= at): moving it overwrites
            // nothing unread.
            if (stream == 0) stream_at = at + 8;
            else std::memmove(bytes + stream_at + stream, data, len);
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
        libdeflate_zlib_decompress_ex(inflater.get(), bytes + stream_at, stream, raw.data(), raw.size(), &used,
                                      &made) != LIBDEFLATE_SUCCESS ||
        used != stream || made != raw.size())
        return false;
    std::vector<unsigned char>().swap(file);

    // Each row is reconstructed over its filter byte and the rows before it (png_unfilter.hpp
    // reads a row ahead of where it writes): the passes' rows end up together, in one pass over
    // the bytes.
    const size_t row_bytes = size_t{width} * static_cast<size_t>(bpp);
    const std::vector<uint8_t> zeros(row_bytes, 0);
    const UnfilterIsa isa = best_unfilter_isa();
    size_t at = 0, out_at = 0;  // where the pass's filtered rows are, and where its pixels go
    for (const Pass& p : passes) {
        const size_t pass_row = p.width * static_cast<size_t>(bpp);
        for (size_t y = 0; y < p.height; ++y) {
            const uint8_t* row = raw.data() + at + y * (pass_row + 1);
            uint8_t* to = raw.data() + out_at + y * pass_row;
            if (!unfilter_row(row[0], row + 1, to, y ? to - pass_row : zeros.data(), p.width, bpp, isa)) return false;
        }
        at += p.height * (pass_row + 1);
        out_at += p.height * pass_row;
    }
    if (!ihdr.interlaced) {
        raw.resize(row_bytes * height);
    } else {  // each pass's pixels to their places in the image
        std::vector<uint8_t> image(row_bytes * height);
        out_at = 0;
        for (const Pass& p : passes) {
            const size_t pass_row = p.width * static_cast<size_t>(bpp);
            for (size_t y = 0; y < p.height; ++y) {
                const uint8_t* src = raw.data() + out_at + y * pass_row;
                uint8_t* dst = image.data() + (p.y0 + y * p.dy) * row_bytes + p.x0 * static_cast<size_t>(bpp);
                for (size_t x = 0; x < p.width; ++x)
                    std::memcpy(dst + x * p.dx * static_cast<size_t>(bpp), src + x * static_cast<size_t>(bpp),
                                static_cast<size_t>(bpp));
            }
            out_at += p.height * pass_row;
        }
        raw = std::move(image);
    }
    if (ihdr.bit_depth == 16) to_host_order16(raw);
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
