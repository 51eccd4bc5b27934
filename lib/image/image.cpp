#include "image/image.hpp"

// Only OpenImageIO's version macros (no library to link): the name of the library file the
// module links, for image_library_version.
#include <OpenImageIO/oiioversion.h>

#include <dlfcn.h>

#include <cstdio>  // before jpeglib.h, which uses FILE

#include <jpeglib.h>
#include <webp/decode.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <new>

#include "base/file_identity.hpp"
#include "image/direct.hpp"
#include "image/oiio_module.hpp"
#include "image/png_writer.hpp"

namespace mf {
namespace {

namespace fs = std::filesystem;

// The OpenImageIO module's table (image/oiio_loader.cpp), loaded on first use.
using oiio_module::table;

// Some OpenImageIO plugins throw on hostile bytes (the GIF reader's vector resize, bad_alloc on
// absurd headers): every decode is guarded here, at the module boundary, and becomes an error.
template <class F>
auto guarded(const InputFile& in, std::string& error, F&& f) -> decltype(f()) {
    try {
        return f();
    } catch (const std::bad_alloc&) {
        // Headers are checked against the pixel budget before decoding, so this is most often a
        // machine (or its memory limit) without the memory for the image, not malformed data.
        error = in.display +
                ": decoding it needed more memory than could be allocated (too little free memory or a memory "
                "limit, or a header that claims more than the file holds); run with fewer --jobs, or set the "
                "preset's max_size";
    } catch (const std::exception& e) {
        error = in.display + ": the decoder failed on malformed data (" + e.what() + ")";
    } catch (...) {
        error = in.display + ": the decoder failed on malformed data";
    }
    return {};
}

// The order of every read, decided here once: the direct readers first (image/direct.hpp); a
// file one of them refuses (damaged, lying about its size) fails with its reason and goes no
// further; one they leave (another format, a kind they do not read) goes to the OpenImageIO
// module, guarded. `direct(refusal)` and `module(table)` say whether they read it.
template <class Direct, class Module>
bool direct_then_module(const InputFile& in, std::string& error, Direct&& direct, Module&& module) {
    std::string refusal;
    if (direct(refusal)) return true;
    if (!refusal.empty()) {
        error = in.display + ": " + refusal;
        return false;
    }
    const auto* t = table(error, in.display + ": ");
    return t && guarded(in, error, [&] { return module(*t); });
}

// What a file's header says, remembered for the run (ReadScope) by the file's identity and
// change times: a set's plan reads each map's header once per preset and the checks read it again, and
// OpenImageIO's JPEG reader entropy-decodes a progressive file whole to open it (52 of the
// corpus's 91 JPEGs are progressive: an ingest of it for glTF and HDRP opened each JPEG 4.8
// times, 2.8 with these memos, and took 12 % less CPU). A file changed since is another key;
// in-memory entries (.zip) are read each time.
//
// The key of a file on disk: its settled identity (base/file_identity.hpp, the rule the result
// cache keeps digests by), empty for what is not one and for a file changed in the last seconds.
std::atomic<int>& open_scopes() {
    static std::atomic<int> n{0};
    return n;
}

std::string file_key(const InputFile& in) {
    if (in.bytes || open_scopes().load() == 0) return {};
    const std::string id = settled_identity(in.path);
    return id.empty() ? id : id + ':' + in.display + '\n' + in.path.string();
}

template <class T>
class FileMemo {
public:
    // Remembers `value` under `key` (file_key's; an empty key remembers nothing).
    void put(const std::string& key, T value) {
        if (key.empty()) return;
        std::lock_guard lock(mutex_);
        if (entries_.size() >= kMaxEntries) entries_.clear();  // a bound, not a policy: a library's maps fit
        entries_.emplace(key, std::move(value));
    }
    // f() once per key.
    template <class F>
    T get(const std::string& key, F&& f) {
        if (!key.empty()) {
            std::lock_guard lock(mutex_);
            if (const auto it = entries_.find(key); it != entries_.end()) return it->second;
        }
        T value = f();
        put(key, value);
        return value;
    }

