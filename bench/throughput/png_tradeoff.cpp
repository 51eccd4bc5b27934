// png_tradeoff: what PNG output size costs in time. Re-encodes a folder of 8-bit PNGs (for
// example matforge's outputs of the throughput library) with OpenImageIO under each zlib level,
// row filter and deflate strategy, and with matforge's own writer (Paeth rows, libdeflate level
// 1: lib/image/png_writer.hpp), and reports encode time, decode time and total size, so the
// default matforge writes is a measured choice, not a guess.
//
//   png_tradeoff <folder> [--repeat N] [--csv FILE]
//
// Every PNG under <folder> is read once into memory (untimed); each setting then encodes all of
// them to memory (timed, best of --repeat, default 3) and decodes the result once (timed), and
// checks the decoded pixels equal the originals (PNG is lossless: any difference is a bug).

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "image/image.hpp"

namespace fs = std::filesystem;

namespace {

struct Picture {
    std::string path;
    OIIO::ImageSpec spec;
    std::vector<std::uint8_t> pixels;
    mf::Image8 codes;  // the same pixels, for matforge's writer
};

struct Setting {
    std::string label;
    int level;
    int filter;             // libpng PNG_FILTER_* mask; -1: libpng's default (adaptive, all five)
    std::string strategy;   // OpenImageIO "compression" for PNG: default | filtered | huffman | rle | fixed
    bool matforge = false;  // matforge's encode_image instead (its own fixed settings)
};

// libpng's filter masks (png.h): NONE 0x08, SUB 0x10, UP 0x20, AVG 0x40, PAETH 0x80.
constexpr int kNone = 0x08, kSub = 0x10, kUp = 0x20, kPaeth = 0x80;

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Read configuration: a 4th channel as stored (OpenImageIO premultiplies PNG alpha otherwise,
// which no encoding round-trips).
const OIIO::ImageSpec& unassociated() {
    static const OIIO::ImageSpec config = [] {
        OIIO::ImageSpec c;
        c.attribute("oiio:UnassociatedAlpha", 1);
        return c;
    }();
    return config;
}

bool encode(const Picture& p, const Setting& s, std::vector<unsigned char>& bytes) {
    bytes.clear();
    if (s.matforge) {
        std::string error;
        return mf::encode_image(p.codes, {mf::FileFormat::png, 8}, bytes, error);
    }
    OIIO::ImageSpec spec(p.spec.width, p.spec.height, p.spec.nchannels, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:UnassociatedAlpha", 1);  // a 4th channel as it is, as matforge writes it
    spec.attribute("png:compressionLevel", s.level);
    if (s.filter >= 0) spec.attribute("png:filter", s.filter);
    if (s.strategy != "default") spec.attribute("compression", s.strategy);
    auto out = OIIO::ImageOutput::create("x.png");
    OIIO::Filesystem::IOVecOutput vec(bytes);
    out->set_ioproxy(&vec);
    return out->open("x.png", spec) && out->write_image(OIIO::TypeDesc::UINT8, p.pixels.data()) && out->close();
}

bool decode_equals(const Picture& p, std::vector<unsigned char>& bytes) {
    OIIO::Filesystem::IOMemReader mem(bytes.data(), bytes.size());
    auto in = OIIO::ImageInput::create("png");
    OIIO::ImageSpec spec;
    if (!in || !in->set_ioproxy(&mem) || !in->open("x.png", spec, unassociated())) return false;
    std::vector<std::uint8_t> px(p.pixels.size());
    const bool ok = in->read_image(0, 0, 0, p.spec.nchannels, OIIO::TypeDesc::UINT8, px.data());
    return ok && px == p.pixels;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::cerr << "usage: png_tradeoff <folder> [--repeat N] [--csv FILE]\n";
        return 2;
    }
    const fs::path folder = argv[1];
    int repeat = 3;
    std::string csv_path;
    for (int i = 2; i + 1 < argc; i += 2) {
        const std::string a = argv[i];
        if (a == "--repeat") repeat = std::max(1, std::atoi(argv[i + 1]));
        else if (a == "--csv") csv_path = argv[i + 1];
        else {
            std::cerr << "png_tradeoff: unknown option " << a << "\n";
            return 2;
        }
    }
    OIIO::attribute("threads", 1);  // one encode at a time, as matforge runs one per set thread

    std::vector<Picture> pictures;
    std::size_t raw = 0;
    std::error_code ec;
    for (const auto& e : fs::recursive_directory_iterator(folder, ec)) {
        if (!e.is_regular_file() || e.path().extension() != ".png") continue;
        auto in = OIIO::ImageInput::open(e.path().string(), &unassociated());
        if (!in) continue;
        Picture p{e.path().string(), in->spec(), {}, {}};
        p.pixels.resize(p.spec.image_pixels() * static_cast<std::size_t>(p.spec.nchannels));
        if (!in->read_image(0, 0, 0, p.spec.nchannels, OIIO::TypeDesc::UINT8, p.pixels.data())) continue;
        raw += p.pixels.size();
        p.codes = mf::Image8(p.spec.width, p.spec.height, p.spec.nchannels);
        p.codes.pixels = p.pixels;
        pictures.push_back(std::move(p));
    }
    std::sort(pictures.begin(), pictures.end(), [](const Picture& a, const Picture& b) { return a.path < b.path; });
    if (pictures.empty()) {
        std::cerr << "png_tradeoff: no PNG under " << folder << "\n";
        return 1;
    }

    const std::vector<Setting> settings = {
        {"level 6, adaptive (libpng/oiiotool default)", 6, -1, "default"},
        {"level 9, adaptive", 9, -1, "default"},
        {"level 3, adaptive", 3, -1, "default"},
        {"level 1, adaptive", 1, -1, "default"},
        {"level 6, paeth", 6, kPaeth, "default"},
        {"level 3, paeth", 3, kPaeth, "default"},
        {"level 2, paeth", 2, kPaeth, "default"},
        {"level 1, paeth", 1, kPaeth, "default"},
        {"level 1, up", 1, kUp, "default"},
        {"level 1, sub", 1, kSub, "default"},
        {"level 1, none", 1, kNone, "default"},
        {"level 1, paeth, rle", 1, kPaeth, "rle"},
        {"level 1, sub, rle", 1, kSub, "rle"},
        {"level 1, paeth, huffman", 1, kPaeth, "huffman"},
        {"level 0 (stored)", 0, kNone, "default"},
        {"matforge: paeth, libdeflate level 1", 1, kPaeth, "libdeflate", true},
    };

    const double raw_mb = static_cast<double>(raw) / 1e6;
    std::printf("%zu PNGs, %.1f MB of pixels; encode best of %d\n\n", pictures.size(), raw_mb, repeat);
    std::printf("| setting | encode s | MB/s in | decode s | size MB | size vs default |\n");
    std::printf("| --- | ---: | ---: | ---: | ---: | ---: |\n");
    std::ofstream csv;
    if (!csv_path.empty()) {
        csv.open(csv_path);
        csv << "setting,level,filter,strategy,encode_s,decode_s,bytes\n";
    }
    double default_size = 0;
    std::vector<std::vector<unsigned char>> encoded(pictures.size());
    int status = 0;
    for (const auto& s : settings) {
        double best = 1e30;
        std::size_t total = 0;
        for (int r = 0; r < repeat; ++r) {
            total = 0;
            const auto t0 = std::chrono::steady_clock::now();
            for (std::size_t i = 0; i < pictures.size(); ++i) {
                if (!encode(pictures[i], s, encoded[i])) {
                    std::cerr << "png_tradeoff: encoding " << pictures[i].path << " failed\n";
                    return 1;
                }
                total += encoded[i].size();
            }
            best = std::min(best, seconds_since(t0));
        }
        const auto t0 = std::chrono::steady_clock::now();
        for (std::size_t i = 0; i < pictures.size(); ++i)
            if (!decode_equals(pictures[i], encoded[i])) {
                std::cerr << "png_tradeoff: " << s.label << ": " << pictures[i].path << " does not round-trip\n";
                status = 1;
            }
        const double decode = seconds_since(t0);
        if (default_size == 0) default_size = static_cast<double>(total);
        const double size = static_cast<double>(total);
        std::printf("| %s | %.3f | %.0f | %.3f | %.2f | %.3f |\n", s.label.c_str(), best, raw_mb / best, decode,
                    size / 1e6, size / default_size);
        if (csv) {
            csv << '"' << s.label << "\"," << s.level << ',' << s.filter << ',' << s.strategy << ',' << best << ','
                << decode << ',' << total << "\n";
        }
    }
    return status;
}
