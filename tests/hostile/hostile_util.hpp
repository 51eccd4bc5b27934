// Helpers for the hostile-input and interrupt tests: running the binary with a deadline (a hang
// is a failure, never a stuck CI job), and hand-built file bytes that encoders refuse to make
// (bombs, palettes, broken headers).
#pragma once
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include "core/files.hpp"
#include "image/image.hpp"
#include "run_binary.hpp"
#include "test_files.hpp"

namespace mfh {
namespace fs = std::filesystem;
using Bytes = std::vector<unsigned char>;

using mf::testbin::Proc;

// The deadline of a hostile run: a hang is reported, never a stuck CI job.
inline Proc spawn(const std::vector<std::string>& argv, double deadline_s = 120,
                  std::optional<double> kill_after_s = std::nullopt) {
    return mf::testbin::spawn(argv, deadline_s, kill_after_s);
}

inline std::string bin() { return mf::testenv::bin(); }

// A matforge run in the background, for what spawn() cannot do: signal it (SIGINT, SIGSTOP)
// while it works, or run a second one beside it. wait() reaps it (a deadline: a hang is killed
// and reported).
class Background {
public:
    explicit Background(const std::vector<std::string>& argv) {
        char log_name[] = "/tmp/matforge-test-log-XXXXXX";
        log_fd_ = ::mkstemp(log_name);
        ::unlink(log_name);
        std::vector<char*> args;
        for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
        args.push_back(nullptr);
        pid_ = ::fork();
        if (pid_ == 0) {
            ::dup2(log_fd_, STDOUT_FILENO);
            ::dup2(log_fd_, STDERR_FILENO);
            ::execvp(args[0], args.data());
            ::_exit(127);
        }
    }
    ~Background() {
        if (!reaped_ && pid_ > 0) {
            ::kill(pid_, SIGKILL);
            ::waitpid(pid_, nullptr, 0);
        }
        if (log_fd_ >= 0) ::close(log_fd_);
    }
    Background(const Background&) = delete;
    Background& operator=(const Background&) = delete;

    pid_t pid() const { return pid_; }
    void signal(int sig) const { ::kill(pid_, sig); }
    // Polls `ready` every 2 ms for at most `max_s` seconds; false when it never became true.
    template <class F>
    static bool until(F&& ready, double max_s = 60) {
        const auto t0 = std::chrono::steady_clock::now();
        while (!ready()) {
            if (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() > max_s) return false;
            std::this_thread::sleep_for(std::chrono::milliseconds(2));
        }
        return true;
    }
    Proc wait(double deadline_s = 120) {
        Proc p;
        int status = 0;
        const auto t0 = std::chrono::steady_clock::now();
        for (;;) {
            const pid_t r = ::waitpid(pid_, &status, WNOHANG);
            if (r == pid_) break;
            if (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() > deadline_s && !p.hung) {
                ::kill(pid_, SIGKILL);
                p.hung = true;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
        }
        reaped_ = true;
        if (WIFEXITED(status)) p.code = WEXITSTATUS(status);
        if (WIFSIGNALED(status)) p.signal = WTERMSIG(status);
        ::lseek(log_fd_, 0, SEEK_SET);
        std::array<char, 4096> buf{};
        for (ssize_t n; (n = ::read(log_fd_, buf.data(), buf.size())) > 0;)
            p.output.append(buf.data(), static_cast<size_t>(n));
        return p;
    }

private:
    pid_t pid_ = -1;
    int log_fd_ = -1;
    bool reaped_ = false;
};

// A fresh, empty folder per test (ctest runs tests in parallel, one process each).
inline fs::path temp_dir(const std::string& name) { return mf::testdirs::fresh_for_test("matforge-hostile-", name); }

inline void write_bytes(const fs::path& p, const Bytes& b) {
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary)
        .write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}
inline void write_text(const fs::path& p, const std::string& s) { write_bytes(p, Bytes(s.begin(), s.end())); }

inline Bytes read_bytes(const fs::path& p) {
    Bytes b;
    std::string err;
    EXPECT_TRUE(mf::read_file(p, b, err)) << err;
    return b;
}

using mf::testfiles::read_json;
using mf::testfiles::read_pixels;

// sha256 of every regular file under `dir`, by path relative to it (symlinks not followed).
inline std::map<std::string, std::string> tree_hashes(const fs::path& dir) {
    std::map<std::string, std::string> h;
    for (auto& e : fs::recursive_directory_iterator(dir)) {
        if (!e.is_regular_file() || e.is_symlink()) continue;
        h[e.path().lexically_relative(dir).string()] = mf::sha256_hex(read_bytes(e.path()));
    }
    return h;
}

// Temporaries matforge left under `dir`: names of exactly its temporary form (mf::temp_owner),
// except those of this test process itself (a test may plant a "live writer's" temporary). A
// user's file that merely contains the marker ("holiday.matforge-tmp-photo.jpg") is not one.
inline std::vector<std::string> temp_files_under(const fs::path& dir) {
    std::vector<std::string> found;
    std::error_code ec;
    for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const auto owner = mf::temp_owner(it->path().filename().string());
        if (owner && owner->pid != ::getpid()) found.push_back(it->path().string());
    }
    return found;
}