    void clear() {
        std::lock_guard lock(mutex_);
        entries_.clear();
    }

private:
    static constexpr size_t kMaxEntries = 1u << 16;
    std::mutex mutex_;
    std::map<std::string, T> entries_;
};

struct HeaderRead {
    std::optional<ImageInfo> info;
    std::string error;
};
FileMemo<HeaderRead>& header_memo() {
    static FileMemo<HeaderRead> memo;
    return memo;
}
FileMemo<StatedColorSpace>& stated_memo() {
    static FileMemo<StatedColorSpace> memo;
    return memo;
}
}  // namespace

ReadScope::ReadScope() { ++open_scopes(); }
ReadScope::ReadScope(const ReadScope&) { ++open_scopes(); }
ReadScope::~ReadScope() {
    if (--open_scopes() > 0) return;
    header_memo().clear();
    stated_memo().clear();
}

std::optional<ImageInfo> read_info(const InputFile& in, std::string& error) {
    const std::string key = file_key(in);
    HeaderRead r = header_memo().get(key, [&] {
        HeaderRead h;
        std::optional<StatedColorSpace> stated;  // from the same open, where it is stated_color_space's
        ImageInfo info;
        if (direct_then_module(
                in, h.error, [&](std::string& refusal) { return direct::read_info(in, info, stated, refusal); },
                [&](const oiio_module::Table& t) {
                    auto read = t.read_info(in, h.error, stated);
                    if (read) info = std::move(*read);
                    return read.has_value();
                }))
            h.info = std::move(info);
        // The colour-tag check then needs no open of its own (a JPEG's costs a decode).
        if (stated) stated_memo().put(key, *stated);
        return h;
    });
    if (!r.info) error = std::move(r.error);
    return std::move(r.info);
}

// Decodes `in`: directly where image/direct.hpp reads it, else through the module.
bool read_decoded(const InputFile& in, Decoded& out, ImageInfo& info, std::string& error, bool keep_codes) {
    const bool ok = direct_then_module(
        in, error, [&](std::string& refusal) { return direct::read_image(in, out, info, keep_codes, refusal); },
        [&](const oiio_module::Table& t) { return t.read_image(in, out, info, error, keep_codes); });
    if (!ok) out = Decoded{};
    return ok;
}

bool read_image(const InputFile& in, Image& out, ImageInfo& info, std::string& error) {
    Decoded d;
    const bool ok = read_decoded(in, d, info, error, false);
    out = ok ? std::move(d.floats) : Image{};
    return ok;
}

bool read_image(const InputFile& in, Decoded& out, ImageInfo& info, std::string& error) {
    return read_decoded(in, out, info, error, true);
}

bool read_bands(const InputFile& in, int band_rows, ImageInfo& info, std::string& error,
                const std::function<void(int, int, const float*)>& fn) {
    return read_bands(in, band_rows, info, error, fn, {});
}

bool read_bands(const InputFile& in, int band_rows, ImageInfo& info, std::string& error,
                const std::function<void(int, int, const float*)>& fn,
                const std::function<void(int, int, const uint8_t*)>& codes) {
    return direct_then_module(
        in, error, [&](std::string& refusal) { return direct::read_bands(in, band_rows, info, refusal, fn, codes); },
        [&](const oiio_module::Table& t) { return t.read_bands(in, band_rows, info, error, fn); });
}

// PNG is matforge's own writer (png_writer.hpp says why); every other format OpenImageIO's.
bool encode_image(const Image& img, const EncodeOptions& opt, std::vector<unsigned char>& bytes, std::string& error) {
    bytes.clear();
    if (opt.format == FileFormat::png) {
        // Quantized here (round to nearest, clamp) so results never depend on a writer's rounding.
        if (opt.bit_depth == 16) {
            std::vector<uint16_t> q16(img.pixels.size());
            for (size_t i = 0; i < q16.size(); ++i) q16[i] = quantize_unorm(img.pixels[i], 65535.f);
            return png::write(q16.data(), img.width, img.height, img.channels, 16, bytes, error);
        }
        std::vector<uint8_t> q8(img.pixels.size());
        for (size_t i = 0; i < q8.size(); ++i) q8[i] = quantize8(img.pixels[i]);
        return png::write(q8.data(), img.width, img.height, img.channels, 8, bytes, error);
    }
    const auto* t = table(error);
    return t && t->encode_floats(img, opt, bytes, error);
}

bool encode_image(const Image8& img, const EncodeOptions& opt, std::vector<unsigned char>& bytes, std::string& error) {
    bytes.clear();
    if (opt.format == FileFormat::png && opt.bit_depth == 8)
        return png::write(img.pixels.data(), img.width, img.height, img.channels, 8, bytes, error);
    const auto* t = table(error);
    return t && t->encode_codes(img, opt, bytes, error);
}

StatedColorSpace stated_color_space(const InputFile& in) {
    return stated_memo().get(file_key(in), [&] {
        // A JPEG read directly is stated as OpenImageIO states every JPEG, without the module; a
        // reader that throws on hostile bytes states nothing (decoding the file reports it).
        StatedColorSpace s;
        std::string error;
        direct_then_module(
            in, error,
            [&](std::string& refusal) {
                ImageInfo info;
                std::optional<StatedColorSpace> stated;
                if (!direct::read_info(in, info, stated, refusal) || !stated) return false;
                s = *stated;
                return true;
            },
            [&](const oiio_module::Table& t) {
                s = t.stated_color_space(in);
                return true;
            });
        return s;
    });
}

Image resize_lanczos3(const Image& src, int w, int h) {
    Image out(w, h, src.channels);
    std::string error;
    if (const auto* t = table(error)) t->resize_lanczos3(src, out);
    return out;
}

// OpenImageIO reads 8-bit code k as k * (1/255) in float (its convert_pixel_values; the codes
// tests check read_image's floats against this table bit for bit). Computed here, not asked of
// the module, so that a run which decodes nothing (an up-to-date re-ingest builds its colour
// context, which tabulates these) never loads OpenImageIO.
const std::array<float, 256>& unorm8_values() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> v{};
        for (size_t k = 0; k < v.size(); ++k) v[k] = static_cast<float>(k) * (1.0f / 255.0f);
        return v;
    }();
    return table;
}

