// JPEG reader (lib/image/jpeg_reader.hpp): any bytes as a JPEG, read for its header (markers,
// EXIF orientation) and whole. Whatever it accepts must come back as exactly width x height x
// channels codes, with the size and orientation its header read stated; anything else is refused
// (false; a damaged file with the reason, which check() gives alike), never a crash, an overread, a hang or an
// unbounded allocation.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "image/jpeg_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::vector<unsigned char> file(data, data + size);
    const uint64_t end = mf::jpeg::first_scan_header_end(file.size(), [&](uint64_t at, size_t n, unsigned char* out) {
        if (at > file.size() || n > file.size() - at) return false;
        std::copy_n(file.data() + at, n, out);
        return true;
    });
    if (end > file.size()) std::abort();
    constexpr uint64_t kMaxSamples = uint64_t{1} << 22;  // small: libjpeg's work is the image's size
    mf::jpeg::Plain head;
    const bool head_ok = end > 0 && mf::jpeg::read_plain(file.data(), static_cast<size_t>(end), true, kMaxSamples, head,
                                                         file.size());
    if (head_ok && (head.width <= 0 || head.height <= 0 || !head.pixels.empty())) std::abort();
    mf::jpeg::Plain p;
    // check() is the same rule for the files read_plain declines: it never doubts one it reads.
    const std::string doubt = mf::jpeg::check(file.data(), file.size(), false, kMaxSamples, file.size());
    if (!mf::jpeg::read_plain(file.data(), file.size(), false, kMaxSamples, p, file.size())) {
        if (!p.pixels.empty()) std::abort();  // a refusal leaves nothing
        return 0;
    }
    if (!doubt.empty() || !p.refusal.empty()) std::abort();
    if (p.width <= 0 || p.height <= 0 || (p.channels != 1 && p.channels != 3) ||
        p.pixels.size() !=
            static_cast<size_t>(p.width) * static_cast<size_t>(p.height) * static_cast<size_t>(p.channels))
        std::abort();
    if (head_ok && (head.width != p.width || head.height != p.height || head.channels != p.channels ||
                    head.orientation != p.orientation))
        std::abort();  // the header read states what the decode reads
    return 0;
}
