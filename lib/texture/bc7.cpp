// BC7 blocks: the format's tables, the decoder, and an encoder that searches what the best open
// encoders search (bc7e, Compressonator, DirectXTex): every subset is fitted on its principal
// axis, refined by least squares on its indices, its endpoints quantized under each p-bit choice
// and, in near-flat blocks, nudged a step at a time; the 64 partitions of the 2- and 3-subset
// modes are ranked by their subsets' scatter off and along their lines (from moment sums, four
// partitions per vector) and only the best few are fitted; the separate-alpha modes try each
// channel rotation. bc7.hpp states the contract.
#include "texture/bc7.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>

namespace mf::texture::bc7 {
namespace {

// ---------------------------------------------------------------------------------------------
// The format (KDFS 1.3 "BPTC": tables of partitions, anchor indices and interpolation weights)

// 2-subset partitions: bit t is texel t's subset.
constexpr std::array<uint16_t, 64> kPartition2 = {0xCCCC, 0x8888, 0xEEEE, 0xECC8, 0xC880, 0xFEEC, 0xFEC8, 0xEC80,
                                                  0xC800, 0xFFEC, 0xFE80, 0xE800, 0xFFE8, 0xFF00, 0xFFF0, 0xF000,
                                                  0xF710, 0x008E, 0x7100, 0x08CE, 0x008C, 0x7310, 0x3100, 0x8CCE,
                                                  0x088C, 0x3110, 0x6666, 0x366C, 0x17E8, 0x0FF0, 0x718E, 0x399C,
                                                  0xAAAA, 0xF0F0, 0x5A5A, 0x33CC, 0x3C3C, 0x55AA, 0x9696, 0xA55A,
                                                  0x73CE, 0x13C8, 0x324C, 0x3BDC, 0x6996, 0xC33C, 0x9966, 0x0660,
                                                  0x0272, 0x04E4, 0x4E40, 0x2720, 0xC936, 0x936C, 0x39C6, 0x639C,
                                                  0x9336, 0x9CC6, 0x817E, 0xE718, 0xCCF0, 0x0FCC, 0x7744, 0xEE22};
// 3-subset partitions: bits 2t, 2t+1 are texel t's subset.
constexpr std::array<uint32_t, 64> kPartition3 = {
    0xAA685050, 0x6A5A5040, 0x5A5A4200, 0x5450A0A8, 0xA5A50000, 0xA0A05050, 0x5555A0A0, 0x5A5A5050,
    0xAA550000, 0xAA555500, 0xAAAA5500, 0x90909090, 0x94949494, 0xA4A4A4A4, 0xA9A59450, 0x2A0A4250,
    0xA5945040, 0x0A425054, 0xA5A5A500, 0x55A0A0A0, 0xA8A85454, 0x6A6A4040, 0xA4A45000, 0x1A1A0500,
    0x0050A4A4, 0xAAA59090, 0x14696914, 0x69691400, 0xA08585A0, 0xAA821414, 0x50A4A450, 0x6A5A0200,
    0xA9A58000, 0x5090A0A8, 0xA8A09050, 0x24242424, 0x00AA5500, 0x24924924, 0x24499224, 0x50A50A50,
    0x500AA550, 0xAAAA4444, 0x66660000, 0xA5A0A5A0, 0x50A050A0, 0x69286928, 0x44AAAA44, 0x66666600,
    0xAA444444, 0x54A854A8, 0x95809580, 0x96969600, 0xA85454A8, 0x80959580, 0xAA141414, 0x96960000,
    0xAAAA1414, 0xA05050A0, 0xA0A5A5A0, 0x96000000, 0x40804080, 0xA9A8A9A8, 0xAAAAAA44, 0x2A4A5254};
// The anchor texel (its index has one bit less) of subset 1 of a 2-subset partition, and of
// subsets 1 and 2 of a 3-subset one; subset 0's is texel 0.
constexpr std::array<uint8_t, 64> kAnchor2 = {15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15,
                                              15, 2,  8,  2,  2,  8,  8,  15, 2,  8,  2,  2,  8,  8,  2,  2,
                                              15, 15, 6,  8,  2,  8,  15, 15, 2,  8,  2,  2,  2,  15, 15, 6,
                                              6,  2,  6,  8,  15, 15, 2,  2,  15, 15, 15, 15, 15, 2,  2,  15};
constexpr std::array<uint8_t, 64> kAnchor3a = {3, 3,  15, 15, 8, 3,  15, 15, 8,  8,  6,  6,  6,  5,  3,  3,
                                               3, 3,  8,  15, 3, 3,  6,  10, 5,  8,  8,  6,  8,  5,  15, 15,
                                               8, 15, 3,  5,  6, 10, 8,  15, 15, 3,  15, 5,  15, 15, 15, 15,
                                               3, 15, 5,  5,  5, 8,  5,  10, 5,  10, 8,  13, 15, 12, 3,  3};
constexpr std::array<uint8_t, 64> kAnchor3b = {15, 8, 8,  3,  15, 15, 3,  8,  15, 15, 15, 15, 15, 15, 15, 8,
                                               15, 8, 15, 3,  15, 8,  15, 8,  3,  15, 6,  10, 15, 15, 10, 8,
                                               15, 3, 15, 10, 10, 8,  9,  10, 6,  15, 8,  15, 3,  6,  6,  8,
                                               15, 3, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 3,  15, 15, 8};
// Interpolation weights (of 64) for 2-, 3- and 4-bit indices; w[K-1-i] = 64 - w[i], so swapping a
// subset's endpoints and complementing its indices decodes to the same texels.
constexpr std::array<uint8_t, 4> kWeights2 = {0, 21, 43, 64};
constexpr std::array<uint8_t, 8> kWeights3 = {0, 9, 18, 27, 37, 46, 55, 64};
constexpr std::array<uint8_t, 16> kWeights4 = {0, 4, 9, 13, 17, 21, 26, 30, 34, 38, 43, 47, 51, 55, 60, 64};

const uint8_t* weights(int index_bits) {
    return index_bits == 2 ? kWeights2.data() : index_bits == 3 ? kWeights3.data() : kWeights4.data();
}

enum class PBits : uint8_t { none, shared, per_endpoint };

struct ModeInfo {
    int subsets, partition_bits, rotation_bits, isb_bits, color_bits, alpha_bits;
    PBits pbits;
    int index_bits, index2_bits;
};
constexpr std::array<ModeInfo, 8> kModes = {{
    {3, 4, 0, 0, 4, 0, PBits::per_endpoint, 3, 0},  // 0: 3 subsets, RGB 4+p, 3-bit indices
    {2, 6, 0, 0, 6, 0, PBits::shared, 3, 0},        // 1: 2 subsets, RGB 6+shared p
    {3, 6, 0, 0, 5, 0, PBits::none, 2, 0},          // 2: 3 subsets, RGB 5, 2-bit indices
    {2, 6, 0, 0, 7, 0, PBits::per_endpoint, 2, 0},  // 3: 2 subsets, RGB 7+p, 2-bit indices
    {1, 0, 2, 1, 5, 6, PBits::none, 2, 3},          // 4: RGB 5 and A 6, index sets of 2 and 3 bits
    {1, 0, 2, 0, 7, 8, PBits::none, 2, 2},          // 5: RGB 7 and A 8, two 2-bit index sets
    {1, 0, 0, 0, 7, 7, PBits::per_endpoint, 4, 0},  // 6: RGBA 7+p, 4-bit indices
    {2, 6, 0, 0, 5, 5, PBits::per_endpoint, 2, 0},  // 7: 2 subsets, RGBA 5+p
}};

int subset_of(int subsets, int partition, int texel) {
    if (subsets == 1) return 0;
    if (subsets == 2) return (kPartition2[static_cast<size_t>(partition)] >> texel) & 1;
    return static_cast<int>((kPartition3[static_cast<size_t>(partition)] >> (2 * texel)) & 3u);
}

int anchor_of(int subsets, int partition, int subset) {
    if (subset == 0) return 0;
    const auto p = static_cast<size_t>(partition);
    if (subsets == 2) return kAnchor2[p];
    return subset == 1 ? kAnchor3a[p] : kAnchor3b[p];
}

bool is_anchor(int subsets, int partition, int texel) {
    for (int s = 0; s < subsets; ++s)
        if (anchor_of(subsets, partition, s) == texel) return true;
    return false;
}

// An n-bit endpoint value (p-bit included) to 8 bits: the top bits repeated below.
int expand(int v, int n) {
    v <<= 8 - n;
    return v | (v >> n);
}

int interpolate(int e0, int e1, int w) { return ((64 - w) * e0 + w * e1 + 32) >> 6; }

// Bits from the least significant up, into two 64-bit halves; `flush` stores the 16 bytes
// little-endian.
struct BitWriter {
    std::array<uint64_t, 2> word{};
    int pos = 0;
    void put(unsigned v, int n) {
        const uint64_t bits = v & ((1u << n) - 1u);
        const int at = pos & 63;
        word[static_cast<size_t>(pos >> 6)] |= bits << at;
        if (at + n > 64) word[1] |= bits >> (64 - at);
        pos += n;
    }
    void flush(uint8_t* out) const {
        for (size_t i = 0; i < 16; ++i) out[i] = static_cast<uint8_t>(word[i / 8] >> (8 * (i % 8)));
    }
};
struct BitReader {
    const uint8_t* in = nullptr;
    int pos = 0;
    int get(int n) {
        int v = 0;
        for (int i = 0; i < n; ++i, ++pos) v |= ((in[pos >> 3] >> (pos & 7)) & 1) << i;
        return v;
    }
};

// ---------------------------------------------------------------------------------------------
// Quantization: the stored value whose expansion is nearest each 8-bit code, per stored width
// (4..8 bits) and p-bit (0, 1, none).

struct QuantTable {
    // [bits - 4][p: 0, 1, 2 = none][code] -> stored value (8 stored bits come without a p-bit)
    std::array<std::array<std::array<uint8_t, 256>, 3>, 5> q{};
    QuantTable() {
        for (int bits = 4; bits <= 8; ++bits)
            for (int p = bits < 8 ? 0 : 2; p < 3; ++p)
                for (int v = 0; v < 256; ++v) {
                    int best = 0, best_d = 1 << 30;
                    for (int s = 0; s < (1 << bits); ++s) {
                        const int d = std::abs(decoded(bits, p, s) - v);
                        if (d < best_d) best = s, best_d = d;
                    }
                    q[static_cast<size_t>(bits - 4)][static_cast<size_t>(p)][static_cast<size_t>(v)] =
                        static_cast<uint8_t>(best);
                }
    }
    static int decoded(int bits, int p, int stored) {
        return p == 2 ? expand(stored, bits) : expand((stored << 1) | p, bits + 1);
    }
    int quantize(int bits, int p, int code) const {
        return q[static_cast<size_t>(bits - 4)][static_cast<size_t>(p)][static_cast<size_t>(code)];
    }
};
const QuantTable& quant() {
    static const QuantTable table;
    return table;
}

// ---------------------------------------------------------------------------------------------
// The encoder

// Four lanes of a vector (GCC's and Clang's vector extension: SSE on x86-64, NEON on ARM, plain
// code elsewhere): four texels in `assign`, four partitions in the ranking.
using Lanes = float __attribute__((vector_size(16)));
using IntLanes = int __attribute__((vector_size(16)));
using LaneMask = IntLanes;          // a comparison's result: -1 (true) or 0 in each lane
using Row = std::array<Lanes, 16>;  // one value of the 64 partitions

Lanes splat(float v) { return Lanes{v, v, v, v}; }
Lanes select(LaneMask m, Lanes a, Lanes b) {
    return reinterpret_cast<Lanes>((reinterpret_cast<LaneMask>(a) & m) | (reinterpret_cast<LaneMask>(b) & ~m));
}
IntLanes select(LaneMask m, IntLanes a, IntLanes b) { return (a & m) | (b & ~m); }

struct Source {
    std::array<std::array<int, 4>, 16> px{};
};

using Endpoints = std::array<std::array<int, 4>, 2>;    // decoded 8-bit endpoint values by channel
using FloatEnds = std::array<std::array<float, 4>, 2>;  // endpoints before quantization

// How one subset is stored: `bits` per channel, `pbits`, indices of `index_bits`. `opaque`:
// channel 3 is fitted on a block whose alpha is all 255 and is data, so its endpoints are 255
// (stored all ones with p-bit 1) and an opaque block stays opaque. `all_pbits`: every p-bit
// combination is tried; else each endpoint takes the p-bit that quantizes it closest.
struct FitSpec {
    std::array<int, 4> bits{};
    PBits pbits = PBits::none;
    int index_bits = 2;
    bool opaque = false;
    bool all_pbits = true;
    uint32_t nudge_below = 0;        // nudge_endpoints after a fit leaving less error per texel
    float nudge_flatter_than = 0.f;  // ... of texels whose scatter per texel is below this
};

struct SubsetFit {
    uint32_t err = std::numeric_limits<uint32_t>::max();
    std::array<std::array<uint8_t, 4>, 2> q{};  // stored endpoint values by channel
    std::array<uint8_t, 2> p{};                 // p-bits (shared: both equal)
    std::array<uint8_t, 16> idx{};              // by position in the subset's texel list
};

struct Subset {
    std::array<uint8_t, 16> tex{};
    int n = 0;
};

// The fitting routines work on the NC channels from C0 (RGB: 3, 0; RGBA: 4, 0; alpha: 1, 3).

// Indices nearest the palette of decoded endpoints `e`, and their error over the fitted channels.
// The palette lies (to rounding) on the segment: each texel is projected on it, and of the two
// entries either side of the projection the nearer is taken (to rounding, the nearest). Four
// texels at a time in vector lanes, each entry computed as the decoder does, no palette table.
template <size_t NC, size_t C0>
uint32_t assign(const Source& src, const Subset& s, const FitSpec& f, const Endpoints& e,
                std::array<uint8_t, 16>& idx) {
    const int k_count = 1 << f.index_bits;
    const uint8_t* w = weights(f.index_bits);
    std::array<int, NC> d{};
    int dd = 0;
    for (size_t c = 0; c < NC; ++c) {
        d[c] = e[1][C0 + c] - e[0][C0 + c];
        dd += d[c] * d[c];
    }
    const float scale = dd > 0 ? static_cast<float>(k_count - 1) / static_cast<float>(dd) : 0.0f;
    const auto n = static_cast<size_t>(s.n);
    uint32_t total = 0;
    // In float lanes (SSE2 multiplies floats, not 32-bit integers): every value here is an integer
    // below 2^24, so each product and sum is exact and the results are the integer ones.
    std::array<float, NC> df{}, base{};
    for (size_t c = 0; c < NC; ++c) {
        df[c] = static_cast<float>(d[c]);
        base[c] = static_cast<float>(64 * e[0][C0 + c] + 32);
    }
    for (size_t i0 = 0; i0 < n; i0 += 4) {
        // Past the subset's end, lanes repeat its last texel (left out of the sums below).
        const auto& p0 = src.px[s.tex[i0]];
        const auto& p1 = src.px[s.tex[std::min(i0 + 1, n - 1)]];
        const auto& p2 = src.px[s.tex[std::min(i0 + 2, n - 1)]];
        const auto& p3 = src.px[s.tex[std::min(i0 + 3, n - 1)]];
        std::array<Lanes, NC> x{};
        for (size_t c = 0; c < NC; ++c)
            x[c] = __builtin_convertvector((IntLanes{p0[C0 + c], p1[C0 + c], p2[C0 + c], p3[C0 + c]}), Lanes);
        Lanes dot{};
        for (size_t c = 0; c < NC; ++c) dot += (x[c] - static_cast<float>(e[0][C0 + c])) * df[c];
        IntLanes lo = __builtin_convertvector(dot * scale, IntLanes);
        lo = select(lo < 0, IntLanes{}, lo);
        lo = select(lo > k_count - 2, IntLanes{} + (k_count - 2), lo);
        const Lanes w_lo = __builtin_convertvector((IntLanes{w[lo[0]], w[lo[1]], w[lo[2]], w[lo[3]]}), Lanes);
        const Lanes w_hi = __builtin_convertvector((IntLanes{w[lo[0] + 1], w[lo[1] + 1], w[lo[2] + 1], w[lo[3] + 1]}),
                                                   Lanes);
        Lanes err_lo{}, err_hi{};
        for (size_t c = 0; c < NC; ++c) {
            // ((64 - w) e0 + w e1 + 32) >> 6, as the decoder interpolates (truncation is the
            // floor: the sum is positive)
            const Lanes v_lo = __builtin_convertvector(
                __builtin_convertvector((w_lo * df[c] + base[c]) * (1.0f / 64.0f), IntLanes), Lanes);
            const Lanes v_hi = __builtin_convertvector(
                __builtin_convertvector((w_hi * df[c] + base[c]) * (1.0f / 64.0f), IntLanes), Lanes);
            err_lo += (v_lo - x[c]) * (v_lo - x[c]);
            err_hi += (v_hi - x[c]) * (v_hi - x[c]);
        }
        const LaneMask hi = err_hi < err_lo;
        const IntLanes best = __builtin_convertvector(select(hi, err_hi, err_lo), IntLanes);
        const IntLanes k = select(hi, lo + 1, lo);
        for (size_t l = 0; l < 4 && i0 + l < n; ++l) {
            idx[i0 + l] = static_cast<uint8_t>(k[l]);
            total += static_cast<uint32_t>(best[l]);
        }
    }
    return total;
}

// The 8-bit code nearest a fitted endpoint value, clamped (halves away from zero, as std::lround;
// below 0.5, NaN included, 0): for a value of at least 0.5, adding 0.5 in float is exact below
// 2^23, so the truncation is the rounding.
int code_of(float v) {
    if (!(v >= 0.5f)) return 0;
    if (v >= 254.5f) return 255;
    const float up = v + 0.5f;
    return static_cast<int>(up);
}

// Quantizes endpoints `ep` under the p-bits allowed and keeps the best in `best`.
template <size_t NC, size_t C0>
void try_endpoints(const Source& src, const Subset& s, const FitSpec& f, const FloatEnds& ep, SubsetFit& best) {
    const QuantTable& qt = quant();
    std::array<std::array<int, 4>, 2> v{};  // endpoint codes
    for (size_t j = 0; j < 2; ++j)
        for (size_t c = C0; c < C0 + NC; ++c) v[j][c] = f.opaque && c == 3 ? 255 : code_of(ep[j][c]);
    // The quantization error of endpoint j under p-bit p.
    const auto quant_error = [&](size_t j, int p) {
        int err = 0;
        for (size_t c = C0; c < C0 + NC; ++c) {
            const int bits = f.bits[c];
            const int diff = QuantTable::decoded(bits, p, qt.quantize(bits, p, v[j][c])) - v[j][c];
            err += diff * diff;
        }
        return err;
    };
    std::array<std::array<int, 2>, 4> combos{};
    size_t n_combos = 0;
    if (f.pbits == PBits::none) {
        combos[n_combos++] = {2, 2};

    } else if (f.opaque) {
        combos[n_combos++] = {1, 1};
    } else if (f.pbits == PBits::shared) {
        if (f.all_pbits) {
            combos[n_combos++] = {0, 0}, combos[n_combos++] = {1, 1};
        } else {
            const int p = quant_error(0, 0) + quant_error(1, 0) <= quant_error(0, 1) + quant_error(1, 1) ? 0 : 1;
            combos[n_combos++] = {p, p};
        }
    } else if (f.all_pbits) {
        combos = {{{0, 0}, {0, 1}, {1, 0}, {1, 1}}}, n_combos = 4;
    } else {
        combos[n_combos++] = {quant_error(0, 0) <= quant_error(0, 1) ? 0 : 1,
                              quant_error(1, 0) <= quant_error(1, 1) ? 0 : 1};
    }
    for (size_t ci = 0; ci < n_combos; ++ci) {
        const auto& pc = combos[ci];
        SubsetFit cand;
        Endpoints dec{};
        for (size_t j = 0; j < 2; ++j) {
            for (size_t c = C0; c < C0 + NC; ++c) {
                const int stored = qt.quantize(f.bits[c], pc[j], v[j][c]);
                cand.q[j][c] = static_cast<uint8_t>(stored);
                dec[j][c] = QuantTable::decoded(f.bits[c], pc[j], stored);
            }
            cand.p[j] = static_cast<uint8_t>(pc[j] == 2 ? 0 : pc[j]);
        }
        cand.err = assign<NC, C0>(src, s, f, dec, cand.idx);
        if (cand.err < best.err) best = cand;
    }
}

// Moves each stored endpoint value one step up or down, channel by channel, while that lowers the
// error: rounding each channel to its nearest stored value (under one p-bit for all of an
// endpoint's channels) misses the pairs that straddle a value, which near-flat blocks need
// (a dark, smooth photograph: 54.6 dB without, against 71.6 from bc7e).
template <size_t NC, size_t C0>
void nudge_endpoints(const Source& src, const Subset& s, const FitSpec& f, SubsetFit& best) {
    const auto decode_ends = [&](const SubsetFit& fit) {
        Endpoints e{};
        for (size_t j = 0; j < 2; ++j)
            for (size_t c = C0; c < C0 + NC; ++c)
                e[j][c] = QuantTable::decoded(f.bits[c], f.pbits == PBits::none ? 2 : fit.p[j], fit.q[j][c]);
        return e;
    };
    for (int round = 0; round < 2 && best.err > 0; ++round) {
        const uint32_t before = best.err;
        for (size_t j = 0; j < 2; ++j)
            for (size_t c = C0; c < C0 + NC; ++c) {
                if (f.opaque && c == 3) continue;
                for (const int step : {-1, 1}) {
                    const int v = best.q[j][c] + step;
                    if (v < 0 || v >= (1 << f.bits[c])) continue;
                    SubsetFit cand = best;
                    cand.q[j][c] = static_cast<uint8_t>(v);
                    cand.err = assign<NC, C0>(src, s, f, decode_ends(cand), cand.idx);
                    if (cand.err < best.err) best = cand;
                }
            }
        if (best.err >= before) break;
    }
}

// Fits one subset: endpoints at the extremes of its texels on their principal axis, then
// `refine` rounds of least squares on the indices found (kept while the error falls).
template <size_t NC, size_t C0>
SubsetFit fit_subset(const Source& src, const Subset& s, const FitSpec& f, int refine) {
    const auto n = static_cast<size_t>(s.n);
    std::array<float, NC> mean{};
    for (size_t i = 0; i < n; ++i)
        for (size_t c = 0; c < NC; ++c) mean[c] += static_cast<float>(src.px[s.tex[i]][C0 + c]);
    for (float& m : mean) m /= static_cast<float>(std::max<size_t>(1, n));
    std::array<std::array<float, NC>, NC> cov{};
    for (size_t i = 0; i < n; ++i) {
        std::array<float, NC> x{};
        for (size_t c = 0; c < NC; ++c) x[c] = static_cast<float>(src.px[s.tex[i]][C0 + c]) - mean[c];
        for (size_t a = 0; a < NC; ++a)
            for (size_t b = 0; b < NC; ++b) cov[a][b] += x[a] * x[b];
    }
    // Principal axis by power iteration from the channel of largest variance.
    size_t start = 0;
    for (size_t c = 1; c < NC; ++c)
        if (cov[c][c] > cov[start][start]) start = c;
    std::array<float, NC> axis = cov[start];
    for (int it = 0; it < 3; ++it) {
        std::array<float, NC> next{};
        for (size_t a = 0; a < NC; ++a)
            for (size_t b = 0; b < NC; ++b) next[a] += cov[a][b] * axis[b];
        float len = 0;
        for (const float x : next) len += x * x;
        if (len < 1e-12f) break;
        len = 1.0f / std::sqrt(len);
        for (size_t a = 0; a < NC; ++a) axis[a] = next[a] * len;
    }
    float len = 0;
    for (const float x : axis) len += x * x;
    if (len < 1e-12f) axis.fill(1.0f), len = static_cast<float>(NC);
    len = 1.0f / std::sqrt(len);
    for (float& x : axis) x *= len;
    float tmin = 0, tmax = 0;
    for (size_t i = 0; i < n; ++i) {
        float t = 0;
        for (size_t c = 0; c < NC; ++c) t += (static_cast<float>(src.px[s.tex[i]][C0 + c]) - mean[c]) * axis[c];
        tmin = std::min(tmin, t);
        tmax = std::max(tmax, t);
    }
    FloatEnds ep{};
    for (size_t c = 0; c < NC; ++c) {
        ep[0][C0 + c] = mean[c] + tmin * axis[c];
        ep[1][C0 + c] = mean[c] + tmax * axis[c];
    }
    SubsetFit best;
    try_endpoints<NC, C0>(src, s, f, ep, best);
    const uint8_t* w = weights(f.index_bits);
    for (int r = 0; r < refine && best.err > 0; ++r) {
        // Least squares: minimise sum |(1 - a) e0 + a e1 - x|^2 over e0, e1 for the indices' a.
        float aa = 0, ab = 0, bb = 0;
        std::array<float, NC> x0{}, x1{};
        for (size_t i = 0; i < n; ++i) {
            const float a = static_cast<float>(w[best.idx[i]]) * (1.0f / 64.0f), b = 1.0f - a;
            aa += b * b, ab += a * b, bb += a * a;
            for (size_t c = 0; c < NC; ++c) {
                const auto x = static_cast<float>(src.px[s.tex[i]][C0 + c]);
                x0[c] += b * x, x1[c] += a * x;
            }
        }
        const float det = aa * bb - ab * ab;
        if (std::fabs(det) < 1e-6f) break;
        for (size_t c = 0; c < NC; ++c) {
            ep[0][C0 + c] = (bb * x0[c] - ab * x1[c]) / det;
            ep[1][C0 + c] = (aa * x1[c] - ab * x0[c]) / det;
        }
        const uint32_t before = best.err;
        try_endpoints<NC, C0>(src, s, f, ep, best);
        if (best.err >= before) break;
    }
    float scatter = 0;  // per texel, summed over the channels
    for (size_t c = 0; c < NC; ++c) scatter += cov[c][c];
    if (best.err > 0 && best.err <= f.nudge_below * static_cast<uint32_t>(s.n) &&
        scatter <= f.nudge_flatter_than * static_cast<float>(n))
        nudge_endpoints<NC, C0>(src, s, f, best);
    return best;
}

// A block as the encoder chose it, before its bits are written.
struct Encoded {
    uint32_t err = std::numeric_limits<uint32_t>::max();
    int mode = 6, partition = 0, rotation = 0, isb = 0;
    std::array<std::array<std::array<uint8_t, 4>, 2>, 3> q{};
    std::array<std::array<uint8_t, 2>, 3> p{};
    std::array<uint8_t, 16> idx{}, idx2{};  // colour (or joint) indices; mode 4/5's alpha indices
};

// The texel lists of every subset of every partition, built once.
struct PartitionLists {
    std::array<std::array<Subset, 2>, 64> two{};
    std::array<std::array<Subset, 3>, 64> three{};
    PartitionLists() {
        for (int p = 0; p < 64; ++p)
            for (int t = 0; t < 16; ++t) {
                Subset& s2 = two[static_cast<size_t>(p)][static_cast<size_t>(subset_of(2, p, t))];
                s2.tex[static_cast<size_t>(s2.n++)] = static_cast<uint8_t>(t);
                Subset& s3 = three[static_cast<size_t>(p)][static_cast<size_t>(subset_of(3, p, t))];
                s3.tex[static_cast<size_t>(s3.n++)] = static_cast<uint8_t>(t);
            }
    }
};
const PartitionLists& partition_lists() {
    static const PartitionLists lists;
    return lists;
}
const Subset& whole_block() {
    static const Subset all = [] {
        Subset s;
        for (int t = 0; t < 16; ++t) s.tex[static_cast<size_t>(t)] = static_cast<uint8_t>(t);
        s.n = 16;
        return s;
    }();
    return all;
}

// Makes each subset's anchor index's top bit 0 by swapping the subset's endpoints and
// complementing its indices (the same texels decode: see the weights).
void fix_anchors(Encoded& e) {
    const ModeInfo& m = kModes[static_cast<size_t>(e.mode)];
    const int kc = 1 << m.index_bits;
    if (m.index2_bits == 0) {
        for (int s = 0; s < m.subsets; ++s) {
            const auto a = static_cast<size_t>(anchor_of(m.subsets, e.partition, s));
            if (e.idx[a] < kc / 2) continue;
            auto& q = e.q[static_cast<size_t>(s)];
            std::swap(q[0], q[1]);
            std::swap(e.p[static_cast<size_t>(s)][0], e.p[static_cast<size_t>(s)][1]);
            for (int t = 0; t < 16; ++t)
                if (subset_of(m.subsets, e.partition, t) == s)
                    e.idx[static_cast<size_t>(t)] = static_cast<uint8_t>(kc - 1 - e.idx[static_cast<size_t>(t)]);
        }
        return;
    }
    // Modes 4 and 5: the colour and the alpha index sets, each anchored at texel 0.
    const int color_bits = e.isb ? m.index2_bits : m.index_bits;
    const int alpha_bits = e.isb ? m.index_bits : m.index2_bits;
    auto& q = e.q[0];
    if (e.idx[0] >= (1 << color_bits) / 2) {
        for (size_t c = 0; c < 3; ++c) std::swap(q[0][c], q[1][c]);
        for (auto& i : e.idx) i = static_cast<uint8_t>((1 << color_bits) - 1 - i);
    }
    if (e.idx2[0] >= (1 << alpha_bits) / 2) {
        std::swap(q[0][3], q[1][3]);
        for (auto& i : e.idx2) i = static_cast<uint8_t>((1 << alpha_bits) - 1 - i);
    }
}

void pack(const Encoded& e, uint8_t out[16]) {
    const ModeInfo& m = kModes[static_cast<size_t>(e.mode)];
    BitWriter w;
    w.put(1u << e.mode, e.mode + 1);
    w.put(static_cast<unsigned>(e.partition), m.partition_bits);
    w.put(static_cast<unsigned>(e.rotation), m.rotation_bits);
    w.put(static_cast<unsigned>(e.isb), m.isb_bits);
    const auto ns = static_cast<size_t>(m.subsets);
    for (size_t c = 0; c < 3; ++c)
        for (size_t s = 0; s < ns; ++s)
            for (size_t j = 0; j < 2; ++j) w.put(e.q[s][j][c], m.color_bits);
    if (m.alpha_bits)
        for (size_t s = 0; s < ns; ++s)
            for (size_t j = 0; j < 2; ++j) w.put(e.q[s][j][3], m.alpha_bits);
    if (m.pbits == PBits::per_endpoint)
        for (size_t s = 0; s < ns; ++s)
            for (size_t j = 0; j < 2; ++j) w.put(e.p[s][j], 1);
    if (m.pbits == PBits::shared)
        for (size_t s = 0; s < ns; ++s) w.put(e.p[s][0], 1);
    // Modes 4 and 5 write the 2-bit set first: the colour's unless the index selector is set.
    const auto& first = e.isb ? e.idx2 : e.idx;
    const auto& second = e.isb ? e.idx : e.idx2;
    for (int t = 0; t < 16; ++t)
        w.put(first[static_cast<size_t>(t)], m.index_bits - (is_anchor(m.subsets, e.partition, t) ? 1 : 0));
    if (m.index2_bits)
        for (int t = 0; t < 16; ++t) w.put(second[static_cast<size_t>(t)], m.index2_bits - (t == 0 ? 1 : 0));
    w.flush(out);
}

uint32_t alpha_error_at_255(const Source& src) {
    uint32_t err = 0;
    for (const auto& x : src.px) err += static_cast<uint32_t>((255 - x[3]) * (255 - x[3]));
    return err;
}

// How far the encoder searches at each level. Measured on the corpus's 1K photographs
// (bench/texture/bc7_vs_bc7e.sh): the p-bits of mode 6 are worth 0.3-0.6 dB and are always
// searched; searching those of the 2-subset modes adds 0.04 dB for 20 % more time. Textured
// photographs gain little from the partitioned modes where one line already fits a block to a
// summed squared error of 32 (2/3 per sample), nor from the endpoint nudge; smooth and flat ones
// (3dtextures' Obsidian, ambientCG's OfficeCeiling005) need both: 54.6 -> 67.3 and 64.0 -> 66.0
// dB. The nudge goes to flat subsets only (scatter under 16 per texel): on the textured ones it
// bought 0.04 dB for a fifth of the time. Blocks with alpha (a cut-out's edges) rank mode 7's
// partitions less well: fitting 8 rather than 1 gains 0.9 dB on ambientCG's Net004A.
struct Search {
    int refine;                // least-squares rounds per subset
    int parts2;                // 2-subset partitions fitted in modes 1 and 3 (7 with alpha)
    int parts3;                // 3-subset partitions fitted in modes 0 and 2 (0: not tried)
    int rotations;             // channel rotations of modes 4 and 5 on opaque blocks (0: not tried)
    bool all_pbits;            // every p-bit combination in every mode (else mode 6's only, and the
                               // nearest per endpoint in the others)
    uint32_t split_above;      // the partitioned modes are tried where mode 6 leaves more error
    bool mode3;                // mode 3 beside mode 1 on the ranked partitions
    int parts7;                // partitions fitted in mode 7 (blocks with alpha)
    uint32_t nudge_below;      // endpoints nudged where a fit leaves less error per texel than this
    float nudge_flatter_than;  // ... in subsets whose texels scatter less than this (per texel)
};
Search search_of(int level) {
    if (level <= 0) return {1, 1, 0, 0, false, 128, false, 4, 2, 16.f};
    if (level == 1) return {1, 1, 0, 0, false, 32, true, 8, 2, 16.f};
    return {2, 4, 2, 3, true, 0, true, 16, 1u << 20, 1e9f};
}

// One block's search: its texels, whether every alpha is 255, whether alpha is data.
struct Block {
    Source src;
    bool opaque = true;
    bool alpha_data = true;
    Search search{};
};

// Modes 0, 1, 2, 3, 6, 7: one fit per subset over RGB (RGBA for 6 and 7 where alpha is data; where
// it is not, their alpha endpoints are stored all ones, decoding to 255 or, through a p-bit of 0,
// 254).
Encoded encode_joint(const Block& b, int mode, int partition) {
    const ModeInfo& m = kModes[static_cast<size_t>(mode)];
    const bool fit_alpha = m.alpha_bits > 0 && b.alpha_data;
    FitSpec f;
    f.bits = {m.color_bits, m.color_bits, m.color_bits, m.alpha_bits};
    f.pbits = m.pbits;
    f.index_bits = m.index_bits;
    f.opaque = fit_alpha && b.opaque;
    f.all_pbits = b.search.all_pbits || mode == 6;
    f.nudge_below = b.search.nudge_below;
    f.nudge_flatter_than = b.search.nudge_flatter_than;
    Encoded e;
    e.mode = mode, e.partition = partition;
    e.err = m.alpha_bits == 0 && b.alpha_data ? alpha_error_at_255(b.src) : 0;
    const PartitionLists& lists = partition_lists();
    const auto p = static_cast<size_t>(partition);
    for (size_t s = 0; s < static_cast<size_t>(m.subsets); ++s) {
        const Subset& sub = m.subsets == 1 ? whole_block() : m.subsets == 2 ? lists.two[p][s] : lists.three[p][s];
        SubsetFit fit = fit_alpha ? fit_subset<4, 0>(b.src, sub, f, b.search.refine)
                                  : fit_subset<3, 0>(b.src, sub, f, b.search.refine);
        if (m.alpha_bits > 0 && !fit_alpha) fit.q[0][3] = fit.q[1][3] = static_cast<uint8_t>((1 << m.alpha_bits) - 1);
        e.err += fit.err;
        e.q[s] = fit.q;
        e.p[s] = fit.p;
        for (size_t i = 0; i < static_cast<size_t>(sub.n); ++i) e.idx[sub.tex[i]] = fit.idx[i];
    }
    return e;
}

// Modes 4 and 5: colour and alpha fitted apart, after `rotation` swapped alpha with R, G or B.
Encoded encode_separate(const Block& b, int mode, int rotation, int isb) {
    const ModeInfo& m = kModes[static_cast<size_t>(mode)];
    Source rot = b.src;
    if (rotation > 0)
        for (auto& x : rot.px) std::swap(x[static_cast<size_t>(rotation - 1)], x[3]);
    FitSpec color;
    color.bits = {m.color_bits, m.color_bits, m.color_bits, 0};
    color.index_bits = isb ? m.index2_bits : m.index_bits;
    FitSpec alpha;
    alpha.bits = {0, 0, 0, m.alpha_bits};
    alpha.index_bits = isb ? m.index_bits : m.index2_bits;
    const SubsetFit c = fit_subset<3, 0>(rot, whole_block(), color, b.search.refine);
    const SubsetFit a = fit_subset<1, 3>(rot, whole_block(), alpha, b.search.refine);
    Encoded e;
    e.mode = mode, e.rotation = rotation, e.isb = isb;
    e.err = c.err + (rotation == 0 && !b.alpha_data ? 0 : a.err);
    for (size_t j = 0; j < 2; ++j) {
        for (size_t ch = 0; ch < 3; ++ch) e.q[0][j][ch] = c.q[j][ch];
        e.q[0][j][3] = a.q[j][3];
    }
    e.idx = c.idx;
    e.idx2 = a.idx;
    return e;
}

// ---------------------------------------------------------------------------------------------
// Partition ranking: how far each subset's texels lie off their principal line, from moment sums
// (the residual scatter: the scatter matrix's trace minus its largest eigenvalue). Quantization is
// left out; the few best are fitted in full. The 64 partitions are scored four at a time in the
// lanes of a vector (GCC's and Clang's vector extension: SSE on x86-64, NEON on ARM, plain code
// elsewhere): this ranking would otherwise cost as much as all the fits together.

// Which texels each partition puts in subsets 1 and 2 (subset 0 is the rest), as 0/1 factors,
// and the subsets' texel counts.
struct PartitionMasks {
    std::array<Row, 16> two1{}, three1{}, three2{};
    Row n_two1{}, n_two0{}, n_three1{}, n_three2{}, n_three0{};
    PartitionMasks() {
        for (int t = 0; t < 16; ++t)
            for (int p = 0; p < 64; ++p) {
                const auto tt = static_cast<size_t>(t), chunk = static_cast<size_t>(p / 4);
                const int lane = p % 4;
                const int s2 = subset_of(2, p, t), s3 = subset_of(3, p, t);
                two1[tt][chunk][lane] = s2 == 1 ? 1.0f : 0.0f;
                three1[tt][chunk][lane] = s3 == 1 ? 1.0f : 0.0f;
                three2[tt][chunk][lane] = s3 == 2 ? 1.0f : 0.0f;
                (s2 == 1 ? n_two1 : n_two0)[chunk][lane] += 1.0f;
                (s3 == 0 ? n_three0 : s3 == 1 ? n_three1 : n_three2)[chunk][lane] += 1.0f;
            }
    }
};
const PartitionMasks& partition_masks() {
    static const PartitionMasks masks;
    return masks;
}

template <size_t NC>
struct Moments {
    static constexpr size_t kTerms = NC + NC * (NC + 1) / 2;  // x, then the products x_a x_b, a <= b
    using Sums = std::array<Row, kTerms>;
    std::array<std::array<float, kTerms>, 16> m{};  // per texel
    std::array<float, kTerms> total{};
    explicit Moments(const Source& src) {
        for (size_t t = 0; t < 16; ++t) {
            auto& r = m[t];
            size_t k = NC;
            for (size_t a = 0; a < NC; ++a) r[a] = static_cast<float>(src.px[t][a]);
            for (size_t a = 0; a < NC; ++a)
                for (size_t b = a; b < NC; ++b) r[k++] = r[a] * r[b];
            for (size_t i = 0; i < kTerms; ++i) total[i] += r[i];
        }
    }
    // The sums over the texels `mask` selects in each partition.
    void sum(const std::array<Row, 16>& mask, Sums& out) const {
        for (auto& row : out) row.fill(Lanes{});
        for (size_t t = 0; t < 16; ++t)
            for (size_t k = 0; k < kTerms; ++k) {
                const Lanes v = splat(m[t][k]);
                for (size_t c = 0; c < 16; ++c) out[k][c] += mask[t][c] * v;
            }
    }
    // Adds each partition's scatter of the subset with sums `s` and `n` texels off its principal
    // line to `off`, and along it (the largest eigenvalue) to `along`.
    static void add_scatter(const Sums& s, const Row& n, Row& off, Row& along) {
        for (size_t ch = 0; ch < 16; ++ch) {
            const Lanes inv = splat(1.0f) / (n[ch] + splat(1e-30f));
            std::array<std::array<Lanes, NC>, NC> c{};
            size_t k = NC;
            for (size_t a = 0; a < NC; ++a)
                for (size_t b = a; b < NC; ++b, ++k) c[a][b] = c[b][a] = s[k][ch] - s[a][ch] * s[b][ch] * inv;
            // Power iteration from the row of largest variance, unnormalized (values below 2^22
            // stay finite through two products), then the Rayleigh quotient.
            std::array<Lanes, NC> v = c[0];
            Lanes trace = c[0][0], top = c[0][0];
            for (size_t a = 1; a < NC; ++a) {
                trace += c[a][a];
                const LaneMask larger = c[a][a] > top;
                top = select(larger, c[a][a], top);
                for (size_t b = 0; b < NC; ++b) v[b] = select(larger, c[a][b], v[b]);
            }
            for (int it = 0; it < 2; ++it) {
                std::array<Lanes, NC> nv{};
                for (size_t a = 0; a < NC; ++a)
                    for (size_t b = 0; b < NC; ++b) nv[a] += c[a][b] * v[b];
                v = nv;
            }
            Lanes vv{}, vcv{};
            for (size_t a = 0; a < NC; ++a) {
                Lanes cv{};
                for (size_t b = 0; b < NC; ++b) cv += c[a][b] * v[b];
                vv += v[a] * v[a];
                vcv += v[a] * cv;
            }
            const Lanes lambda = vcv / (vv + splat(1e-30f));
            const Lanes r = trace - lambda;
            off[ch] += select(r > splat(0.0f), r, Lanes{});
            along[ch] += lambda;
        }
    }
};

// Every partition's scatter off and along its subsets' lines.
struct PartitionScores {
    Row off{}, along{};
};
template <size_t NC>
PartitionScores score_partitions(const Moments<NC>& mo, int subsets) {
    using M = Moments<NC>;
    const PartitionMasks& pm = partition_masks();
    PartitionScores sc;
    typename M::Sums a, b;
    if (subsets == 2) {
        mo.sum(pm.two1, a);
        for (size_t k = 0; k < M::kTerms; ++k)
            for (size_t c = 0; c < 16; ++c) b[k][c] = splat(mo.total[k]) - a[k][c];
        M::add_scatter(a, pm.n_two1, sc.off, sc.along);
        M::add_scatter(b, pm.n_two0, sc.off, sc.along);
    } else {
        typename M::Sums c;
        mo.sum(pm.three1, a);
        mo.sum(pm.three2, b);
        for (size_t k = 0; k < M::kTerms; ++k)
            for (size_t ch = 0; ch < 16; ++ch) c[k][ch] = splat(mo.total[k]) - a[k][ch] - b[k][ch];
        M::add_scatter(a, pm.n_three1, sc.off, sc.along);
        M::add_scatter(b, pm.n_three2, sc.off, sc.along);
        M::add_scatter(c, pm.n_three0, sc.off, sc.along);
    }
    return sc;
}

// The `count` partitions among the first `partitions` whose estimated error is least for indices
// of `index_bits`, best first: the scatter off the lines, plus the along-line scatter spread over
// the 2^bits index steps (a uniform spread of variance v over K steps leaves v / (K - 1)^2): the
// off-line scatter alone ranks every partition of a grey block equal.
int best_partitions(const PartitionScores& sc, int partitions, int index_bits, int count, std::array<int, 64>& out) {
    const auto steps = static_cast<float>((1 << index_bits) - 1);
    const float w = 1.0f / (steps * steps);
    std::array<std::pair<float, int>, 64> score{};
    for (size_t p = 0; p < static_cast<size_t>(partitions); ++p) {
        const float e = sc.off[p / 4][static_cast<int>(p % 4)] + w * sc.along[p / 4][static_cast<int>(p % 4)];
        score[p] = {e, static_cast<int>(p)};
    }
    count = std::min(count, partitions);
    std::partial_sort(score.begin(), score.begin() + count, score.begin() + partitions);
    for (size_t i = 0; i < static_cast<size_t>(count); ++i) out[i] = score[i].second;
    return count;
}

}  // namespace

int block_mode(const uint8_t in[16]) {
    int mode = 0;
    while (mode < 8 && !((in[0] >> mode) & 1)) ++mode;
    return mode;
}

void decode_block(const uint8_t in[16], uint8_t rgba[64]) {
    const int mode = block_mode(in);
    if (mode == 8) {
        std::memset(rgba, 0, 64);
        return;
    }
    const ModeInfo& m = kModes[static_cast<size_t>(mode)];
    BitReader r{in, mode + 1};
    const int partition = r.get(m.partition_bits), rotation = r.get(m.rotation_bits), isb = r.get(m.isb_bits);
    const size_t ne = 2 * static_cast<size_t>(m.subsets);
    std::array<std::array<int, 4>, 6> ep{};
    for (size_t c = 0; c < 3; ++c)
        for (size_t e = 0; e < ne; ++e) ep[e][c] = r.get(m.color_bits);
    for (size_t e = 0; e < ne; ++e) ep[e][3] = m.alpha_bits ? r.get(m.alpha_bits) : 0;
    int cbits = m.color_bits, abits = m.alpha_bits;
    if (m.pbits != PBits::none) {
        std::array<int, 6> p{};
        if (m.pbits == PBits::per_endpoint)
            for (size_t e = 0; e < ne; ++e) p[e] = r.get(1);
        else
            for (size_t s = 0; s < ne / 2; ++s) p[2 * s] = p[2 * s + 1] = r.get(1);
        for (size_t e = 0; e < ne; ++e)
            for (size_t c = 0; c < 4; ++c) ep[e][c] = (ep[e][c] << 1) | p[e];
        ++cbits;
        if (abits) ++abits;
    }
    for (size_t e = 0; e < ne; ++e) {
        for (size_t c = 0; c < 3; ++c) ep[e][c] = expand(ep[e][c], cbits);
        ep[e][3] = abits ? expand(ep[e][3], abits) : 255;
    }
    std::array<int, 16> i1{}, i2{};
    for (int t = 0; t < 16; ++t)
        i1[static_cast<size_t>(t)] = r.get(m.index_bits - (is_anchor(m.subsets, partition, t) ? 1 : 0));
    if (m.index2_bits)
        for (int t = 0; t < 16; ++t) i2[static_cast<size_t>(t)] = r.get(m.index2_bits - (t == 0 ? 1 : 0));
    for (int t = 0; t < 16; ++t) {
        const auto s = static_cast<size_t>(subset_of(m.subsets, partition, t));
        const auto& e0 = ep[2 * s];
        const auto& e1 = ep[2 * s + 1];
        const auto tt = static_cast<size_t>(t);
        int cw = weights(m.index_bits)[i1[tt]], aw = cw;
        if (m.index2_bits) {
            const int w2 = weights(m.index2_bits)[i2[tt]];
            if (isb) aw = cw, cw = w2;
            else aw = w2;
        }
        std::array<int, 4> v{};
        for (size_t c = 0; c < 3; ++c) v[c] = interpolate(e0[c], e1[c], cw);
        v[3] = interpolate(e0[3], e1[3], aw);
        if (rotation > 0) std::swap(v[static_cast<size_t>(rotation - 1)], v[3]);
        for (size_t c = 0; c < 4; ++c) rgba[tt * 4 + c] = static_cast<uint8_t>(v[c]);
    }
}

void encode_block(const uint8_t rgba[64], const Options& opt, uint8_t out[16]) {
    constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();
    Block b;
    b.alpha_data = opt.alpha_data;
    b.search = search_of(opt.level);
    for (size_t t = 0; t < 16; ++t) {
        for (size_t c = 0; c < 4; ++c) b.src.px[t][c] = c == 3 && !opt.alpha_data ? 255 : rgba[t * 4 + c];
        b.opaque = b.opaque && b.src.px[t][3] == 255;
    }
    const Search& search = b.search;
    const auto allowed = [&](int mode) { return (opt.modes >> mode) & 1; };
    Encoded best;
    const auto consider = [&](const Encoded& e) {
        if (e.err < best.err) best = e;
    };
    if (allowed(6)) consider(encode_joint(b, 6, 0));
    std::array<int, 64> parts{};
    if (b.opaque) {
        const Moments<3> mo(b.src);
        // Partitions pay where one line fits the block badly: below `split_above` mode 6 stays.
        if (best.err > search.split_above && (allowed(1) || allowed(3))) {
            const PartitionScores sc = score_partitions(mo, 2);
            for (const int mode : {1, 3}) {
                if (!allowed(mode) || (mode == 3 && !search.mode3)) continue;
                const int n = best_partitions(sc, 64, kModes[static_cast<size_t>(mode)].index_bits, search.parts2,
                                              parts);
                for (size_t i = 0; i < static_cast<size_t>(n) && best.err > 0; ++i)
                    consider(encode_joint(b, mode, parts[i]));
            }
        }
        if (best.err > 0 && (search.parts3 > 0 || best.err == kNone) && (allowed(0) || allowed(2))) {
            const PartitionScores sc = score_partitions(mo, 3);
            for (const int mode : {0, 2}) {
                if (!allowed(mode)) continue;
                const int n = best_partitions(sc, mode == 0 ? 16 : 64, kModes[static_cast<size_t>(mode)].index_bits,
                                              std::max(1, search.parts3), parts);
                for (size_t i = 0; i < static_cast<size_t>(n) && best.err > 0; ++i)
                    consider(encode_joint(b, mode, parts[i]));
            }
        }
    } else if (allowed(7) && best.err > 0) {
        const Moments<4> mo(b.src);
        const int n = best_partitions(score_partitions(mo, 2), 64, 2, search.parts7, parts);
        for (size_t i = 0; i < static_cast<size_t>(n) && best.err > 0; ++i) consider(encode_joint(b, 7, parts[i]));
    }
    // Modes 4 and 5: alpha on its own line (blocks with alpha), or, in an opaque block, R, G or B
    // rotated into the alpha slot where it does not follow the other two (packed maps).
    const int first_rot = b.opaque && best.err != kNone ? 1 : 0;
    const int last_rot = b.opaque ? (best.err == kNone ? 0 : search.rotations) : 0;
    for (int rot = first_rot; rot <= last_rot && best.err > 0; ++rot) {
        if (allowed(5)) consider(encode_separate(b, 5, rot, 0));
        if (allowed(4)) {
            consider(encode_separate(b, 4, rot, 0));
            consider(encode_separate(b, 4, rot, 1));
        }
    }
    if (best.err == kNone) {
        // Only modes the block cannot use were allowed (0-3 or 7 on a block with alpha, in tests).
        for (int mode = 0; mode < 8 && best.err == kNone; ++mode)
            if (allowed(mode))
                best = mode == 4 || mode == 5 ? encode_separate(b, mode, 0, 0) : encode_joint(b, mode, 0);
    }
    fix_anchors(best);
    pack(best, out);
}

}  // namespace mf::texture::bc7
