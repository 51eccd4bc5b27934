// Knobs of the GPU textures (lib/texture): the block encoders and their efforts on a real
// photograph; a cut-out's mips with and without the alpha test's coverage kept (and through BC7);
// a cut-out's hidden edge texels with and without dilate_under_alpha before BC7.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/srgb.hpp"
#include "harness.hpp"
#include "image/image.hpp"
#include "preset/texture_fields.hpp"
#include "texture/texture.hpp"

namespace mf::bench {
namespace {

using texture::ChannelKind;

const std::string kRealCorpus = std::string(MATFORGE_SOURCE_DIR) + "/tests/data/corpus/real/";

// A file's 8-bit codes, read with lib/image as bench/texture/texture_bench.cpp reads them (a
// non-8-bit file rounded to codes).
Image8 read_codes(const std::string& file) {
    InputFile in;
    in.path = file;
    in.display = file;
    Decoded d;
    ImageInfo info;
    std::string error;
    if (!read_image(in, d, info, error)) throw std::runtime_error(error);
    if (d.is_codes()) return std::move(d.codes);
    Image8 out(d.floats.width, d.floats.height, d.floats.channels);
    for (size_t i = 0; i < out.pixels.size(); ++i)
        out.pixels[i] = static_cast<uint8_t>(std::lround(std::clamp(d.floats.pixels[i], 0.f, 1.f) * 255.f));
    return out;
}

// The whole map, or (--quick) the 256x256 from its middle.
int crop_size(const Config& c, const Image8& img) { return c.quick ? std::min({256, img.width, img.height}) : 0; }
Image8 middle(const Image8& img, int size) {
    if (size <= 0) return img;
    Image8 out(size, size, img.channels);
    const int x0 = (img.width - size) / 2, y0 = (img.height - size) / 2;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            for (int k = 0; k < img.channels; ++k) out.at(x, y, k) = img.at(x0 + x, y0 + y, k);
    return out;
}

// Channels [first, first + n) of `img`.
Image8 take(const Image8& img, int first, int n) {
    Image8 out(img.width, img.height, n);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            for (int k = 0; k < n; ++k) out.at(x, y, k) = img.at(x, y, std::min(first + k, img.channels - 1));
    return out;
}

const BlockFormatInfo& format(const char* name) {
    const BlockFormatInfo* f = block_format_info(name);
    if (!f) throw std::runtime_error(std::string("block format ") + name + " unknown to this build");
    return *f;
}

texture::CodecOptions codec(const BlockFormatInfo& f, Effort effort) {
    texture::CodecOptions o;
    o.format = &f;
    o.srgb = true;
    o.effort = effort;
    o.threads = 1;
    return o;
}

Image8 encode_decode(const Image8& level, const texture::CodecOptions& opt) {
    std::vector<uint8_t> blocks;
    Image8 rgba;
    std::string error;
    if (!texture::encode_level(level, opt, blocks, error) ||
        !texture::decode_level(blocks, level.width, level.height, opt, rgba, error))
        throw std::runtime_error(std::string(opt.format->name) + ": " + error);
    return rgba;
}

std::string printf_string(const char* fmt, double a, double b = 0, double c = 0) {
    char buf[160];
    std::snprintf(buf, sizeof buf, fmt, a, b, c);
    return buf;
}

void per_1k_map(Variant& v, const Image8& img) {
    v.pixels = static_cast<double>(img.width) * img.height;
    v.unit = "ms/map";
    v.map_pixels = 1024.0 * 1024.0;
    v.map_name = "1K";
}

// ambientCG's Net004A (a net: strands over holes), its colour and opacity as one RGBA map of codes.
Image8 net_rgba(const Config& c) {
    const std::string dir = kRealCorpus + "ambientcg_Net004A_1K-JPG/Net004A_1K-JPG";
    const Image8 color = read_codes(dir + "_Color.jpg"), opacity = read_codes(dir + "_Opacity.jpg");
    if (color.width != opacity.width || color.height != opacity.height)
        throw std::runtime_error("Net004A: colour and opacity differ in size");
    Image8 rgba(color.width, color.height, 4);
    for (int y = 0; y < color.height; ++y)
        for (int x = 0; x < color.width; ++x) {
            for (int k = 0; k < 3; ++k) rgba.at(x, y, k) = color.at(x, y, std::min(k, color.channels - 1));
            rgba.at(x, y, 3) = opacity.at(x, y, 0);
        }
    return middle(rgba, crop_size(c, rgba));
}

// The kinds a preset's sRGB base colour with its opacity in A gets (texture::channel_kinds):
// with `cutout`, A is alpha_tested (coverage kept); without, it is data (plain averages).
std::vector<ChannelKind> net_kinds(bool cutout) {
    ChannelSpec rgb, a;
    rgb.key = "RGB", rgb.kind = Channel::Kind::role, rgb.role = Role::albedo;
    a.key = "A", a.kind = Channel::Kind::role, a.role = Role::opacity;
    return texture::channel_kinds({rgb, a}, true, cutout);
}

constexpr float kCutoff = 0.5f;  // the presets' alpha_cutoff
constexpr uint8_t kShownFrom = 128;

}  // namespace

// ------------------------------------------------------------------------------------------
// Block encoders on a photograph (Poly Haven's brown_planks_09 albedo, 8-bit sRGB RGB codes):
// each format and effort encoded on one thread, decoded back, its code error over R, G, B.

std::vector<Variant> encoder_variants(const Config& c) {
    const Image8 file = read_codes(kRealCorpus + "polyhaven_brown_planks_09_1k_jpg+webp/brown_planks_09_diff_1k.jpg");
    auto src = std::make_shared<const Image8>(middle(take(file, 0, 3), crop_size(c, file)));
    struct Format {
        const char* name;
        const char* label;
        const char* tag;
    };
    const Format formats[] = {{"bc1", "BC1", "BC1"},
                              {"bc7", "BC7", "BC7"},
                              {"astc-4x4", "ASTC 4x4", "A4"},
                              {"astc-6x6", "ASTC 6x6", "A6"}};
    const std::pair<Effort, const char*> efforts[] = {{Effort::fast, "fast"},
                                                      {Effort::normal, "normal"},
                                                      {Effort::thorough, "thorough"}};
    std::vector<Variant> out;
    for (const Format& fm : formats) {
        const BlockFormatInfo& f = format(fm.name);
        const double bytes_per_texel = static_cast<double>(f.block_bytes) / (f.block_width * f.block_height);
        for (const auto& [effort, word] : efforts) {
            const texture::CodecOptions opt = codec(f, effort);
            const Image8 dec = encode_decode(*src, opt);
            Acc codes;
            for (size_t p = 0; p < static_cast<size_t>(src->width) * src->height; ++p)
                for (size_t k = 0; k < 3; ++k)
                    codes.add(static_cast<double>(src->pixels[p * 3 + k]) - static_cast<double>(dec.pixels[p * 4 + k]));
            Variant v;
            v.knob = "block encoders (sRGB photograph)";
            v.name = std::string(fm.label) + ", " + word;
            v.tag = std::string(fm.tag) + " " + static_cast<char>(word[0] - 'a' + 'A');
            v.max_codes = codes.max, v.mean_codes = codes.mean();
            v.max_linear = v.mean_linear = std::nan("");
            v.note = printf_string("PSNR %.2f dB; %.2f bytes/texel", texture::psnr(*src, dec, 3), bytes_per_texel);
            v.work = [src, opt] {
                std::vector<uint8_t> blocks;
                std::string error;
                if (!texture::encode_level(*src, opt, blocks, error)) throw std::runtime_error(error);
            };
            per_1k_map(v, *src);
            out.push_back(std::move(v));
        }
    }
    return out;
}

// ------------------------------------------------------------------------------------------
// A cut-out's mips: the alpha test's coverage of the 16x16 level against level 0's, with alpha
// averaged as data, with the coverage kept (alpha_tested), and kept then through BC7.

std::vector<Variant> cutout_mip_variants(const Config& c) {
    auto src = std::make_shared<const Image8>(net_rgba(c));
    const double cov0 = texture::alpha_coverage(*src, 3, kCutoff);
    auto chain_of = [src](bool keep) {
        texture::MipOptions mo;
        mo.alpha_cutoff = kCutoff;
        return texture::make_mips(*src, net_kinds(keep), mo);
    };
    const texture::CodecOptions bc7 = codec(format("bc7"), Effort::normal);
    std::vector<Variant> out;
    auto add = [&](const std::string& name, const std::string& tag, bool keep, bool encode) {
        std::vector<Image8> chain = chain_of(keep);
        size_t l16 = 0;
        while (l16 + 1 < chain.size() && chain[l16].width > 16) ++l16;
        // Every level down to 16x16: the worst of them goes to the note.
        double worst = 0, at16 = 0;
        for (size_t l = 1; l <= l16; ++l) {
            const Image8 level = encode ? encode_decode(chain[l], bc7) : chain[l];
            const double d = (texture::alpha_coverage(level, 3, kCutoff) - cov0) * 100.0;
            if (std::abs(d) > std::abs(worst)) worst = d;
            if (l == l16) at16 = d;
        }
        Variant v;
        v.knob = "cut-out mips (alpha-test coverage)";
        v.name = name, v.tag = tag;
        v.max_codes = v.mean_codes = std::nan("");
        v.max_linear = v.mean_linear = std::abs(at16);
        v.linear_unit = "% points";
        v.note = printf_string("coverage %.1f %% at level 0, %.1f %% at 16x16; worst level down to 16x16: %+.1f points",
                               cov0 * 100.0, cov0 * 100.0 + at16, worst);
        v.work = [chain_of, keep, encode, bc7] {
            const std::vector<Image8> mips = chain_of(keep);
            if (!encode) return;
            std::vector<uint8_t> blocks;
            std::string error;
            for (const Image8& level : mips)
                if (!texture::encode_level(level, bc7, blocks, error)) throw std::runtime_error(error);
        };
        per_1k_map(v, *src);
        out.push_back(std::move(v));
    };
    add("alpha averaged as data (coverage lost)", "AVERAGED", false, false);
    add("coverage kept (alpha_tested), stored", "KEPT", true, false);
    add("coverage kept, then BC7 (normal) as decoded", "KEPT+BC7", true, true);
    return out;
}

// ------------------------------------------------------------------------------------------
// A cut-out's edges: the hidden texels next to shown ones are what bilinear filtering and the
// mips mix into the shown colour. Measured as tests/texture/gpu_presets_test.cpp
// (CutOutKeepsItsCoverageAndItsEdgesTakeTheShownColour) measures the ingested outputs: each hidden
// texel (A < 128) with a shown 8-neighbour (wrapping), the code distance of its BC7-decoded colour
// from the sRGB encoding of its shown neighbours' mean in linear light (source codes), per channel.

std::vector<Variant> cutout_edge_variants(const Config& c) {
    auto src = std::make_shared<const Image8>(net_rgba(c));
    const std::vector<ChannelKind> kinds = net_kinds(true);
    const texture::CodecOptions bc7 = codec(format("bc7"), Effort::normal);
    auto lin = [](uint8_t code) { return srgb_to_linear(code / 255.0); };
    // The colour each hidden edge texel should show: -1 where the texel is shown or no edge.
    std::vector<std::array<double, 3>> want(static_cast<size_t>(src->width) * src->height, {-1, -1, -1});
    const int w = src->width, h = src->height;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (src->at(x, y, 3) >= kShownFrom) continue;
            std::array<double, 3> sum{};
            int shown = 0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int qx = (x + dx + w) % w, qy = (y + dy + h) % h;
                    if (src->at(qx, qy, 3) < kShownFrom) continue;
                    for (size_t k = 0; k < 3; ++k) sum[k] += lin(src->at(qx, qy, static_cast<int>(k)));
                    ++shown;
                }
            if (!shown) continue;
            auto& t = want[static_cast<size_t>(y) * w + x];
            for (size_t k = 0; k < 3; ++k) t[k] = 255.0 * linear_to_srgb(sum[k] / shown);
        }
    auto distance = [&](const Image8& img, size_t& edge) {
        Acc a;
        edge = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const auto& t = want[static_cast<size_t>(y) * w + x];
                if (t[0] < 0) continue;
                for (size_t k = 0; k < 3; ++k) a.add(img.at(x, y, static_cast<int>(k)) - t[k]);
                ++edge;
            }
        return a;
    };
    size_t edge = 0;
    const Acc in_source = distance(*src, edge);

    std::vector<Variant> out;
    auto add = [&](const std::string& name, const std::string& tag, bool dilate) {
        Image8 level = *src;
        size_t filled = 0;
        if (dilate) filled = texture::dilate_under_alpha(level, kinds, 3, kShownFrom);
        const Acc gpu = distance(encode_decode(level, bc7), edge);
        Variant v;
        v.knob = "cut-out edges (BC7 level 0)";
        v.name = name, v.tag = tag;
        v.max_codes = gpu.max, v.mean_codes = gpu.mean();
        v.max_linear = v.mean_linear = std::nan("");
        v.note = std::to_string(edge) + " hidden edge texels; " +
                 printf_string("%.1f codes from the shown colour in the source", in_source.mean()) +
                 (dilate ? "; " + std::to_string(filled) + " texels filled" : "");
        if (dilate) {
            v.work = [src, kinds] {
                Image8 img = *src;
                (void)texture::dilate_under_alpha(img, kinds, 3, kShownFrom);
            };
        } else {
            v.work = nullptr;
            v.note += "; no preprocessing, so no time (not on the plot)";
        }
        per_1k_map(v, *src);
        out.push_back(std::move(v));
    };
    add("hidden texels as the source left them", "AS IS", false);
    add("dilate_under_alpha (A, shown from 128) before BC7", "DILATED", true);
    return out;
}

}  // namespace mf::bench
