#include "report/images.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <type_traits>
#include <vector>

#include "base/srgb.hpp"
#include "validate/albedo_class.hpp"
#include "validate/validate.hpp"

namespace mf::report {
namespace {

// The sRGB curves through 65536-step tables with linear interpolation: within 1e-6 of the exact
// IEC 61966-2-1 functions (base/srgb.hpp) on [0, 1], a few ns per value instead of a pow.
constexpr int kSteps = 65536;
struct Curve {
    std::vector<float> table;
    explicit Curve(bool decode) : table(kSteps + 1) {
        for (int i = 0; i <= kSteps; ++i) {
            const double v = static_cast<double>(i) / kSteps;
            table[static_cast<size_t>(i)] = static_cast<float>(decode ? srgb_to_linear(v) : linear_to_srgb(v));
        }
    }
    float operator()(float v) const {
        const float c = v > 0.f ? (v < 1.f ? v : 1.f) : 0.f;  // NaN -> 0
        const float f = c * kSteps;
        const auto i = static_cast<size_t>(f);
        if (i >= kSteps) return table[kSteps];
        const float t = f - static_cast<float>(i);
        return table[i] + t * (table[i + 1] - table[i]);
    }
};
const Curve& decode_curve() {
    static const Curve c(true);
    return c;
}
const Curve& encode_curve() {
    static const Curve c(false);
    return c;
}

float clamp01(float v) { return v > 0.f ? (v < 1.f ? v : 1.f) : 0.f; }

// Output size of a box reduction to at most max_size on the long side (never larger).
void reduced_size(int w, int h, int max_size, int& ow, int& oh) {
    const int longest = std::max(w, h);
    if (longest <= max_size) {
        ow = w;
        oh = h;
        return;
    }
    const double s = static_cast<double>(max_size) / longest;
    ow = std::max(1, static_cast<int>(std::lround(w * s)));
    oh = std::max(1, static_cast<int>(std::lround(h * s)));
}

// The boxes of a reduction of w x h to at most max_size on the long side (max_size <= 0: none):
// source column x goes to output column x * ow / w, and output row oy holds the source rows
// [row_end(oy - 1), row_end(oy)).
struct BoxGrid {
    int w = 0, h = 0, ow = 0, oh = 0;
    bool identity = true;
    std::vector<int> col0;  // output column ox holds source columns [col0[ox], col0[ox + 1])

