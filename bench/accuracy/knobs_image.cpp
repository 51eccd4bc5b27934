// Knobs on whole maps: resampling filters and spaces; normal-map mips, renormalization and
// Toksvig's roughness adjustment.
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>

#include "base/srgb.hpp"
#include "brdf_reference.hpp"
#include "color/color.hpp"
#include "harness.hpp"
#include "image/image.hpp"
#include "pack/pack.hpp"

namespace mf::bench {
namespace {

// ------------------------------------------------------------------------------------------
// Resampling. Source: an 8-bit sRGB albedo (values k/255) with the content that separates the
// filters: 1-px black/white lines and checkers (where averaging encoded values darkens: the
// gamma error), a zone plate (aliasing), colour edges and smooth noise.

Image make_resample_source(int w) {
    Image img(w, w, 3);
    uint32_t s = 2024;
    for (int y = 0; y < w; ++y)
        for (int x = 0; x < w; ++x) {
            const double u = (x + 0.5) / w, v = (y + 0.5) / w;
            std::array<double, 3> c;
            if (u < 0.5 && v < 0.5) {  // lines and checkers
                const bool on = (u < 0.25) ? (x % 2 == 0) : (((x / 1) + (y / 1)) % 2 == 0);
                const double k = on ? 1.0 : 0.0;
                c = {k, k, k};
            } else if (u >= 0.5 && v < 0.5) {  // zone plate
                const double dx = u - 0.75, dy = v - 0.25;
                const double k = 0.5 + 0.5 * std::cos(std::numbers::pi * w * 0.9 * (dx * dx + dy * dy) * 2.0);
                c = {k, k * 0.8, k * 0.3};
            } else if (u < 0.5) {  // colour edges
                const int cell = (x / 7 + y / 5) % 4;
                const std::array<std::array<double, 3>, 4> pal = {
                    {{0.9, 0.1, 0.1}, {0.1, 0.8, 0.2}, {0.1, 0.2, 0.9}, {0.95, 0.9, 0.2}}};
                c = pal[static_cast<size_t>(cell)];
            } else {  // smooth gradient with noise
                const double n = static_cast<double>(xorshift(s) & 255) / 255.0 - 0.5;
                c = {0.3 + 0.4 * u + 0.05 * n, 0.4 + 0.2 * v + 0.05 * n, 0.5 + 0.05 * n};
            }
            for (int k = 0; k < 3; ++k)
                img.at(x, y,
                       k) = static_cast<float>(std::lround(std::clamp(c[static_cast<size_t>(k)], 0.0, 1.0) * 255.0)) /
                            255.f;
        }
    return img;
}

double lanczos3(double x) {
    x = std::abs(x);
    if (x < 1e-12) return 1.0;
    if (x >= 3.0) return 0.0;
    const double px = std::numbers::pi * x;
    return 3.0 * std::sin(px) * std::sin(px / 3.0) / (px * px);
}

// The reference: separable Lanczos-3 in double precision on linear light, the kernel widened
// by the reduction ratio (a low-pass at the destination's Nyquist rate), weights normalized.
std::vector<double> reference_resample(const Image& srgb, int dw) {
    const int sw = srgb.width;
    const double scale = static_cast<double>(sw) / dw;
    const double support = 3.0 * std::max(1.0, scale);
    struct Tap {
        int first;
        std::vector<double> w;
    };
    std::vector<Tap> taps(static_cast<size_t>(dw));
    for (int i = 0; i < dw; ++i) {
        const double centre = (i + 0.5) * scale;  // in source pixel units
        const int j0 = std::max(0, static_cast<int>(std::floor(centre - support)));
        const int j1 = std::min(sw - 1, static_cast<int>(std::ceil(centre + support)));
        Tap t{j0, {}};
        double sum = 0;
        for (int j = j0; j <= j1; ++j) {
            const double wgt = lanczos3(((j + 0.5) - centre) / std::max(1.0, scale));
            t.w.push_back(wgt), sum += wgt;
        }
        for (double& wgt : t.w) wgt /= sum;
        taps[static_cast<size_t>(i)] = std::move(t);
    }
    std::vector<double> lin(srgb.pixels.size());
    for (size_t i = 0; i < lin.size(); ++i) lin[i] = srgb_to_linear(static_cast<double>(srgb.pixels[i]));
    std::vector<double> h(static_cast<size_t>(sw) * dw * 3);  // sw rows × dw columns
    for (int y = 0; y < sw; ++y)
        for (int i = 0; i < dw; ++i) {
            const Tap& t = taps[static_cast<size_t>(i)];
            for (int c = 0; c < 3; ++c) {
                double acc = 0;
                for (size_t k = 0; k < t.w.size(); ++k)
                    acc += t.w[k] * lin[(static_cast<size_t>(y) * sw + t.first + k) * 3 + c];
                h[(static_cast<size_t>(y) * dw + i) * 3 + c] = acc;
            }
        }
    std::vector<double> out(static_cast<size_t>(dw) * dw * 3);
    for (int i = 0; i < dw; ++i) {
        const Tap& t = taps[static_cast<size_t>(i)];
        for (int x = 0; x < dw; ++x)
            for (int c = 0; c < 3; ++c) {
                double acc = 0;
                for (size_t k = 0; k < t.w.size(); ++k) acc += t.w[k] * h[((t.first + k) * dw + x) * 3 + c];
                out[(static_cast<size_t>(i) * dw + x) * 3 + c] = acc;
            }
    }
    return out;  // linear
}

Image oiio_resize(const Image& src, int w, const char* filter) {
    OIIO::ImageSpec in_spec(src.width, src.height, src.channels, OIIO::TypeDesc::FLOAT);
    OIIO::ImageBuf in(in_spec, const_cast<float*>(src.pixels.data()));
    Image out(w, w, src.channels);
    OIIO::ImageSpec out_spec(w, w, src.channels, OIIO::TypeDesc::FLOAT);
    OIIO::ImageBuf dst(out_spec, out.pixels.data());
    if (!OIIO::ImageBufAlgo::resize(dst, in, filter, 0.f, OIIO::ROI::All(), 1))
        throw std::runtime_error(std::string("resize: ") + dst.geterror());
    return out;
}

}  // namespace

std::vector<Variant> resample_variants(const Config& c) {
    std::string err;
    auto color = ColorContext::create(err);
    if (!color) throw std::runtime_error(err);
    const int sw = c.quick ? 256 : 4096;
    auto src = std::make_shared<const Image>(make_resample_source(sw));
    auto lut = std::make_shared<std::array<float, 256>>();
    for (int k = 0; k < 256; ++k) (*lut)[static_cast<size_t>(k)] = static_cast<float>(srgb_to_linear(k / 255.0));

    std::vector<Variant> out;
    for (int dw : {sw / 2, sw * 3 / 8}) {
        const bool mip = dw * 2 == sw;
        const std::vector<double> ref = reference_resample(*src, dw);
        const std::string knob = mip ? "resample: mip 4K->2K" : "resample: resize 4K->1.5K";
        struct Way {
            const char* filter;
            int space;  // 0 sRGB values, 1 linear via OpenColorIO (matforge), 2 linear via 8-bit LUT
        };
        const Way ways[] = {{"box", 0},      {"triangle", 0}, {"lanczos3", 0}, {"box", 1},
                            {"triangle", 1}, {"lanczos3", 1}, {"lanczos3", 2}};
        for (const Way& way : ways) {
            const std::string filter = way.filter;
            auto run = [src, dw, filter, space = way.space, color, lut]() {
                if (space == 0) return oiio_resize(*src, dw, filter.c_str());
                Image lin = *src;
                if (space == 1) {
                    color->convert(lin, ColorEncoding::srgb, ColorEncoding::linear);
                } else {
                    for (float& v : lin.pixels) v = (*lut)[static_cast<size_t>(v * 255.f + 0.5f)];
                }
                Image r = oiio_resize(lin, dw, filter.c_str());
                color->convert(r, ColorEncoding::linear, ColorEncoding::srgb);
                return r;
            };
            const Image res = run();
            Acc codes, lin;
            const int border = 4;  // edge handling differs between implementations; not the point
            for (int y = border; y < dw - border; ++y)
                for (int x = border; x < dw - border; ++x)
                    for (int k = 0; k < 3; ++k) {
                        const size_t i = (static_cast<size_t>(y) * dw + x) * 3 + k;
                        const double got = res.pixels[i];
                        // Compared as the file gets them: clamped to [0, 1]. (Ringing makes
                        // negatives, which OpenColorIO and the IEC formula extend differently.)
                        const double g = std::clamp(got, 0.0, 1.0), r = std::clamp(ref[i], 0.0, 1.0);
                        codes.add((g - linear_to_srgb(r)) * 255.0);
                        lin.add(srgb_to_linear(g) - r);
                    }
            Variant v;
            v.knob = knob;
            const char* space_name[] = {"in sRGB values", "in linear light (OCIO, as matforge)",
                                        "in linear light (8-bit LUT decode)"};
            v.name = filter + " " + space_name[way.space] + (mip ? ", 4K->2K" : ", 4K->1536");
            v.tag = std::string(filter == "lanczos3"   ? "LANCZOS3"
                                : filter == "triangle" ? "TRIANGLE"
                                                       : "BOX") +
                    (way.space == 0   ? " SRGB"
                     : way.space == 1 ? " LIN"
                                      : " LIN LUT");
            v.max_codes = codes.max, v.mean_codes = codes.mean(), v.max_linear = lin.max, v.mean_linear = lin.mean();
            v.linear_unit = "linear";
            v.work = [run] { (void)run(); };
            v.pixels = static_cast<double>(sw) * sw;
            v.unit = "ms/map";
            v.map_pixels = 4096.0 * 4096.0;
            v.map_name = "4K";
            v.iterations = c.quick ? 0 : 1;
            out.push_back(std::move(v));
        }
    }
    return out;
}

// ------------------------------------------------------------------------------------------
// Normal maps. A 1K bumpy normal map (rivets and ridges) under one light, viewed so the flat
// highlight sits at n = +Z. The previewed result of a mip level is compared with the truth: the
// full-resolution shading averaged over each level texel's footprint (what a supersampled render
// of the distant surface shows). BRDF: the standard model in double (brdf_reference.hpp).

namespace {

using cpubrdf::V3;

constexpr double kBaseRoughness = 0.25;
const V3<double> kView{-0.4, 0.0, 0.916515139};
const V3<double> kLight{0.4, 0.0, 0.916515139};

double shade_one(V3<double> n, double roughness) {
    cpubrdf::Inputs<double> in{n, kView, kLight, {0.5, 0.5, 0.5}, roughness, 0.0, 0.8};
    return cpubrdf::shade(in, cpubrdf::Model::standard)[1];
}

Image make_normal_source(int w) {
    Image n(w, w, 3);
    // Height field: ridges along x, a rivet grid, fine bumps; normals from its gradient.
    auto height = [w](double x, double y) {
        const double u = x / w, v = y / w;
        double h = 0.6 * std::sin(2 * std::numbers::pi * 37 * u) * std::sin(2 * std::numbers::pi * 3 * v);
        const double cu = std::fmod(u * 24, 1.0) - 0.5, cv = std::fmod(v * 24, 1.0) - 0.5;
        h += 1.5 * std::exp(-(cu * cu + cv * cv) * 40);
        h += 0.25 * std::sin(2 * std::numbers::pi * 97 * (u + 0.3 * v));
        return h * w / 256.0;  // slopes independent of resolution
    };
    for (int y = 0; y < w; ++y)
        for (int x = 0; x < w; ++x) {
            const double dx = (height(x + 1, y) - height(x - 1, y)) / 2, dy = (height(x, y + 1) - height(x, y - 1)) / 2;
            const double len = std::sqrt(dx * dx + dy * dy + 1);
            n.at(x, y, 0) = static_cast<float>(-dx / len), n.at(x, y, 1) = static_cast<float>(-dy / len);
            n.at(x, y, 2) = static_cast<float>(1 / len);
        }
    return n;
}

// Box mip chain of *unnormalized* averages: level L texel = mean of the level-0 unit vectors
// in its footprint (the vector whose shortening Toksvig reads as variance).
std::vector<Image> box_chain(const Image& level0, int levels) {
    std::vector<Image> chain{level0};
    for (int l = 1; l <= levels; ++l) {
        const Image& p = chain.back();
        Image m(p.width / 2, p.height / 2, 3);
        for (int y = 0; y < m.height; ++y)
            for (int x = 0; x < m.width; ++x)
                for (int k = 0; k < 3; ++k)
                    m.at(x, y, k) = 0.25f * (p.at(2 * x, 2 * y, k) + p.at(2 * x + 1, 2 * y, k) +
                                             p.at(2 * x, 2 * y + 1, k) + p.at(2 * x + 1, 2 * y + 1, k));
        chain.push_back(std::move(m));
    }
    return chain;
}

float code8(float v) { return static_cast<float>(quantize(v, 8)) / 255.f; }

// Toksvig 2005 ("Mipmapping Normal Maps"): the averaged normal's length |n̄| gives the spread of
// the footprint's normals. For a Phong/Blinn exponent s the filtered exponent is
// s' = |n̄| s / (|n̄| + s (1 − |n̄|)), i.e. 1/s' = 1/s + (1 − |n̄|)/|n̄|. With the usual
// correspondence s = 2/α² − 2 (Walter et al. 2007, eq. 34), α'² = α² + 2 (1 − |n̄|)/|n̄|;
// perceptual roughness r' = α'^(1/2), clamped to 1.
double toksvig_roughness(double r, double len) {
    len = std::clamp(len, 1e-4, 1.0);
    const double a2 = r * r * r * r + 2.0 * (1.0 - len) / len;
    return std::min(1.0, std::pow(a2, 0.25));
}

}  // namespace

std::vector<Variant> normal_variants(const Config& c) {
    const int w = c.quick ? 256 : 1024;
    const int level = 3;  // 8×8 texel footprint
    auto level0 = std::make_shared<const Image>(make_normal_source(w));
    const int lw = w >> level, fp = 1 << level;

    // Truth: full-resolution shading averaged per footprint.
    std::vector<double> truth(static_cast<size_t>(lw) * lw, 0.0);
    for (int y = 0; y < w; ++y)
        for (int x = 0; x < w; ++x) {
            const V3<double> n{level0->at(x, y, 0), level0->at(x, y, 1), level0->at(x, y, 2)};
            truth[static_cast<size_t>(y / fp) * lw + x / fp] += shade_one(n, kBaseRoughness) / (fp * fp);
        }

    // Previewed value of each variant at `level`: shade the stored (decoded) normal, normalized
    // by the shader, with the stored roughness.
    struct Level {
        Image normals;    // decoded as the shader reads them
        Image roughness;  // empty: the base roughness
    };
    auto evaluate = [&](const Level& L, Variant& v) {
        Acc codes, lin;
        for (int y = 0; y < lw; ++y)
            for (int x = 0; x < lw; ++x) {
                const V3<double> n{L.normals.at(x, y, 0), L.normals.at(x, y, 1), L.normals.at(x, y, 2)};
                const double r = L.roughness.empty() ? kBaseRoughness : L.roughness.at(x, y, 0);
                const double got = shade_one(n, r), want = truth[static_cast<size_t>(y) * lw + x];
                codes.add(display_code(got) - display_code(want));
                lin.add(got - want);
            }
        v.max_codes = codes.max, v.mean_codes = codes.mean(), v.max_linear = lin.max, v.mean_linear = lin.mean();
        v.linear_unit = "radiance";
    };
    const int levels = [&] {
        int l = 0;
        while ((w >> (l + 1)) >= 1 && l < 10) ++l;
        return l;
    }();

    // The preprocessing each variant needs for the full chain, with 8-bit storage (timed).
    auto build = [level0, levels](int mode) {
        // mode 0: box, not renormalized; 1: box, renormalized; 2: box, renormalized + Toksvig;
        // 3: Lanczos-3 (mf::resample) per level from the previous one, renormalized (fit_plane's way).
        std::vector<Level> out;
        if (mode == 3) {
            Image cur = *level0;
            for (int l = 1; l <= levels; ++l) {
                cur = resample(cur, std::max(1, cur.width / 2), std::max(1, cur.height / 2));
                renormalize(cur);
                Level L{cur, {}};
                for (float& x : L.normals.pixels) x = code8(x * 0.5f + 0.5f) * 2.f - 1.f;
                out.push_back(std::move(L));
            }
            return out;
        }
        const auto chain = box_chain(*level0, levels);
        for (int l = 1; l <= levels; ++l) {
            Level L{chain[static_cast<size_t>(l)], {}};
            if (mode == 2) L.roughness = Image(L.normals.width, L.normals.height, 1);
            for (size_t i = 0; i < L.normals.pixels.size(); i += 3) {
                float* p = &L.normals.pixels[i];
                const float len = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
                if (mode == 2)
                    L.roughness.pixels[i / 3] = code8(static_cast<float>(toksvig_roughness(kBaseRoughness, len)));
                if (mode >= 1 && len > 1e-6f) p[0] /= len, p[1] /= len, p[2] /= len;
                for (int k = 0; k < 3; ++k) p[k] = code8(p[k] * 0.5f + 0.5f) * 2.f - 1.f;
            }
            out.push_back(std::move(L));
        }
        return out;
    };

    std::vector<Variant> out;
    auto add = [&](const std::string& name, const std::string& tag, int mode) {
        Variant v;
        v.knob = "normal mips (8x8 footprint)";
        v.name = name, v.tag = tag;
        if (mode < 0) {  // no mips: the texel at the footprint's centre of level 0
            Level L{Image(lw, lw, 3), {}};
            for (int y = 0; y < lw; ++y)
                for (int x = 0; x < lw; ++x)
                    for (int k = 0; k < 3; ++k) L.normals.at(x, y, k) = level0->at(x * fp + fp / 2, y * fp + fp / 2, k);
            evaluate(L, v);
            v.work = nullptr;  // nothing to time
            v.note = "no preprocessing, so no time (not on the plot); unbiased but noisy: aliasing";
        } else {
            const auto levels_built = build(mode);
            evaluate(levels_built[static_cast<size_t>(level - 1)], v);
            v.work = [build, mode] { (void)build(mode); };
        }
        v.pixels = static_cast<double>(w) * w;
        v.unit = "ms/map";
        v.map_pixels = 1024.0 * 1024.0;
        v.map_name = "1K";
        out.push_back(std::move(v));
    };
    add("level 0 point-sampled (no mips)", "NO MIPS", -1);
    add("box mips, not renormalized (shader normalizes)", "BOX", 0);
    add("box mips, renormalized", "BOX RENORM", 1);
    add("box mips, renormalized + Toksvig roughness", "BOX+TOKSVIG", 2);
    add("Lanczos-3 mips (mf::resample), renormalized", "LANCZOS RENORM", 3);
    return out;
}

}  // namespace mf::bench
