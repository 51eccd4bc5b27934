// texture_bench: matforge's block encoders as one process per map, the way the peer command-line
// tools (nvcompress, astcenc) run, and the error measure all of them are judged by. Driven by
// bench/texture/run.sh, which times each process (wall, /usr/bin/time) and writes the table.
//
//   texture_bench encode IN.png OUT.dds|OUT.ktx2 FORMAT EFFORT [--srgb] [--normal] [--mips]
//                        [--threads N] [--encode-seconds]
//       reads IN (lib/image), encodes level 0 (with --mips: the whole chain, lib/texture's
//       filters) with matforge's codec for FORMAT (bc1, bc3, bc4, bc5, astc-4x4, astc-6x6, ...)
//       at EFFORT (fast, normal, thorough) on N threads (default 1), writes the container;
//       --normal: IN is a normal map (BC5: X, Y kept; mips renormalized). Prints the seconds
//       from reading IN to the file written: the time per map inside a run (`ingest` pays its
//       process start-up, OpenImageIO's plugins, once per run, not per map). With
//       --encode-seconds, two more figures on that line: texture::encode_level for level 0 alone
//       (no reading, no mips, no container, no writing), its wall seconds, then its CPU seconds
//       (std::clock: every thread of the process added up), which is what bc7enc's "Total encoding
//       time" line measures (clock() around its encoding loop; bench/texture/bc7_vs_bc7e.sh).
//   texture_bench decode IN.dds|IN.ktx2 OUT.png
//       level 0 decoded back with the codec that wrote it (libsquish, astcenc).
//   texture_bench psnr REF DECODED CHANNELS
//       PSNR in dB of the first CHANNELS channels of DECODED against REF (8-bit codes, any file
//       OpenImageIO reads: the peers' TGA and PNG decodes too), and for CHANNELS = 2 (a normal's
//       X, Y) also the mean angle in degrees between the unit vectors they give.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <iostream>
#include <numbers>
#include <string>
#include <vector>

#include "core/files.hpp"
#include "image/image.hpp"
#include "texture/texture.hpp"