    BoxGrid(int width, int height, int max_size) : w(width), h(height) {
        if (max_size <= 0) ow = w, oh = h;
        else reduced_size(w, h, max_size, ow, oh);
        identity = ow == w && oh == h;
        if (identity) return;
        col0.assign(static_cast<size_t>(ow) + 1, w);
        for (int x = w - 1; x >= 0; --x) col0[static_cast<size_t>(static_cast<int64_t>(x) * ow / w)] = x;
        for (auto ox = static_cast<size_t>(ow); ox-- > 0;)  // (no output column is empty when ow <= w)
            col0[ox] = std::min(col0[ox], col0[ox + 1]);
    }
    int row_end(int oy) const {
        const int y0 = static_cast<int>(static_cast<int64_t>(oy) * h / oh);
        return std::max(y0 + 1, static_cast<int>(static_cast<int64_t>(oy + 1) * h / oh));
    }
    size_t columns(size_t ox) const { return static_cast<size_t>(col0[ox + 1] - col0[ox]); }
};

// Box reduction of an RGB image (values averaged as they are), fed row by row: each output row
// is finished as its last source row arrives, so no full-size intermediate is held (an 8192²
// RGB float picture is 768 MB). Each output pixel's sum is taken in double, source rows in
// order and each row's columns left to right.
class BoxReducer {
public:
    BoxReducer(int w, int h, int max_size) : g_(w, h, max_size) {
        out_ = Image(g_.ow, g_.oh, 3);
        if (g_.identity) return;
        acc_.assign(static_cast<size_t>(g_.ow) * 3, 0.0);
        y1_ = g_.row_end(0);
    }
    // Rows in order, 0 to h - 1, three floats a pixel.
    void add_row(int y, const float* rgb) {
        if (g_.identity) {
            std::copy_n(rgb, static_cast<size_t>(g_.w) * 3, &out_.pixels[out_.index(0, y)]);
            return;
        }
        while (y >= y1_) flush();
        for (size_t ox = 0; ox < static_cast<size_t>(g_.ow); ++ox) {
            double a0 = acc_[ox * 3], a1 = acc_[ox * 3 + 1], a2 = acc_[ox * 3 + 2];
            for (auto x = static_cast<size_t>(g_.col0[ox]); x < static_cast<size_t>(g_.col0[ox + 1]); ++x) {
                a0 += rgb[x * 3];
                a1 += rgb[x * 3 + 1];
                a2 += rgb[x * 3 + 2];
            }
            acc_[ox * 3] = a0;
            acc_[ox * 3 + 1] = a1;
            acc_[ox * 3 + 2] = a2;
        }
        ++rows_;
        if (y == g_.h - 1) flush();
    }
    Image take() { return std::move(out_); }

private:
    void flush() {
        for (size_t ox = 0; ox < static_cast<size_t>(g_.ow); ++ox) {
            const auto count = static_cast<double>(g_.columns(ox) * rows_);
            for (size_t c = 0; c < 3; ++c)
                out_.at(static_cast<int>(ox), oy_, static_cast<int>(c)) = static_cast<float>(acc_[ox * 3 + c] / count);
        }
        std::fill(acc_.begin(), acc_.end(), 0.0);
        rows_ = 0;
        y1_ = ++oy_ < g_.oh ? g_.row_end(oy_) : g_.h;
    }

