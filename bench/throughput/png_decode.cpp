// png_decode: one thread's time to decode PNGs with matforge's plain-PNG reader
// (lib/image/png_reader.hpp), whole and by step: the inflate alone (libdeflate into a buffer
// allocated once), the row filters reversed alone by each form lib/image/png_unfilter.hpp has
// (scalar, SSE2, SSE4.1), and OpenImageIO's decode (libpng and zlib) for reference.
//
//   png_decode <folder>... [--repeat N] [--rows]
//
// Every PNG under the folders is read into memory once (untimed). Each round decodes all of
// them in each way; a file's bytes (read_plain uses them up) and the filtered rows (reversed over
// themselves) are copied back before each decode, untimed. The table gives each way's median round
// (and the fastest and slowest) over --repeat rounds (default 7), in ms per round and per file.
// Every way's pixels are checked against read_plain's first decode (and OpenImageIO's against
// them), so a faster wrong decode fails the run. --rows adds a table of synthetic 1024 x 1024
// images, every row of one filter, per pixel size: the row reversal alone, in each form.

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <libdeflate.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "image/png_reader.hpp"
#include "image/png_unfilter.hpp"

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;
using mf::png::UnfilterIsa;
constexpr UnfilterIsa kIsas[] = {UnfilterIsa::scalar, UnfilterIsa::sse2, UnfilterIsa::sse41};
constexpr int kIsaCount = 3;

double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

struct Png {
    std::string path;
    std::vector<unsigned char> bytes;
    mf::png::Plain plain;               // read_plain's decode (empty when it declines the file)
    std::vector<unsigned char> stream;  // the IDAT chunks' data (plain, not interlaced files)
    std::vector<uint8_t> filtered;      // the inflated rows, each behind its filter byte
};

// The IDAT chunks' data of a PNG, in order (the file's chunks were checked by read_plain).
std::vector<unsigned char> idat_stream(const std::vector<unsigned char>& f) {
    std::vector<unsigned char> out;
    for (size_t at = 8; at + 12 <= f.size();) {
        const size_t len = mf::png::be32(f.data() + at);
        if (std::memcmp(f.data() + at + 4, "IDAT", 4) == 0)
            out.insert(out.end(), f.begin() + at + 8, f.begin() + at + 8 + len);
        at += 12 + len;
    }
    return out;
}

// Reverses every row of `rows` (each behind its filter byte), each moved over its filter byte
// and the rows before it as read_plain does: the image ends up in the first width x height x bpp
// bytes.
bool unfilter_all(std::vector<uint8_t>& rows, size_t width, size_t height, int bpp, UnfilterIsa isa) {
    const size_t row_bytes = width * static_cast<size_t>(bpp);
    const std::vector<uint8_t> zeros(row_bytes, 0);
    for (size_t y = 0; y < height; ++y) {
        const uint8_t* row = rows.data() + y * (row_bytes + 1);
        uint8_t* to = rows.data() + y * row_bytes;
        if (!mf::png::unfilter_row(row[0], row + 1, to, y ? to - row_bytes : zeros.data(), width, bpp, isa))
            return false;
    }
    return true;
}

// Whether the first pixels of `rows` are read_plain's (8-bit files).
bool rows_equal(const std::vector<uint8_t>& rows, const mf::png::Plain& p) {
    return std::equal(p.pixels.begin(), p.pixels.end(), rows.begin());
}

struct Stat {
    std::vector<double> ms;
    double median() const {
        std::vector<double> s = ms;
        std::sort(s.begin(), s.end());
        return s.empty() ? 0 : (s.size() % 2 ? s[s.size() / 2] : (s[s.size() / 2 - 1] + s[s.size() / 2]) / 2);
    }
    double min() const { return ms.empty() ? 0 : *std::min_element(ms.begin(), ms.end()); }
    double max() const { return ms.empty() ? 0 : *std::max_element(ms.begin(), ms.end()); }
};

const char* isa_name(UnfilterIsa isa) {
    return isa == UnfilterIsa::sse41 ? "SSE4.1" : isa == UnfilterIsa::sse2 ? "SSE2" : "scalar";
}

// OpenImageIO's decode of `bytes` (unassociated alpha, as matforge's module opens a PNG).
bool oiio_decode(const std::vector<unsigned char>& bytes, std::vector<uint8_t>& px, int& nchannels) {
    OIIO::Filesystem::IOMemReader mem(bytes.data(), bytes.size());
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::create("png", false, &config);
    OIIO::ImageSpec spec;
    if (!in || !in->set_ioproxy(&mem) || !in->open("memory.png", spec, config)) return false;
    nchannels = in->spec().nchannels;
    px.resize(in->spec().image_bytes());
    return in->read_image(0, 0, 0, nchannels, in->spec().format, px.data());
}

