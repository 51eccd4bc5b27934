// Test helpers: tiny material sets built in memory, read through a BandReader that slices
// mf::Image objects (the validator cannot tell it from files), and height→normal generation.
#pragma once
#include <cmath>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "validate/validate.hpp"

namespace mft {

using mf::Image;
using mf::NormalConvention;
using mf::Role;

// A set of in-memory maps. Inputs name their image by InputFile::display.
struct MemSet {
    std::map<std::string, std::shared_ptr<Image>> images;
    std::map<std::string, mf::ImageInfo> infos;
    std::vector<mf::validate::MapInput> inputs;
    std::vector<std::string> broken;  // names whose reads fail

    void add(Role role, const std::string& name, Image img, bool is_float = false,
             NormalConvention conv = NormalConvention::unknown, int bit_depth = 8) {
        mf::ImageInfo info;
        info.width = img.width;
        info.height = img.height;
        info.channels = img.channels;
        info.is_float = is_float;
        info.bit_depth = is_float ? 32 : bit_depth;
        info.format = "memory";
        images[name] = std::make_shared<Image>(std::move(img));
        infos[name] = info;
        mf::validate::MapInput in;
        in.role = role;
        in.file.display = name;
        in.name = name;
        in.info = info;
        in.name_convention = conv;
        // replace an existing input of the same name
        for (auto& e : inputs)
            if (e.name == name) {
                e = in;
                return;
            }
        inputs.push_back(in);
    }
    mf::validate::MapInput* input(const std::string& name) {
        for (auto& e : inputs)
            if (e.name == name) return &e;
        return nullptr;
    }
    void remove(const std::string& name) {
        std::erase_if(inputs, [&](const auto& e) { return e.name == name; });
    }

    mf::validate::BandReader reader() const {
        auto imgs = images;
        auto inf = infos;
        auto bad = broken;
        return [imgs, inf, bad](const mf::InputFile& in, int band_rows, mf::ImageInfo& info, std::string& err,
                                const std::function<void(int, int, mf::validate::Samples)>& fn) {
            if (std::find(bad.begin(), bad.end(), in.display) != bad.end()) {
                err = in.display + ": truncated file";
                return false;
            }
            auto it = imgs.find(in.display);
            if (it == imgs.end()) {
                err = in.display + ": not found";
                return false;
            }
            const Image& im = *it->second;
            info = inf.at(in.display);
            for (int y0 = 0; y0 < im.height; y0 += band_rows) {
                const int rows = std::min(band_rows, im.height - y0);
                fn(y0, rows, {im.pixels.data() + im.index(0, y0)});
            }
            return true;
        };
    }

    mf::validate::SetValidation run(const mf::rules::RuleConfig& cfg = {}, const std::string& material = "Test",
                                    int band_rows = 16) const {
        mf::validate::ValidateOptions opt;
        opt.material = material;
        opt.reader = reader();
        opt.band_rows = band_rows;
        auto res = mf::validate::validate_set(inputs, cfg, opt);
        dropped = mf::rules::apply_config(res.findings, material, cfg);  // as plan's reported_findings
        return res;
    }
    mutable int dropped = 0;  // by the last run()'s rules config
};

inline Image constant(int w, int h, std::vector<float> v) {
    Image im(w, h, static_cast<int>(v.size()));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < im.channels; ++c) im.at(x, y, c) = v[c];
    return im;
}

// Smooth isotropic height: a sum of plane waves at `freq` cycles per image with random
// directions and phases, values in about [0, 1].
inline Image make_height(int size, double freq, unsigned seed, int waves = 6) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    struct Wave {
        double kx, ky, ph;
    };
    std::vector<Wave> ws;
    for (int i = 0; i < waves; ++i) {
        const double th = 2 * M_PI * u(rng);
        const double f = freq * (0.7 + 0.6 * u(rng));
        ws.push_back({2 * M_PI * f * std::cos(th) / size, 2 * M_PI * f * std::sin(th) / size, 2 * M_PI * u(rng)});
    }
    Image h(size, size, 1);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            double v = 0;
            for (const auto& w : ws) v += std::sin(w.kx * x + w.ky * y + w.ph);
            h.at(x, y) = static_cast<float>(0.5 + 0.5 * v / waves);
        }
    return h;
}

