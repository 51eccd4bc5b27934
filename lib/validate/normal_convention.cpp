#include "validate/normal_convention.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <utility>
#include <vector>

#include "base/simd.hpp"

namespace mf::validate {
namespace {

// Uncentered correlation: the tests are about proportionality through the origin (q = ±s·g).
// A row's x = 1 .. width - 2 four at a time (simd.hpp's lanes): float products (the figure needs a
// few digits) summed in float over 16 steps, those sums in double, the lanes added in order; the
// last 0-3 one by one. The same figures on every machine.
struct Corr {
    double xy = 0, xx = 0, yy = 0;
    long n = 0;
    // The pairs (a, b) of x = 1 .. width - 2 (the interior of a row): pair(load, x) reads its
    // samples through `load`, which gives the floats at p .. p + 3 as an F4, or the one at p.
    template <class Pair>
    void add_row(int width, Pair pair) {
        const size_t end = width >= 2 ? static_cast<size_t>(width) - 1 : 1;
        simd::Sum4 sxy, sxx, syy;
        size_t x = 1;
        while (x + 4 <= end) {
            simd::F4 bxy{}, bxx{}, byy{};
            for (int k = 0; k < 16 && x + 4 <= end; ++k, x += 4) {
                const auto [a, b] = pair([](const float* p) { return simd::load4(p); }, x);
                bxy += a * b;
                bxx += a * a;
                byy += b * b;
            }
            sxy.add(bxy), sxx.add(bxx), syy.add(byy);
        }
        xy += sxy.total(), xx += sxx.total(), yy += syy.total();
        for (; x < end; ++x) {
            const auto [a, b] = pair([](const float* p) { return *p; }, x);
            xy += double{a * b};
            xx += double{a * a};
            yy += double{b * b};
        }
        n += static_cast<long>(end - 1);
    }
    double r() const {
        const double d = std::sqrt(xx * yy);
        return d > 1e-30 ? xy / d : 0.0;
    }
};

struct Level {
    int width = 0;
    bool with_height = false;
    // The last three rows of slopes p, q and height h (ring, oldest first after rotation).
    std::array<std::vector<float>, 3> p, q, h;
    int rows = 0;
    Corr cx, cy, curl;
    // Rows accumulated for the next level (2×2 block mean).
    std::vector<float> ap, aq, ah;
    int acc_rows = 0;
};

double clamp01(double v) { return std::clamp(v, 0.0, 1.0); }

// Maps of |r| to confidence (docs/rules.md): the height test is direct evidence, so a weaker
// correlation already counts; the curl test compares second derivatives and needs more.
double height_confidence(double r) { return clamp01((std::abs(r) - 0.05) / 0.25); }
double curl_confidence(double r) { return clamp01((std::abs(r) - 0.1) / 0.4); }

NormalConvention sign_convention(double r) {
    return r > 0 ? NormalConvention::gl : (r < 0 ? NormalConvention::dx : NormalConvention::unknown);
}

}  // namespace

namespace {

// decode_normal_row over any sample kind: `dec(i)` is the component of sample i.
template <class Dec>
void decode_row(Dec dec, int channels, int width, NormalRow& out, bool rebuild_z) {
    const auto nc = static_cast<size_t>(channels), n = static_cast<size_t>(width);
    out.x.resize(n), out.y.resize(n), out.z.resize(n);
    for (size_t x = 0; x < n; ++x) {
        const size_t s = x * nc;
        const float nx = dec(s);
        const float ny = channels > 1 ? dec(s + 1) : 0.f;
        const float nz = channels > 2 && !rebuild_z ? dec(s + 2) : std::sqrt(std::max(0.f, 1.f - nx * nx - ny * ny));
        out.x[x] = nx, out.y[x] = ny, out.z[x] = nz;
    }
}

// A stored (unsigned) value's component: n = 2c − 1.
float component_of(float c) { return 2.f * c - 1.f; }

}  // namespace

void decode_normal_row(const float* src, int channels, int width, bool signed_values, NormalRow& out, bool rebuild_z) {
    decode_row([&](size_t i) { return signed_values ? src[i] : component_of(src[i]); }, channels, width, out,
               rebuild_z);
}

void decode_normal_row(const uint8_t* codes, int channels, int width, NormalRow& out, bool rebuild_z) {
    static const std::array<float, 256> component = unorm8_table(component_of);
    decode_row([&](size_t i) { return component[codes[i]]; }, channels, width, out, rebuild_z);
}

struct NormalConventionDetector::Impl {
    DetectorOptions opt;
    bool with_height = false;
    std::vector<Level> levels;
    // Full-resolution slope moments (the flat test).
    double sp = 0, sq = 0, spp = 0, sqq = 0;
    long long ns = 0;
    std::vector<float> row_p, row_q;  // add_row's slopes, kept between rows

