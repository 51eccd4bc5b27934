#include "validate/map_stats.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <type_traits>
#include <utility>

#include "base/simd.hpp"
#include "base/srgb.hpp"
#include "core/text.hpp"

namespace mf::validate::detail {
namespace {

// Roles whose values must lie in [0, 1] (normals: [−1, 1] when stored signed). Height and
// emissive are unbounded (displacement in scene units, HDR emission).
bool has_unit_range(Role r) { return r != Role::height && r != Role::emissive; }

const char* channel_letter(int c) {
    static const char* names[] = {"R", "G", "B", "A"};
    return c >= 0 && c < 4 ? names[c] : "?";
}

}  // namespace

const std::vector<float>& srgb_decode_table() {
    static const std::vector<float> lut = [] {
        std::vector<float> v(65536);
        for (int i = 0; i < 65536; ++i) v[static_cast<size_t>(i)] = srgb_to_linear(static_cast<float>(i) / 65535.f);
        return v;
    }();
    return lut;
}

std::optional<Role> channel_role(Role input_role, int channel) {
    if (traits(input_role).packed) {
        if (channel < 0 || channel > 3) return std::nullopt;
        const PackedLayout layout = packed_layout(input_role);
        const auto& c = layout[static_cast<size_t>(channel)];
        if (!c) return std::nullopt;
        return c->role;
    }
    return input_role;
}

MapStats::MapStats(MapInput in, const ImageInfo& info, const rules::Thresholds& th)
    : input(std::move(in)), t(th), width(info.width), height(info.height), channels(info.channels) {
    const std::string ext = input.file.extension();
    is_jpeg = ext == "jpg" || ext == "jpeg" || info.format == "jpeg";
    min.fill(std::numeric_limits<double>::infinity());
    max.fill(-std::numeric_limits<double>::infinity());
    if (input.role == Role::metalness) metal_channel = 0;
    for (int c = 0; c < 4 && traits(input.role).packed; ++c)
        if (channel_role(input.role, c) == Role::metalness) metal_channel = c;
    if (metal_channel >= channels) metal_channel = -1;
    // The albedo's alpha is glTF's opacity when the set has no opacity map (the set-level
    // caller overrides this when it has one).
    if (input.role == Role::opacity) opacity_channel = 0;
    else if (input.role == Role::albedo && channels == 4) opacity_channel = 3;
    if (!input.info.is_float) normal_signed = 0;
    if (!input.info.is_float && (input.info.bit_depth == 8 || input.info.bit_depth == 16))
        code_scale = input.info.bit_depth == 8 ? 255.f : 65535.f;
}

bool MapStats::scalar_role() const { return traits(input.role).channels == 1; }

bool MapStats::packed_rgb() const {
    if (!traits(input.role).packed || channels < 3) return false;
    const PackedLayout layout = packed_layout(input.role);
    return layout[0] && layout[1] && layout[2];
}

namespace {

// An 8-bit band read as floats through a table (unorm8_values, or one built from it), indexed as
// a float pointer is: add_band_t's loops are the same code for both, so the same values meet the
// same operations in the same order.
struct CodeReader {
    const uint8_t* p;
    const float* table;
    float operator[](size_t i) const { return table[p[i]]; }
    CodeReader operator+(size_t n) const { return {p + n, table}; }
};

// How MapStats::codes_band reads one kind of integer file's samples: floats (code / scale, 8 or
// 16 bits) four to a vector, or 8-bit codes sixteen to a vector. Sums are kept per lane in `Sum`
// and widened every kFlush blocks, before a lane can overflow.
struct FloatLanes {
    using T = float;
    using Vec = float __attribute__((vector_size(16)));
    using Sum = int32_t __attribute__((vector_size(16)));
    static constexpr size_t kLanes = 4;
    static constexpr size_t kFlush = size_t{1} << 15;  // a lane adds one code (< 65536) a block: below 2^31
    static constexpr T kTop = std::numeric_limits<float>::infinity(), kBottom = -kTop;
    float scale;  // the file's code_scale
    void add(Sum& s, const Vec& v) const {
        // NOLINTNEXTLINE(bugprone-incorrect-roundings): v is code / scale, the nearest code is exact
        s += __builtin_convertvector(v * scale + 0.5f, Sum);
    }
    // NOLINTNEXTLINE(bugprone-incorrect-roundings): v is code / scale, the nearest code is exact
    long long code(T v) const { return static_cast<long long>(v * scale + 0.5f); }
    static double value(T v) { return v; }
};

struct CodeLanes {
    using T = uint8_t;
    using Vec = uint8_t __attribute__((vector_size(16)));
    using Sum = uint16_t __attribute__((vector_size(32)));
    static constexpr size_t kLanes = 16;
    static constexpr size_t kFlush = 256;  // a 16-bit lane adds at most 255 a block: 257 blocks fit
    static constexpr T kTop = 255, kBottom = 0;
    static void add(Sum& s, const Vec& v) { s += __builtin_convertvector(v, Sum); }
    static long long code(T v) { return v; }
    static double value(T v) { return unorm8_values()[v]; }
};

// Per-lane min, max and code sums over whole blocks of V vectors (V = 3 for three channels, else
// 1), accumulators in registers (a compile-time V); returns the samples consumed.
template <size_t V, class L>
size_t lane_blocks(const typename L::T* px, size_t total, const L& lanes, typename L::Vec (&mn)[3],
                   typename L::Vec (&mx)[3], long long (&wide)[3][L::kLanes]) {
    using Vec = typename L::Vec;
    using Sum = typename L::Sum;
    Vec lo[V] = {}, hi[V] = {};
    Sum sums[V] = {};
    for (size_t j = 0; j < V; ++j) {
        lo[j] = Vec{} + L::kTop;
        hi[j] = Vec{} + L::kBottom;
    }
    auto flush = [&] {
        for (size_t j = 0; j < V; ++j) {
            for (size_t l = 0; l < L::kLanes; ++l) wide[j][l] += sums[j][l];
            sums[j] = Sum{};
        }
    };
    size_t i = 0, blocks = 0;
    for (; i + L::kLanes * V <= total; i += L::kLanes * V) {
        for (size_t j = 0; j < V; ++j) {
            Vec v;
            std::memcpy(&v, px + i + L::kLanes * j, sizeof v);
            lo[j] = v < lo[j] ? v : lo[j];
            hi[j] = v > hi[j] ? v : hi[j];
            lanes.add(sums[j], v);
        }
        if (++blocks == L::kFlush) {
            flush();
            blocks = 0;
        }
    }
    flush();
    for (size_t j = 0; j < V; ++j) {
        mn[j] = lo[j];
        mx[j] = hi[j];
    }
    return i;
}

}  // namespace

void MapStats::add_band(int /*y0*/, int rows, const float* px) { add_band_t(static_cast<long long>(rows) * width, px); }

void MapStats::add_band(int /*y0*/, int rows, const uint8_t* codes) {
    add_band_t(static_cast<long long>(rows) * width, CodeReader{codes, unorm8_values().data()});
}

template <class P>
void MapStats::add_band_t(long long n, P px) {
    const bool check_range = input.info.is_float && has_unit_range(input.role);
    const double lo = is_normal() ? -1.0 : 0.0;
    const double eps = t.range_epsilon;
    const bool gray = (scalar_role() && channels >= 3) || packed_rgb();
    const double gtol = is_jpeg ? t.grayscale_tolerance_jpeg : t.grayscale_tolerance;
    if (is_normal() && normal_signed < 0) {
        // Float normal maps come both ways; negative values mean "already signed".
        bool neg = false;
        for (long long i = 0; i < n * channels && !neg; ++i) neg = px[static_cast<size_t>(i)] < -1e-3f;
        normal_signed = neg ? 1 : 0;
    }
    if (is_normal() && channels >= 3 && normal_z < 0 && n > 0) {
        // Blue holding one value (within an 8-bit code; JPEG moves it a few) while X and Y vary,
        // or one value far from "up": no tangent map stores that, a two-channel export does.
        float bmin = px[2], bmax = px[2], xmin = px[0], xmax = px[0], ymin = px[1], ymax = px[1];
        for (long long i = 0; i < n; ++i) {
            const auto p = px + static_cast<size_t>(i) * static_cast<size_t>(channels);
            bmin = std::min(bmin, p[2]), bmax = std::max(bmax, p[2]);
            xmin = std::min(xmin, p[0]), xmax = std::max(xmax, p[0]);
            ymin = std::min(ymin, p[1]), ymax = std::max(ymax, p[1]);
        }
        const float tol = is_jpeg ? 4.f / 255.f : 1.f / 255.f;
        const bool blue_constant = bmax - bmin <= tol;
        const bool xy_vary = xmax - xmin > 4.f / 255.f || ymax - ymin > 4.f / 255.f;
        const float up = normal_signed == 1 ? 1.f : 1.f - 0.5f / 255.f;  // z = +1 stored
        normal_z = blue_constant && (xy_vary || bmax < up - 0.1f) ? 1 : 0;
    }
    // Per-channel min/max/sum. Integer file: no NaN or Inf can occur, min/max in float are exact,
    // the sum is exact in codes: any order gives the same figures, so the band is walked as it
    // lies in memory, four samples a step (codes_band).
    if (code_scale > 0.f && channels <= 4) {
        if constexpr (std::is_same_v<P, CodeReader>) codes_band(n, px.p, CodeLanes{});
        else codes_band(n, px, FloatLanes{code_scale});
    } else if (code_scale > 0.f) {
        for (int c = 0; c < 4; ++c) {
            float mn = std::numeric_limits<float>::infinity(), mx = -mn;
            long long codes = 0;
            for (long long i = 0; i < n; ++i) {
                const float v = px[static_cast<size_t>(i * channels + c)];
                mn = std::min(mn, v);
                mx = std::max(mx, v);
                // NOLINTNEXTLINE(bugprone-incorrect-roundings): v is code / scale, the nearest code is exact
                codes += static_cast<long long>(v * code_scale + 0.5f);
            }
            min[c] = std::min(min[c], double{mn});
            max[c] = std::max(max[c], double{mx});
            code_sum[c] += codes;
            finite[c] += n;
        }
    } else {
        for (int c = 0; c < channels; ++c) {
            const int k = std::min(c, 3);
            double mn = min[k], mx = max[k], sm = sum[k];
            long long fin = 0, nans = 0, infs = 0;
            for (long long i = 0; i < n; ++i) {
                const float v = px[static_cast<size_t>(i * channels + c)];
                if (!std::isfinite(v)) {
                    ++(std::isnan(v) ? nans : infs);
                    continue;
                }
                mn = std::min(mn, double{v});
                mx = std::max(mx, double{v});
                sm += v;
                ++fin;
            }
            nan += nans;
            inf += infs;
            if (c < 4) {
                min[k] = mn, max[k] = mx, sum[k] = sm;
                finite[k] += fin;
            }
        }
    }
    samples += n * channels;
    pixels += n;
    // One loop per check, each with its counters in locals (members would be stored back every
    // pixel); the same operations in the same order as one loop: results are bit-identical.
    if (check_range) {
        long long bad = 0;
        for (long long i = 0; i < n; ++i) {
            const auto p = px + static_cast<size_t>(i * channels);
            bool bad_range = false;
            for (int c = 0; c < channels; ++c) {
                const float v = p[c];
                if (std::isfinite(v) && (v < lo - eps || v > 1.0 + eps)) bad_range = true;
            }
            bad += bad_range ? 1 : 0;
        }
        out_of_range_pixels += bad;
    }
    if (gray) {
        long long differing = 0;
        double max_diff = gray_max_diff, sum_rg = gray_sum_rg, sum_rb = gray_sum_rb;
        for (long long i = 0; i < n; ++i) {
            const auto p = px + static_cast<size_t>(i * channels);
            if constexpr (std::is_same_v<P, CodeReader>) {
                // Three equal codes add 0 to the sums (which are >= 0: x + 0.0 is x) and leave
                // the max as it is: skipped, the same figures.
                if (p.p[0] == p.p[1] && p.p[0] == p.p[2]) continue;
            }
            const double rg = std::abs(double{p[0]} - p[1]), rb = std::abs(double{p[0]} - p[2]),
                         gb = std::abs(double{p[1]} - p[2]);
            const double d = std::max({rg, rb, gb});
            if (std::isfinite(d)) {
                if (d > gtol) ++differing;
                max_diff = std::max(max_diff, d);
                sum_rg += rg;
                sum_rb += rb;
            }
        }
        gray_differing += differing;
        gray_max_diff = max_diff, gray_sum_rg = sum_rg, gray_sum_rb = sum_rb;
    }
    if (metal_channel >= 0) {
        long long dielectric = 0, metal = 0, between = 0;
        for (long long i = 0; i < n; ++i) {
            const float m = px[static_cast<size_t>(i * channels + metal_channel)];
            if (m <= t.dielectric_max) ++dielectric;
            else if (m >= t.metal_min) ++metal;
            else if (std::isfinite(m)) ++between;
        }
        metal_dielectric += dielectric, metal_metal += metal, metal_between += between;
    }
    if (opacity_channel >= 0 && opacity_channel < channels) {
        long long invisible = 0, below = 0;
        const auto inv = static_cast<float>(t.opacity_invisible_max), cut = static_cast<float>(t.opacity_visible);
        for (long long i = 0; i < n; ++i) {
            const float o = px[static_cast<size_t>(i * channels + opacity_channel)];
            invisible += o <= inv ? 1 : 0;  // NaN counts as neither
            below += o < cut ? 1 : 0;
        }
        opacity_invisible += invisible, opacity_below_cutoff += below;
    }
    if (is_normal() && channels >= 2) normal_band(n, px);
}

namespace {

// 2 · decode(c) − 1 of an integer file's value c = code / scale in [0, 1]: its 16-bit code (8-bit
// k is 257 k) indexes the decode table (`lut`, srgb_decode_table) exactly.
float srgb_normal_component(const float* lut, float c) {
    // NOLINTNEXTLINE(bugprone-incorrect-roundings): c is a code / scale in [0, 1]
    return 2.f * lut[static_cast<size_t>(c * 65535.f + 0.5f)] - 1.f;
}

// srgb_normal_component of every 8-bit code's float.
const std::array<float, 256>& srgb_normal_codes() {
    static const std::array<float, 256> table = unorm8_table([](float c) {
        return srgb_normal_component(srgb_decode_table().data(), c);
    });
    return table;
}

}  // namespace

// min, max and code sums of an integer file's band of 1-4 channels: blocks of lcm(channels,
// lanes) samples, as whole vectors whose lane's channel is fixed by its place in the block
// ((lanes j + lane) mod channels); the rest sample by sample. The same figures as one channel at
// a time, several times faster (GCC vector types: SSE2 on any x86-64, NEON on ARM). The table
// rises with the code, so the smallest and largest code give the smallest and largest value.
template <class L>
void MapStats::codes_band(long long n, const typename L::T* px, const L& lanes) {
    using T = typename L::T;
    if (n <= 0) return;
    const auto nc = static_cast<size_t>(channels);
    const size_t vectors = nc == 3 ? 3 : 1;  // per block
    const size_t total = static_cast<size_t>(n) * nc;
    typename L::Vec mn[3], mx[3];
    long long wide[3][L::kLanes] = {};
    const size_t done = vectors == 3 ? lane_blocks<3>(px, total, lanes, mn, mx, wide)
                                     : lane_blocks<1>(px, total, lanes, mn, mx, wide);
    T cmin[4] = {L::kTop, L::kTop, L::kTop, L::kTop}, cmax[4] = {L::kBottom, L::kBottom, L::kBottom, L::kBottom};
    long long csum[4] = {};
    for (size_t j = 0; j < vectors; ++j)
        for (size_t l = 0; l < L::kLanes; ++l) {
            const size_t c = (L::kLanes * j + l) % nc;
            cmin[c] = std::min(cmin[c], T{mn[j][l]});
            cmax[c] = std::max(cmax[c], T{mx[j][l]});
            csum[c] += wide[j][l];
        }
    for (size_t i = done; i < total; ++i) {
        const size_t c = i % nc;
        cmin[c] = std::min(cmin[c], px[i]);
        cmax[c] = std::max(cmax[c], px[i]);
        csum[c] += lanes.code(px[i]);
    }
    for (size_t c = 0; c < nc; ++c) {
        min[c] = std::min(min[c], lanes.value(cmin[c]));
        max[c] = std::max(max[c], lanes.value(cmax[c]));
        code_sum[c] += csum[c];
        finite[c] += n;
    }
}

// The normal-map statistics of one band: the stored vectors, and the vectors the same codes
// would give if the file were sRGB-encoded (integer files only). Blocks of pixels are read into
// planes of components (a code through its table, as the float would be), then the figures are
// taken four pixels at a time: float math per pixel (the figures need a few digits), float sums
// per lane over a block (16 values), double sums over blocks, integer counts, no branch on the
// pixel's values.
template <class P>
void MapStats::normal_band(long long n, P px) {
    using namespace simd;
    if (n <= 0) return;
    const bool is_signed = normal_signed == 1;
    const auto nc = static_cast<size_t>(channels);
    const bool rgb = channels >= 3 && normal_z != 1;  // else z is rebuilt from x and y
    const bool srgb = !input.info.is_float && code_scale > 0.f;
    const F4 len_tol = F4{} + static_cast<float>(t.normal_length_tolerance),
             z_eps = F4{} + static_cast<float>(t.normal_z_epsilon),
             gtol = F4{} + static_cast<float>(is_jpeg ? t.grayscale_tolerance_jpeg : t.grayscale_tolerance);
    const F4 a = F4{} + (is_signed ? 1.f : 2.f), b = F4{} + (is_signed ? 0.f : -1.f);  // n = a c + b
    const F4 zero{}, one = F4{} + 1.f;
    // The components as if sRGB-encoded: an 8-bit band's codes through a table of them, a float
    // band's values through srgb_normal_component (the table's entries are its values).
    const float* lut = std::is_same_v<P, CodeReader> ? srgb_normal_codes().data() : srgb_decode_table().data();
    auto dec = [&px, lut](size_t i) {
        if constexpr (std::is_same_v<P, CodeReader>) return lut[px.p[i]];
        else return srgb_normal_component(lut, px[i]);
    };
    I4 bad_length{}, negative_z{}, upward{}, grey{}, srgb_upward{};
    Sum4 sum_length, sum_z, sxx, syy, ssx, ssy, ssl;
    constexpr size_t kBlock = 64;
    alignas(16) float c[3][kBlock] = {}, s[3][kBlock] = {};
    const auto total_px = static_cast<size_t>(n);
    for (size_t i0 = 0; i0 < total_px; i0 += kBlock) {
        const size_t m = std::min(kBlock, total_px - i0), m4 = (m + 3) & ~size_t{3};
        for (size_t i = 0; i < m; ++i) {
            const size_t q = (i0 + i) * nc;
            c[0][i] = px[q], c[1][i] = px[q + 1], c[2][i] = nc >= 3 ? px[q + 2] : 0.f;
            if (srgb) s[0][i] = dec(q), s[1][i] = dec(q + 1), s[2][i] = rgb ? dec(q + 2) : 0.f;
        }
        for (size_t i = m; i < m4; ++i)  // lanes past the band: zeros, masked out below
            for (size_t k = 0; k < 3; ++k) c[k][i] = s[k][i] = 0.f;
        // Two passes over the block (the stored vectors, then the sRGB ones): each keeps its
        // accumulators in registers. Float sums a block, added to the double sums once a block.
        F4 b_len{}, b_z{}, b_xx{}, b_yy{};
        for (size_t i = 0; i < m4; i += 4) {
            const I4 valid = I4{0, 1, 2, 3} + static_cast<int32_t>(i) < static_cast<int32_t>(m);
            const F4 c0 = load4(&c[0][i]), c1 = load4(&c[1][i]), c2 = load4(&c[2][i]);
            const F4 x = a * c0 + b, y = a * c1 + b;
            const F4 xy = x * x + y * y;
            // Two channels (BC5-style): z rebuilt, the length is 1 unless x, y alone exceed it.
            const F4 z = rgb ? a * c2 + b : sqrt4(max4(zero, one - xy));
            const F4 len = rgb ? sqrt4(xy + z * z) : max4(one, sqrt4(xy));
            const I4 ok = valid & finite4(len);
            if (channels >= 3) grey += valid & (max4(max4(abs4(c0 - c1), abs4(c0 - c2)), abs4(c1 - c2)) <= gtol);
            bad_length += ok & (abs4(len - one) > len_tol);
            negative_z += ok & (z < -z_eps);
            upward += ok & (z >= zero) & (z * z >= xy);
            b_len += keep(len, ok);
            b_z += keep(z, ok);
            b_xx += keep(x * x, ok);
            b_yy += keep(y * y, ok);
        }
        sum_length.add(b_len), sum_z.add(b_z), sxx.add(b_xx), syy.add(b_yy);
        if (!srgb) continue;
        F4 b_sx{}, b_sy{}, b_sl{};
        for (size_t i = 0; i < m4; i += 4) {
            const I4 valid = I4{0, 1, 2, 3} + static_cast<int32_t>(i) < static_cast<int32_t>(m);
            const F4 sx = load4(&s[0][i]), sy = load4(&s[1][i]), sz = load4(&s[2][i]);
            const F4 sxy = sx * sx + sy * sy;
            const F4 szr = rgb ? sz : sqrt4(max4(zero, one - sxy));
            b_sx += keep(sx, valid);
            b_sy += keep(sy, valid);
            b_sl += keep(sqrt4(sxy + szr * szr), valid);
            srgb_upward += valid & (szr >= zero) & (szr * szr >= sxy);
        }
        ssx.add(b_sx), ssy.add(b_sy), ssl.add(b_sl);
    }
    normal_bad_length += count(bad_length), normal_negative_z += count(negative_z);
    normal_upward += count(upward), normal_gray += count(grey);
    normal_sum_length += sum_length.total(), normal_sum_z += sum_z.total();
    normal_sum_xx += sxx.total(), normal_sum_yy += syy.total();
    if (!srgb) return;
    normal_srgb_upward += count(srgb_upward);
    normal_srgb_sum_x += ssx.total(), normal_srgb_sum_y += ssy.total(), normal_srgb_sum_length += ssl.total();
}

bool MapStats::normal_invalid() const {
    if (!is_normal()) return false;
    if (channels < 2) return true;
    const NormalSummary s = normal_summary();
    return !s.gamma_encoded && !s.invalid.empty();
}

Figures NormalSummary::figures() const {
    Figures j{{"mean_x", mean_x},
              {"mean_y", mean_y},
              {"mean_z", mean_z},
              {"mean_length", mean_length},
              {"std_x", std_x},
              {"std_y", std_y},
              {"bad_length_share", bad_length_share},
              {"negative_z_share", negative_z_share},
              {"upward_share", upward_share},
              {"gray_share", gray_share}};
    if (srgb_measured) {
        j["srgb_decoded_mean_x"] = srgb_mean_x;
        j["srgb_decoded_mean_y"] = srgb_mean_y;
        j["srgb_decoded_mean_length"] = srgb_mean_length;
        j["srgb_decoded_upward_share"] = srgb_upward_share;
    }
    return j;
}

NormalSummary MapStats::normal_summary() const {
    NormalSummary s;
    if (pixels == 0 || channels < 2) return s;
    const auto np = static_cast<double>(pixels);
    // Means of x and y from the (exact) channel sums: x = 2c − 1 is linear in c.
    auto mean_dec = [&](int c) { return normal_signed == 1 ? mean(c) : 2.0 * mean(c) - 1.0; };
    s.mean_x = mean_dec(0);
    s.mean_y = mean_dec(1);
    s.mean_z = normal_sum_z / np;
    s.mean_length = normal_sum_length / np;
    s.std_x = std::sqrt(std::max(0.0, normal_sum_xx / np - s.mean_x * s.mean_x));
    s.std_y = std::sqrt(std::max(0.0, normal_sum_yy / np - s.mean_y * s.mean_y));
    s.bad_length_share = ratio(normal_bad_length, pixels);
    s.negative_z_share = ratio(normal_negative_z, pixels);
    s.upward_share = ratio(normal_upward, pixels);
    s.gray_share = channels >= 3 ? ratio(normal_gray, pixels) : 0.0;
    s.srgb_measured = !input.info.is_float && code_scale > 0.f;
    if (s.srgb_measured) {
        s.srgb_mean_x = normal_srgb_sum_x / np;
        s.srgb_mean_y = normal_srgb_sum_y / np;
        s.srgb_mean_length = normal_srgb_sum_length / np;
        s.srgb_upward_share = ratio(normal_srgb_upward, pixels);
        // Decoded, it must be a tangent-space map: X/Y centred, pointing up, length about 1.
        s.gamma_encoded = s.mean_x > t.normal_gamma_min_stored_mean_xy &&
                          s.mean_y > t.normal_gamma_min_stored_mean_xy &&
                          std::abs(s.srgb_mean_x) <= t.normal_max_mean_xy &&
                          std::abs(s.srgb_mean_y) <= t.normal_max_mean_xy &&
                          s.srgb_upward_share >= t.normal_min_upward_share && s.gray_share <= t.normal_max_gray_share &&
                          (channels < 3 ||
                           std::abs(s.srgb_mean_length - 1.0) <= t.normal_gamma_max_decoded_length_error);
    }
    if (!s.gamma_encoded) {
        // Each test on its own names a kind of wrong map; the message lists every one that fails.
        if (s.upward_share < t.normal_min_upward_share)
            s.invalid.push_back("only " + percent(s.upward_share) +
                                " of the vectors lie within 45 degrees of +Z (a tangent-space map: most)");
        if (std::abs(s.mean_x) > t.normal_max_mean_xy || std::abs(s.mean_y) > t.normal_max_mean_xy)
            s.invalid.push_back("X/Y average (" + fixed(s.mean_x, 3) + ", " + fixed(s.mean_y, 3) +
                                "), not about 0 (codes about 128)");
        if (s.negative_z_share > t.normal_max_negative_z_share)
            s.invalid.push_back(percent(s.negative_z_share) + " point into the surface (Z < 0)");
        if (s.gray_share > t.normal_max_gray_share)
            s.invalid.push_back("R = G = B in " + percent(s.gray_share) + " of the pixels (a greyscale map)");
    }
    s.not_unit_length = s.invalid.empty() && s.bad_length_share > t.normal_max_bad_length_share;
    return s;
}

void MapStats::Emit::operator()(std::string_view code, std::string r, std::string msg, Figures fig) const {
    out.push_back(finding(code, std::move(r), file, std::move(msg), std::move(fig)));
}

// Each rule group below is a stage of findings(), in this order (findings of one code keep the
// order they are raised in; validate_set then sorts by catalog order).
void MapStats::findings(std::vector<Finding>& out) const {
    if (pixels == 0) return;
    const Emit add{input.name.empty() ? input.file.display : input.name, std::string(role_name(input.role)), out};
    value_findings(add);
    grayscale_findings(add);
    packed_findings(add);
    constant_findings(add);
    metalness_findings(add);
    opacity_findings(add);
    normal_findings(add);
    tag_findings(add);
}

// NONFINITE_VALUES, OUT_OF_RANGE_VALUES.
void MapStats::value_findings(const Emit& add) const {
    const std::string& file = add.file;
    const std::string& role = add.role;
    const int nc = std::min(channels, 4);
    auto channel_list = [&](const std::array<double, 4>& a) { return std::vector<double>(a.begin(), a.begin() + nc); };
    if (nan + inf > 0 && ratio(nan + inf, samples) > t.nonfinite_max_share) {
        add(code::nonfinite_values, role,
            file + ": " + std::to_string(nan) + " NaN and " + std::to_string(inf) +
                " Inf values; re-export the map with finite values (they propagate through "
                "filtering and mipmapping)",
            {{"nan", nan}, {"inf", inf}, {"samples", samples}, {"share", ratio(nan + inf, samples)}});
    }
    // OUT_OF_RANGE_VALUES (float inputs only: integer files cannot leave [0, 1])
    const double oor = ratio(out_of_range_pixels, pixels);
    if (out_of_range_pixels > 0 && oor > t.out_of_range_max_share) {
        add(code::out_of_range_values, role,
            file + ": " + percent(oor) + " of pixels hold " + role + " values outside [" + (is_normal() ? "-1" : "0") +
                ", 1] (min " + fixed(*std::min_element(min.begin(), min.begin() + nc), 3) + ", max " +
                fixed(*std::max_element(max.begin(), max.begin() + nc), 3) + "); they will be clamped",
            [&] {
                Figures fig{{"pixels", out_of_range_pixels}, {"share", oor}, {"epsilon", t.range_epsilon}};
                // A channel with no finite value has no extremes to state (NONFINITE_VALUES says so).
                if (std::all_of(finite.begin(), finite.begin() + nc, [](auto n) { return n > 0; })) {
                    fig["min"] = channel_list(min);
                    fig["max"] = channel_list(max);
                }
                return fig;
            }());
    }
}

// NOT_GRAYSCALE.
void MapStats::grayscale_findings(const Emit& add) const {
    const std::string& file = add.file;
    const std::string& role = add.role;
    if (scalar_role() && channels >= 3) {
        const double share = ratio(gray_differing, pixels);
        const double tol = is_jpeg ? t.grayscale_tolerance_jpeg : t.grayscale_tolerance;
        if (share > t.grayscale_max_share) {
            add(code::not_grayscale, role,
                file + ": " + role + " is a scalar map but its R, G and B differ by more than " + fixed(tol * 255, 0) +
                    "/255 in " + percent(share) + " of pixels (largest difference " + fixed(gray_max_diff * 255, 0) +
                    "/255); matforge uses R — check that the file is not a packed or color map",
                {{"share", share},
                 {"max_difference", gray_max_diff},
                 {"mean_abs_rg", gray_sum_rg / static_cast<double>(pixels)},
                 {"mean_abs_rb", gray_sum_rb / static_cast<double>(pixels)},
                 {"tolerance", tol},
                 {"jpeg", is_jpeg}});
        }
    }
}

// PACKED_CHANNELS_IDENTICAL: R, G and B of an ORM-style map hold one image (a greyscale map
// saved under a packed name), so occlusion, roughness and metalness would all be that image. A
// constant image is left to CONSTANT_MAP (each channel is said there). Same tolerance and share
// as NOT_GRAYSCALE: "identical" is what NOT_GRAYSCALE calls grey.
void MapStats::packed_findings(const Emit& add) const {
    if (!packed_rgb()) return;
    const double tol = is_jpeg ? t.constant_tolerance_jpeg : t.constant_tolerance;
    bool varies = false;
    for (int c = 0; c < 3; ++c) varies = varies || (finite[c] > 0 && max[c] - min[c] > tol);
    const double share = ratio(gray_differing, pixels);
    if (!varies || share > t.grayscale_max_share) return;
    std::vector<std::string> roles(3);
    for (int c = 0; c < 3; ++c) roles[static_cast<size_t>(c)] = role_name(*channel_role(input.role, c));
    add(code::packed_channels_identical, add.role,
        add.file + ": R, G and B hold one image (they differ in " + percent(share) +
            " of pixels): a greyscale map saved under a packed name, so " + roles[0] + ", " + roles[1] + " and " +
            roles[2] + " would all be that image — check that the file is the packed export",
        {{"share", share},
         {"max_difference", gray_max_diff},
         {"tolerance", is_jpeg ? t.grayscale_tolerance_jpeg : t.grayscale_tolerance},
         {"jpeg", is_jpeg},
         {"channels", roles}});
}

// CONSTANT_MAP: per channel group (packed inputs: per channel role).
void MapStats::constant_findings(const Emit& add) const {
    const std::string& file = add.file;
    const double tol = is_jpeg ? t.constant_tolerance_jpeg : t.constant_tolerance;
    std::vector<std::pair<std::vector<int>, Role>> groups;
    if (traits(input.role).packed) {
        for (int c = 0; c < std::min(channels, 4); ++c)
            if (auto r = channel_role(input.role, c)) groups.push_back({{c}, *r});
    } else if (scalar_role()) {
        groups.push_back({{0}, input.role});
    } else {
        std::vector<int> g;
        for (int c = 0; c < std::min(channels, 3); ++c) g.push_back(c);
        groups.emplace_back(std::move(g), input.role);
    }
    for (const auto& group : groups) {
        // Named, not a structured binding: the lambda below captures chs (clang < 16 cannot).
        const std::vector<int>& chs = group.first;
        const Role r = group.second;
        bool constant = true;
        std::vector<double> value, range;
        std::vector<std::string> letters;
        for (int c : chs) {
            letters.emplace_back(channel_letter(c));
            if (finite[c] == 0 || max[c] - min[c] > tol) constant = false;
            value.push_back(mean(c));
            range.push_back(finite[c] ? max[c] - min[c] : 0.0);
        }
        if (!constant) continue;
        std::string where = file;
        if (traits(input.role).packed) where = "channel " + std::string(channel_letter(chs[0])) + " of " + file;
        std::string vtext;
        for (size_t i = 0; i < value.size(); ++i) vtext += (i ? ", " : "") + fixed(value[i], 3);
        add(code::constant_map, std::string(role_name(r)),
            where + " holds one value (" + vtext + "); a constant or a 2x2 map does the same",
            {{"value", value}, {"range", range}, {"tolerance", tol}, {"channels", letters}});
    }
}

// METALNESS_NOT_BINARY.
void MapStats::metalness_findings(const Emit& add) const {
    const std::string& file = add.file;
    if (metal_channel >= 0) {
        const long long total = metal_dielectric + metal_metal + metal_between;
        const double share = ratio(metal_between, total);
        if (share > t.metalness_max_intermediate_share) {
            add(code::metalness_not_binary, "metalness",
                (traits(input.role).packed ? "channel " + std::string(channel_letter(metal_channel)) + " of "
                                           : std::string()) +
                    file + ": " + percent(share) + " of pixels have metalness between " + fixed(t.dielectric_max, 2) +
                    " and " + fixed(t.metal_min, 2) +
                    "; real surfaces are metal or not — use grey only for transitions (rust, dirt)",
                {{"share_between", share},
                 {"share_dielectric", ratio(metal_dielectric, total)},
                 {"share_metal", ratio(metal_metal, total)},
                 {"dielectric_max", t.dielectric_max},
                 {"metal_min", t.metal_min},
                 {"max_share", t.metalness_max_intermediate_share}});
        }
    }
}

bool MapStats::all_transparent() const {
    return opacity_channel >= 0 && opacity_channel < channels &&
           ratio(opacity_invisible, pixels) > t.opacity_max_invisible_share;
}

// OPACITY_ALL_TRANSPARENT.
void MapStats::opacity_findings(const Emit& add) const {
    const std::string& file = add.file;
    if (!all_transparent()) return;
    const double share = ratio(opacity_invisible, pixels);
    const bool alpha = input.role != Role::opacity;
    const int oc = std::min(opacity_channel, 3);
    add(code::opacity_all_transparent, "opacity",
        (alpha ? "the alpha of " + file + " (the set's opacity: it has no opacity map)" : file) + ": " +
            percent(share) + " of pixels have opacity at most " + fixed(t.opacity_invisible_max, 2) + " (max " +
            fixed(max[oc], 3) +
            "): it would make the whole material invisible, so it is not applied (the material is "
            "written opaque) — if the map stores transparency, invert it; if it is a placeholder, remove "
            "it",
        {{"invisible_share", share},
         {"invisible_max", t.opacity_invisible_max},
         {"below_cutoff_share", ratio(opacity_below_cutoff, pixels)},
         {"cutoff", t.opacity_visible},
         {"max", max[oc]},
         {"channel", channel_letter(oc)},
         {"max_share", t.opacity_max_invisible_share}});
}

// NORMAL_Z_RECONSTRUCTED, NORMAL_INVALID, NORMAL_GAMMA_ENCODED, NORMAL_NOT_UNIT_LENGTH.
void MapStats::normal_findings(const Emit& add) const {
    if (!is_normal()) return;
    const std::string& file = add.file;
    const std::string& role = add.role;
    if (rebuilds_z()) {
        const std::string what = channels == 2 ? "two channels (X, Y)"
                                               : "a blue channel holding one value (B = " + fixed(max[2], 3) + ")";
        add(code::normal_z_reconstructed, role,
            file + ": stored with " + what + ", as BC5 exports leave it: Z is reconstructed as sqrt(1 - x² - y²)",
            {{"channels", channels},
             {"blue_min", channels >= 3 ? min[2] : 0.0},
             {"blue_max", channels >= 3 ? max[2] : 0.0}});
    }
    if (channels < 2) {
        add(code::normal_invalid, role,
            file + ": a one-channel image cannot be a tangent-space normal map (is it a "
                   "height or bump map?)",
            {{"channels", channels}});
        return;
    }
    const NormalSummary s = normal_summary();
    Figures fig = s.figures();
    fig["decoding"] = std::string(normal_signed == 1 ? "signed" : "2c-1");
    // The summary's figures and the thresholds the finding was judged by.
    auto with = [&fig](const Figures& thresholds) {
        Figures g = fig;
        for (const auto& [name, v] : thresholds) g.insert_or_assign(name, v);
        return g;
    };
    if (s.gamma_encoded) {
        add(code::normal_gamma_encoded, role,
            file + ": stored sRGB/gamma-encoded: mean R, G = " + fixed(127.5 * (s.mean_x + 1), 1) + ", " +
                fixed(127.5 * (s.mean_y + 1), 1) + " instead of about 128 (X/Y centred at " +
                fixed(0.5 * (s.mean_x + 1), 2) + ", " + fixed(0.5 * (s.mean_y + 1), 2) +
                ", not 0.5); decoded with the sRGB curve they average " + fixed(s.srgb_mean_x, 2) + ", " +
                fixed(s.srgb_mean_y, 2) + " with mean length " + fixed(s.srgb_mean_length, 2) +
                " — re-export it as linear data (no sRGB conversion)",
            with({{"min_stored_mean_xy", t.normal_gamma_min_stored_mean_xy},
                  {"max_mean_xy", t.normal_max_mean_xy},
                  {"min_upward_share", t.normal_min_upward_share},
                  {"max_decoded_length_error", t.normal_gamma_max_decoded_length_error}}));
    } else if (!s.invalid.empty()) {
        std::string why;
        for (const auto& w : s.invalid) why += (why.empty() ? "" : "; ") + w;
        add(code::normal_invalid, role,
            file + ": not a tangent-space normal map: " + why +
                " — is it a height, color or object-space map named as normal?",
            with({{"min_upward_share", t.normal_min_upward_share},
                  {"max_mean_xy", t.normal_max_mean_xy},
                  {"max_negative_z_share", t.normal_max_negative_z_share},
                  {"max_gray_share", t.normal_max_gray_share}}));
    }
    if (s.not_unit_length) {
        add(code::normal_not_unit_length, role,
            file + ": vectors not unit length (mean |2c-1| = " + fixed(s.mean_length, 3) + ", " +
                percent(s.bad_length_share) + " off by > " + fixed(t.normal_length_tolerance, 1) +
                "); renormalized on ingest",
            with({{"length_tolerance", t.normal_length_tolerance},
                  {"max_bad_length_share", t.normal_max_bad_length_share}}));
    }
}

// COLOR_SPACE_MISMATCH (the file's color tag against the role).
void MapStats::tag_findings(const Emit& add) const {
    const std::string& file = add.file;
    const std::string& role = add.role;
    const ColorTag tag = input.color_tag.tag;
    const bool color = is_color_role(input.role);
    Figures tagfig{{"tag", color_tag_name(tag)},
                   {"tag_source", input.color_tag.source},
                   {"tag_value", input.color_tag.value}};
    if (!color && (tag == ColorTag::srgb || tag == ColorTag::other)) {
        // An ICC profile of any name on a data map is a color statement too.
        tagfig["expected"] = "linear";
        add(code::color_space_mismatch, role,
            file + ": " +
                (tag == ColorTag::srgb
                     ? "tagged sRGB (" + input.color_tag.source + ")"
                     : "carries a color profile (" + input.color_tag.source + " \"" + input.color_tag.value + "\")") +
                " but holds " + role +
                " data; matforge reads it as data by its role and ignores the tag (other tools "
                "that honour it would decode it as color: re-export it untagged or as linear/raw)",
            tagfig);
    } else if (color && !input.info.is_float && tag == ColorTag::linear) {
        tagfig["expected"] = "srgb";
        add(code::color_space_mismatch, role,
            file + ": an 8/16-bit " + role +
                " map is sRGB-encoded by convention but the file is "
                "tagged linear (" +
                input.color_tag.source + "); check how it was exported",
            tagfig);
    } else if (color && input.info.is_float && tag == ColorTag::srgb) {
        tagfig["expected"] = "linear";
        add(code::color_space_mismatch, role,
            file + ": a float " + role + " map is read as linear but the file is tagged sRGB (" +
                input.color_tag.source + ")",
            tagfig);
    }
}

}  // namespace mf::validate::detail
