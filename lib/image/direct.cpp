#include "image/direct.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <fstream>
#include <new>

#include "image/header_notes.hpp"
#include "image/jpeg_reader.hpp"
#include "image/png_reader.hpp"
#include "image/webp_reader.hpp"

namespace mf::direct {
namespace {

namespace fs = std::filesystem;

enum class Kind { none, jpeg, png, webp };

// OpenImageIO's WebP reader: its format name and its one extension (it states "sRGB" for every
// WebP, as its JPEG reader does for every JPEG).
constexpr const char* kWebp = "webp";

// OpenImageIO's JPEG reader's extensions: a file named so is stated "sRGB" by that reader, the
// one stated_color_space opens by name. A JPEG under another name is the module's.
bool jpeg_name(const InputFile& in) {
    static constexpr std::array<std::string_view, 6> kExtensions = {"jpg", "jpe", "jpeg", "jif", "jfif", "jfi"};
    const std::string ext = in.extension();
    return std::find(kExtensions.begin(), kExtensions.end(), ext) != kExtensions.end();
}

// A file or memory image opened for reading parts of it; `size` 0 when it is neither a regular
// file nor held bytes (a FIFO, a folder, a missing file: the module says which).
struct Source {
    const InputFile& in;
    std::ifstream file;
    uint64_t size = 0;
    Kind kind = Kind::none;
    bool jpeg_signature = false;  // a JPEG by its first bytes, whatever its name