    Impl(int width, bool wh, const DetectorOptions& o) : opt(o), with_height(wh) {
        int w = width;
        for (int l = 0; l < std::max(1, opt.levels) && w >= 3; ++l, w /= 2) {
            Level lv;
            lv.width = w;
            lv.with_height = wh;
            for (int i = 0; i < 3; ++i) {
                lv.p[i].assign(w, 0.f);
                lv.q[i].assign(w, 0.f);
                if (wh) lv.h[i].assign(w, 0.f);
            }
            lv.ap.assign(w / 2, 0.f);
            lv.aq.assign(w / 2, 0.f);
            if (wh) lv.ah.assign(w / 2, 0.f);
            levels.push_back(std::move(lv));
        }
    }

    void push(size_t li, const float* p, const float* q, const float* h) {
        Level& L = levels[li];
        // Rotate the ring: slot 2 is the newest row.
        std::rotate(L.p.begin(), L.p.begin() + 1, L.p.end());
        std::rotate(L.q.begin(), L.q.begin() + 1, L.q.end());
        std::copy(p, p + L.width, L.p[2].begin());
        std::copy(q, q + L.width, L.q[2].begin());
        if (L.with_height) {
            std::rotate(L.h.begin(), L.h.begin() + 1, L.h.end());
            std::copy(h, h + L.width, L.h[2].begin());
        }
        ++L.rows;
        if (L.rows >= 3) {
            // Central differences at the middle row (slot 1).
            const float *p0 = L.p[0].data(), *p1 = L.p[1].data(), *p2 = L.p[2].data();
            const float* q1 = L.q[1].data();
            // Central differences at x of the middle row: ∂p/∂y and ∂q/∂x for the curl; with a
            // height, ∂h/∂x and ∂h/∂y against p and q.
            L.curl.add_row(L.width, [&](auto load, size_t x) {
                return std::pair{0.5f * (load(p2 + x) - load(p0 + x)), 0.5f * (load(q1 + x + 1) - load(q1 + x - 1))};
            });
            if (L.with_height) {
                const float *h0 = L.h[0].data(), *h1 = L.h[1].data(), *h2 = L.h[2].data();
                L.cx.add_row(L.width, [&](auto load, size_t x) {
                    return std::pair{load(p1 + x), 0.5f * (load(h1 + x + 1) - load(h1 + x - 1))};
                });
                L.cy.add_row(L.width, [&](auto load, size_t x) {
                    return std::pair{load(q1 + x), 0.5f * (load(h2 + x) - load(h0 + x))};
                });
            }
        }
        // Build the next level's row from 2×2 blocks.
        if (li + 1 >= levels.size()) return;
        const int w2 = L.width / 2;
        for (int x = 0; x < w2; ++x) {
            L.ap[x] += 0.25f * (p[2 * x] + p[2 * x + 1]);
            L.aq[x] += 0.25f * (q[2 * x] + q[2 * x + 1]);
            if (L.with_height) L.ah[x] += 0.25f * (h[2 * x] + h[2 * x + 1]);
        }
        if (++L.acc_rows == 2) {
            // Copy out first: push() of the next level does not touch this level's buffers,
            // but keep the order obvious.
            std::vector<float> np = L.ap, nq = L.aq, nh = L.ah;
            std::fill(L.ap.begin(), L.ap.end(), 0.f);
            std::fill(L.aq.begin(), L.aq.end(), 0.f);
            std::fill(L.ah.begin(), L.ah.end(), 0.f);
            L.acc_rows = 0;
            push(li + 1, np.data(), nq.data(), with_height ? nh.data() : nullptr);
        }
    }
};

NormalConventionDetector::NormalConventionDetector(int width, bool with_height, const DetectorOptions& opt)
    : impl_(std::make_unique<Impl>(width, with_height, opt)) {}
NormalConventionDetector::~NormalConventionDetector() = default;
NormalConventionDetector::NormalConventionDetector(NormalConventionDetector&&) noexcept = default;
NormalConventionDetector& NormalConventionDetector::operator=(NormalConventionDetector&&) noexcept = default;

void NormalConventionDetector::add_row(const NormalRow& row, const float* height) {
    using namespace simd;
    if (impl_->levels.empty()) return;
    const int w = impl_->levels[0].width;
    const auto n = static_cast<size_t>(w);
    std::vector<float>&p = impl_->row_p, &q = impl_->row_q;
    p.resize(n), q.resize(n);
    const F4 min_nz = F4{} + static_cast<float>(impl_->opt.min_nz);
    // Slopes four texels at a time (the last group padded with flat texels, left out of the sums).
    Sum4 sp, sq, spp, sqq;
    I4 counted{};
    for (size_t x = 0; x < n; x += 4) {
        const size_t m = std::min<size_t>(4, n - x);
        F4 nx, ny, nz;
        if (m == 4) {
            nx = load4(row.x.data() + x), ny = load4(row.y.data() + x), nz = load4(row.z.data() + x);
        } else {
            nx = ny = F4{}, nz = F4{} + 1.f;
            for (size_t l = 0; l < m; ++l) nx[l] = row.x[x + l], ny[l] = row.y[x + l], nz[l] = row.z[x + l];
        }
        nz = max4(nz, min_nz);
        const F4 pv = -nx / nz, qv = ny / nz;
        if (m == 4) {
            std::memcpy(p.data() + x, &pv, sizeof pv);
            std::memcpy(q.data() + x, &qv, sizeof qv);
        } else {
            for (size_t l = 0; l < m; ++l) p[x + l] = pv[l], q[x + l] = qv[l];
        }
        const I4 ok = (I4{0, 1, 2, 3} < static_cast<int32_t>(m)) & finite4(pv) & finite4(qv);
        sp.add(keep(pv, ok));
        sq.add(keep(qv, ok));
        spp.add_squares(keep(pv, ok));
        sqq.add_squares(keep(qv, ok));
        counted += ok;
    }
    impl_->sp += sp.total(), impl_->sq += sq.total(), impl_->spp += spp.total(), impl_->sqq += sqq.total();
    impl_->ns += count(counted);
    // A missing height row (the height map ended early) reads as flat: no evidence, no crash.
    std::vector<float> flat;
    if (impl_->with_height && !height) {
        flat.assign(w, 0.f);
        height = flat.data();
    }
    impl_->push(0, p.data(), q.data(), impl_->with_height ? height : nullptr);
}

NormalVerdict NormalConventionDetector::verdict() const {
    NormalVerdict v;
    const Impl& I = *impl_;
    double best_curl = 0, best_hy = 0, best_hx = 0;
    int curl_scale = 0, height_scale = 0;
    // Each pyramid level's evidence, one list a figure (level_scale[i] is level i's).
    std::vector<std::int64_t> level_scale, level_samples;
    std::vector<double> level_r_curl, level_r_x, level_r_y;
    int scale = 1;
    for (const Level& L : I.levels) {
        level_scale.push_back(scale);
        level_samples.push_back(static_cast<std::int64_t>(L.curl.n));
        level_r_curl.push_back(L.curl.r());
        if (I.with_height) {
            level_r_x.push_back(L.cx.r());
            level_r_y.push_back(L.cy.r());
        }
        if (L.curl.n >= I.opt.min_samples) {
            // Only levels whose terms carry energy vote (a flat map has no evidence).
            if (L.curl.xx > 0 && L.curl.yy > 0 && std::abs(L.curl.r()) > std::abs(best_curl)) {
                best_curl = L.curl.r();
                curl_scale = scale;
            }
            if (I.with_height && std::abs(L.cy.r()) > std::abs(best_hy)) {
                best_hy = L.cy.r();
                best_hx = L.cx.r();
                height_scale = scale;
            }
        }
        scale *= 2;
    }
    v.figures["level_scale"] = std::move(level_scale);
    v.figures["level_samples"] = std::move(level_samples);
    v.figures["level_r_curl"] = std::move(level_r_curl);
    if (I.with_height) {
        v.figures["level_r_x"] = std::move(level_r_x);
        v.figures["level_r_y"] = std::move(level_r_y);
    }
    const double cc = curl_confidence(best_curl);
    v.figures["r_curl"] = best_curl;
    v.figures["curl_scale"] = curl_scale;
    v.figures["confidence_curl"] = cc;
    NormalConvention dir = sign_convention(best_curl);
    double conf = cc;
    v.method = "curl";
    if (I.with_height) {
        // The red channel has no convention ambiguity: without a clear corr(p, ∂h/∂x) the height
        // map may not match this normal map, so its evidence counts half. Clearly negative, the
        // map is depth (white = deep): inverting a height flips both correlations, so the green
        // one read against the red one's sign is the convention's evidence either way.
        v.height_is_depth = best_hx <= -kDepthMinCorrelation;
        v.height_is_height = best_hx >= kDepthMinCorrelation;
        const double r_y = v.height_is_depth ? -best_hy : best_hy;
        double ch = height_confidence(r_y);
        if (!v.height_is_depth && !(best_hx > 0.05)) ch *= 0.5;
        v.figures["r_height_y"] = best_hy;
        v.figures["r_height_x"] = best_hx;
        v.figures["height_is_depth"] = v.height_is_depth;
        v.figures["height_scale"] = height_scale;
        v.figures["confidence_height"] = ch;
        const NormalConvention hdir = sign_convention(r_y);
        v.method = "height+curl";
        if (hdir == dir || dir == NormalConvention::unknown || cc == 0.0) {
            dir = hdir != NormalConvention::unknown ? hdir : dir;
            conf = 1.0 - (1.0 - ch) * (1.0 - cc);
        } else if (ch >= cc) {
            dir = hdir;
            conf = ch - cc;
        } else {
            conf = cc - ch;
        }
    }
    if (I.ns > 0) {
        const auto n = static_cast<double>(I.ns);
        const double mp = I.sp / n, mq = I.sq / n;
        const double std_p = std::sqrt(std::max(0.0, I.spp / n - mp * mp));
        const double std_q = std::sqrt(std::max(0.0, I.sqq / n - mq * mq));
        v.flat = std_p <= I.opt.flat_max_slope_std && std_q <= I.opt.flat_max_slope_std;
        v.figures["slope_std_x"] = std_p;
        v.figures["slope_std_y"] = std_q;
        v.figures["flat"] = v.flat;
    }
    if (dir == NormalConvention::unknown) conf = 0.0;
    v.leaning = dir;
    v.confidence = conf;
    v.convention = conf >= I.opt.min_confidence ? dir : NormalConvention::unknown;
    if (I.levels.empty() || I.levels[0].curl.n < I.opt.min_samples) v.method = "none";
    return v;
}

NormalVerdict detect_normal_convention(const Image& normal, const Image* height, const DetectorOptions& opt,
                                       bool signed_values) {
    const bool wh = height && !height->empty();
    NormalConventionDetector det(normal.width, wh, opt);
    NormalRow row;
    std::vector<float> hrow(wh ? normal.width : 0);
    std::vector<int> xmap(wh ? normal.width : 0);
    if (wh)
        for (int x = 0; x < normal.width; ++x)
            xmap[x] = std::min(height->width - 1, static_cast<int>((x + 0.5) * height->width / normal.width));
    for (int y = 0; y < normal.height; ++y) {
        decode_normal_row(&normal.pixels[normal.index(0, y)], normal.channels, normal.width, signed_values, row);
        if (wh) {
            const int hy = std::min(height->height - 1, static_cast<int>((y + 0.5) * height->height / normal.height));
            for (int x = 0; x < normal.width; ++x) hrow[x] = height->at(xmap[x], hy, 0);
        }
        det.add_row(row, wh ? hrow.data() : nullptr);
    }
    return det.verdict();
}

}  // namespace mf::validate
