// Plain images (float, or the untouched codes of 8-bit files) and the file access every stage
// shares.
//
// Conventions of this module (as OpenImageIO's ImageBufAlgo, decided once here):
//  - pixels are float32 (Image) or 8-bit codes (Image8, only where a reader asked for them),
//    interleaved, rows top to bottom, channels R,G,B,A in file order;
//  - values are as stored in the file, normalized to [0,1] for integer files; no color
//    transform is ever applied on read (the role decides the encoding, not the file's tags);
//  - alpha is read unassociated (never premultiplied): a 4th channel is data until a role
//    says otherwise;
//  - errors are returned as text naming the file and the problem, never thrown.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "base/ascii.hpp"
#include "base/limits.hpp"
#include "base/vocabulary.hpp"

namespace mf {

template <class T>
struct BasicImage {
    int width = 0, height = 0, channels = 0;
    std::vector<T> pixels;  // width * height * channels

    BasicImage() = default;
    BasicImage(int w, int h, int c, T fill = T{})
        : width(w), height(h), channels(c), pixels(static_cast<size_t>(w) * h * c, fill) {}
    bool empty() const { return pixels.empty(); }
    size_t index(int x, int y, int c = 0) const { return (static_cast<size_t>(y) * width + x) * channels + c; }
    T& at(int x, int y, int c = 0) { return pixels[index(x, y, c)]; }
    T at(int x, int y, int c = 0) const { return pixels[index(x, y, c)]; }
};
using Image = BasicImage<float>;
// The codes of an 8-bit file, untouched. Code k stands for the float unorm8_values()[k]: an
// 8-bit map that needs no float step (no resampling, no color change) goes from decoder to
// encoder in a quarter of the memory and without two conversions.
using Image8 = BasicImage<uint8_t>;

// The float OpenImageIO reads 8-bit code k as (its own conversion: read_image's floats of an
// 8-bit file and these agree bit for bit).
const std::array<float, 256>& unorm8_values();
// `f` of every 8-bit code's float: a table indexed by code that gives what `f` gives for the
// float read_image holds for that code, bit for bit (the rules read codes through such tables).
template <class F>
std::array<float, 256> unorm8_table(F f) {
    std::array<float, 256> t{};
    for (size_t k = 0; k < t.size(); ++k) t[k] = f(unorm8_values()[k]);
    return t;
}
// The codes as floats through a 256-entry `table`: by default unorm8_values() (what read_image
// gives), or another per-code table such as ColorContext::srgb_codes_to_linear().
Image to_float(const Image8& codes, const float* table = nullptr);
// One row band of codes as floats into `out` (size n), as above.
void to_float(const uint8_t* codes, size_t n, float* out, const float* table = nullptr);

// A readable input: a file on disk, or bytes held in memory (an entry of a .zip).
struct InputFile {
    std::string display;                                      // name used in messages
    std::filesystem::path path;                               // set for files on disk
    std::shared_ptr<const std::vector<unsigned char>> bytes;  // set for in-memory entries
    std::string open_error;  // why an in-memory entry could not be read (then bytes is empty)
    // Lower case, without the dot (of `display`, else of `path`).
    std::string extension() const {
        std::string name = display.empty() ? path.string() : display;
        const auto dot = name.rfind('.');
        if (dot == std::string::npos || name.find('/', dot) != std::string::npos) return {};
        return ascii_lower(name.substr(dot + 1));
    }
};

struct ImageInfo {
    int width = 0, height = 0, channels = 0;
    int bit_depth = 0;      // 8, 16, 32 (float), 16 for half
    bool is_float = false;  // half or float samples (EXR, HDR, float TIFF)
    std::string format;     // OpenImageIO format name ("png", "openexr", …)
    // What reading the file decided that its user should know, as (finding code, message naming
    // the file): MULTIPART_IMAGE (the first of several images is read), ORIENTATION_IGNORED (an
    // EXIF/TIFF orientation is not applied: maps of a set must line up pixel for pixel).
    std::vector<std::pair<std::string, std::string>> notes;
};

// Largest image matforge agrees to decode (decompression-bomb guard): kMaxImageSide² pixels,
// 8 channels.
inline constexpr int64_t kMaxPixels = int64_t{kMaxImageSide} * kMaxImageSide;
inline constexpr int kMaxChannels = 8;

// A run's read memo. While a ReadScope is alive (process/batch.hpp's Batch holds one for its
// run), what a file's header says (read_info, stated_color_space) is remembered by the file's
// settled identity (base/file_identity.hpp: the rule the result cache keeps digests by; a file
// changed in the last seconds is not remembered); when the last scope ends, the memo is dropped.
// So a process that runs batch after batch (the Python bindings) holds nothing between runs,
// and nothing is remembered outside one. Copies count as scopes of their own.
class ReadScope {
public:
    ReadScope();
    ReadScope(const ReadScope&);
    ReadScope& operator=(const ReadScope&) = default;  // both are counted already
    ~ReadScope();
};

// Header only (cheap). Returns nullopt and sets `error` when the file is not a readable image.
std::optional<ImageInfo> read_info(const InputFile& in, std::string& error);

// Whole image as float. Returns false and sets `error` on failure (the image is left empty).
bool read_image(const InputFile& in, Image& out, ImageInfo& info, std::string& error);

// A decoded file: an 8-bit integer file as its codes, any other as float (exactly one is set).
struct Decoded {
    Image floats;
    Image8 codes;
    bool is_codes() const { return !codes.empty(); }
    int width() const { return is_codes() ? codes.width : floats.width; }
    int height() const { return is_codes() ? codes.height : floats.height; }
    int channels() const { return is_codes() ? codes.channels : floats.channels; }
};
// As read_image, but an 8-bit file keeps its codes (no float conversion).
bool read_image(const InputFile& in, Decoded& out, ImageInfo& info, std::string& error);

// Streams the image in horizontal bands of at most `band_rows` rows (bounded memory for 8K
// maps). `fn(y0, rows, pixels)` gets float pixels of rows [y0, y0+rows). Returns false on error.
bool read_bands(const InputFile& in, int band_rows, ImageInfo& info, std::string& error,
                const std::function<void(int y0, int rows, const float* pixels)>& fn);
// As above, but an 8-bit file decoded by matforge's own readers (JPEG, plain PNG, WebP) hands its
// bands to `codes` as its codes (code k standing for unorm8_values()[k]): no float copy.
bool read_bands(const InputFile& in, int band_rows, ImageInfo& info, std::string& error,
                const std::function<void(int y0, int rows, const float* pixels)>& fn,
                const std::function<void(int y0, int rows, const uint8_t* codes)>& codes);

struct EncodeOptions {
    FileFormat format = FileFormat::png;  // png | exr | tif | tga (no blocks: lib/texture writes dds, ktx2)
    int bit_depth = 8;                    // 8 or 16 for png/tif/tga; 16 (half) or 32 for exr
};

// OpenImageIO's version (its readers decode every input, its TIFF/EXR writers encode those
// outputs) and the PNG writer's library (libdeflate), for the ingest cache's action key.
std::string image_library_version();
// For `matforge --version`: OpenImageIO's version (major.minor.patch) and the format libraries
// it was built with, as it reports them ("png:libpng 1.6.39;jpeg:jpeg-turbo 2.1.5;...").
std::string image_library_versions();

// Encodes `img` (values already in the output encoding, [0,1] for integer formats) to bytes,
// deterministically (no timestamps). Rounds to nearest code. Returns false and sets `error`.
bool encode_image(const Image& img, const EncodeOptions& opt, std::vector<unsigned char>& bytes, std::string& error);

// Encodes 8-bit codes as they are (an 8-bit integer format: png, tif, tga). Returns false and
// sets `error` for any other format or depth.
bool encode_image(const Image8& img, const EncodeOptions& opt, std::vector<unsigned char>& bytes, std::string& error);

// What a file's reader states as its colour space (OpenImageIO's "oiio:ColorSpace"; for PNG
// and JPEG it says "sRGB" whether or not the file is tagged) and the reader's format name; both
// empty when the file does not open. lib/validate's colour-tag check reads it.
struct StatedColorSpace {
    std::string color_space, format;
};
StatedColorSpace stated_color_space(const InputFile& in);

// `src` resized to w x h by OpenImageIO's Lanczos-3 resize (lib/pack's resample decides when).
Image resize_lanczos3(const Image& src, int w, int h);

// The quantization of every integer output: round half up of clamp(v, 0, 1) * maxv, NaN -> 0.
// Branch-free: the cast truncates a non-negative value, which is floor, so loops vectorize with
// no call to std::floor.
inline uint16_t quantize_unorm(float v, float maxv) {
    const float c = v > 0.f ? (v < 1.f ? v : 1.f) : 0.f;
    // NOLINTNEXTLINE(bugprone-incorrect-roundings): round half up is the contract; lround is a call per sample
    return static_cast<uint16_t>(c * maxv + 0.5f);
}
inline uint8_t quantize8(float v) { return static_cast<uint8_t>(quantize_unorm(v, 255.f)); }

// Quantization used by encode_image, exposed for tests: round-half-up of clamp(v,0,1)*max.
uint16_t quantize(float v, int bit_depth);

}  // namespace mf