int synthetic_rows(int repeat) {
    constexpr size_t kW = 1024, kH = 1024;
    std::mt19937 rng(7);
    std::printf("\nRow filters reversed alone: %zu x %zu pixels, every row of one filter, residuals 0-6 "
                "(median ms of %d rounds)\n\n",
                kW, kH, repeat);
    std::printf("| bytes/pixel | filter |");
    for (const UnfilterIsa isa : kIsas)
        if (mf::png::can_unfilter_with(isa)) std::printf(" %s ms |", isa_name(isa));
    std::printf(" speed-up |\n| ---: | --- |");
    for (const UnfilterIsa isa : kIsas)
        if (mf::png::can_unfilter_with(isa)) std::printf(" ---: |");
    std::printf(" ---: |\n");
    const char* names[] = {"None", "Sub", "Up", "Average", "Paeth"};
    for (int bpp : {1, 2, 3, 4, 6, 8}) {
        const size_t n = kW * static_cast<size_t>(bpp);
        std::vector<uint8_t> image(kH * (n + 1));
        for (auto& v : image) v = static_cast<uint8_t>(rng() % 7);
        for (int type = 1; type <= 4; ++type) {
            for (size_t y = 0; y < kH; ++y) image[y * (n + 1)] = static_cast<uint8_t>(type);
            Stat t[kIsaCount];
            std::vector<uint8_t> out[kIsaCount];
            for (int r = 0; r < repeat; ++r)
                for (int k = 0; k < kIsaCount; ++k) {
                    if (!mf::png::can_unfilter_with(kIsas[k])) continue;
                    std::vector<uint8_t> work = image;
                    const auto t0 = Clock::now();
                    unfilter_all(work, kW, kH, bpp, kIsas[k]);
                    t[k].ms.push_back(ms_since(t0));
                    out[k] = std::move(work);
                }
            std::printf("| %d | %s |", bpp, names[type]);
            double fastest = t[0].median();
            for (int k = 0; k < kIsaCount; ++k) {
                if (!mf::png::can_unfilter_with(kIsas[k])) continue;
                if (!std::equal(out[0].begin(), out[0].begin() + static_cast<std::ptrdiff_t>(kH * n), out[k].begin())) {
                    std::cerr << "png_decode: " << isa_name(kIsas[k]) << " and scalar differ, " << bpp
                              << " bytes, filter " << type << "\n";
                    return 1;
                }
                std::printf(" %.2f |", t[k].median());
                fastest = std::min(fastest, t[k].median());
            }
            std::printf(" %.1fx |\n", t[0].median() / fastest);
        }
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<fs::path> folders;
    int repeat = 7;
    bool rows = false;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--repeat" && i + 1 < argc) repeat = std::max(1, std::atoi(argv[++i]));
        else if (a == "--rows") rows = true;
        else if (a.rfind("--", 0) == 0) {
            std::cerr << "usage: png_decode <folder>... [--repeat N] [--rows]\n";
            return 2;
        } else folders.emplace_back(a);
    }
    OIIO::attribute("threads", 1);

    std::vector<Png> pngs;
    for (const auto& folder : folders) {
        std::error_code ec;
        for (const auto& e : fs::recursive_directory_iterator(folder, ec)) {
            if (!e.is_regular_file() || e.path().extension() != ".png") continue;
            std::ifstream f(e.path(), std::ios::binary);
            pngs.push_back({e.path().string(), {std::istreambuf_iterator<char>(f), {}}, {}, {}, {}});
        }
    }
    std::sort(pngs.begin(), pngs.end(), [](const Png& a, const Png& b) { return a.path < b.path; });
    const std::unique_ptr<libdeflate_decompressor, decltype(&libdeflate_free_decompressor)> inflater(
        libdeflate_alloc_decompressor(), &libdeflate_free_decompressor);
    size_t samples = 0, step_samples = 0, plain = 0, stepped = 0, file_bytes = 0;
    for (auto& p : pngs) {
        std::vector<unsigned char> copy = p.bytes;
        file_bytes += p.bytes.size();
        if (!mf::png::read_plain(copy, size_t{1} << 30, p.plain)) continue;
        ++plain;
        samples += p.plain.pixels.size();
        if (p.plain.interlaced || p.plain.bit_depth != 8) continue;  // the steps: 8-bit rows as they are stored
        ++stepped;
        step_samples += p.plain.pixels.size();
        p.stream = idat_stream(p.bytes);
        p.filtered.resize(static_cast<size_t>(p.plain.height) *
                          (static_cast<size_t>(p.plain.width) * static_cast<size_t>(p.plain.channels) + 1));
        size_t made = 0;
        if (libdeflate_zlib_decompress(inflater.get(), p.stream.data(), p.stream.size(), p.filtered.data(),
                                       p.filtered.size(), &made) != LIBDEFLATE_SUCCESS ||
            made != p.filtered.size()) {
            std::cerr << "png_decode: cannot inflate " << p.path << "\n";
            return 1;
        }
    }
    if (pngs.empty() && !rows) {
        std::cerr << "png_decode: no PNG under the folders given\n";
        return 1;
    }

    Stat whole, inflate, oiio, unfilter[kIsaCount];
    std::vector<uint8_t> inflated, work;
    for (int r = 0; r < repeat && !pngs.empty(); ++r) {
        double t_whole = 0, t_inflate = 0, t_oiio = 0, t_unfilter[kIsaCount] = {};
        for (auto& p : pngs) {
            if (p.plain.pixels.empty()) continue;
            std::vector<unsigned char> copy = p.bytes;
            mf::png::Plain out;
            auto t0 = Clock::now();
            const bool ok = mf::png::read_plain(copy, size_t{1} << 30, out);
            t_whole += ms_since(t0);
            if (!ok || out.pixels != p.plain.pixels) {
                std::cerr << "png_decode: " << p.path << " decodes differently\n";
                return 1;
            }
            std::vector<uint8_t> px;
            int nchannels = 0;
            t0 = Clock::now();
            const bool oiio_ok = oiio_decode(p.bytes, px, nchannels);
            t_oiio += ms_since(t0);
            if (!oiio_ok || (p.plain.bit_depth == 8 && px != p.plain.pixels)) {
                std::cerr << "png_decode: OpenImageIO reads " << p.path << " differently\n";
                return 1;
            }
            if (p.filtered.empty()) continue;
            inflated.resize(p.filtered.size());  // allocated once for the largest file: the inflate alone
            size_t made = 0;
            t0 = Clock::now();
            const auto inflated_ok = libdeflate_zlib_decompress(inflater.get(), p.stream.data(), p.stream.size(),
                                                                inflated.data(), p.filtered.size(), &made);
            t_inflate += ms_since(t0);
            if (inflated_ok != LIBDEFLATE_SUCCESS || made != p.filtered.size()) {
                std::cerr << "png_decode: cannot inflate " << p.path << "\n";
                return 1;
            }
            for (int k = 0; k < kIsaCount; ++k) {
                const UnfilterIsa isa = kIsas[k];
                if (!mf::png::can_unfilter_with(isa)) continue;
                work = p.filtered;
                t0 = Clock::now();
                const bool good = unfilter_all(work, static_cast<size_t>(p.plain.width),
                                               static_cast<size_t>(p.plain.height), p.plain.channels, isa);
                t_unfilter[k] += ms_since(t0);
                if (!good || !rows_equal(work, p.plain)) {
                    std::cerr << "png_decode: " << isa_name(isa) << " reverses " << p.path << "'s rows differently\n";
                    return 1;
                }
            }
        }
        whole.ms.push_back(t_whole);
        inflate.ms.push_back(t_inflate);
        oiio.ms.push_back(t_oiio);
        for (int k = 0; k < kIsaCount; ++k) unfilter[k].ms.push_back(t_unfilter[k]);
    }
    if (!pngs.empty()) {
        std::printf("%zu PNGs (%zu read by the plain reader, %zu of them 8-bit, not interlaced: the steps), "
                    "%.1f MB of files, %.1f MB of samples; one thread, %d rounds\n\n",
                    pngs.size(), plain, stepped, static_cast<double>(file_bytes) / 1e6,
                    static_cast<double>(samples) / 1e6, repeat);
        std::printf("| decode | ms per round, median (min-max) | ms per file | MB/s of samples |\n");
        std::printf("| --- | ---: | ---: | ---: |\n");
        auto line = [&](const char* what, const Stat& s, size_t files, size_t bytes) {
            std::printf("| %s | %.1f (%.1f-%.1f) | %.2f | %.0f |\n", what, s.median(), s.min(), s.max(),
                        s.median() / static_cast<double>(std::max<size_t>(files, 1)),
                        static_cast<double>(bytes) / 1e3 / std::max(s.median(), 1e-9));
        };
        line("read_plain, whole (matforge)", whole, plain, samples);
        line("  inflate alone (libdeflate)", inflate, stepped, step_samples);
        for (int k = 0; k < kIsaCount; ++k) {
            if (!mf::png::can_unfilter_with(kIsas[k])) continue;
            const std::string what = std::string("  row filters reversed, ") + isa_name(kIsas[k]) +
                                     (kIsas[k] == mf::png::best_unfilter_isa() ? " (read_plain's)" : "");
            line(what.c_str(), unfilter[k], stepped, step_samples);
        }
        line("OpenImageIO (libpng, zlib)", oiio, plain, samples);
    }
    return rows ? synthetic_rows(repeat) : 0;
}