// Whether a finished (not temporary) file whose name ends in `suffix` is anywhere under `dir`:
// the first output of a run, whichever set the run took first (ingest orders its sets by cost,
// so that a given set's output may come last, when a signal would arrive after the end).
inline bool any_output_under(const fs::path& dir, const std::string& suffix) {
    std::error_code ec;
    for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (!mf::temp_owner(name) && name.size() >= suffix.size() &&
            name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
            return true;
    }
    return false;
}

// A smooth test image with distinct channels (never constant, never out of range).
inline mf::Image gradient(int w, int h, int c) {
    mf::Image img(w, h, c);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int k = 0; k < c; ++k)
                img.at(x, y, k) = 0.2f + 0.6f * static_cast<float>((x * 7 + y * 3 + k * 50) % 256) / 255.f;
    return img;
}

// `img` as a file of `format`: a format presets write through encode_image, a JPEG (which
// vendors ship and no preset writes) through OpenImageIO's own writer.
inline Bytes encode(const mf::Image& img, const std::string& format = "png", int bits = 8) {
    Bytes b;
    std::string err;
    if (const auto f = mf::from_word<mf::FileFormat>(format)) {
        EXPECT_TRUE(mf::encode_image(img, {*f, bits}, b, err)) << err;
        return b;
    }
    EXPECT_EQ(format, "jpg") << "a fixture format this helper writes";
    std::vector<uint8_t> q(img.pixels.size());
    for (size_t i = 0; i < q.size(); ++i) q[i] = mf::quantize8(img.pixels[i]);
    const fs::path tmp = fs::temp_directory_path() / ("matforge-fixture-" + std::to_string(::getpid()) + ".jpg");
    auto out = OIIO::ImageOutput::create(tmp.string());
    const OIIO::ImageSpec spec(img.width, img.height, img.channels, OIIO::TypeDesc::UINT8);
    EXPECT_TRUE(out && out->open(tmp.string(), spec) && out->write_image(OIIO::TypeDesc::UINT8, q.data()) &&
                out->close());
    b = read_bytes(tmp);
    fs::remove(tmp);
    return b;
}

// ---- hand-built PNG (stored deflate: no zlib needed, any bit depth / color type)

