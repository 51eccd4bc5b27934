// Plain float images and the file access every stage shares.
//
// Conventions of this module (as OpenImageIO's ImageBufAlgo, decided once here):
//  - pixels are float32, interleaved, rows top to bottom, channels R,G,B,A in file order;
//  - values are as stored in the file, normalized to [0,1] for integer files; no color
//    transform is ever applied on read (the role decides the encoding, not the file's tags);
//  - alpha is read unassociated (never premultiplied): a 4th channel is data until a role
//    says otherwise;
//  - errors are returned as text naming the file and the problem, never thrown.
#pragma once
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace mf {

struct Image {
    int width = 0, height = 0, channels = 0;
    std::vector<float> pixels;  // width * height * channels

    Image() = default;
    Image(int w, int h, int c, float fill = 0.f)
        : width(w), height(h), channels(c), pixels(static_cast<size_t>(w) * h * c, fill) {}
    bool empty() const { return pixels.empty(); }
    size_t index(int x, int y, int c = 0) const {
        return (static_cast<size_t>(y) * width + x) * channels + c;
    }
    float& at(int x, int y, int c = 0) { return pixels[index(x, y, c)]; }
    float at(int x, int y, int c = 0) const { return pixels[index(x, y, c)]; }
};

// A readable input: a file on disk, or bytes held in memory (an entry of a .zip).
struct InputFile {
    std::string display;                                   // name used in messages
    std::filesystem::path path;                            // set for files on disk
    std::shared_ptr<const std::vector<unsigned char>> bytes;  // set for in-memory entries
    std::string open_error;  // why an in-memory entry could not be read (then bytes is empty)
    std::string extension() const;                         // lower case, without the dot
};

struct ImageInfo {
    int width = 0, height = 0, channels = 0;
    int bit_depth = 0;      // 8, 16, 32 (float), 16 for half
    bool is_float = false;  // half or float samples (EXR, HDR, float TIFF)
    std::string format;     // OpenImageIO format name ("png", "openexr", …)
};

// Largest image matforge agrees to decode (decompression-bomb guard): 16384² pixels, 8 channels.
inline constexpr int64_t kMaxPixels = int64_t{16384} * 16384;
inline constexpr int kMaxChannels = 8;

// Header only (cheap). Returns nullopt and sets `error` when the file is not a readable image.
std::optional<ImageInfo> read_info(const InputFile& in, std::string& error);

// Whole image as float. Returns false and sets `error` on failure (the image is left empty).
bool read_image(const InputFile& in, Image& out, ImageInfo& info, std::string& error);

// Streams the image in horizontal bands of at most `band_rows` rows (bounded memory for 8K
// maps). `fn(y0, rows, pixels)` gets float pixels of rows [y0, y0+rows). Returns false on error.
bool read_bands(const InputFile& in, int band_rows, ImageInfo& info, std::string& error,
                const std::function<void(int y0, int rows, const float* pixels)>& fn);

struct EncodeOptions {
    std::string format = "png";  // png | exr | tif | tga
    int bit_depth = 8;           // 8 or 16 for png/tif/tga; 16 (half) or 32 for exr
};

// Encodes `img` (values already in the output encoding, [0,1] for integer formats) to bytes,
// deterministically (no timestamps). Rounds to nearest code. Returns false and sets `error`.
bool encode_image(const Image& img, const EncodeOptions& opt, std::vector<unsigned char>& bytes,
                  std::string& error);

// Quantization used by encode_image, exposed for tests: round-half-up of clamp(v,0,1)*max.
uint16_t quantize(float v, int bit_depth);

}  // namespace mf
