#include "image/png_unfilter.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>

// The vector forms: x86-64, whose baseline is SSE2 (64-bit moves between registers included).
#if defined(__x86_64__) && defined(__SSE2__)
#define MF_PNG_UNFILTER_SSE2 1
#include <emmintrin.h>
#endif

namespace mf::png {
// Named, as the library is built as one unity file: png_reader.cpp and png_writer.cpp have
// Paeth helpers of their own in their anonymous namespaces.
namespace unfilter_impl {
namespace {

// ---- Byte at a time: every machine, and the reference the vector forms are held to. ----

// Every form reads the filtered row `in` ahead of where it writes the reconstructed `out`
// (unfilter_row's contract: out is in, or lies before it).

// Reverses the Paeth filter (PNG spec 9.4) of one row (`up`: the row above, reconstructed, or
// zeros). Each pixel depends on the one before it; its channels are independent chains, which
// the processor overlaps.
template <int Bpp>
void unpaeth(const uint8_t* in, uint8_t* out, const uint8_t* up, size_t width) {
    int a[Bpp] = {}, c[Bpp] = {};
    for (size_t x = 0; x < width; ++x) {
        const uint8_t* above = up + x * Bpp;
        for (int k = 0; k < Bpp; ++k) {
            const int b = above[k];
            const int pa = std::abs(b - c[k]), pb = std::abs(a[k] - c[k]), pc = std::abs(a[k] + b - 2 * c[k]);
            const int by_b = pb <= pc ? b : c[k];
            const int pred = (pa <= pb && pa <= pc) ? a[k] : by_b;
            a[k] = (in[x * Bpp + k] + pred) & 0xFF;
            out[x * Bpp + k] = static_cast<uint8_t>(a[k]);
            c[k] = b;
        }
    }
}

bool unfilter_scalar(int type, const uint8_t* in, uint8_t* out, const uint8_t* up, size_t width, int bpp) {
    const size_t n = width * static_cast<size_t>(bpp);
    const auto k = static_cast<size_t>(bpp);
    switch (type) {
        case 0:
            if (out != in) std::memmove(out, in, n);
            return true;
        case 1:
            for (size_t i = 0; i < n; ++i) out[i] = static_cast<uint8_t>(in[i] + (i >= k ? out[i - k] : 0));
            return true;
        case 2:
            for (size_t i = 0; i < n; ++i) out[i] = static_cast<uint8_t>(in[i] + up[i]);
            return true;
        case 3:  // the first pixel has no left neighbour (0): its own loop, none of it in the chain
            for (size_t i = 0; i < std::min(k, n); ++i) out[i] = static_cast<uint8_t>(in[i] + up[i] / 2);
            for (size_t i = k; i < n; ++i) out[i] = static_cast<uint8_t>(in[i] + (out[i - k] + up[i]) / 2);
            return true;
        case 4:
            switch (bpp) {  // bytes per pixel: 1-4 channels of 8 bits, or 1-4 of 16
                case 1: unpaeth<1>(in, out, up, width); return true;
                case 2: unpaeth<2>(in, out, up, width); return true;
                case 3: unpaeth<3>(in, out, up, width); return true;
                case 4: unpaeth<4>(in, out, up, width); return true;
                case 6: unpaeth<6>(in, out, up, width); return true;
                default: unpaeth<8>(in, out, up, width); return true;
            }
        default: return false;
    }
}

#if defined(MF_PNG_UNFILTER_SSE2)
// ---- SSE2 (x86-64's baseline) ----
//
// Sub, Average and Paeth make each pixel from the one before it: that chain sets their pace, so
// a step takes a whole pixel, its channels side by side in one register, and whatever does not
// depend on the pixel to the left is taken out of the chain. Lanes beyond the pixel's are
// computed and never stored. The byte comparisons and selects are GCC's vector operations, so
// that the SSE4.1 copy of Paeth (target attribute below) selects with pblendvb.

using V8 = int8_t __attribute__((vector_size(16)));  // signed: bytes offset by 128 compare in order
inline V8 v8(__m128i x) { return reinterpret_cast<V8>(x); }
inline __m128i m128(V8 x) { return reinterpret_cast<__m128i>(x); }
// Sums and differences mod 256 (a signed vector's + would overflow: undefined, and UBSan says so).
inline V8 add(V8 x, V8 y) { return v8(_mm_add_epi8(m128(x), m128(y))); }
inline V8 sub(V8 x, V8 y) { return v8(_mm_sub_epi8(m128(x), m128(y))); }
inline V8 k80() { return v8(_mm_set1_epi8(static_cast<char>(0x80))); }
inline __m128i loadu(const uint8_t* p) { return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p)); }
inline void storeu(uint8_t* p, __m128i v) { _mm_storeu_si128(reinterpret_cast<__m128i*>(p), v); }

// A pixel's Bpp bytes into the low lanes, and back, never touching a byte beyond it. 3 and 6
// bytes are put together from whole loads and stores: GCC passes a memcpy of 3 bytes through the
// stack, where reading the word back stalls on its narrower stores (5x slower a pixel).
template <int Bpp>
inline V8 load_px(const uint8_t* p) {
    if constexpr (Bpp == 1) return v8(_mm_cvtsi32_si128(p[0]));
    if constexpr (Bpp == 2 || Bpp == 3) {
        uint16_t v;
        std::memcpy(&v, p, 2);
        if constexpr (Bpp == 2) return v8(_mm_cvtsi32_si128(v));
        else return v8(_mm_cvtsi32_si128(static_cast<int>(v | (uint32_t{p[2]} << 16))));
    }
    if constexpr (Bpp == 4 || Bpp == 6) {
        uint32_t v;
        std::memcpy(&v, p, 4);
        if constexpr (Bpp == 4) return v8(_mm_cvtsi32_si128(static_cast<int>(v)));
        uint16_t w;
        std::memcpy(&w, p + 4, 2);
        return v8(_mm_cvtsi64_si128(static_cast<long long>(v | (uint64_t{w} << 32))));
    }
    if constexpr (Bpp == 8) return v8(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(p)));
}
template <int Bpp>
inline void store_px(uint8_t* p, V8 x) {
    if constexpr (Bpp <= 4) {
        const auto v = static_cast<uint32_t>(_mm_cvtsi128_si32(m128(x)));
        if constexpr (Bpp == 1) p[0] = static_cast<uint8_t>(v);
        if constexpr (Bpp == 2 || Bpp == 3) {
            const auto w = static_cast<uint16_t>(v);
            std::memcpy(p, &w, 2);
        }
        if constexpr (Bpp == 3) p[2] = static_cast<uint8_t>(v >> 16);
        if constexpr (Bpp == 4) std::memcpy(p, &v, 4);
    } else if constexpr (Bpp == 6) {
        const auto v = static_cast<uint64_t>(_mm_cvtsi128_si64(m128(x)));
        const auto lo = static_cast<uint32_t>(v);
        const auto hi = static_cast<uint16_t>(v >> 32);
        std::memcpy(p, &lo, 4);
        std::memcpy(p + 4, &hi, 2);
    } else {
        _mm_storel_epi64(reinterpret_cast<__m128i*>(p), m128(x));
    }
}
// The same, wide: 4 bytes for pixels of 3, 8 for pixels of 6 (one instruction each), reading or
// writing the next pixel's first bytes; exact for the other sizes.
template <int Bpp>
inline V8 load_wide(const uint8_t* p) {
    if constexpr (Bpp == 3) {
        uint32_t v;
        std::memcpy(&v, p, 4);
        return v8(_mm_cvtsi32_si128(static_cast<int>(v)));
    } else if constexpr (Bpp == 6) {
        return v8(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(p)));
    } else {
        return load_px<Bpp>(p);
    }
}
template <int Bpp>
inline void store_wide(uint8_t* p, V8 x) {
    if constexpr (Bpp == 3) {
        const auto v = static_cast<uint32_t>(_mm_cvtsi128_si32(m128(x)));
        std::memcpy(p, &v, 4);
    } else if constexpr (Bpp == 6) {
        _mm_storel_epi64(reinterpret_cast<__m128i*>(p), m128(x));
    } else {
        store_px<Bpp>(p, x);
    }
}

