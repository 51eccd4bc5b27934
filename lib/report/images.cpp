#include "report/images.hpp"

#include <algorithm>
#include <array>
#include <cmath>
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

// Box reduction of an RGB image (values averaged as they are), fed row by row: each output row
// is finished as its last source row arrives, so no full-size intermediate is held (an 8192²
// RGB float picture is 768 MB). max_size <= 0: the image as it is.
class BoxReducer {
public:
    BoxReducer(int w, int h, int max_size) : w_(w), h_(h) {
        if (max_size <= 0) ow_ = w, oh_ = h;
        else reduced_size(w, h, max_size, ow_, oh_);
        out_ = Image(ow_, oh_, 3);
        identity_ = ow_ == w && oh_ == h;
        if (identity_) return;
        acc_.assign(static_cast<size_t>(ow_) * 3, 0.0);
        count_.assign(static_cast<size_t>(ow_), 0);
        col_of_.resize(static_cast<size_t>(w));
        for (int x = 0; x < w; ++x)
            col_of_[static_cast<size_t>(x)] = static_cast<int>(static_cast<int64_t>(x) * ow_ / w);
        y1_ = row_end(0);
    }
    // Rows in order, 0 to h - 1, three floats a pixel.
    void add_row(int y, const float* rgb) {
        if (identity_) {
            std::copy_n(rgb, static_cast<size_t>(w_) * 3, &out_.pixels[out_.index(0, y)]);
            return;
        }
        while (y >= y1_) flush();
        for (int x = 0; x < w_; ++x) {
            const auto ox = static_cast<size_t>(col_of_[static_cast<size_t>(x)]);
            for (size_t c = 0; c < 3; ++c) acc_[ox * 3 + c] += rgb[static_cast<size_t>(x) * 3 + c];
            ++count_[ox];
        }
        if (y == h_ - 1) flush();
    }
    Image take() { return std::move(out_); }

private:
    int row_end(int oy) const {
        const int y0 = static_cast<int>(static_cast<int64_t>(oy) * h_ / oh_);
        return std::max(y0 + 1, static_cast<int>(static_cast<int64_t>(oy + 1) * h_ / oh_));
    }
    void flush() {
        for (int ox = 0; ox < ow_; ++ox) {
            const auto o = static_cast<size_t>(ox);
            for (size_t c = 0; c < 3; ++c)
                out_.at(ox, oy_,
                        static_cast<int>(c)) = static_cast<float>(acc_[o * 3 + c] / static_cast<double>(count_[o]));
        }
        std::fill(acc_.begin(), acc_.end(), 0.0);
        std::fill(count_.begin(), count_.end(), 0);
        y1_ = ++oy_ < oh_ ? row_end(oy_) : h_;
    }

    int w_, h_, ow_ = 0, oh_ = 0, oy_ = 0, y1_ = 0;
    bool identity_ = true;
    Image out_;
    std::vector<double> acc_;
    std::vector<size_t> count_;
    std::vector<int> col_of_;
};

}  // namespace

namespace {

// The value a picture holds at index i: a float as it is, a code as the float it stands for.
float value_at(const Image& img, size_t i) { return img.pixels[i]; }
float value_at(const Image8& img, size_t i) { return unorm8_values()[img.pixels[i]]; }

template <class T>
Image thumbnail_of(const BasicImage<T>& src, int max_size, bool srgb) {
    BoxReducer reduce(src.width, src.height, max_size);
    std::vector<float> row(static_cast<size_t>(src.width) * 3);
    const Curve& dec = decode_curve();
    const auto sc = static_cast<size_t>(src.channels);
    for (int y = 0; y < src.height; ++y) {
        size_t s = src.index(0, y);
        for (size_t x = 0; x < static_cast<size_t>(src.width); ++x, s += sc) {
            const float r = value_at(src, s);
            float v[3] = {r, sc > 1 ? value_at(src, s + 1) : r, sc > 2 ? value_at(src, s + 2) : (sc == 2 ? 0.f : r)};
            for (float& c : v) c = srgb ? dec(c) : clamp01(c);
            std::copy_n(v, 3, &row[x * 3]);
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
    BoxReducer reduce(src.width, src.height, max_size);
    std::vector<float> row(static_cast<size_t>(src.width) * 3);
    const auto sc = static_cast<size_t>(src.channels);
    const auto ch = static_cast<size_t>(std::clamp(channel, 0, src.channels - 1));
    for (int y = 0; y < src.height; ++y) {
        const size_t s = src.index(0, y);
        for (size_t x = 0; x < static_cast<size_t>(src.width); ++x)
            row[x * 3] = row[x * 3 + 1] = row[x * 3 + 2] = clamp01(value_at(src, s + x * sc + ch));
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
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            ++stats.pixels;
            // As the rules: a pixel whose opacity is below the cutoff (or not a number) is not judged.
            const float o = opacity.at(x, y, w, h);
            const size_t s = albedo.index(x, y);
            const float r = value_at(albedo, s);
            const float rgb[3] = {r, ac > 1 ? value_at(albedo, s + 1) : r, ac > 2 ? value_at(albedo, s + 2) : r};
            const float luminance = classify.luminance(rgb);
            const validate::AlbedoJudgement j = o >= t.opacity_visible
                                                    ? classify.judge(luminance, metalness.at(x, y, w, h))
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
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            ++stats.pixels;
            const float m = metalness.at(x, y, width, height);
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