inline uint32_t crc32(const unsigned char* p, size_t n, uint32_t crc = 0) {
    crc = ~crc;
    for (size_t i = 0; i < n; ++i) {
        crc ^= p[i];
        for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

inline void put32be(Bytes& b, uint32_t v) {
    for (int s = 24; s >= 0; s -= 8) b.push_back(static_cast<unsigned char>(v >> s));
}

inline void png_chunk(Bytes& png, const char* type, const Bytes& data) {
    put32be(png, static_cast<uint32_t>(data.size()));
    Bytes td(type, type + 4);
    td.insert(td.end(), data.begin(), data.end());
    png.insert(png.end(), td.begin(), td.end());
    put32be(png, crc32(td.data(), td.size()));
}

// zlib stream of stored (uncompressed) deflate blocks.
inline Bytes zlib_stored(const Bytes& raw) {
    Bytes z{0x78, 0x01};
    size_t pos = 0;
    do {
        const size_t n = std::min<size_t>(65535, raw.size() - pos);
        z.push_back(pos + n == raw.size() ? 1 : 0);
        z.push_back(static_cast<unsigned char>(n & 0xff));
        z.push_back(static_cast<unsigned char>(n >> 8));
        z.push_back(static_cast<unsigned char>(~n & 0xff));
        z.push_back(static_cast<unsigned char>((~n >> 8) & 0xff));
        z.insert(z.end(), raw.begin() + static_cast<long>(pos), raw.begin() + static_cast<long>(pos + n));
        pos += n;
    } while (pos < raw.size());
    uint32_t a = 1, b = 0;
    for (unsigned char c : raw) {
        a = (a + c) % 65521;
        b = (b + a) % 65521;
    }
    put32be(z, (b << 16) | a);
    return z;
}

// color_type: 0 grey, 2 RGB, 3 palette, 4 grey+alpha, 6 RGBA. `rows` are the raw scanlines
// without filter bytes; `idat` false writes a header-only file (a bomb declares, never holds).
inline Bytes make_png(uint32_t w, uint32_t h, int bit_depth, int color_type, const Bytes& rows,
                      const Bytes& palette = {}, bool idat = true) {
    Bytes png{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    Bytes ihdr;
    put32be(ihdr, w);
    put32be(ihdr, h);
    ihdr.insert(ihdr.end(), {static_cast<unsigned char>(bit_depth), static_cast<unsigned char>(color_type), 0, 0, 0});
    png_chunk(png, "IHDR", ihdr);
    if (!palette.empty()) png_chunk(png, "PLTE", palette);
    if (idat) {
        const size_t row_bytes = h ? rows.size() / h : 0;
        Bytes raw;
        for (uint32_t y = 0; y < h; ++y) {
            raw.push_back(0);  // filter: none
            raw.insert(raw.end(), rows.begin() + static_cast<long>(y * row_bytes),
                       rows.begin() + static_cast<long>((y + 1) * row_bytes));
        }
        png_chunk(png, "IDAT", zlib_stored(raw));
    } else {
        png_chunk(png, "IDAT", Bytes{0x78, 0x01});
    }
    png_chunk(png, "IEND", {});
    return png;
}

// ---- other formats' headers that declare what they do not hold

inline void put16le(Bytes& b, uint32_t v) {
    b.push_back(static_cast<unsigned char>(v));
    b.push_back(static_cast<unsigned char>(v >> 8));
}
inline void put32le(Bytes& b, uint32_t v) {
    put16le(b, v & 0xffff);
    put16le(b, v >> 16);
}

// Little-endian baseline TIFF, 8-bit grey, one strip of 16 bytes, declaring w×h.
inline Bytes make_tiff_bomb(uint32_t w, uint32_t h) {
    Bytes t{'I', 'I', 42, 0};
    put32le(t, 8);  // first IFD
    const uint16_t n = 9;
    const uint32_t data_at = 8 + 2 + n * 12 + 4;
    put16le(t, n);
    auto entry = [&](uint16_t tag, uint16_t type, uint32_t value) {
        put16le(t, tag);
        put16le(t, type);
        put32le(t, 1);
        if (type == 3) {
            put16le(t, value);
            put16le(t, 0);
        } else {
            put32le(t, value);
        }
    };
    entry(256, 4, w);        // ImageWidth
    entry(257, 4, h);        // ImageLength
    entry(258, 3, 8);        // BitsPerSample
    entry(259, 3, 1);        // Compression: none
    entry(262, 3, 1);        // Photometric: min-is-black
    entry(273, 4, data_at);  // StripOffsets
    entry(277, 3, 1);        // SamplesPerPixel
    entry(278, 4, h);        // RowsPerStrip
    entry(279, 4, 16);       // StripByteCounts
    put32le(t, 0);           // no next IFD
    t.insert(t.end(), 16, 0x80);
    return t;
}

// Windows BMP, 24-bit, declaring w×h, holding one row.
inline Bytes make_bmp_bomb(uint32_t w, uint32_t h) {
    Bytes b{'B', 'M'};
    put32le(b, 54 + 64);
    put32le(b, 0);
    put32le(b, 54);
    put32le(b, 40);
    put32le(b, w);
    put32le(b, h);
    put16le(b, 1);
    put16le(b, 24);
    put32le(b, 0);  // BI_RGB
    put32le(b, 0);
    put32le(b, 2835);
    put32le(b, 2835);
    put32le(b, 0);
    put32le(b, 0);
    b.insert(b.end(), 64, 0x40);
    return b;
}

inline std::string make_hdr_bomb(uint32_t w, uint32_t h) {
    return "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(h) + " +X " + std::to_string(w) + "\n";
}

}  // namespace mfh