// Runs `step(filtered, i, wide)` over the pixels of a row of n bytes in order; it returns pixel
// i made (`wide`: the bytes after the pixel may be read, it is not the row's last). A pixel's
// filtered bytes are read wide before the pixel to its left is stored wide over their start.
template <int Bpp, class Step>
__attribute__((always_inline)) inline void each_pixel(const uint8_t* in, uint8_t* out, size_t n, Step step) {
    V8 filtered = Bpp < n ? load_wide<Bpp>(in) : load_px<Bpp>(in);
    for (size_t i = 0;; i += Bpp) {
        const bool wide = i + Bpp < n;
        const V8 made = step(filtered, i, wide);
        if (!wide) return store_px<Bpp>(out + i, made);
        filtered = i + 2 * Bpp < n ? load_wide<Bpp>(in + i + Bpp) : load_px<Bpp>(in + i + Bpp);
        store_wide<Bpp>(out + i, made);
    }
}

void up_sse2(const uint8_t* in, uint8_t* out, const uint8_t* up, size_t n) {
    size_t i = 0;
    for (; i + 16 <= n; i += 16) storeu(out + i, _mm_add_epi8(loadu(in + i), loadu(up + i)));
    for (; i < n; ++i) out[i] = static_cast<uint8_t>(in[i] + up[i]);
}