void to_float(const uint8_t* codes, size_t n, float* out, const float* table) {
    if (table && table != unorm8_values().data()) {
        for (size_t i = 0; i < n; ++i) out[i] = table[codes[i]];
        return;
    }
    // unorm8_values' own expression, 8 codes at a time: the same floats bit for bit, without a
    // table load per code (GCC's -O2 vectorizes neither form; this was 3 % of an ingest's CPU).
    using U8x8 = uint8_t __attribute__((vector_size(8)));
    using F32x8 = float __attribute__((vector_size(32)));
    size_t i = 0;
    for (; i + 8 <= n; i += 8) {
        U8x8 k;
        std::memcpy(&k, codes + i, sizeof k);
        const F32x8 v = __builtin_convertvector(k, F32x8) * (1.0f / 255.0f);
        std::memcpy(out + i, &v, sizeof v);
    }
    for (; i < n; ++i) out[i] = static_cast<float>(codes[i]) * (1.0f / 255.0f);
}

Image to_float(const Image8& codes, const float* table) {
    Image out(codes.width, codes.height, codes.channels);
    to_float(codes.pixels.data(), codes.pixels.size(), out.pixels.data(), table);
    return out;
}

uint16_t quantize(float v, int bit_depth) { return quantize_unorm(v, bit_depth == 16 ? 65535.f : 255.f); }

namespace {
// A library file's real name and size ("libjpeg.so.62.3.0 413904"): an upgrade replaces the
// file, so the key changes, whatever version the headers of the build named.
std::string file_identity(const fs::path& file) {
    std::error_code ec;
    const fs::path real = fs::canonical(file, ec);
    const auto size = ec ? 0 : fs::file_size(real, ec);
    return ec ? file.string() : real.filename().string() + " " + std::to_string(size);
}
}  // namespace

// The ingest cache's key names the libraries that decode and encode: OpenImageIO's file, and
// libjpeg-turbo's and libwebp's, and libdeflate (image/direct.hpp, png_writer.hpp). Asking the loaded
// OpenImageIO costs loading it (0.3 s, 261 libraries) in every run, also one that finds
// everything up to date, so its file is looked up where the build linked it. Where the loader
// could pick another (LD_LIBRARY_PATH set, or no file there), the module is loaded and names the
// file it loaded: the same key either way. libjpeg and libwebp are linked: the files the loader loaded.
std::string image_library_version() {
    fs::path file = fs::path(MATFORGE_OIIO_LIBRARY_DIR) / ("libOpenImageIO.so." + std::to_string(OIIO_VERSION_MAJOR) +
                                                           "." + std::to_string(OIIO_VERSION_MINOR));
    std::error_code ec;
    const char* ld_path = std::getenv("LD_LIBRARY_PATH");
    if ((ld_path && *ld_path) || !fs::exists(file, ec)) {
        std::string error;
        const auto* t = table(error);
        if (!t) return "OpenImageIO (" + error + ")";
        file = t->library_file();
    }
    // The file the loader loaded that holds `symbol` (a linked library's).
    auto loaded = [](void* symbol) {
        Dl_info where{};
        const bool found = ::dladdr(symbol, &where) != 0 && where.dli_fname;
        return found ? file_identity(where.dli_fname) : std::string("?");
    };
    return "OpenImageIO " + file_identity(file) + ", libjpeg " + loaded(reinterpret_cast<void*>(&jpeg_read_header)) +
           ", libwebp " + loaded(reinterpret_cast<void*>(&WebPGetDecoderVersion)) +
           ", libdeflate " MATFORGE_LIBDEFLATE_VERSION;
}

std::string image_library_versions() {
    std::string error;
    const auto* t = table(error);
    if (!t) return "OpenImageIO: " + error;
    const int v = t->version();  // 20407 is 2.4.7
    std::string s = "OpenImageIO " + std::to_string(v / 10000) + "." + std::to_string(v / 100 % 100) + "." +
                    std::to_string(v % 100);
    const std::string formats = t->format_libraries();
    if (!formats.empty()) s += " (formats: " + formats + ")";
    return s;
}

}  // namespace mf