    explicit Source(const InputFile& i) : in(i) {
        if (in.bytes) {
            size = in.bytes->size();
        } else {
            std::error_code ec;
            if (!fs::is_regular_file(in.path, ec)) return;
            file.open(in.path, std::ios::binary);
            const uint64_t n = fs::file_size(in.path, ec);
            if (!file || ec) return;
            size = n;
        }
        unsigned char head[8] = {};
        if (size < sizeof head || !read(0, sizeof head, head)) {
            size = 0;
            return;
        }
        unsigned char riff[12] = {};
        jpeg_signature = head[0] == 0xFF && head[1] == 0xD8 && head[2] == 0xFF;
        if (jpeg_signature && jpeg_name(in)) kind = Kind::jpeg;
        else if (std::memcmp(head, png::kSignature, 8) == 0) kind = Kind::png;
        else if (std::memcmp(head, "RIFF", 4) == 0 && in.extension() == kWebp && read(0, sizeof riff, riff) &&
                 std::memcmp(riff + 8, "WEBP", 4) == 0)
            kind = Kind::webp;
    }
    bool read(uint64_t at, size_t n, unsigned char* out) {
        if (at > size || n > size - at) return false;
        if (in.bytes) {
            std::memcpy(out, in.bytes->data() + at, n);
            return true;
        }
        file.clear();
        file.seekg(static_cast<std::streamoff>(at));
        file.read(reinterpret_cast<char*>(out), static_cast<std::streamsize>(n));
        return static_cast<size_t>(file.gcount()) == n;
    }
    ReadAt reader() {
        return [this](uint64_t at, size_t n, unsigned char* out) { return read(at, n, out); };
    }
    // The first `n` bytes (n <= size), or empty on a read error.
    std::vector<unsigned char> bytes(uint64_t n) {
        std::vector<unsigned char> b(static_cast<size_t>(n));
        if (!read(0, b.size(), b.data())) b.clear();
        return b;
    }
};

ImageInfo info_of(int width, int height, int channels, int bit_depth, const char* format) {
    ImageInfo info;
    info.width = width;
    info.height = height;
    info.channels = channels;
    info.bit_depth = bit_depth;
    info.format = format;
    return info;
}

bool within_limits(int width, int height, int channels) {
    return int64_t{width} * height <= kMaxPixels && channels <= kMaxChannels;
}

ImageInfo jpeg_info(const InputFile& in, const jpeg::Plain& p) {
    ImageInfo info = info_of(p.width, p.height, p.channels, 8, "jpeg");
    if (p.orientation != 1) info.notes.push_back(orientation_note(in.display, p.orientation));
    return info;
}

// A whole file that is at most twice the largest decode (its compressed pixels), else empty.
std::vector<unsigned char> whole(Source& src) {
    if (src.size > 2 * uint64_t{kMaxSampleBytes}) return {};
    return src.bytes(src.size);
}

// A decode into codes of `bit_depth` (8: bytes; 16: uint16_t in host order) and its facts.
struct Raw {
    ImageInfo info;
    int bit_depth = 8;
    std::vector<uint8_t> samples;
};

// Why a JPEG this reader declines must not be decoded another way either (jpeg::check: a
// declared size its data cannot hold, lost data), or empty. `file`: the whole file when the
// caller has read it (a decode), else null (a header read: the header alone is checked). A whole
// file beyond whole()'s bound is left to the module unchecked but for its header.
std::string declined_jpeg(Source& src, const std::vector<unsigned char>* file) {
    if (!src.jpeg_signature) return {};
    if (file && !file->empty()) return jpeg::check(file->data(), file->size(), false, kMaxSampleBytes, file->size());
    const uint64_t end = jpeg::first_scan_header_end(src.size, src.reader());
    const std::vector<unsigned char> head = end ? src.bytes(end) : std::vector<unsigned char>{};
    return head.empty() ? std::string() : jpeg::check(head.data(), head.size(), true, kMaxSampleBytes, src.size);
}

// One decode per codec (the source sniffed as it): false + `refusal` as direct.hpp says.
bool jpeg_decode(const InputFile& in, Source& src, Raw& raw, std::string& refusal) {
    std::vector<unsigned char> file = whole(src);
    jpeg::Plain p;
    if (file.empty() || !jpeg::read_plain(file.data(), file.size(), false, kMaxSampleBytes, p, file.size()) ||
        !within_limits(p.width, p.height, p.channels)) {
        refusal = !p.refusal.empty() ? p.refusal : declined_jpeg(src, &file);
        return false;
    }
    raw.info = jpeg_info(in, p);
    raw.bit_depth = 8;
    raw.samples = std::move(p.pixels);
    return true;
}

bool webp_decode(const InputFile&, Source& src, Raw& raw, std::string&) {
    std::vector<unsigned char> file = whole(src);
    webp::Plain p;
    if (file.empty() || !webp::read_plain(file.data(), file.size(), false, kMaxSampleBytes, p) ||
        !within_limits(p.width, p.height, p.channels))
        return false;
    raw.info = info_of(p.width, p.height, p.channels, 8, kWebp);
    raw.bit_depth = 8;
    raw.samples = std::move(p.pixels);
    return true;
}

bool png_decode(const InputFile&, Source& src, Raw& raw, std::string& refusal) {
    // The head first: any other PNG (palette, interlaced, too large) is left to OpenImageIO
    // before the whole file is read or copied.
    png::Plain p;
    std::vector<unsigned char> head = src.bytes(std::min<uint64_t>(src.size, png::kHeaderBytes));
    if (head.size() < png::kHeaderBytes || !png::plain_ihdr(head.data(), kMaxSampleBytes, p)) {
        refusal = png::size_refusal(src.size, src.reader());
        return false;
    }
    std::vector<unsigned char> file = whole(src);
    if (file.empty() || !png::read_plain(file, kMaxSampleBytes, p) || !within_limits(p.width, p.height, p.channels)) {
        refusal = png::size_refusal(src.size, src.reader());
        return false;
    }
    raw.info = info_of(p.width, p.height, p.channels, p.bit_depth, "png");
    raw.bit_depth = p.bit_depth;
    raw.samples = std::move(p.pixels);
    return true;
}

// One header read per codec: false + `refusal` as direct.hpp says.
bool jpeg_header(const InputFile& in, Source& src, ImageInfo& info, std::optional<StatedColorSpace>& stated,
                 std::string& refusal) {
    const uint64_t end = jpeg::first_scan_header_end(src.size, src.reader());
    if (end == 0) return false;
    const std::vector<unsigned char> head = src.bytes(end);
    jpeg::Plain p;
    if (head.empty() || !jpeg::read_plain(head.data(), head.size(), true, kMaxSampleBytes, p, src.size) ||
        !within_limits(p.width, p.height, p.channels)) {
        refusal = !p.refusal.empty() ? p.refusal : declined_jpeg(src, nullptr);
        return false;
    }
    info = jpeg_info(in, p);
    stated = StatedColorSpace{"sRGB", "jpeg"};
    return true;
}

bool webp_header(const InputFile&, Source& src, ImageInfo& info, std::optional<StatedColorSpace>& stated,
                 std::string&) {
    // The RIFF header and the first chunk's, which state the size, alpha and animation.
    const std::vector<unsigned char> head = src.bytes(std::min<uint64_t>(src.size, 4096));
    webp::Plain p;
    if (head.empty() || !webp::read_plain(head.data(), head.size(), true, kMaxSampleBytes, p) ||
        !within_limits(p.width, p.height, p.channels))
        return false;
    info = info_of(p.width, p.height, p.channels, 8, kWebp);
    stated = StatedColorSpace{"sRGB", kWebp};
    return true;
}

bool png_header(const InputFile&, Source& src, ImageInfo& info, std::optional<StatedColorSpace>&,
                std::string& refusal) {
    png::Plain p;
    if (!png::read_plain_header(src.size, src.reader(), kMaxSampleBytes, p) ||
        !within_limits(p.width, p.height, p.channels)) {
        refusal = png::size_refusal(src.size, src.reader());
        return false;
    }
    info = info_of(p.width, p.height, p.channels, p.bit_depth, "png");
    return true;
}

// The direct readers, one row each: what Source sniffed a file as picks its row. A file no row
// takes is the OpenImageIO module's (image.cpp asks it next).
struct Codec {
    Kind kind;
    bool (*header)(const InputFile&, Source&, ImageInfo&, std::optional<StatedColorSpace>&, std::string& refusal);
    bool (*decode)(const InputFile&, Source&, Raw&, std::string& refusal);
};
constexpr Codec kCodecs[] = {
    {Kind::jpeg, jpeg_header, jpeg_decode},
    {Kind::png, png_header, png_decode},
    {Kind::webp, webp_header, webp_decode},
};
const Codec* codec_of(Kind kind) {
    for (const Codec& c : kCodecs)
        if (c.kind == kind) return &c;
    return nullptr;
}

bool decode_or_throw(const InputFile& in, Raw& raw, std::string& refusal) {
    Source src(in);
    if (const Codec* c = codec_of(src.kind)) return c->decode(in, src, raw, refusal);
    if (src.jpeg_signature) {  // a JPEG under another name: refused here when damaged, else the module's
        const std::vector<unsigned char> file = whole(src);
        refusal = declined_jpeg(src, &file);
    }
    return false;
}

bool decode(const InputFile& in, Raw& raw, std::string& refusal) {
    try {
        return decode_or_throw(in, raw, refusal);
    } catch (const std::bad_alloc&) {
        raw = Raw{};
        return false;
    }
}

// 16-bit code k as OpenImageIO reads it: k * (1/65535) in float (its convert_type<uint16_t,
// float>; PngReader.Reads16BitAsOpenImageIoDoes compares every value).
void unorm16_to_float(const uint8_t* samples, size_t n, float* out) {
    for (size_t i = 0; i < n; ++i) {
        uint16_t k;
        std::memcpy(&k, samples + 2 * i, 2);
        out[i] = static_cast<float>(k) * (1.0f / 65535.0f);
    }
}

void to_floats(const Raw& raw, size_t first, size_t n, float* out) {
    if (raw.bit_depth == 16) unorm16_to_float(raw.samples.data() + 2 * first, n, out);
    else to_float(raw.samples.data() + first, n, out);
}

bool read_info_or_throw(const InputFile& in, ImageInfo& info, std::optional<StatedColorSpace>& stated,
                        std::string& refusal) {
    Source src(in);
    if (const Codec* c = codec_of(src.kind)) return c->header(in, src, info, stated, refusal);
    refusal = declined_jpeg(src, nullptr);  // a JPEG under another name
    return false;
}
}  // namespace

bool read_info(const InputFile& in, ImageInfo& info, std::optional<StatedColorSpace>& stated, std::string& refusal) {
    try {
        return read_info_or_throw(in, info, stated, refusal);
    } catch (const std::bad_alloc&) {
        return false;
    }
}

bool read_image(const InputFile& in, Decoded& out, ImageInfo& info, bool keep_codes, std::string& refusal) {
    Raw raw;
    if (!decode(in, raw, refusal)) return false;
    Decoded d;
    if (keep_codes && raw.bit_depth == 8) {
        d.codes.width = raw.info.width;
        d.codes.height = raw.info.height;
        d.codes.channels = raw.info.channels;
        d.codes.pixels = std::move(raw.samples);
    } else {
        try {
            d.floats = Image(raw.info.width, raw.info.height, raw.info.channels);
        } catch (const std::bad_alloc&) {
            return false;
        }
        to_floats(raw, 0, d.floats.pixels.size(), d.floats.pixels.data());
    }
    out = std::move(d);
    info = std::move(raw.info);
    return true;
}

bool read_bands(const InputFile& in, int band_rows, ImageInfo& info, std::string& refusal,
                const std::function<void(int, int, const float*)>& fn,
                const std::function<void(int, int, const uint8_t*)>& codes) {
    Raw raw;
    if (!decode(in, raw, refusal)) return false;
    band_rows = std::max(1, band_rows);
    const size_t row = static_cast<size_t>(raw.info.width) * static_cast<size_t>(raw.info.channels);
    const bool as_codes = codes && raw.bit_depth == 8;
    std::vector<float> band;
    try {
        if (!as_codes) band.resize(row * static_cast<size_t>(std::min(band_rows, raw.info.height)));
    } catch (const std::bad_alloc&) {
        return false;
    }
    info = std::move(raw.info);
    for (int y0 = 0; y0 < info.height; y0 += band_rows) {
        const int rows = std::min(band_rows, info.height - y0);
        const size_t first = row * static_cast<size_t>(y0);
        if (as_codes) {
            codes(y0, rows, raw.samples.data() + first);
            continue;
        }
        to_floats(raw, first, row * static_cast<size_t>(rows), band.data());
        fn(y0, rows, band.data());
    }
    return true;
}

}  // namespace mf::direct