// The last pixel of `x` in every pixel's lanes (Bpp divides 16).
template <int Bpp>
inline __m128i last_pixel_everywhere(__m128i x) {
    if constexpr (Bpp == 8) return _mm_unpackhi_epi64(x, x);
    if constexpr (Bpp == 4) return _mm_shuffle_epi32(x, 0xFF);
    if constexpr (Bpp == 2) {
        const __m128i w = _mm_shufflehi_epi16(x, 0xFF);
        return _mm_unpackhi_epi64(w, w);
    }
    if constexpr (Bpp == 1) {
        const __m128i w = _mm_shufflehi_epi16(_mm_unpackhi_epi8(x, x), 0xFF);
        return _mm_unpackhi_epi64(w, w);
    }
}

// Sub: each byte plus the one Bpp before it, reconstructed. Where pixels tile 16 bytes, a
// block's running sums take log2(16 / Bpp) shift-adds off the chain, which is then one add and
// a broadcast per 16 bytes; pixels of 3 and 6 bytes take one add a pixel.
template <int Bpp>
void sub_sse2(const uint8_t* in, uint8_t* out, size_t n) {
    if constexpr (16 % Bpp == 0) {
        __m128i carry = _mm_setzero_si128();  // the last pixel made, in every pixel's lanes
        size_t i = 0;
        for (; i + 16 <= n; i += 16) {
            __m128i x = loadu(in + i);
            x = _mm_add_epi8(x, _mm_slli_si128(x, Bpp));
            if constexpr (Bpp <= 4) x = _mm_add_epi8(x, _mm_slli_si128(x, 2 * Bpp));
            if constexpr (Bpp <= 2) x = _mm_add_epi8(x, _mm_slli_si128(x, 4 * Bpp));
            if constexpr (Bpp == 1) x = _mm_add_epi8(x, _mm_slli_si128(x, 8));
            x = _mm_add_epi8(x, carry);
            storeu(out + i, x);
            carry = last_pixel_everywhere<Bpp>(x);
        }
        for (; i < n; ++i) out[i] = static_cast<uint8_t>(in[i] + (i >= Bpp ? out[i - Bpp] : 0));
    } else {
        V8 a{};
        each_pixel<Bpp>(in, out, n, [&a](V8 filtered, size_t, bool) { return a = add(a, filtered); });
    }
}