// Bricks: plateaus of random height with bevelled mortar joints, offset every other row —
// man-made content whose slopes sit on edges and corners only.
inline Image make_bricks(int size, int rows_of_bricks, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double bh = static_cast<double>(size) / rows_of_bricks, bw = 2 * bh, mortar = std::max(1.5, bh * 0.12);
    std::vector<double> top(static_cast<size_t>(rows_of_bricks) * (rows_of_bricks + 2));
    for (auto& t : top) t = 0.6 + 0.4 * u(rng);
    Image h(size, size, 1);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const int row = static_cast<int>(y / bh);
            const double xo = x + (row % 2 ? bw / 2 : 0.0);
            const int col = static_cast<int>(xo / bw);
            const double dy = std::min(y - row * bh, (row + 1) * bh - y);
            const double dx = std::min(xo - col * bw, (col + 1) * bw - xo);
            const double d = std::min(dx, dy);  // distance to the nearest joint
            const double bevel = std::clamp(d / mortar, 0.0, 1.0);
            h.at(x, y) = static_cast<float>(0.2 +
                                            bevel * (top[static_cast<size_t>(row) * (rows_of_bricks + 2) + col] - 0.2));
        }
    return h;
}

// Encodes a tangent-space normal map from a height (central differences, wrapping), in the
// given convention, as 2n−1-encoded RGB in [0, 1]; optional Gaussian noise per channel and
// quantization to 8 bits. Strength is chosen so that the RMS slope is `slope`.
inline Image normal_from_height(const Image& h, NormalConvention conv, double slope = 0.6, double noise = 0.0,
                                unsigned seed = 1, bool quantize = true) {
    const int w = h.width, H = h.height;
    std::vector<double> gx(static_cast<size_t>(w) * H), gr(gx.size());
    double ss = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < w; ++x) {
            const double a = 0.5 * (h.at((x + 1) % w, y) - h.at((x + w - 1) % w, y));
            const double b = 0.5 * (h.at(x, (y + 1) % H) - h.at(x, (y + H - 1) % H));
            gx[y * w + x] = a;
            gr[y * w + x] = b;
            ss += a * a + b * b;
        }
    const double s = ss > 0 ? slope / std::sqrt(ss / (w * H)) : 0.0;
    const double sign = conv == NormalConvention::dx ? -1.0 : 1.0;
    std::mt19937 rng(seed);
    std::normal_distribution<double> nd(0.0, noise > 0 ? noise : 1.0);
    Image n(w, H, 3);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < w; ++x) {
            double v[3] = {-s * gx[y * w + x], sign * s * gr[y * w + x], 1.0};
            const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
            for (int c = 0; c < 3; ++c) {
                double e = 0.5 * (v[c] / len) + 0.5;
                if (noise > 0) e += nd(rng);
                e = std::clamp(e, 0.0, 1.0);
                if (quantize) e = std::round(e * 255.0) / 255.0;
                n.at(x, y, c) = static_cast<float>(e);
            }
        }
    return n;
}

inline bool has_code(const std::vector<mf::Finding>& fs, std::string_view code) {
    for (const auto& f : fs)
        if (f.code == code) return true;
    return false;
}

inline std::string dump(const std::vector<mf::Finding>& fs) {
    std::string s;
    for (const auto& f : fs) s += mf::to_json(f).dump() + "\n";
    return s;
}

// A plausible, clean 64×64 set: textured mid albedo, a metal square with bright albedo,
// binary metalness, varying roughness/occlusion, height and its GL normal map.
inline MemSet clean_set(int size = 64) {
    MemSet s;
    std::mt19937 rng(42);
    std::uniform_real_distribution<float> u(-0.08f, 0.08f);
    Image albedo(size, size, 3), metal(size, size, 1), rough(size, size, 1), ao(size, size, 1);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const bool m = x >= size / 2 && y >= size / 2;
            metal.at(x, y) = m ? 1.f : 0.f;
            const float base = m ? 0.85f : 0.5f;  // sRGB-encoded: ~217 and ~128
            const float n = u(rng);
            albedo.at(x, y, 0) = base + n;
            albedo.at(x, y, 1) = base + n * 0.8f;
            albedo.at(x, y, 2) = base + n * 0.6f;
            rough.at(x, y) = 0.3f + 0.4f * static_cast<float>(x) / static_cast<float>(size);
            ao.at(x, y) = 0.7f + 0.3f * static_cast<float>(y) / static_cast<float>(size);
        }
    Image height = make_height(size, 4, 7);
    Image normal = normal_from_height(height, NormalConvention::gl);
    s.add(Role::albedo, "T_albedo.png", albedo);
    s.add(Role::metalness, "T_metallic.png", metal);
    s.add(Role::roughness, "T_roughness.png", rough);
    s.add(Role::occlusion, "T_ao.png", ao);
    s.add(Role::height, "T_height.png", height);
    s.add(Role::normal, "T_normal_gl.png", normal, false, NormalConvention::gl);
    return s;
}

}  // namespace mft
