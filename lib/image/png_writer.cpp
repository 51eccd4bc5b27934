#include "image/png_writer.hpp"

#include <libdeflate.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>

#include "image/png_reader.hpp"  // kSignature

namespace mf::png {
namespace {

// IDAT chunks are cut at this size: any size is valid (PNG spec 11.2.4); streaming decoders
// buffer a chunk at a time.
constexpr size_t kIdatBytes = size_t{1} << 20;

// Paeth filter (PNG spec 9.4) of one row, 16 samples at a time. `left` and `upleft` are the
// bytes `bpp` before `cur` and `up`. GCC's -O2 does not vectorize the scalar form (150 MB/s
// against 1.5 GB/s for 8-sample vectors on SSE2, measured on random rows); GCC and clang both
// take these vector types on any target. The same body is compiled twice, for x86-64's baseline
// and for AVX2 (picked once by the CPU's features; 16 lanes of 16 bits are one AVX2 register,
// two SSE2 ones): the filtered bytes are the same either way.
using I16x16 = int16_t __attribute__((vector_size(32)));
using U8x16 = uint8_t __attribute__((vector_size(16)));

uint8_t paeth1(int a, int b, int c, int x) {
    const int pa = std::abs(b - c), pb = std::abs(a - c), pc = std::abs(a + b - 2 * c);
    return static_cast<uint8_t>(x - ((pa <= pb && pa <= pc) ? a : (pb <= pc ? b : c)));
}

// out[0] is the filter type; out[1..n] the filtered bytes of `cur` (n bytes) over `up` (zeros
// for the first row).
__attribute__((always_inline)) inline void paeth_body(const uint8_t* cur, const uint8_t* up, size_t n, size_t bpp,
                                                      uint8_t* out) {
    // Out-parameters, not return values: a 32-byte vector returned without AVX changes the
    // ABI (GCC's -Wpsabi), though all of it is inlined.
    auto load = [](I16x16& to, const uint8_t* p) {
        U8x16 v;
        std::memcpy(&v, p, sizeof v);
        to = __builtin_convertvector(v, I16x16);
    };
    auto abs16 = [](I16x16& x) {
        const I16x16 sign = x >> 15;
        x = (x ^ sign) - sign;
    };
    *out++ = 4;  // Paeth
    const size_t head = std::min(bpp, n);
    for (size_t i = 0; i < head; ++i) out[i] = paeth1(0, up[i], 0, cur[i]);
    size_t i = head;
    for (; i + 16 <= n; i += 16) {
        I16x16 a, b, c, x;
        load(a, cur + i - bpp), load(b, up + i), load(c, up + i - bpp), load(x, cur + i);
        I16x16 pa = b - c, pb = a - c, pc = a + b - c - c;
        abs16(pa), abs16(pb), abs16(pc);
        const I16x16 use_a = (pa <= pb) & (pa <= pc);
        const I16x16 use_b = ~use_a & (pb <= pc);
        const U8x16 r = __builtin_convertvector(x - ((a & use_a) | (b & use_b) | (c & ~(use_a | use_b))), U8x16);
        std::memcpy(out + i, &r, sizeof r);
    }
    for (; i < n; ++i) out[i] = paeth1(cur[i - bpp], up[i], up[i - bpp], cur[i]);
}

void paeth_row_baseline(const uint8_t* cur, const uint8_t* up, size_t n, size_t bpp, uint8_t* out) {
    paeth_body(cur, up, n, bpp, out);
}

#if defined(__x86_64__)
__attribute__((target("avx2"))) void paeth_row_avx2(const uint8_t* cur, const uint8_t* up, size_t n, size_t bpp,
                                                    uint8_t* out) {
    paeth_body(cur, up, n, bpp, out);
}
#endif

using PaethRow = void (*)(const uint8_t*, const uint8_t*, size_t, size_t, uint8_t*);

void paeth_row(const uint8_t* cur, const uint8_t* up, size_t n, size_t bpp, uint8_t* out) {
#if defined(__x86_64__)
    static const PaethRow row = __builtin_cpu_supports("avx2") ? &paeth_row_avx2 : &paeth_row_baseline;
#else
    static const PaethRow row = &paeth_row_baseline;
#endif
    row(cur, up, n, bpp, out);
}

void put_be32(std::vector<unsigned char>& out, uint32_t v) {
    const unsigned char b[4] = {static_cast<unsigned char>(v >> 24), static_cast<unsigned char>(v >> 16),
                                static_cast<unsigned char>(v >> 8), static_cast<unsigned char>(v)};
    out.insert(out.end(), b, b + 4);
}

// One chunk (PNG spec 5.3): length, type, data, and the CRC-32 of type and data (ISO 3309, the
// one zlib and libdeflate compute).
void put_chunk(std::vector<unsigned char>& out, const char (&type)[5], const unsigned char* data, size_t n) {
    put_be32(out, static_cast<uint32_t>(n));
    const size_t from = out.size();
    out.insert(out.end(), type, type + 4);
    if (n) out.insert(out.end(), data, data + n);
    put_be32(out, libdeflate_crc32(0, out.data() + from, n + 4));
}

}  // namespace

bool write(const void* samples, int width, int height, int channels, int bit_depth, std::vector<unsigned char>& bytes,
           std::string& error) {
    // PNG spec 11.2.2's colour types: greyscale 0, greyscale with alpha 4, truecolour 2, with alpha 6.
    static constexpr unsigned char kColorType[] = {0, 0, 4, 2, 6};
    if (width <= 0 || height <= 0 || channels < 1 || channels > 4 || (bit_depth != 8 && bit_depth != 16)) {
        error = "PNG cannot hold a " + std::to_string(width) + "x" + std::to_string(height) + " image of " +
                std::to_string(channels) + " channels at " + std::to_string(bit_depth) + " bits";
        return false;
    }
    const size_t bpp = static_cast<size_t>(channels) * static_cast<size_t>(bit_depth / 8);
    const size_t row_bytes = static_cast<size_t>(width) * bpp;
    // Every row filtered, each behind its filter-type byte: what the zlib stream holds. This and
    // the compressed buffer are allocated for overwrite: zeroing them first was 2 % of an ingest.
    const size_t filtered_size = (row_bytes + 1) * static_cast<size_t>(height);
    auto filtered = std::make_unique_for_overwrite<uint8_t[]>(filtered_size);
    const std::vector<uint8_t> zeros(row_bytes, 0);
    if (bit_depth == 8) {
        const auto* rows = static_cast<const uint8_t*>(samples);
        for (size_t y = 0; y < static_cast<size_t>(height); ++y)
            paeth_row(rows + y * row_bytes, y ? rows + (y - 1) * row_bytes : zeros.data(), row_bytes, bpp,
                      filtered.get() + y * (row_bytes + 1));
    } else {  // PNG's 16-bit samples are big-endian: each row is swapped into one of two buffers
        const auto* rows = static_cast<const uint16_t*>(samples);
        std::vector<uint8_t> big[2] = {std::vector<uint8_t>(row_bytes), std::vector<uint8_t>(row_bytes)};
        const size_t per_row = row_bytes / 2;
        for (size_t y = 0; y < static_cast<size_t>(height); ++y) {
            uint8_t* cur = big[y & 1].data();
            for (size_t i = 0; i < per_row; ++i) {
                const uint16_t v = rows[y * per_row + i];
                cur[2 * i] = static_cast<uint8_t>(v >> 8);
                cur[2 * i + 1] = static_cast<uint8_t>(v & 0xFF);
            }
            paeth_row(cur, y ? big[(y - 1) & 1].data() : zeros.data(), row_bytes, bpp,
                      filtered.get() + y * (row_bytes + 1));
        }
    }

    const std::unique_ptr<libdeflate_compressor, decltype(&libdeflate_free_compressor)> deflater(
        libdeflate_alloc_compressor(1), &libdeflate_free_compressor);
    if (!deflater) {
        error = "encoding png: out of memory for the compressor";
        return false;
    }
    const size_t z_bound = libdeflate_zlib_compress_bound(deflater.get(), filtered_size);
    const auto z = std::make_unique_for_overwrite<unsigned char[]>(z_bound);
    const size_t z_bytes = libdeflate_zlib_compress(deflater.get(), filtered.get(), filtered_size, z.get(), z_bound);
    if (z_bytes == 0) {  // cannot happen with the bound's room; said rather than assumed
        error = "encoding png: the compressed pixels did not fit their bound";
        return false;
    }
    filtered.reset();

    const size_t chunks = (z_bytes + kIdatBytes - 1) / kIdatBytes;
    static constexpr char kSoftware[] = "Software\0matforge";  // tEXt: keyword, NUL, text (no NUL at the end)
    bytes.clear();
    // Signature, IHDR, tEXt (Software=matforge), the IDAT chunks and IEND, exactly.
    bytes.reserve(8 + 25 + (12 + sizeof kSoftware - 1) + z_bytes + 12 * chunks + 12);
    bytes.insert(bytes.end(), kSignature, kSignature + 8);
    std::vector<unsigned char> ihdr;  // PNG spec 11.2.2: no compression, filter or interlace method but 0
    put_be32(ihdr, static_cast<uint32_t>(width));
    put_be32(ihdr, static_cast<uint32_t>(height));
    ihdr.insert(ihdr.end(), {static_cast<unsigned char>(bit_depth), kColorType[channels], 0, 0, 0});
    put_chunk(bytes, "IHDR", ihdr.data(), ihdr.size());
    put_chunk(bytes, "tEXt", reinterpret_cast<const unsigned char*>(kSoftware), sizeof kSoftware - 1);
    for (size_t at = 0; at < z_bytes; at += kIdatBytes)
        put_chunk(bytes, "IDAT", z.get() + at, std::min(kIdatBytes, z_bytes - at));
    put_chunk(bytes, "IEND", nullptr, 0);
    return true;
}

}  // namespace mf::png