// Average: each byte plus floor((left + above) / 2). Held inverted (255 - v): floor((a + b) / 2)
// is 255 - pavgb(255 - a, 255 - b) (pavgb rounds up), so the chain is a pavgb and a subtract.
template <int Bpp>
void avg_sse2(const uint8_t* in, uint8_t* out, const uint8_t* up, size_t n) {
    const V8 ones = v8(_mm_set1_epi8(-1));
    V8 na = ones;  // the first pixel's left neighbour: 0
    each_pixel<Bpp>(in, out, n, [&](V8 filtered, size_t i, bool wide) {
        const V8 nb = (wide ? load_wide<Bpp>(up + i) : load_px<Bpp>(up + i)) ^ ones;
        na = sub(v8(_mm_avg_epu8(m128(na), m128(nb))), filtered);
        return na ^ ones;
    });
}

// Paeth picks a (left), b (above) or c (upper left), whichever is nearest p = a + b - c, ties to
// a, then b (PNG spec 9.4). |p - a| = |b - c|, |p - b| = |a - c|, |p - c| = |(a - c) + (b - c)|,
// so for given b and c the choice is a function of a alone:
//   lo < a < hi: max(b, c) where a > mid, else min(b, c); otherwise a;
// with lo, hi = min, max(b, 3c - 2b) (lo = hi = b where b = c: always a), and mid =
// floor((3c - b - 1) / 2) where b > c (b wins from 2a >= 3c - b), floor((3c - b) / 2) where
// b < c (b wins up to 2a <= 3c - b). So everything but three compares and two selects comes from
// the row above and the filtered byte, 16 bytes at a time, ahead of the chain ("planes"):
//   lo:    L = clamp(lo + 1, 0, 255); "lo < a < hi" is the unsigned (a - L) mod 256 < W, with
//   width: W = max(min(hi, 256) - max(lo + 1, 0), 0), at most 255;
//   mid:   clamp(mid, 0, 255); where mid < 0 (a > mid always) min(b, c) is replaced by max(b, c);
//   big, small: max(b, c) and min(b, c), plus the filtered byte (each candidate's sum ready);
//   raw:   the filtered bytes, read before the pixels to their left are stored over them.
// Bytes are held offset by 128 (x ^ 0x80) where SSE2's signed compares order them. In 8-bit
// terms, with e = max - min: where b >= c, L = min + 1 - 2e, W = max - L (both at least 0),
// mid = min - e / 2 - 1 (negative where min <= e / 2); where b < c, L = min + 1,
// W = min(max + 2e - 1, 255) - min, mid = min(max + e / 2, 255); all in saturating byte arithmetic.
// PngUnfilter.PaethTakesEveryTripleAsTheSpecDoes checks all 2^24 (a, b, c).
constexpr size_t kBlock = 48;  // bytes of planes at a time: whole pixels of every size, 3 vectors

struct PaethBlock {
    // + 16: a pixel's plane bytes are read 4 or 8 at a time (its lanes, then unused ones).
    alignas(16) uint8_t lo[kBlock + 16], width[kBlock + 16], mid[kBlock + 16], big[kBlock + 16], small[kBlock + 16],
        raw[kBlock + 16];
};

