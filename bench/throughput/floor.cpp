// floor: the I/O floor of the throughput benchmark.
//
//   floor <library-dir> -o <out-dir> [--jobs N] [--durable] [--png-default]
//
// For each set of <library-dir>/library.tsv (written by make_library), OpenImageIO reads every
// input file in its native pixel type and writes what matforge's gltf preset writes — three
// 8-bit PNGs per set (basecolor RGB, normal RGB, orm RGB) at the set's size, with matforge's
// PNG settings (Paeth filter, zlib RLE) — with no processing: no float conversion, no color management, no normal
// decode, no validation. The only work is the byte interleave that puts AO/roughness/metalness into one RGB buffer, so
// the PNG encoder compresses real content rather than a constant. Sets run in parallel on --jobs threads, as matforge's
// --jobs.
//
// --durable writes each output aside, fsyncs and renames it, as matforge does (its contract: a
// killed run leaves no partial file); plain mode is OpenImageIO writing to the final path.
// --png-default writes with libpng's defaults instead (adaptive filters, zlib level 6), as
// oiiotool does: the floor of the peer script.

#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;

namespace {

struct Row {
    std::string name, dir, albedo, normal, ao, roughness, metalness, arm, height;
    int size = 0;
};

bool read_tsv(const fs::path& p, std::vector<Row>& rows, std::string& err) {
    std::ifstream f(p);
    if (!f) {
        err = p.string() + ": cannot read";
        return false;
    }
    std::string line;
    std::getline(f, line);  // header
    while (std::getline(f, line)) {
        std::vector<std::string> c;
        std::stringstream ss(line);
        for (std::string cell; std::getline(ss, cell, '\t');) c.push_back(cell);
        if (c.size() != 11) {
            err = p.string() + ": bad row '" + line + "'";
            return false;
        }
        Row r{c[0], c[1], c[3], c[4], c[6], c[7], c[8], c[9], c[10], 0};
        std::from_chars(c[2].data(), c[2].data() + c[2].size(), r.size);
        rows.push_back(std::move(r));
    }
    return true;
}

struct Pixels {
    OIIO::ImageSpec spec;
    std::vector<unsigned char> data;
};

bool read_native(const fs::path& p, Pixels& px, std::string& err) {
    auto in = OIIO::ImageInput::open(p.string());
    if (!in) {
        err = p.string() + ": " + OIIO::geterror();
        return false;
    }
    px.spec = in->spec();
    px.data.resize(px.spec.image_bytes(true));
    if (!in->read_image(0, 0, 0, px.spec.nchannels, px.spec.format, px.data.data())) {
        err = p.string() + ": " + in->geterror();
        return false;
    }
    return true;
}

struct Options {
    bool durable = false;
    bool png_default = false;
};

bool write_png(const fs::path& p, int w, int h, int ch, const unsigned char* data, const Options& opt,
               std::string& err) {
    const bool durable = opt.durable;
    OIIO::ImageSpec spec(w, h, ch, OIIO::TypeDesc::UINT8);
    if (!opt.png_default) {  // matforge's settings (lib/image/image.cpp encode_image)
        spec.attribute("png:compressionLevel", 1);
        spec.attribute("png:filter", 0x80);  // PNG_FILTER_PAETH
        spec.attribute("compression", "rle");
    }
    const fs::path target = durable ? fs::path(p.string() + ".tmp") : p;
    auto out = OIIO::ImageOutput::create("png");  // by format: the aside name ends in .tmp
    if (!out || !out->open(target.string(), spec) || !out->write_image(OIIO::TypeDesc::UINT8, data) || !out->close()) {
        err = p.string() + ": " + (out ? out->geterror() : OIIO::geterror());
        return false;
    }
    if (durable) {
        const int fd = ::open(target.c_str(), O_RDONLY);
        const bool synced = fd >= 0 && ::fsync(fd) == 0;
        if (fd >= 0) ::close(fd);
        std::error_code ec;
        if (!synced) {
            err = target.string() + ": fsync failed";
            return false;
        }
        fs::rename(target, p, ec);
        if (ec) {
            err = p.string() + ": " + ec.message();
            return false;
        }
    }
    return true;
}

// The pixels of an 8-bit map, or nullptr when the map is not 8-bit.
const unsigned char* plane8(const Pixels& px) {
    return px.spec.format == OIIO::TypeDesc::UINT8 ? px.data.data() : nullptr;
}

bool run_set(const fs::path& lib, const fs::path& out, const Row& r, const Options& opt,
             std::atomic<uint64_t>& bytes_read, std::string& err) {
    const fs::path d = lib / "sets" / r.dir;
    // Every input of the set, native type, as matforge decodes every chosen map (height too).
    Pixels albedo, normal, ao, rough, metal, arm, height;
    struct Item {
        const std::string& file;
        Pixels& px;
    };
    for (Item it : {Item{r.albedo, albedo}, Item{r.normal, normal}, Item{r.ao, ao}, Item{r.roughness, rough},
                    Item{r.metalness, metal}, Item{r.arm, arm}, Item{r.height, height}}) {
        if (it.file == "-") continue;
        if (!read_native(d / it.file, it.px, err)) return false;
        bytes_read += it.px.data.size();
    }
    const int w = albedo.spec.width, h = albedo.spec.height;
    const fs::path od = out / r.name;
    std::error_code ec;
    fs::create_directories(od, ec);
    if (!write_png(od / (r.name + "_basecolor.png"), w, h, albedo.spec.nchannels, albedo.data.data(), opt, err) ||
        !write_png(od / (r.name + "_normal.png"), w, h, normal.spec.nchannels, normal.data.data(), opt, err))
        return false;
    const unsigned char* orm = nullptr;
    std::vector<unsigned char> packed;
    if (r.arm != "-") {
        orm = arm.data.data();
    } else {
        const unsigned char *a = r.ao == "-" ? nullptr : plane8(ao), *g = plane8(rough),
                            *m = r.metalness == "-" ? nullptr : plane8(metal);
        if (!g || (r.ao != "-" && !a) || (r.metalness != "-" && !m)) {
            err = r.name + ": the floor expects 8-bit scalar maps";
            return false;
        }
        const size_t n = static_cast<size_t>(w) * static_cast<size_t>(h);
        const size_t ca = static_cast<size_t>(ao.spec.nchannels), cg = static_cast<size_t>(rough.spec.nchannels),
                     cm = static_cast<size_t>(metal.spec.nchannels);
        packed.resize(n * 3);
        for (size_t i = 0; i < n; ++i) {
            packed[i * 3] = a ? a[i * ca] : 255;
            packed[i * 3 + 1] = g[i * cg];
            packed[i * 3 + 2] = m ? m[i * cm] : 0;
        }
        orm = packed.data();
    }
    return write_png(od / (r.name + "_orm.png"), w, h, 3, orm, opt, err);
}

int usage() {
    std::cerr << "usage: floor <library-dir> -o <out-dir> [--jobs N (2)] [--durable] [--png-default]\n";
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    std::string lib, out;
    int jobs = 2;
    Options opt;
    for (size_t i = 0; i < args.size(); ++i) {
        if ((args[i] == "-o" || args[i] == "--out") && i + 1 < args.size()) {
            out = args[++i];
        } else if (args[i] == "--jobs" && i + 1 < args.size()) {
            const std::string& v = args[++i];
            const auto res = std::from_chars(v.data(), v.data() + v.size(), jobs);
            if (res.ec != std::errc() || jobs < 1) return usage();
        } else if (args[i] == "--durable") {
            opt.durable = true;
        } else if (args[i] == "--png-default") {
            opt.png_default = true;
        } else if (!args[i].starts_with("-") && lib.empty()) {
            lib = args[i];
        } else {
            return usage();
        }
    }
    if (lib.empty() || out.empty()) return usage();

    std::vector<Row> rows;
    std::string err;
    if (!read_tsv(fs::path(lib) / "library.tsv", rows, err)) {
        std::cerr << "floor: " << err << "\n";
        return 1;
    }
    std::vector<std::string> errors(rows.size());
    std::atomic<uint64_t> bytes_read{0};
    std::atomic<size_t> next{0};
    auto worker = [&] {
        for (size_t i = next++; i < rows.size(); i = next++)
            if (!run_set(lib, out, rows[i], opt, bytes_read, errors[i]) && errors[i].empty()) errors[i] = "failed";
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < std::min<int>(jobs, static_cast<int>(rows.size())); ++t) pool.emplace_back(worker);
    worker();
    for (auto& t : pool) t.join();
    int failed = 0;
    for (const auto& e : errors)
        if (!e.empty()) {
            std::cerr << "floor: " << e << "\n";
            ++failed;
        }
    std::cerr << "floor: " << rows.size() - static_cast<size_t>(failed) << " sets, "
              << bytes_read.load() / (1024 * 1024) << " MiB decoded" << (opt.durable ? " (durable writes)" : "")
              << (opt.png_default ? " (libpng default PNG settings)" : "") << "\n";
    return failed ? 1 : 0;
}
