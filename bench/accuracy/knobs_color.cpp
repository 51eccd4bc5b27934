// Knobs on colour data: the transfer curve, output quantization, validation statistics.
#include <OpenColorIO/OpenColorIO.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <numeric>
#include <stdexcept>

#include "base/srgb.hpp"
#include "harness.hpp"
#include "image/image.hpp"

namespace OCIO = OCIO_NAMESPACE;

namespace mf::bench {
namespace {

// ------------------------------------------------------------------------------------------
// Transfer curve. Decoding takes 8-bit sRGB codes (what albedo files hold) to linear float;
// encoding takes linear float to sRGB. Reference: IEC 61966-2-1 in double (srgb.hpp).

struct TransferData {
    size_t pixels;
    std::vector<uint8_t> codes;         // decode input, 3 per pixel
    std::vector<float> codes_f;         // the same as code / 255
    std::vector<float> linear_in;       // encode input
    mutable std::vector<float> out;     // 3 per pixel
    mutable std::vector<uint8_t> out8;  // LUT encoder output
    std::array<float, 256> decode_lut{};
    std::array<uint8_t, 4096> encode_lut{};
    OCIO::ConstCPUProcessorRcPtr dec_lossless, dec_default, dec_u8_default, dec_u8_lossless;
    OCIO::ConstCPUProcessorRcPtr enc_lossless, enc_default;
};

std::shared_ptr<TransferData> make_transfer_data(const Config& c) {
    auto d = std::make_shared<TransferData>();
    d->pixels = c.quick ? 65536 : 1 << 20;
    const size_t n = d->pixels * 3;
    d->codes.resize(n), d->codes_f.resize(n), d->linear_in.resize(n), d->out.resize(n), d->out8.resize(n);
    uint32_t s = 12345;
    for (size_t i = 0; i < n; ++i) {
        d->codes[i] = static_cast<uint8_t>(xorshift(s) & 255u);
        d->codes_f[i] = static_cast<float>(d->codes[i]) / 255.f;
        // Uniform in encoded space, so the dark end (where the curves differ most) is sampled
        // as densely as a texture's codes are.
        d->linear_in[i] = static_cast<float>(srgb_to_linear((static_cast<double>(i) + 0.5) / static_cast<double>(n)));
    }
    for (int k = 0; k < 256; ++k) d->decode_lut[static_cast<size_t>(k)] = static_cast<float>(srgb_to_linear(k / 255.0));
    for (int k = 0; k < 4096; ++k)
        d->encode_lut[static_cast<size_t>(k)] = static_cast<uint8_t>(std::lround(linear_to_srgb(k / 4095.0) * 255.0));
    auto config = OCIO::Config::CreateFromFile(c.ocio_config.c_str());
    auto dec = config->getProcessor("srgb_texture", "lin_rec709");
    auto enc = config->getProcessor("lin_rec709", "srgb_texture");
    using OCIO::BIT_DEPTH_F32, OCIO::BIT_DEPTH_UINT8;
    d->dec_lossless = dec->getOptimizedCPUProcessor(BIT_DEPTH_F32, BIT_DEPTH_F32, OCIO::OPTIMIZATION_LOSSLESS);
    d->dec_default = dec->getOptimizedCPUProcessor(BIT_DEPTH_F32, BIT_DEPTH_F32, OCIO::OPTIMIZATION_DEFAULT);
    d->dec_u8_default = dec->getOptimizedCPUProcessor(BIT_DEPTH_UINT8, BIT_DEPTH_F32, OCIO::OPTIMIZATION_DEFAULT);
    d->dec_u8_lossless = dec->getOptimizedCPUProcessor(BIT_DEPTH_UINT8, BIT_DEPTH_F32, OCIO::OPTIMIZATION_LOSSLESS);
    d->enc_lossless = enc->getOptimizedCPUProcessor(BIT_DEPTH_F32, BIT_DEPTH_F32, OCIO::OPTIMIZATION_LOSSLESS);
    d->enc_default = enc->getOptimizedCPUProcessor(BIT_DEPTH_F32, BIT_DEPTH_F32, OCIO::OPTIMIZATION_DEFAULT);
    return d;
}

void ocio_apply_f32(const OCIO::ConstCPUProcessorRcPtr& p, const std::vector<float>& in, std::vector<float>& out,
                    size_t pixels) {
    std::copy(in.begin(), in.end(), out.begin());
    OCIO::PackedImageDesc desc(out.data(), static_cast<long>(pixels), 1, 3);
    p->apply(desc);
}

void ocio_apply_u8(const OCIO::ConstCPUProcessorRcPtr& p, const std::vector<uint8_t>& in, std::vector<float>& out,
                   size_t pixels) {
    const long w = static_cast<long>(pixels);
    OCIO::PackedImageDesc src(const_cast<uint8_t*>(in.data()), w, 1, 3, OCIO::BIT_DEPTH_UINT8, 1, 3, 3 * w);
    OCIO::PackedImageDesc dst(out.data(), w, 1, 3, OCIO::BIT_DEPTH_F32, 4, 12, 12 * w);
    p->apply(src, dst);
}

// Decode errors over the output buffer: linear |out − exact| and, in code units, how far the
// exact re-encoding of the output lands from the input code.
void decode_errors(const TransferData& d, Variant& v) {
    Acc lin, codes;
    for (size_t i = 0; i < d.out.size(); ++i) {
        const double code = d.codes[i];
        lin.add(d.out[i] - srgb_to_linear(code / 255.0));
        codes.add(linear_to_srgb(static_cast<double>(d.out[i])) * 255.0 - code);
    }
    v.max_codes = codes.max, v.mean_codes = codes.mean(), v.max_linear = lin.max, v.mean_linear = lin.mean();
}

// Encode errors: in code units |out − exact| · 255 (continuous), in linear terms the exact
// decoding of the output against the input; the note counts 8-bit codes that differ.
void encode_errors(const TransferData& d, Variant& v, bool from_u8) {
    Acc lin, codes;
    size_t wrong = 0;
    for (size_t i = 0; i < d.linear_in.size(); ++i) {
        const double x = d.linear_in[i];
        const double out = from_u8 ? d.out8[i] / 255.0 : static_cast<double>(d.out[i]);
        const double exact = linear_to_srgb(x);
        codes.add((out - exact) * 255.0);
        lin.add(srgb_to_linear(out) - x);
        wrong += quantize(static_cast<float>(out), 8) != quantize(static_cast<float>(exact), 8);
    }
    v.max_codes = codes.max, v.mean_codes = codes.mean(), v.max_linear = lin.max, v.mean_linear = lin.mean();
    char buf[96];
    std::snprintf(buf, sizeof buf, "8-bit codes differing from exact: %.3f %%",
                  100.0 * static_cast<double>(wrong) / static_cast<double>(d.linear_in.size()));
    v.note = buf;
}

}  // namespace

std::vector<Variant> transfer_variants(const Config& c) {
    auto d = make_transfer_data(c);
    std::vector<Variant> out;
    auto add = [&](const std::string& knob, const std::string& name, const std::string& tag, std::function<void()> work,
                   bool decode, bool u8_out = false, std::string note = {}) {
        Variant v;
        v.knob = knob, v.name = name, v.tag = tag, v.work = std::move(work);
        v.pixels = static_cast<double>(d->pixels), v.unit = "ns/px";
        v.linear_unit = "linear";
        v.work();  // once for the errors
        if (decode) decode_errors(*d, v);
        else encode_errors(*d, v, u8_out);
        if (!note.empty()) v.note = note + (v.note.empty() ? "" : "; " + v.note);
        out.push_back(std::move(v));
    };
    const size_t n = d->pixels * 3;
    const std::string dk = "transfer: decode sRGB->linear", ek = "transfer: encode linear->sRGB";
    add(
        dk, "exact IEC 61966-2-1 (float)", "EXACT",
        [d, n] {
            for (size_t i = 0; i < n; ++i) d->out[i] = srgb_to_linear(d->codes_f[i]);
        },
        true);
    add(
        dk, "pow(x, 2.2) (gamma 2.2 approximation)", "POW 2.2",
        [d, n] {
            for (size_t i = 0; i < n; ++i) d->out[i] = std::pow(d->codes_f[i], 2.2f);
        },
        true);
    add(
        dk, "OCIO float, lossless optimization", "OCIO LOSSLESS",
        [d] { ocio_apply_f32(d->dec_lossless, d->codes_f, d->out, d->pixels); }, true, false, "matforge's processor");
    add(
        dk, "OCIO float, default optimization", "OCIO DEFAULT",
        [d] { ocio_apply_f32(d->dec_default, d->codes_f, d->out, d->pixels); }, true);
    add(
        dk, "OCIO uint8 in, default optimization", "OCIO U8 DEFAULT",
        [d] { ocio_apply_u8(d->dec_u8_default, d->codes, d->out, d->pixels); }, true, false,
        "bakes a LUT for 8-bit input");
    add(
        dk, "OCIO uint8 in, lossless optimization", "OCIO U8 LOSSLESS",
        [d] { ocio_apply_u8(d->dec_u8_lossless, d->codes, d->out, d->pixels); }, true);
    add(
        dk, "256-entry lookup table (uint8 in)", "LUT 8-BIT",
        [d, n] {
            for (size_t i = 0; i < n; ++i) d->out[i] = d->decode_lut[d->codes[i]];
        },
        true);

    add(
        ek, "exact IEC 61966-2-1 (float)", "EXACT",
        [d, n] {
            for (size_t i = 0; i < n; ++i) d->out[i] = linear_to_srgb(d->linear_in[i]);
        },
        false);
    add(
        ek, "pow(x, 1/2.2) (gamma 2.2 approximation)", "POW 1/2.2",
        [d, n] {
            for (size_t i = 0; i < n; ++i) d->out[i] = std::pow(d->linear_in[i], 1.f / 2.2f);
        },
        false);
    add(
        ek, "OCIO float, lossless optimization", "OCIO LOSSLESS",
        [d] { ocio_apply_f32(d->enc_lossless, d->linear_in, d->out, d->pixels); }, false, false,
        "matforge's processor");
    add(
        ek, "OCIO float, default optimization", "OCIO DEFAULT",
        [d] { ocio_apply_f32(d->enc_default, d->linear_in, d->out, d->pixels); }, false);
    add(
        ek, "4096-entry table to 8-bit codes", "LUT 12->8 BIT",
        [d, n] {
            for (size_t i = 0; i < n; ++i) {
                const float x = std::clamp(d->linear_in[i], 0.f, 1.f);
                d->out8[i] = d->encode_lut[static_cast<size_t>(x * 4095.f + 0.5f)];
            }
        },
        false, true, "output is a code: includes the <= 0.5-code rounding");
    return out;
}

// ------------------------------------------------------------------------------------------
// Output quantization: albedo (sRGB-encoded in integer files, linear in EXR) and roughness
// (linear data) written as 8-bit PNG, 16-bit PNG, half EXR, float EXR, read back.

namespace {

Image read_back(const std::vector<unsigned char>& bytes, const std::string& ext) {
    InputFile in;
    in.display = "bench." + ext;
    in.bytes = std::make_shared<const std::vector<unsigned char>>(bytes);
    Image img;
    ImageInfo info;
    std::string err;
    if (!read_image(in, img, info, err)) throw std::runtime_error(err);
    return img;
}

// Longest run of identical output values along a slow 4096-px ramp: the width of a visible band.
int longest_band(const std::vector<float>& ramp_out) {
    int best = 1, run = 1;
    for (size_t i = 1; i < ramp_out.size(); ++i) {
        run = ramp_out[i] == ramp_out[i - 1] ? run + 1 : 1;
        best = std::max(best, run);
    }
    return best;
}

}  // namespace

std::vector<Variant> quantize_variants(const Config& c) {
    const int w = c.quick ? 256 : 1024;
    // Texture-like content: gradients, a soft pattern and fine noise, in linear light / data.
    auto albedo = std::make_shared<Image>(w, w, 3);
    auto rough = std::make_shared<Image>(w, w, 1);
    uint32_t s = 777;
    for (int y = 0; y < w; ++y)
        for (int x = 0; x < w; ++x) {
            const double u = (x + 0.5) / w, t = (y + 0.5) / w;
            const double pat = 0.5 + 0.5 * std::sin(12.0 * u + 3.0 * std::sin(9.0 * t));
            const double noise = (static_cast<double>(xorshift(s) & 0xffff) / 65535.0 - 0.5) * 0.01;
            for (int k = 0; k < 3; ++k)
                albedo->at(x, y, k) = static_cast<float>(
                    std::clamp(0.02 + 0.7 * u * (0.6 + 0.4 * pat) * (1.0 - 0.2 * k) + noise, 0.0, 1.0));
            rough->at(x, y, 0) = static_cast<float>(std::clamp(0.1 + 0.8 * t * (0.7 + 0.3 * pat) + noise, 0.0, 1.0));
        }
    // A slow ramp: 4096 px from 0.18 to 0.22 (linear), where a mid-grey albedo or roughness band shows.
    std::vector<float> ramp(4096);
    for (size_t i = 0; i < ramp.size(); ++i) ramp[i] = 0.18f + 0.04f * static_cast<float>(i) / 4095.f;

    struct Fmt {
        const char* name;
        const char* tag;
        EncodeOptions opt;
    };
    const Fmt fmts[] = {{"8-bit PNG", "8-BIT", {mf::FileFormat::png, 8}},
                        {"16-bit PNG", "16-BIT", {mf::FileFormat::png, 16}},
                        {"half EXR", "HALF", {mf::FileFormat::exr, 16}},
                        {"float EXR", "FLOAT", {mf::FileFormat::exr, 32}}};
    std::vector<Variant> out;
    for (bool is_albedo : {true, false}) {
        for (const Fmt& f : fmts) {
            const bool srgb_file = is_albedo && f.opt.format == mf::FileFormat::png;
            // What the file receives: sRGB-encoded albedo in integer files, linear otherwise.
            auto src = std::make_shared<Image>(is_albedo ? *albedo : *rough);
            if (srgb_file)
                for (float& v : src->pixels) v = static_cast<float>(linear_to_srgb(static_cast<double>(v)));
            std::vector<unsigned char> bytes;
            std::string err;
            if (!encode_image(*src, f.opt, bytes, err)) throw std::runtime_error(err);
            const Image back = read_back(bytes, std::string(mf::word(f.opt.format)));
            Acc lin, codes;
            const Image& ref = is_albedo ? *albedo : *rough;
            for (size_t i = 0; i < ref.pixels.size(); ++i) {
                const double truth = ref.pixels[i];
                const double got = srgb_file ? srgb_to_linear(static_cast<double>(back.pixels[i])) : back.pixels[i];
                lin.add(got - truth);
                // Code units: of the sRGB encoding for albedo (what the eye sees), of the data otherwise.
                codes.add(is_albedo ? (linear_to_srgb(got) - linear_to_srgb(truth)) * 255.0 : (got - truth) * 255.0);
            }
            // Banding on the ramp.
            Image r(static_cast<int>(ramp.size()), 1, 1);
            for (size_t i = 0; i < ramp.size(); ++i)
                r.pixels[i] = srgb_file ? static_cast<float>(linear_to_srgb(static_cast<double>(ramp[i]))) : ramp[i];
            std::vector<unsigned char> rb;
            encode_image(r, f.opt, rb, err);
            const int band = longest_band(read_back(rb, std::string(mf::word(f.opt.format))).pixels);

            Variant v;
            v.knob = is_albedo ? "quantize: albedo" : "quantize: roughness";
            v.name = std::string(is_albedo ? "albedo " : "roughness ") + f.name + (srgb_file ? " (sRGB)" : " (linear)");
            v.tag = f.tag;
            v.max_codes = codes.max, v.mean_codes = codes.mean(), v.max_linear = lin.max, v.mean_linear = lin.mean();
            v.linear_unit = "linear";
            char buf[160];
            std::snprintf(buf, sizeof buf,
                          "%.2f bytes/px (%zu B per %dx%d); widest band %d px of a 4096-px 0.18-0.22 ramp",
                          static_cast<double>(bytes.size()) / (static_cast<double>(w) * w), bytes.size(), w, w, band);
            v.note = buf;
            const EncodeOptions opt = f.opt;
            v.work = [src, opt] {
                std::vector<unsigned char> b;
                std::string e;
                encode_image(*src, opt, b, e);
            };
            v.pixels = static_cast<double>(w) * w;
            v.unit = "ms/map";
            v.map_pixels = 1024.0 * 1024.0;
            v.map_name = "1K";
            out.push_back(std::move(v));
        }
    }
    return out;
}

// ------------------------------------------------------------------------------------------
// Validation statistics from every pixel vs sampled subsets, on a synthetic 8K albedo held as
// 8-bit sRGB (what an 8K PNG decodes to). Figures as lib/validate reports them: luminance
// Y = 0.2126 R + 0.7152 G + 0.0722 B of the linear colour, re-encoded to an sRGB code; mean,
// 5th and 95th percentile code; share below code 30 and above 240 (the PBR guide's bounds).

namespace {

struct Figures {
    double mean = 0, p5 = 0, p95 = 0, below = 0, above = 0;  // codes; shares in %
};

struct StatsData {
    int size = 0;
    std::vector<uint8_t> rgb;
    std::array<float, 256> lin{};    // code -> linear
    std::array<float, 256> edges{};  // linear luminance at code k + 0.5
};

template <class Visit>
Figures figures(const StatsData& d, Visit&& visit) {
    std::array<uint64_t, 256> hist{};
    visit([&](size_t i) {
        const uint8_t* p = &d.rgb[i * 3];
        const float y = 0.2126f * d.lin[p[0]] + 0.7152f * d.lin[p[1]] + 0.0722f * d.lin[p[2]];
        const size_t code = static_cast<size_t>(std::upper_bound(d.edges.begin(), d.edges.end() - 1, y) -
                                                d.edges.begin());
        ++hist[code];
    });
    Figures f;
    const double n = static_cast<double>(std::accumulate(hist.begin(), hist.end(), uint64_t{0}));
    double acc = 0, sum = 0;
    bool got5 = false, got95 = false;
    for (size_t k = 0; k < 256; ++k) {
        sum += static_cast<double>(hist[k]) * static_cast<double>(k);
        acc += static_cast<double>(hist[k]);
        if (!got5 && acc >= 0.05 * n) f.p5 = static_cast<double>(k), got5 = true;
        if (!got95 && acc >= 0.95 * n) f.p95 = static_cast<double>(k), got95 = true;
        if (k < 30) f.below += static_cast<double>(hist[k]);
        if (k > 240) f.above += static_cast<double>(hist[k]);
    }
    f.mean = sum / n, f.below *= 100.0 / n, f.above *= 100.0 / n;
    return f;
}

}  // namespace

std::vector<Variant> stats_variants(const Config& c) {
    auto d = std::make_shared<StatsData>();
    d->size = c.quick ? 1024 : 8192;
    const size_t n = static_cast<size_t>(d->size) * d->size;
    d->rgb.resize(n * 3);
    for (int k = 0; k < 256; ++k) d->lin[static_cast<size_t>(k)] = static_cast<float>(srgb_to_linear(k / 255.0));
    for (int k = 0; k < 256; ++k)
        d->edges[static_cast<size_t>(k)] = static_cast<float>(srgb_to_linear(std::min(k + 0.5, 255.0) / 255.0));
    // Content: a noisy brick wall (period 64 × 32) with 2-px light mortar every 16 px in x
    // (a pattern that a regular stride can alias with), a dark corner (soot), a bright patch.
    uint32_t s = 4242;
    for (int y = 0; y < d->size; ++y)
        for (int x = 0; x < d->size; ++x) {
            uint8_t* p = &d->rgb[(static_cast<size_t>(y) * d->size + x) * 3];
            const uint32_t r = xorshift(s);
            int base = 120 + static_cast<int>(r & 63) - 32 + ((x / 64 + y / 32) % 3) * 12;
            if (x % 16 < 2) base = 236 + static_cast<int>((r >> 8) & 15);                          // mortar: bright
            if (x < d->size / 5 && y < d->size / 4) base = 18 + static_cast<int>((r >> 12) & 15);  // soot
            p[0] = static_cast<uint8_t>(std::clamp(base + 12, 0, 255));
            p[1] = static_cast<uint8_t>(std::clamp(base, 0, 255));
            p[2] = static_cast<uint8_t>(std::clamp(base - 16, 0, 255));
        }
    const Figures full = figures(*d, [&](auto&& f) {
        for (size_t i = 0; i < n; ++i) f(i);
    });

    std::vector<Variant> out;
    auto add = [&](const std::string& name, const std::string& tag, std::function<Figures()> run) {
        const Figures f = run();
        Variant v;
        v.knob = "validation statistics";
        v.name = name, v.tag = tag;
        const double e_codes[] = {std::abs(f.mean - full.mean), std::abs(f.p5 - full.p5), std::abs(f.p95 - full.p95)};
        const double e_pp[] = {std::abs(f.below - full.below), std::abs(f.above - full.above)};
        v.max_codes = *std::max_element(std::begin(e_codes), std::end(e_codes));
        v.mean_codes = (e_codes[0] + e_codes[1] + e_codes[2]) / 3.0;
        v.max_linear = std::max(e_pp[0], e_pp[1]);
        v.mean_linear = (e_pp[0] + e_pp[1]) / 2.0;
        v.linear_unit = "% points";
        char buf[200];
        std::snprintf(buf, sizeof buf,
                      "mean %.2f p5 %.0f p95 %.0f below30 %.2f%% above240 %.2f%% (full: %.2f %.0f %.0f %.2f%% %.2f%%)",
                      f.mean, f.p5, f.p95, f.below, f.above, full.mean, full.p5, full.p95, full.below, full.above);
        v.note = buf;
        v.work = [run] { (void)run(); };
        v.pixels = static_cast<double>(n);
        v.unit = "ms/map";
        v.map_pixels = 8192.0 * 8192.0;
        v.map_name = "8K";
        v.iterations = c.quick ? 0 : 2;
        out.push_back(std::move(v));
    };
    const int sz = d->size;
    add("every pixel", "ALL", [d, n] {
        return figures(*d, [&](auto&& f) {
            for (size_t i = 0; i < n; ++i) f(i);
        });
    });
    for (int stride : {2, 4, 16}) {
        const char* ord = stride == 2 ? "2nd" : stride == 4 ? "4th" : "16th";
        add(std::string("regular grid, every ") + ord + " pixel in x and y (1/" + std::to_string(stride * stride) + ")",
            "GRID 1/" + std::to_string(stride * stride), [d, sz, stride] {
                return figures(*d, [&](auto&& f) {
                    for (int y = 0; y < sz; y += stride)
                        for (int x = 0; x < sz; x += stride) f(static_cast<size_t>(y) * sz + x);
                });
            });
    }
    for (int frac : {64, 1024, 16384}) {
        const size_t count = n / static_cast<size_t>(frac);
        add("random subset, " + std::to_string(count) + " pixels (1/" + std::to_string(frac) + ")",
            "RANDOM 1/" + std::to_string(frac), [d, n, count] {
                uint32_t st = 99;
                return figures(*d, [&](auto&& f) {
                    for (size_t i = 0; i < count; ++i) {
                        const uint64_t r = (static_cast<uint64_t>(xorshift(st)) << 32) | xorshift(st);
                        f(static_cast<size_t>(r % n));
                    }
                });
            });
    }
    return out;
}

}  // namespace mf::bench