__attribute__((always_inline)) inline void paeth_planes16(__m128i b, __m128i c, __m128i raw, PaethBlock& pb,
                                                          size_t at) {
    const __m128i one = _mm_set1_epi8(1);
    const __m128i mn = _mm_min_epu8(b, c), mx = _mm_max_epu8(b, c);
    const __m128i e = _mm_sub_epi8(mx, mn), e2 = _mm_adds_epu8(e, e);
    const __m128i half_e = _mm_and_si128(_mm_srli_epi16(e, 1), _mm_set1_epi8(0x7F));
    const V8 b_ge_c = v8(_mm_cmpeq_epi8(mx, b));
    const __m128i lo_lt = _mm_adds_epu8(mn, one), lo_ge = _mm_subs_epu8(lo_lt, e2);
    const __m128i width_ge = _mm_subs_epu8(mx, lo_ge);
    const __m128i width_lt = _mm_sub_epi8(_mm_adds_epu8(_mm_subs_epu8(mx, one), e2), mn);
    const __m128i mn_less_half = _mm_subs_epu8(mn, half_e);  // 0 where mid < 0 (b >= c)
    const __m128i mid_ge = _mm_subs_epu8(mn_less_half, one), mid_lt = _mm_adds_epu8(mx, half_e);
    const V8 always_big = b_ge_c & v8(_mm_cmpeq_epi8(mn_less_half, _mm_setzero_si128()));
    storeu(pb.lo + at, m128(b_ge_c ? v8(lo_ge) : v8(lo_lt)));
    storeu(pb.width + at, m128((b_ge_c ? v8(width_ge) : v8(width_lt)) ^ k80()));
    storeu(pb.mid + at, m128((b_ge_c ? v8(mid_ge) : v8(mid_lt)) ^ k80()));
    storeu(pb.big + at, m128(add(v8(mx) ^ k80(), v8(raw))));
    storeu(pb.small + at, m128(add((always_big ? v8(mx) : v8(mn)) ^ k80(), v8(raw))));
    storeu(pb.raw + at, raw);
}

// The planes of the row's bytes [blk, blk + kBlock); bytes left of the row or beyond its end
// come from a zero-padded copy (the spec's zeros left of the row), never read past it.
template <int Bpp>
__attribute__((always_inline)) inline void paeth_planes(const uint8_t* in, const uint8_t* up, size_t n, size_t blk,
                                                        PaethBlock& pb) {
    for (size_t j = blk; j < std::min(n, blk + kBlock); j += 16) {
        if (j >= Bpp && j + 16 <= n) {
            paeth_planes16(loadu(up + j), loadu(up + j - Bpp), loadu(in + j), pb, j - blk);
        } else {
            uint8_t above[16 + Bpp] = {}, filtered[16] = {};  // above[k] = up[j - Bpp + k]
            const size_t from = j >= Bpp ? j - Bpp : 0, to = std::min(n, j + 16);
            std::memcpy(above + (from + Bpp - j), up + from, to - from);
            std::memcpy(filtered, in + j, to - j);
            paeth_planes16(loadu(above + Bpp), loadu(above), loadu(filtered), pb, j - blk);
        }
    }
}

// A pixel's plane bytes (4 or 8 at a time; the lanes beyond Bpp unused).
template <int Bpp>
inline V8 plane(const uint8_t* p) {
    if constexpr (Bpp <= 4) {
        uint32_t v;
        std::memcpy(&v, p, 4);
        return v8(_mm_cvtsi32_si128(static_cast<int>(v)));
    } else {
        return v8(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(p)));
    }
}

// The chain: 3 instructions deep with SSE4.1 (subtract, compare, blend). The planes of the next
// block are made before this block's pixels are stored (its first bytes may be stored over).
template <int Bpp>
__attribute__((always_inline)) inline void paeth_body(const uint8_t* in, uint8_t* out, const uint8_t* up, size_t n) {
    PaethBlock pb[2];
    for (PaethBlock& b : pb)
        for (uint8_t* p : {b.lo, b.width, b.mid, b.big, b.small, b.raw}) std::memset(p + kBlock, 0, 16);
    V8 a = k80();  // left of the row: 0
    paeth_planes<Bpp>(in, up, n, 0, pb[0]);
    for (size_t blk = 0, k = 0; blk < n; blk += kBlock, ++k) {
        if (blk + kBlock < n) paeth_planes<Bpp>(in, up, n, blk + kBlock, pb[(k + 1) & 1]);
        const PaethBlock& p = pb[k & 1];
        for (size_t i = blk; i < std::min(n, blk + kBlock); i += Bpp) {
            const size_t o = i - blk;
            const V8 inside = plane<Bpp>(p.width + o) > sub(a, plane<Bpp>(p.lo + o));
            const V8 b_or_c = a > plane<Bpp>(p.mid + o) ? plane<Bpp>(p.big + o) : plane<Bpp>(p.small + o);
            a = inside ? b_or_c : add(a, plane<Bpp>(p.raw + o));
            if (i + Bpp < n) store_wide<Bpp>(out + i, a ^ k80());
            else store_px<Bpp>(out + i, a ^ k80());
        }
    }
}