namespace {

using mf::Image8;

bool read8(const std::string& file, Image8& out, std::string& error) {
    mf::InputFile in;
    in.path = file;
    in.display = file;
    mf::Decoded d;
    mf::ImageInfo info;
    if (!mf::read_image(in, d, info, error)) return false;
    if (d.is_codes()) {
        out = std::move(d.codes);
        return true;
    }
    out = Image8(d.floats.width, d.floats.height, d.floats.channels);
    for (size_t i = 0; i < out.pixels.size(); ++i)
        out.pixels[i] = static_cast<uint8_t>(std::lround(std::clamp(d.floats.pixels[i], 0.f, 1.f) * 255.f));
    return true;
}

// The first `n` channels of `img` (missing ones: grey copies of channel 0, or 255 for alpha).
Image8 channels(const Image8& img, int n) {
    Image8 out(img.width, img.height, n);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            for (int c = 0; c < n; ++c)
                out.at(x, y, c) = c < img.channels ? img.at(x, y, c) : c == 3 ? 255 : img.at(x, y, 0);
    return out;
}

int fail(const std::string& what) {
    std::cerr << "texture_bench: " << what << "\n";
    return 1;
}

int encode(int argc, char** argv) {
    if (argc < 6) return fail("encode IN OUT FORMAT EFFORT [--srgb] [--normal] [--mips]");
    const std::string in = argv[2], out = argv[3];
    bool srgb = false, normal = false, mips = false, encode_seconds = false;
    int threads = 1;
    for (int i = 6; i < argc; ++i) {
        const std::string f = argv[i];
        srgb = srgb || f == "--srgb";
        normal = normal || f == "--normal";
        mips = mips || f == "--mips";
        encode_seconds = encode_seconds || f == "--encode-seconds";
        if (f == "--threads" && i + 1 < argc) threads = std::max(1, std::atoi(argv[++i]));
    }
    // OpenImageIO is a module loaded on the first read (lib/image): once per `ingest` run, so
    // outside the time per map.
    (void)mf::image_library_versions();
    const auto t0 = std::chrono::steady_clock::now();
    mf::texture::CodecOptions opt;
    opt.format = mf::block_format_info(argv[4]);
    if (!opt.format) return fail(std::string("unknown format ") + argv[4] + " (" + mf::block_format_names() + ")");
    const auto effort = mf::from_word<mf::Effort>(argv[5]);
    if (!effort) return fail(std::string("unknown effort ") + argv[5]);
    opt.effort = *effort;
    opt.srgb = srgb && opt.format->has_srgb;
    opt.normal_xy = normal && opt.format->channels == 2;
    opt.mask = !srgb && !normal && opt.format->channels >= 3;
    opt.threads = threads;
    std::string error;
    Image8 src;
    if (!read8(in, src, error)) return fail(error);
    // The channels the format stores (a normal keeps X, Y, Z for ASTC; BC5 encodes X, Y).
    const int keep = opt.format->channels == 1 ? 1
                     : normal                  ? 3
                                               : std::min(std::max(src.channels, 3), opt.format->channels);
    const Image8 level0 = channels(src, keep);
    std::vector<mf::texture::ChannelKind> kinds;
    for (int c = 0; c < keep; ++c)
        kinds.push_back(normal          ? mf::texture::ChannelKind::normal
                        : srgb && c < 3 ? mf::texture::ChannelKind::srgb_color
                                        : mf::texture::ChannelKind::data);
    std::vector<Image8> chain{level0};
    if (mips) chain = mf::texture::make_mips(level0, kinds, {});
    mf::texture::GpuTexture t;
    t.format = opt.format;
    t.srgb = opt.srgb;
    double level0_seconds = 0, level0_cpu_seconds = 0;
    for (const Image8& level : chain) {
        mf::texture::Level l{level.width, level.height, {}};
        const auto e0 = std::chrono::steady_clock::now();
        const std::clock_t c0 = std::clock();
        if (!mf::texture::encode_level(level, opt, l.data, error)) return fail(in + ": " + error);
        if (t.levels.empty()) {
            level0_cpu_seconds = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
            level0_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - e0).count();
        }
        t.levels.push_back(std::move(l));
    }
    std::vector<uint8_t> bytes;
    const bool ktx2 = out.size() > 5 && out.substr(out.size() - 5) == ".ktx2";
    if (ktx2) {
        if (!mf::texture::write_ktx2(t, {}, bytes, error)) return fail(out + ": " + error);
    } else {
        bytes = mf::texture::write_dds(t);
    }
    if (!mf::write_file_atomic(out, bytes, error)) return fail(error);
    std::printf("%.4f", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    if (encode_seconds) std::printf(" %.4f %.4f", level0_seconds, level0_cpu_seconds);
    std::printf("\n");
    return 0;
}

int decode(int argc, char** argv) {
    if (argc < 4) return fail("decode IN OUT.png");
    const std::string in = argv[2], out = argv[3];
    std::vector<uint8_t> bytes;
    std::string error;
    if (!mf::read_file(in, bytes, error)) return fail(error);
    mf::texture::GpuTexture t;
    const bool ktx2 = in.size() > 5 && in.substr(in.size() - 5) == ".ktx2";
    if (!(ktx2 ? mf::texture::read_ktx2(bytes, t, error) : mf::texture::read_dds(bytes, t, error)))
        return fail(in + ": " + error);
    mf::texture::CodecOptions opt;
    opt.format = t.format;
    opt.srgb = t.srgb;
    Image8 rgba;
    if (!mf::texture::decode_level(t.levels[0].data, t.levels[0].width, t.levels[0].height, opt, rgba, error))
        return fail(in + ": " + error);
    std::vector<unsigned char> png;
    if (!mf::encode_image(rgba, {mf::FileFormat::png, 8}, png, error)) return fail(error);
    if (!mf::write_file_atomic(out, png, error)) return fail(error);
    return 0;
}

int psnr(int argc, char** argv) {
    if (argc < 5) return fail("psnr REF DECODED CHANNELS");
    const int n = std::stoi(argv[4]);
    std::string error;
    Image8 ref, dec;
    if (!read8(argv[2], ref, error) || !read8(argv[3], dec, error)) return fail(error);
    if (ref.width != dec.width || ref.height != dec.height) return fail("sizes differ");
    const Image8 a = channels(ref, n), b = channels(dec, n);
    double se = 0, angle = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        const double d = static_cast<double>(a.pixels[i]) - static_cast<double>(b.pixels[i]);
        se += d * d;
    }
    const double mse = se / static_cast<double>(a.pixels.size());
    const double db = mse > 0 ? 10.0 * std::log10(255.0 * 255.0 / mse) : 99.0;
    std::printf("%.3f", db);
    if (n == 2) {  // a normal's X, Y: Z from the unit length, as the engine rebuilds it
        auto unit = [](const Image8& img, size_t p, double v[3]) {
            v[0] = img.pixels[2 * p] / 127.5 - 1.0;
            v[1] = img.pixels[2 * p + 1] / 127.5 - 1.0;
            v[2] = std::sqrt(std::max(0.0, 1.0 - v[0] * v[0] - v[1] * v[1]));
            const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
            for (int k = 0; k < 3; ++k) v[k] /= len > 0 ? len : 1.0;
        };
        const size_t pixels = size_t(a.width) * a.height;
        for (size_t p = 0; p < pixels; ++p) {
            double u[3], v[3];
            unit(a, p, u);
            unit(b, p, v);
            angle += std::acos(std::clamp(u[0] * v[0] + u[1] * v[1] + u[2] * v[2], -1.0, 1.0));
        }
        std::printf(" %.3f", angle / static_cast<double>(pixels) * 180.0 / std::numbers::pi);
    }
    std::printf("\n");
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string cmd = argc > 1 ? argv[1] : "";
    if (cmd == "encode") return encode(argc, argv);
    if (cmd == "decode") return decode(argc, argv);
    if (cmd == "psnr") return psnr(argc, argv);
    return fail("usage: texture_bench encode|decode|psnr ... (see the source's header)");
}