    BoxGrid g_;
    int oy_ = 0, y1_ = 0;
    size_t rows_ = 0;  // source rows summed into the output row being made
    Image out_;
    std::vector<double> acc_;
};

// The box means of channels [first, first + n) (n of 1 to 3) of 8-bit codes, code k standing for
// table[k], or nullopt where they cannot be made exactly this way (then BoxReducer makes them).
// Every table value here is a multiple of 2^-35 in [0, 1] (floats of at least 2^-12, and 0: so
// are unorm8_values, their sRGB decode and their clamp), so BoxReducer's double sums of a box of
// at most 2^18 pixels never round: they equal these integer sums of the values in units of
// 2^-35, taken in any order, and the means are the same floats bit for bit — at a table load
// and an integer add a value, with no float row in between.
constexpr int kUnitBits = 35;
constexpr uint64_t kMaxBoxPixels = uint64_t{1} << (53 - kUnitBits);
constexpr double kUnit = 1.0 / static_cast<double>(uint64_t{1} << kUnitBits);  // 2^-35: scaling by it is exact

std::optional<Image> code_means(const Image8& src, int first, int n, const std::array<float, 256>& table,
                                const BoxGrid& g) {
    std::array<int64_t, 256> units{};
    for (size_t k = 0; k < table.size(); ++k) {
        const double u = std::ldexp(static_cast<double>(table[k]), kUnitBits);
        if (!(u >= 0.0 && u <= std::ldexp(1.0, kUnitBits)) || u != std::floor(u)) return std::nullopt;
        units[k] = static_cast<int64_t>(u);
    }
    const auto sc = static_cast<size_t>(src.channels), nc = static_cast<size_t>(n);
    Image out(g.ow, g.oh, n);
    if (g.identity) {
        for (size_t p = 0; p < static_cast<size_t>(g.w) * static_cast<size_t>(g.h); ++p)
            for (size_t c = 0; c < nc; ++c)
                out.pixels[p * nc + c] = table[src.pixels[p * sc + static_cast<size_t>(first) + c]];
        return out;
    }
    size_t widest = 0;
    for (size_t ox = 0; ox < static_cast<size_t>(g.ow); ++ox) widest = std::max(widest, g.columns(ox));
    int tallest = 0;
    for (int oy = 0, y0 = 0; oy < g.oh; y0 = g.row_end(oy++)) tallest = std::max(tallest, g.row_end(oy) - y0);
    if (widest * static_cast<uint64_t>(tallest) > kMaxBoxPixels) return std::nullopt;
    std::vector<int64_t> acc(static_cast<size_t>(g.ow) * nc);
    // One source row into the sums, for a channel count the compiler knows: the sums of a box
    // are held in registers along its columns (written out: GCC -O2 neither unrolls the channel
    // loop nor keeps a[c] out of memory).
    auto add_row = [&]<size_t NC>(const uint8_t* row) {
        const int64_t* u = units.data();
        for (size_t ox = 0; ox < static_cast<size_t>(g.ow); ++ox) {
            int64_t* a = &acc[ox * NC];
            int64_t a0 = a[0], a1 = 0, a2 = 0;
            if constexpr (NC > 1) a1 = a[1];
            if constexpr (NC > 2) a2 = a[2];
            const uint8_t* p = row + static_cast<size_t>(g.col0[ox]) * sc;
            for (auto x = static_cast<size_t>(g.col0[ox]); x < static_cast<size_t>(g.col0[ox + 1]); ++x, p += sc) {
                a0 += u[p[0]];
                if constexpr (NC > 1) a1 += u[p[1]];
                if constexpr (NC > 2) a2 += u[p[2]];
            }
            a[0] = a0;
            if constexpr (NC > 1) a[1] = a1;
            if constexpr (NC > 2) a[2] = a2;
        }
    };
    for (int oy = 0, y = 0; oy < g.oh; ++oy) {
        std::fill(acc.begin(), acc.end(), 0);
        const int y1 = g.row_end(oy);
        const auto rows = static_cast<size_t>(y1 - y);
        for (; y < y1; ++y) {
            const uint8_t* row = &src.pixels[src.index(0, y) + static_cast<size_t>(first)];
            if (nc == 1) add_row.operator()<1>(row);
            else if (nc == 2) add_row.operator()<2>(row);
            else add_row.operator()<3>(row);
        }
        for (size_t ox = 0; ox < static_cast<size_t>(g.ow); ++ox) {
            const auto count = static_cast<double>(g.columns(ox) * rows);
            for (size_t c = 0; c < nc; ++c)
                out.at(static_cast<int>(ox), oy,
                       static_cast<int>(c)) = static_cast<float>(static_cast<double>(acc[ox * nc + c]) * kUnit / count);
        }
    }
    return out;
}

// What a thumbnail shows of each 8-bit code: its float (unorm8_values) decoded from sRGB or
// clamped, through the same functions as a float picture's values, so the same floats.
std::array<float, 256> code_table(bool srgb) {
    return unorm8_table([srgb](float v) { return srgb ? decode_curve()(v) : clamp01(v); });
}

// One row of a scalar map sampled onto a w x h grid (Scalar::at for every x of row y): the
// source columns are found once per picture, not once per pixel.
class ScalarRows {
public:
    ScalarRows(const Scalar& s, int w, int h) : s_(s), h_(h), row_(static_cast<size_t>(w), s.constant) {
        const BasicImage<float>* f = s.image;
        const Image8* c = s.codes;
        iw_ = f ? f->width : c ? c->width : 0;
        ih_ = f ? f->height : c ? c->height : 0;
        const int ic = f ? f->channels : c ? c->channels : 0;
        if (iw_ == 0 || ih_ == 0 || ic == 0) return;  // the constant everywhere
        sampled_ = true;
        channel_ = static_cast<size_t>(std::min(s.channel, ic - 1));
        stride_ = static_cast<size_t>(ic);
        col_.resize(static_cast<size_t>(w));
        for (int x = 0; x < w; ++x) col_[static_cast<size_t>(x)] = validate::nearest_index(x, w, iw_);
        if (c)
            for (size_t k = 0; k < codes_.size(); ++k)
                codes_[k] = s.invert ? 1.f - unorm8_values()[k] : unorm8_values()[k];
    }
    const float* row(int y) {
        if (!sampled_) return row_.data();
        const int sy = validate::nearest_index(y, h_, ih_);
        if (s_.codes) {
            const size_t base = s_.codes->index(0, sy) + channel_;
            for (size_t x = 0; x < row_.size(); ++x)
                row_[x] = codes_[s_.codes->pixels[base + static_cast<size_t>(col_[x]) * stride_]];
        } else {
            const size_t base = s_.image->index(0, sy) + channel_;
            for (size_t x = 0; x < row_.size(); ++x) {
                const float v = s_.image->pixels[base + static_cast<size_t>(col_[x]) * stride_];
                row_[x] = s_.invert ? 1.f - v : v;
            }
        }
        return row_.data();
    }

private:
    const Scalar& s_;
    int h_, iw_ = 0, ih_ = 0;
    bool sampled_ = false;
    size_t channel_ = 0, stride_ = 1;
    std::vector<int> col_;
    std::array<float, 256> codes_{};
    std::vector<float> row_;
};

}  // namespace

namespace {

// A thumbnail made from box means of the source's channels (code_means): as thumbnail_of below.
std::optional<Image> thumbnail_from_means(const Image8& src, int max_size, bool srgb) {
    const int n = std::min(src.channels, 3);
    const std::optional<Image> means = code_means(src, 0, n, code_table(srgb),
                                                  BoxGrid(src.width, src.height, max_size));
    if (!means) return std::nullopt;
    Image out(means->width, means->height, 3);
    const Curve& enc = encode_curve();
    const auto nc = static_cast<size_t>(n);
    for (size_t p = 0; p < static_cast<size_t>(out.width) * static_cast<size_t>(out.height); ++p) {
        const float* m = &means->pixels[p * nc];
        // Two channels: (R, G, 0), 0 being what both the curve and the clamp make of 0.
        const float rgb[3] = {m[0], n > 1 ? m[1] : m[0], n > 2 ? m[2] : (n == 2 ? 0.f : m[0])};
        for (size_t c = 0; c < 3; ++c) out.pixels[p * 3 + c] = srgb ? enc(rgb[c]) : rgb[c];
    }
    return out;
}

template <class T>
Image thumbnail_of(const BasicImage<T>& src, int max_size, bool srgb) {
    if constexpr (std::is_same_v<T, uint8_t>)
        if (auto t = thumbnail_from_means(src, max_size, srgb)) return std::move(*t);
    BoxReducer reduce(src.width, src.height, max_size);
    std::vector<float> row(static_cast<size_t>(src.width) * 3);
    const auto sc = static_cast<size_t>(src.channels);
    // Each value as shown: a code through its table, a float through the curve or the clamp.
    std::array<float, 256> table{};
    if constexpr (std::is_same_v<T, uint8_t>) table = code_table(srgb);
    const Curve& dec = decode_curve();
    auto shown = [&](T v) {
        if constexpr (std::is_same_v<T, uint8_t>) return table[v];
        else return srgb ? dec(v) : clamp01(v);
    };
    const float zero = srgb ? dec(0.f) : 0.f;  // the blue of a two-channel picture
    for (int y = 0; y < src.height; ++y) {
        const T* s = &src.pixels[src.index(0, y)];
        for (size_t x = 0; x < static_cast<size_t>(src.width); ++x, s += sc) {
            const float r = shown(s[0]);
            row[x * 3] = r;
            row[x * 3 + 1] = sc > 1 ? shown(s[1]) : r;
            row[x * 3 + 2] = sc > 2 ? shown(s[2]) : (sc == 2 ? zero : r);
        }
        reduce.add_row(y, row.data());
    }
    Image out = reduce.take();
    if (srgb) {
        const Curve& enc = encode_curve();
        for (float& x : out.pixels) x = enc(x);
    }
    return out;
}

template <class T>
Image channel_thumbnail_of(const BasicImage<T>& src, int channel, int max_size) {
    const auto sc = static_cast<size_t>(src.channels);
    const auto ch = static_cast<size_t>(std::clamp(channel, 0, src.channels - 1));
    std::array<float, 256> table{};
    if constexpr (std::is_same_v<T, uint8_t>) {
        table = code_table(false);
        if (const auto means = code_means(src, static_cast<int>(ch), 1, table,
                                          BoxGrid(src.width, src.height, max_size))) {
            Image out(means->width, means->height, 3);
            for (size_t p = 0; p < means->pixels.size(); ++p)
                out.pixels[p * 3] = out.pixels[p * 3 + 1] = out.pixels[p * 3 + 2] = means->pixels[p];
            return out;
        }
    }
    BoxReducer reduce(src.width, src.height, max_size);
    std::vector<float> row(static_cast<size_t>(src.width) * 3);
    for (int y = 0; y < src.height; ++y) {
        const T* s = &src.pixels[src.index(0, y) + ch];
        for (size_t x = 0; x < static_cast<size_t>(src.width); ++x) {
            float v = 0.f;
            if constexpr (std::is_same_v<T, uint8_t>) v = table[s[x * sc]];
            else v = clamp01(s[x * sc]);
            row[x * 3] = row[x * 3 + 1] = row[x * 3 + 2] = v;
        }
        reduce.add_row(y, row.data());
    }
    return reduce.take();
}

}  // namespace

Image thumbnail(const Image& src, int max_size, bool srgb) { return thumbnail_of(src, max_size, srgb); }
Image thumbnail(const Image8& src, int max_size, bool srgb) { return thumbnail_of(src, max_size, srgb); }
Image channel_thumbnail(const Image& src, int channel, int max_size) {
    return channel_thumbnail_of(src, channel, max_size);
}
Image channel_thumbnail(const Image8& src, int channel, int max_size) {
    return channel_thumbnail_of(src, channel, max_size);
}

float Scalar::at(int x, int y, int w, int h) const {
    const int iw = image ? image->width : codes ? codes->width : 0;
    const int ih = image ? image->height : codes ? codes->height : 0;
    const int ic = image ? image->channels : codes ? codes->channels : 0;
    if (iw == 0 || ih == 0 || ic == 0) return constant;
    const int sx = validate::nearest_index(x, w, iw), sy = validate::nearest_index(y, h, ih);
    const int c = std::min(channel, ic - 1);
    const float v = image ? image->at(sx, sy, c) : unorm8_values()[codes->at(sx, sy, c)];
    return invert ? 1.f - v : v;
}

namespace {
template <class T>
Image albedo_overlay_of(const BasicImage<T>& albedo, bool albedo_srgb, const Scalar& metalness, const Scalar& opacity,
                        const rules::Thresholds& t, AlbedoStats& stats, int max_size) {
    stats = {};
    const int w = albedo.width, h = albedo.height;
    const validate::AlbedoClassifier classify(t, !albedo_srgb);
    BoxReducer reduce(w, h, max_size);
    std::vector<float> row(static_cast<size_t>(w) * 3);
    const Curve& enc = encode_curve();
    const int cell = std::max(1, std::max(w, h) / 32);  // checkerboard of invisible pixels: 32 cells across
    const auto ac = static_cast<size_t>(albedo.channels);
    // Overlay colours lie in [0, 1]: what a thumbnail's clamp would leave as it is.
    auto put = [&row](int x, const float* rgb, float scale) {
        for (size_t c = 0; c < 3; ++c) row[static_cast<size_t>(x) * 3 + c] = rgb[c] * scale;
    };
    ScalarRows opacity_rows(opacity, w, h), metalness_rows(metalness, w, h);
    for (int y = 0; y < h; ++y) {
        const float* opacity_row = opacity_rows.row(y);
        const float* metalness_row = metalness_rows.row(y);
        const T* s = &albedo.pixels[albedo.index(0, y)];
        for (int x = 0; x < w; ++x, s += ac) {
            ++stats.pixels;
            // As the rules: a pixel whose opacity is below the cutoff (or not a number) is not judged.
            const float o = opacity_row[x];
            const T rgb[3] = {s[0], ac > 1 ? s[1] : s[0], ac > 2 ? s[2] : s[0]};
            const float luminance = classify.luminance(rgb);  // of codes: bit for bit their floats'
            const validate::AlbedoJudgement j = o >= t.opacity_visible ? classify.judge(luminance, metalness_row[x])
                                                                       : validate::AlbedoJudgement{};
            if (!j.counted) {
                const float g = ((x / cell + y / cell) % 2) ? 0.30f : 0.18f;
                const float grey[3] = {g, g, g};
                put(x, grey, 1.f);
                continue;
            }
            stats.counts.add(j);
            const float shown = enc(luminance);  // display value of the luminance
            const float dark = static_cast<float>(j.dark_weight()) / validate::kWeightUnit;
            const float bright = static_cast<float>(j.bright_weight()) / validate::kWeightUnit;
            if (dark == 1.f) put(x, kTooDark, 1.f);
            else if (bright == 1.f) put(x, kTooBright, 1.f);
            else {
                const float rest = 1.f - dark - bright;
                const float mix[3] = {dark * kTooDark[0] + bright * kTooBright[0] + rest * shown,
                                      dark * kTooDark[1] + bright * kTooBright[1] + rest * shown,
                                      dark * kTooDark[2] + bright * kTooBright[2] + rest * shown};
                put(x, mix, 1.f);
            }
        }
        reduce.add_row(y, row.data());
    }
    return reduce.take();
}
}  // namespace

Image albedo_overlay(const Image& albedo, bool albedo_srgb, const Scalar& metalness, const Scalar& opacity,
                     const rules::Thresholds& t, AlbedoStats& stats, int max_size) {
    return albedo_overlay_of(albedo, albedo_srgb, metalness, opacity, t, stats, max_size);
}
Image albedo_overlay(const Image8& albedo, bool albedo_srgb, const Scalar& metalness, const Scalar& opacity,
                     const rules::Thresholds& t, AlbedoStats& stats, int max_size) {
    return albedo_overlay_of(albedo, albedo_srgb, metalness, opacity, t, stats, max_size);
}

Image metalness_overlay(const Scalar& metalness, int width, int height, const rules::Thresholds& t,
                        MetalnessStats& stats, int max_size) {
    stats = {};
    BoxReducer reduce(width, height, max_size);
    std::vector<float> row(static_cast<size_t>(width) * 3);
    constexpr float kHalfCode = 0.5f / 255.f;
    ScalarRows rows(metalness, width, height);
    for (int y = 0; y < height; ++y) {
        const float* metalness_row = rows.row(y);
        for (int x = 0; x < width; ++x) {
            ++stats.pixels;
            const float m = metalness_row[x];
            const float* rgb = nullptr;
            float g = 0.f;
            if (m < kHalfCode) {
                ++stats.zero;
                g = 0.06f;
            } else if (m > 1.f - kHalfCode) {
                ++stats.one;
                g = 0.94f;
            } else if (m <= t.dielectric_max || m >= t.metal_min) {  // as METALNESS_NOT_BINARY compares
                ++stats.near_binary;
                rgb = kNearBinary;
            } else {
                ++stats.between;
                rgb = kBetween;
            }
            for (size_t c = 0; c < 3; ++c) row[static_cast<size_t>(x) * 3 + c] = rgb ? rgb[c] : g;
        }
        reduce.add_row(y, row.data());
    }
    return reduce.take();
}

}  // namespace mf::report