template <int Bpp>
void paeth_sse2(const uint8_t* in, uint8_t* out, const uint8_t* up, size_t n) {
    paeth_body<Bpp>(in, out, up, n);
}
template <int Bpp>
__attribute__((target("sse4.1"))) void paeth_sse41(const uint8_t* in, uint8_t* out, const uint8_t* up, size_t n) {
    paeth_body<Bpp>(in, out, up, n);
}

template <int Bpp>
bool unfilter_vector(int type, const uint8_t* in, uint8_t* out, const uint8_t* up, size_t n, bool sse41) {
    switch (type) {
        case 0:
            if (out != in) std::memmove(out, in, n);
            return true;
        case 1: sub_sse2<Bpp>(in, out, n); return true;
        case 2: up_sse2(in, out, up, n); return true;
        case 3: avg_sse2<Bpp>(in, out, up, n); return true;
        case 4: sse41 ? paeth_sse41<Bpp>(in, out, up, n) : paeth_sse2<Bpp>(in, out, up, n); return true;
        default: return false;
    }
}

#endif  // MF_PNG_UNFILTER_SSE2

}  // namespace
}  // namespace unfilter_impl

bool can_unfilter_with(UnfilterIsa isa) {
#if defined(MF_PNG_UNFILTER_SSE2)
    static const bool sse41 = __builtin_cpu_supports("sse4.1");
    return isa != UnfilterIsa::sse41 || sse41;
#else
    return isa == UnfilterIsa::scalar;
#endif
}

UnfilterIsa best_unfilter_isa() {
    static const UnfilterIsa best = can_unfilter_with(UnfilterIsa::sse41)  ? UnfilterIsa::sse41
                                    : can_unfilter_with(UnfilterIsa::sse2) ? UnfilterIsa::sse2
                                                                           : UnfilterIsa::scalar;
    return best;
}

bool unfilter_row(int type, const uint8_t* in, uint8_t* out, const uint8_t* up, size_t width, int bpp,
                  UnfilterIsa isa) {
    if (type < 0 || type > 4) return false;
    if (width == 0) return true;
#if !defined(MF_PNG_UNFILTER_SSE2)
    (void)isa;  // every form is the scalar one here
#else
    if (isa != UnfilterIsa::scalar) {
        using unfilter_impl::unfilter_vector;
        const size_t n = width * static_cast<size_t>(bpp);
        const bool sse41 = isa == UnfilterIsa::sse41;
        switch (bpp) {
            case 1: return unfilter_vector<1>(type, in, out, up, n, sse41);
            case 2: return unfilter_vector<2>(type, in, out, up, n, sse41);
            case 3: return unfilter_vector<3>(type, in, out, up, n, sse41);
            case 4: return unfilter_vector<4>(type, in, out, up, n, sse41);
            case 6: return unfilter_vector<6>(type, in, out, up, n, sse41);
            case 8: return unfilter_vector<8>(type, in, out, up, n, sse41);
            default: break;
        }
    }
#endif
    return unfilter_impl::unfilter_scalar(type, in, out, up, width, bpp);
}

}  // namespace mf::png
