// compare_outputs: checks that the oiiotool peer wrote what matforge wrote.
//
//   compare_outputs <matforge-out> <peer-out> [--tol N (1)] [--normal-tol N (2)]
//
// Every PNG under either folder (same relative path) must exist in both, with the same size,
// channel count and pixel type, and pixel codes within --tol (--normal-tol for *_normal.png:
// matforge renormalizes decoded normals, the oiiotool script copies the 8-bit codes). Prints the
// maximum difference per output kind and channel, and each file over its tolerance.
// Exit 0 when everything matches, 1 otherwise.

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

struct Pixels {
    OIIO::ImageSpec spec;
    std::vector<uint8_t> data;
};

bool read8(const fs::path& p, Pixels& px, std::string& err) {
    auto in = OIIO::ImageInput::open(p.string());
    if (!in) {
        err = OIIO::geterror();
        return false;
    }
    px.spec = in->spec();
    px.data.resize(px.spec.image_pixels() * static_cast<size_t>(px.spec.nchannels));
    if (!in->read_image(0, 0, 0, px.spec.nchannels, OIIO::TypeDesc::UINT8, px.data.data())) {
        err = in->geterror();
        return false;
    }
    return true;
}

std::set<std::string> pngs_under(const fs::path& root) {
    std::set<std::string> out;
    std::error_code ec;
    for (auto it = fs::recursive_directory_iterator(root, ec); !ec && it != fs::recursive_directory_iterator();
         it.increment(ec))
        if (it->is_regular_file() && it->path().extension() == ".png")
            out.insert(it->path().lexically_relative(root).generic_string());
    return out;
}

// "Bricks000/Bricks000_basecolor.png" -> "basecolor"
std::string kind_of(const std::string& rel) {
    const std::string stem = fs::path(rel).stem().string();
    const auto u = stem.rfind('_');
    return u == std::string::npos ? stem : stem.substr(u + 1);
}

struct KindStats {
    int files = 0, over = 0, differing_files = 0;
    std::array<int, 4> max_per_channel{0, 0, 0, 0};
    uint64_t differing_codes = 0, codes = 0;
    std::string worst_file;
    int worst = -1;
};

int usage() {
    std::cerr << "usage: compare_outputs <matforge-out> <peer-out> [--tol N (1)] [--normal-tol N (2)]\n";
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    std::vector<std::string> dirs;
    int tol = 1, normal_tol = 2;
    for (size_t i = 0; i < args.size(); ++i) {
        auto value = [&](int& v) {
            if (i + 1 >= args.size()) return false;
            const std::string& s = args[++i];
            return std::from_chars(s.data(), s.data() + s.size(), v).ec == std::errc() && v >= 0;
        };
        if (args[i] == "--tol") {
            if (!value(tol)) return usage();
        } else if (args[i] == "--normal-tol") {
            if (!value(normal_tol)) return usage();
        } else if (!args[i].starts_with("-")) {
            dirs.push_back(args[i]);
        } else {
            return usage();
        }
    }
    if (dirs.size() != 2) return usage();
    const fs::path a_root = dirs[0], b_root = dirs[1];

    const auto a = pngs_under(a_root), b = pngs_under(b_root);
    std::set<std::string> all(a.begin(), a.end());
    all.insert(b.begin(), b.end());
    if (all.empty()) {
        std::cerr << "compare_outputs: no PNG under either folder\n";
        return 1;
    }
    std::map<std::string, KindStats> stats;
    int problems = 0;
    for (const auto& rel : all) {
        if (!a.count(rel) || !b.count(rel)) {
            std::cout << "MISSING  " << rel << " (only in " << (a.count(rel) ? a_root : b_root).string() << ")\n";
            ++problems;
            continue;
        }
        Pixels pa, pb;
        std::string err;
        if (!read8(a_root / rel, pa, err) || !read8(b_root / rel, pb, err)) {
            std::cout << "UNREADABLE  " << rel << ": " << err << "\n";
            ++problems;
            continue;
        }
        if (pa.spec.width != pb.spec.width || pa.spec.height != pb.spec.height ||
            pa.spec.nchannels != pb.spec.nchannels || pa.spec.format != pb.spec.format) {
            std::cout << "SHAPE  " << rel << ": " << pa.spec.width << "x" << pa.spec.height << "x" << pa.spec.nchannels
                      << " " << pa.spec.format << " vs " << pb.spec.width << "x" << pb.spec.height << "x"
                      << pb.spec.nchannels << " " << pb.spec.format << "\n";
            ++problems;
            continue;
        }
        const std::string kind = kind_of(rel);
        KindStats& k = stats[kind];
        ++k.files;
        const size_t nch = static_cast<size_t>(pa.spec.nchannels);
        int file_max = 0;
        uint64_t diff_codes = 0;
        for (size_t i = 0; i < pa.data.size(); ++i) {
            const int d = std::abs(int{pa.data[i]} - int{pb.data[i]});
            if (d == 0) continue;
            ++diff_codes;
            file_max = std::max(file_max, d);
            int& m = k.max_per_channel[std::min<size_t>(i % nch, 3)];
            m = std::max(m, d);
        }
        k.codes += pa.data.size();
        k.differing_codes += diff_codes;
        if (diff_codes) ++k.differing_files;
        if (file_max > k.worst) {
            k.worst = file_max;
            k.worst_file = rel;
        }
        const int limit = kind == "normal" ? normal_tol : tol;
        if (file_max > limit) {
            std::cout << "OVER  " << rel << ": max difference " << file_max << " codes (tolerance " << limit << ")\n";
            ++k.over;
            ++problems;
        }
    }
    std::cout << "kind       files  max-diff  per-channel max   codes differing      worst file\n";
    for (const auto& [kind, k] : stats) {
        std::string per;
        for (int c = 0; c < 4; ++c) {
            if (c) per += '/';
            per += std::to_string(k.max_per_channel[static_cast<size_t>(c)]);
        }
        const double share = k.codes ? 100.0 * static_cast<double>(k.differing_codes) / static_cast<double>(k.codes)
                                     : 0.0;
        std::printf("%-10s %5d  %8d  %-16s  %8.4f%% of codes  %s\n", kind.c_str(), k.files, std::max(k.worst, 0),
                    per.c_str(), share, k.worst_file.c_str());
    }
    std::cout << (problems ? "compare_outputs: MISMATCH (" + std::to_string(problems) + " problems)\n"
                           : "compare_outputs: OK (" + std::to_string(all.size()) + " files within tolerance)\n");
    return problems ? 1 : 0;
}
