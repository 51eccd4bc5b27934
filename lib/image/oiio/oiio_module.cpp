// The matforge_oiio module: every use of OpenImageIO by matforge's own code, built as a shared
// module that lib/image loads (dlopen) the first time a file is decoded or encoded. OpenImageIO
// brings 261 libraries (FFmpeg, OpenCV, GDAL, ...), whose loading took 0.3 s of every start,
// including runs that decode nothing (a re-ingest that finds everything up to date, --help).
// The table at the end is the module's only exported symbol; image.cpp checks its ABI number.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <fstream>
#include <mutex>
#include <new>

#include <dlfcn.h>
#include <unistd.h>

#include "image/header_notes.hpp"
#include "image/jpeg_reader.hpp"
#include "image/oiio_module.hpp"
#include "image/png_reader.hpp"

namespace mf {
namespace {

namespace fs = std::filesystem;

// Formats whose OpenImageIO reader or writer lacks IOProxy support go through a private
// temporary file; this holds its life time.
struct TempFile {
    fs::path path;
    explicit TempFile(const std::string& ext) {
        static std::atomic<unsigned> counter{0};
        path = fs::temp_directory_path() /
               ("matforge-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + "." + ext);
    }
    ~TempFile() {
        std::error_code ec;
        fs::remove(path, ec);
    }
    TempFile(const TempFile&) = delete;
    TempFile& operator=(const TempFile&) = delete;
};

// An open reader plus whatever keeps its bytes alive.
struct Reader {
    // A PNG stripped of bulky metadata, or a JPEG's headers alone (for a header read).
    std::shared_ptr<const std::vector<unsigned char>> owned;
    std::unique_ptr<OIIO::Filesystem::IOMemReader> proxy;
    std::unique_ptr<TempFile> temp;
    std::unique_ptr<OIIO::ImageInput> in;
};

std::string oiio_error_text(std::string text) {
    // OpenImageIO errors often end with a newline; messages are one line.
    while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
    std::replace(text.begin(), text.end(), '\n', ' ');
    return text.empty() ? "not a readable image" : text;
}

// OpenImageIO's format name from a file's first bytes; empty when no signature is known (TGA
// has none). Files are opened by content with the reader chosen here, never through
// OpenImageIO's fallback of trying every reader once the extension's fails: that loop is not
// thread-safe in 2.4 (with sets decoded in parallel, a misnamed PNG read as 0-bit or failed, at
// random), and it is turned off (try_all_readers = 0).
std::string sniff_format(const unsigned char* b, size_t n) {
    auto starts = [&](std::initializer_list<unsigned char> sig) {
        return n >= sig.size() && std::equal(sig.begin(), sig.end(), b);
    };
    if (starts({0x89, 'P', 'N', 'G'})) return "png";
    if (starts({0xFF, 0xD8, 0xFF})) return "jpeg";
    if (starts({0x76, 0x2F, 0x31, 0x01})) return "openexr";
    if (starts({'I', 'I', 42, 0}) || starts({'M', 'M', 0, 42}) || starts({'I', 'I', 43, 0}) ||
        starts({'M', 'M', 0, 43}))
        return "tiff";
    if (starts({'B', 'M'})) return "bmp";
    if (starts({'#', '?'})) return "hdr";
    if (starts({'R', 'I', 'F', 'F'}) && n >= 12 && std::equal(b + 8, b + 12, "WEBP")) return "webp";
    if (starts({'8', 'B', 'P', 'S'})) return "psd";
    if (starts({'D', 'D', 'S', ' '})) return "dds";
    if (starts({'G', 'I', 'F', '8'})) return "gif";
    return {};
}

// Ancillary chunks (lower-case first letter) larger than png::kMaxMetadataChunk are dropped
// before the decoder sees the file; pixels, palette and transparency are critical or small and
// always kept.

// The PNG without its oversized ancillary chunks, or nullptr when it has none (or is not a
// well-formed chunk sequence: the decoder then reports the file as it is).
std::shared_ptr<std::vector<unsigned char>> png_without_bulky_metadata(uint64_t size, const ReadAt& read) {
    struct Chunk {
        uint64_t at;
        uint64_t bytes;
        bool drop;
    };
    std::vector<Chunk> chunks;
    bool any = false;
    uint64_t at = 8;
    unsigned char head[8];
    while (at + 12 <= size) {
        if (!read(at, 8, head)) return nullptr;
        const uint64_t len = png::be32(head);
        if (at + 12 + len > size) return nullptr;
        const bool ancillary = head[4] >= 'a' && head[4] <= 'z';
        const bool drop = ancillary && len > png::kMaxMetadataChunk;
        any = any || drop;
        chunks.push_back({at, 12 + len, drop});
        at += 12 + len;
        if (std::equal(head + 4, head + 8, "IEND")) break;
    }
    if (!any) return nullptr;
    auto out = std::make_shared<std::vector<unsigned char>>(8);
    if (!read(0, 8, out->data())) return nullptr;
    for (const Chunk& c : chunks) {
        if (c.drop) continue;
        const size_t start = out->size();
        out->resize(start + static_cast<size_t>(c.bytes));
        if (!read(c.at, static_cast<size_t>(c.bytes), out->data() + start)) return nullptr;
    }
    return out;
}

// A JPEG's markers up to and including its first scan's header (SOS), then an end-of-image
// marker: everything OpenImageIO's reader needs to state the size, channels, orientation and
// colour space, without the scans. For a header read only: OpenImageIO opens a JPEG by starting
// libjpeg's decompressor, which for a progressive JPEG entropy-decodes every scan. nullptr when
// the markers do not walk to a scan (the decoder then reads the file as it is).
std::shared_ptr<std::vector<unsigned char>> jpeg_through_first_scan_header(uint64_t size, const ReadAt& read) {
    const uint64_t end = jpeg::first_scan_header_end(size, read);
    if (end == 0) return nullptr;
    auto out = std::make_shared<std::vector<unsigned char>>(static_cast<size_t>(end) + 2);
    if (!read(0, static_cast<size_t>(end), out->data())) return nullptr;
    (*out)[end] = 0xFF;
    (*out)[end + 1] = 0xD9;
    return out;
}

// Opens `name` with the reader of `format` (a format name, or a file name whose extension picks
// the reader). Sets `error` on failure.
std::unique_ptr<OIIO::ImageInput> open_with(const std::string& format, const std::string& name,
                                            const OIIO::ImageSpec& config, OIIO::Filesystem::IOProxy* proxy,
                                            std::string& error) {
    static std::once_flag once;
    std::call_once(once, [] { OIIO::attribute("try_all_readers", 0); });
    auto in = OIIO::ImageInput::create(format, false, &config);
    if (!in) {
        error = oiio_error_text(OIIO::geterror());
        return nullptr;
    }
    if (proxy && !in->set_ioproxy(proxy)) {
        error = "the " + std::string(in->format_name()) + " reader cannot read from memory";
        return nullptr;
    }
    OIIO::ImageSpec spec;
    if (!in->open(name, spec, config)) {
        error = oiio_error_text(in->geterror());
        return nullptr;
    }
    return in;
}

// header_only: the reader is used for its spec, never its pixels (a JPEG is then opened over its
// headers alone, jpeg_through_first_scan_header).
bool open_reader(const InputFile& in, Reader& r, std::string& error, bool header_only = false) {
    OIIO::ImageSpec config;
    // Texture data: a 4th channel is not necessarily transparency; never premultiply.
    config.attribute("oiio:UnassociatedAlpha", 1);
    const std::string name = in.bytes ? in.display : in.path.string();
    if (!in.bytes) {
        std::error_code ec;
        const fs::file_status st = fs::status(in.path, ec);
        if (ec) {  // never opened: a FIFO or device would block or never end
            std::error_code lec;
            const bool link = fs::is_symlink(fs::symlink_status(in.path, lec));
            error = in.display + ": " + (link ? "broken symbolic link" : "cannot open") + " (" + ec.message() + ")";
            return false;
        }
        if (!fs::is_regular_file(st)) {
            const char* what = fs::is_directory(st) ? "a folder"
                               : fs::is_fifo(st)    ? "a FIFO"
                               : fs::is_socket(st)  ? "a socket"
                                                    : "a device or special file";
            error = in.display + ": not a regular file (" + what + ")";
            return false;
        }
        if (fs::file_size(in.path, ec) == 0) {
            error = in.display + ": empty file (0 bytes)";
            return false;
        }
        std::array<unsigned char, 16> head{};
        std::ifstream f(in.path, std::ios::binary);
        f.read(reinterpret_cast<char*>(head.data()), head.size());
        const std::string format = sniff_format(head.data(), static_cast<size_t>(f.gcount()));
        std::string why;
        const ReadAt read_at = [&](uint64_t at, size_t n, unsigned char* out) {
            f.clear();
            f.seekg(static_cast<std::streamoff>(at));
            f.read(reinterpret_cast<char*>(out), static_cast<std::streamsize>(n));
            return static_cast<size_t>(f.gcount()) == n;
        };
        if (format == "png") r.owned = png_without_bulky_metadata(fs::file_size(in.path, ec), read_at);
        if (format == "jpeg" && header_only)
            r.owned = jpeg_through_first_scan_header(fs::file_size(in.path, ec), read_at);
        if (r.owned) {
            r.proxy = std::make_unique<OIIO::Filesystem::IOMemReader>(r.owned->data(), r.owned->size());
            r.in = open_with(format, name, config, r.proxy.get(), why);
        } else {
            r.in = open_with(format.empty() ? name : format, name, config, nullptr, why);
        }
        if (!r.in) {
            error = in.display + ": " + why;
            return false;
        }
    } else {
        if (!in.open_error.empty()) {
            error = in.display + ": " + in.open_error;
            return false;
        }
        if (in.bytes->empty()) {
            error = in.display + ": empty file (0 bytes)";
            return false;
        }
        std::string format = sniff_format(in.bytes->data(), in.bytes->size());
        if (format.empty()) format = name;  // no signature: the extension decides
        const ReadAt read_at = [&](uint64_t at, size_t n, unsigned char* out) {
            if (at + n > in.bytes->size()) return false;
            std::copy_n(in.bytes->data() + at, n, out);
            return true;
        };
        if (format == "png") r.owned = png_without_bulky_metadata(in.bytes->size(), read_at);
        if (format == "jpeg" && header_only) r.owned = jpeg_through_first_scan_header(in.bytes->size(), read_at);
        const std::vector<unsigned char>& data = r.owned ? *r.owned : *in.bytes;
        auto probe = OIIO::ImageInput::create(format, false);
        std::string why;
        if (probe && probe->supports("ioproxy")) {
            r.proxy = std::make_unique<OIIO::Filesystem::IOMemReader>(data.data(), data.size());
            r.in = open_with(format, name, config, r.proxy.get(), why);
        } else {
            r.temp = std::make_unique<TempFile>(in.extension());
            std::ofstream(r.temp->path, std::ios::binary)
                .write(reinterpret_cast<const char*>(data.data()), static_cast<std::streamsize>(data.size()));
            r.in = open_with(format, r.temp->path.string(), config, nullptr, why);
        }
        if (!r.in) {
            error = in.display + ": " + why;
            return false;
        }
    }
    return true;
}

ImageInfo info_of(const OIIO::ImageInput& in) {
    const OIIO::ImageSpec& s = in.spec();
    ImageInfo info;
    info.width = s.width;
    info.height = s.height;
    info.channels = s.nchannels;
    info.format = in.format_name();
    switch (s.format.basetype) {
        case OIIO::TypeDesc::UINT8:
        case OIIO::TypeDesc::INT8: info.bit_depth = 8; break;
        case OIIO::TypeDesc::UINT16:
        case OIIO::TypeDesc::INT16: info.bit_depth = 16; break;
        case OIIO::TypeDesc::HALF:
            info.bit_depth = 16;
            info.is_float = true;
            break;
        case OIIO::TypeDesc::FLOAT:
            info.bit_depth = 32;
            info.is_float = true;
            break;
        case OIIO::TypeDesc::DOUBLE:
            info.bit_depth = 64;
            info.is_float = true;
            break;
        default: info.bit_depth = static_cast<int>(s.format.size() * 8); break;
    }
    return info;
}

// What the header says beyond the size: a deep image is refused (samples per pixel vary: there
// is no one value per texel), several images in one file and an orientation tag become notes.
// Leaves the reader on the first image.
bool inspect(OIIO::ImageInput& r, const InputFile& in, ImageInfo& info, std::string& error) {
    if (r.spec().deep) {
        error = in.display + ": a deep " + info.format +
                " image (a varying number of samples per pixel), which matforge "
                "does not read; flatten it first (oiiotool " +
                fs::path(in.display).filename().string() + " --flatten -o flat.exr)";
        return false;
    }
    const std::string part = r.spec().get_string_attribute("oiio:subimagename");
    int count = 1;
    while (count < 1000 && r.seek_subimage(count, 0)) ++count;
    if (!r.seek_subimage(0, 0)) {  // back to the first image, the one every reader uses
        error = in.display + ": " + oiio_error_text(r.geterror());
        return false;
    }
    if (count > 1) {
        const bool exr = info.format == "openexr";
        info.notes.emplace_back("MULTIPART_IMAGE", in.display + ": holds " +
                                                       (count == 1000 ? "1000 or more" : std::to_string(count)) +
                                                       (exr ? " parts" : " images (pages)") + "; the first" +
                                                       (part.empty() ? std::string() : " ('" + part + "')") +
                                                       " is used, the others are ignored");
    }
    const int orientation = r.spec().get_int_attribute("Orientation", 1);
    if (orientation != 1) info.notes.push_back(orientation_note(in.display, orientation));
    return true;
}

bool check_dimensions(const InputFile& in, const ImageInfo& info, std::string& error) {
    if (info.width <= 0 || info.height <= 0 || info.channels <= 0) {
        error = in.display + ": image has no pixels (" + std::to_string(info.width) + "x" +
                std::to_string(info.height) + ", " + std::to_string(info.channels) + " channels)";
        return false;
    }
    if (int64_t{info.width} * info.height > kMaxPixels || info.channels > kMaxChannels) {
        error = in.display + ": declared size " + std::to_string(info.width) + "x" + std::to_string(info.height) + "x" +
                std::to_string(info.channels) + " exceeds the limit of " + std::to_string(kMaxImageSide) + "x" +
                std::to_string(kMaxImageSide) + " pixels and " + std::to_string(kMaxChannels) + " channels";
        return false;
    }
    return true;
}

// A read that succeeded over a file that ends early: libjpeg fills the rows past the end with
// grey and only warns ("Premature end of JPEG file", JWRN_JPEG_EOF), which OpenImageIO keeps as
// a pending error beside a successful read (checked with OpenImageIO 2.4 on a JPEG cut to its
// first 2,000 bytes). Those pixels are not the map's: the file is unreadable. Other pending
// messages are dropped: libjpeg's "Corrupt JPEG data: N extraneous bytes before marker", which
// real vendor files carry with intact pixels, must not fail them.
bool ended_early(OIIO::ImageInput& r, const InputFile& in, std::string& error) {
    if (!r.has_error()) return false;
    const std::string message = r.geterror();
    if (message.find("Premature end") == std::string::npos) return false;
    error = in.display + ": the file ends before its last pixel (" + oiio_error_text(message) +
            "): truncated, the rest would be grey";
    return true;
}

// The format of the reader OpenImageIO picks by the file's name when that reader takes the file
// (2.4's create checks the file's signature with the reader its extension names: through a
// memory proxy for an entry of a .zip, else it looks for the name on disk), else empty.
std::string format_by_name(const InputFile& in) {
    std::unique_ptr<OIIO::Filesystem::IOMemReader> mem;
    if (in.bytes) mem = std::make_unique<OIIO::Filesystem::IOMemReader>(in.bytes->data(), in.bytes->size());
    auto by_name = OIIO::ImageInput::create(in.bytes ? in.display : in.path.string(), false, nullptr, mem.get());
    if (!by_name) {
        (void)OIIO::geterror();  // clear the thread's error
        return {};
    }
    if (in.bytes && !by_name->supports("ioproxy")) return {};
    return by_name->format_name();
}

// The colour space `r` states, when `r` is the reader the file's name picks (a misnamed file's
// sniffed reader is another than stated_color_space's, which opens by name).
std::optional<StatedColorSpace> stated_by(const OIIO::ImageInput& r, const InputFile& in) {
    if (format_by_name(in) != r.format_name()) return std::nullopt;
    return StatedColorSpace{r.spec().get_string_attribute("oiio:ColorSpace"), r.format_name()};
}

std::optional<ImageInfo> read_info_impl(const InputFile& in, std::string& error,
                                        std::optional<StatedColorSpace>& stated) {
    Reader r;
    if (!open_reader(in, r, error, /*header_only=*/true)) return std::nullopt;
    ImageInfo info = info_of(*r.in);
    stated = stated_by(*r.in, in);  // before inspect, which may move to another subimage and back
    if (!check_dimensions(in, info, error) || !inspect(*r.in, in, info, error)) return std::nullopt;
    return info;
}

// Decodes into `codes` when keep_codes and the file is 8-bit integer, else into `floats`.
bool read_image_impl(const InputFile& in, Decoded& out, ImageInfo& info, std::string& error, bool keep_codes) {
    out = Decoded{};
    Reader r;
    if (!open_reader(in, r, error)) return false;
    info = info_of(*r.in);
    if (!check_dimensions(in, info, error) || !inspect(*r.in, in, info, error)) return false;
    const bool codes = keep_codes && !info.is_float && info.bit_depth == 8;
    bool ok = false;
    if (codes) {
        Image8 img(info.width, info.height, info.channels);
        ok = r.in->read_image(0, 0, 0, info.channels, OIIO::TypeDesc::UINT8, img.pixels.data());
        if (ok) out.codes = std::move(img);
    } else {
        Image img(info.width, info.height, info.channels);
        ok = r.in->read_image(0, 0, 0, info.channels, OIIO::TypeDesc::FLOAT, img.pixels.data());
        if (ok) out.floats = std::move(img);
    }
    if (!ok) {
        error = in.display + ": " + oiio_error_text(r.in->geterror());
        return false;
    }
    if (ended_early(*r.in, in, error)) {
        out = Decoded{};
        return false;
    }
    return true;
}

bool read_bands_impl(const InputFile& in, int band_rows, ImageInfo& info, std::string& error,
                     const std::function<void(int, int, const float*)>& fn) {
    Reader r;
    if (!open_reader(in, r, error)) return false;
    info = info_of(*r.in);
    if (!check_dimensions(in, info, error) || !inspect(*r.in, in, info, error)) return false;
    band_rows = std::max(1, band_rows);
    const size_t band_values = static_cast<size_t>(info.width) * info.channels * band_rows;
    std::vector<float> band(band_values);
    // OpenImageIO 2.4's read_scanlines allocates and frees a buffer of up to 64 MB on every call,
    // whatever the format asked (under ASan, each one is faulted in anew: 9x the decode time). The
    // band is read natively into one buffer kept here, and converted by the same OpenImageIO
    // routine (the same values). Files with per-channel formats keep the float read: their native
    // rows are not one type.
    const OIIO::ImageSpec& spec = r.in->spec();
    const bool native = spec.channelformats.empty() && spec.format != OIIO::TypeDesc::FLOAT;
    std::vector<unsigned char> raw(native ? band_values * spec.format.size() : 0);
    for (int y0 = 0; y0 < info.height; y0 += band_rows) {
        const int rows = std::min(band_rows, info.height - y0);
        const size_t n = static_cast<size_t>(info.width) * info.channels * rows;
        const bool ok = native ? r.in->read_native_scanlines(0, 0, y0, y0 + rows, 0, 0, info.channels, raw.data()) &&
                                     OIIO::convert_pixel_values(spec.format, raw.data(), OIIO::TypeDesc::FLOAT,
                                                                band.data(), static_cast<int>(n))
                               : r.in->read_scanlines(0, 0, y0, y0 + rows, 0, 0, info.channels, OIIO::TypeDesc::FLOAT,
                                                      band.data());
        if (!ok) {
            error = in.display + ": " + oiio_error_text(r.in->geterror());
            return false;
        }
        if (ended_early(*r.in, in, error)) return false;
        fn(y0, rows, band.data());
    }
    return true;
}

// The output spec of every encode: reproducible bytes and matforge's PNG settings.
OIIO::ImageSpec output_spec(int width, int height, int channels, const EncodeOptions& opt, const OIIO::TypeDesc& type) {
    OIIO::ImageSpec spec(width, height, channels, type);
    if (channels == 4 || channels == 2) spec.alpha_channel = channels - 1;
    spec.attribute("oiio:UnassociatedAlpha", 1);
    // Reproducible bytes: no timestamps, no software version stamps.
    spec.attribute("DateTime", "2000:01:01 00:00:00");
    spec.attribute("Software", "matforge");
    if (opt.format == FileFormat::exr) spec.attribute("compression", "zip");
    return spec;
}

// Writes `data` (of `memtype`) with `spec` in opt.format to bytes.
bool write_encoded(const OIIO::ImageSpec& spec, const OIIO::TypeDesc& memtype, const void* data,
                   const EncodeOptions& opt, std::vector<unsigned char>& bytes, std::string& error) {
    if (opt.format == FileFormat::png) {  // image.cpp's (png_writer.hpp says why not OpenImageIO's writer)
        error = "PNG is encoded by matforge's own writer, not through OpenImageIO";
        return false;
    }
    const std::string format(word(opt.format));
    const std::string name = "output." + format;
    auto out = is_block_container(opt.format) ? nullptr : OIIO::ImageOutput::create(name);
    if (!out) {
        error = "cannot create a writer for format '" + format + "': " + oiio_error_text(OIIO::geterror());
        return false;
    }
    if (out->supports("ioproxy")) {
        OIIO::Filesystem::IOVecOutput vec(bytes);
        out->set_ioproxy(&vec);
        if (!out->open(name, spec) || !out->write_image(memtype, data) || !out->close()) {
            error = "encoding " + format + ": " + oiio_error_text(out->geterror());
            return false;
        }
        return true;
    }
    TempFile temp(format);
    if (!out->open(temp.path.string(), spec) || !out->write_image(memtype, data) || !out->close()) {
        error = "encoding " + format + ": " + oiio_error_text(out->geterror());
        return false;
    }
    std::ifstream f(temp.path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(f), {});
    return true;
}
bool encode_floats(const Image& img, const EncodeOptions& opt, std::vector<unsigned char>& bytes, std::string& error) {
    bytes.clear();
    const bool is_float = opt.format == FileFormat::exr;
    const OIIO::TypeDesc type = is_float ? (opt.bit_depth == 32 ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::HALF)
                                         : (opt.bit_depth == 16 ? OIIO::TypeDesc::UINT16 : OIIO::TypeDesc::UINT8);
    const OIIO::ImageSpec spec = output_spec(img.width, img.height, img.channels, opt, type);
    // Quantize ourselves (round to nearest, clamp) so results never depend on a plugin's rounding.
    if (is_float) return write_encoded(spec, OIIO::TypeDesc::FLOAT, img.pixels.data(), opt, bytes, error);
    if (opt.bit_depth == 16) {
        std::vector<uint16_t> q16(img.pixels.size());
        for (size_t i = 0; i < q16.size(); ++i) q16[i] = quantize_unorm(img.pixels[i], 65535.f);
        return write_encoded(spec, type, q16.data(), opt, bytes, error);
    }
    std::vector<uint8_t> q8(img.pixels.size());
    for (size_t i = 0; i < q8.size(); ++i) q8[i] = static_cast<uint8_t>(quantize_unorm(img.pixels[i], 255.f));
    return write_encoded(spec, type, q8.data(), opt, bytes, error);
}

bool encode_codes(const Image8& img, const EncodeOptions& opt, std::vector<unsigned char>& bytes, std::string& error) {
    bytes.clear();
    if (opt.format == FileFormat::exr || opt.bit_depth != 8) {
        error = "8-bit codes cannot be written as " + std::to_string(opt.bit_depth) + "-bit " +
                std::string(word(opt.format));
        return false;
    }
    const OIIO::ImageSpec spec = output_spec(img.width, img.height, img.channels, opt, OIIO::TypeDesc::UINT8);
    return write_encoded(spec, OIIO::TypeDesc::UINT8, img.pixels.data(), opt, bytes, error);
}

// What the file's reader states as its colour space ("oiio:ColorSpace"), with the reader's
// format name; both empty when the file does not open (reported where it is decoded).
StatedColorSpace stated_color_space(const InputFile& in) {
    OIIO::ImageSpec config;
    std::unique_ptr<OIIO::ImageInput> input;
    std::unique_ptr<OIIO::Filesystem::IOMemReader> proxy;
    if (in.bytes) {
        // The reader the name picks, over the memory image (ImageInput::open's proxy argument
        // does not reach 2.4's JPEG reader, which then looked for the name on disk).
        const std::string format = format_by_name(in);
        if (format.empty()) return {};
        proxy = std::make_unique<OIIO::Filesystem::IOMemReader>(in.bytes->data(), in.bytes->size());
        std::string why;
        input = open_with(format, in.display, config, proxy.get(), why);
    } else {
        input = OIIO::ImageInput::open(in.path.string(), &config);
    }
    if (!input) {
        (void)OIIO::geterror();  // clear the thread's error
        return {};
    }
    StatedColorSpace s{input->spec().get_string_attribute("oiio:ColorSpace"), input->format_name()};
    input->close();
    return s;
}

void resize_lanczos3(const Image& src, Image& out) {
    OIIO::ImageSpec in_spec(src.width, src.height, src.channels, OIIO::TypeDesc::FLOAT);
    OIIO::ImageBuf in(in_spec, const_cast<float*>(src.pixels.data()));  // read-only use
    OIIO::ImageSpec out_spec(out.width, out.height, src.channels, OIIO::TypeDesc::FLOAT);
    OIIO::ImageBuf dst(out_spec, out.pixels.data());
    OIIO::ImageBufAlgo::resize(dst, in, "lanczos3", 0.f, OIIO::ROI::All(), 1);
}

int library_version() { return OIIO::openimageio_version(); }

std::string library_file() {
    Dl_info info{};
    const bool found = ::dladdr(reinterpret_cast<void*>(&OIIO::openimageio_version), &info) != 0;
    return found && info.dli_fname ? info.dli_fname : "";
}

std::string format_libraries() {
    std::string formats = OIIO::get_string_attribute("library_list");
    std::replace(formats.begin(), formats.end(), ';', ' ');
    return formats;
}

constexpr oiio_module::Table kTable{oiio_module::kAbi, sizeof(oiio_module::Table),
                                    &read_info_impl,   &read_image_impl,
                                    &read_bands_impl,  &encode_floats,
                                    &encode_codes,     &stated_color_space,
                                    &resize_lanczos3,  &library_version,
                                    &library_file,     &format_libraries};

}  // namespace
}  // namespace mf

extern "C" __attribute__((visibility("default"))) const mf::oiio_module::Table* matforge_oiio_table() {
    return &mf::kTable;
}
