// The one way the image readers read part of a file or of a memory image (an entry of a .zip).
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>

namespace mf {

// Reads `n` bytes at `at` into `out`; false past the end or on a read error.
using ReadAt = std::function<bool(uint64_t at, size_t n, unsigned char* out)>;

}  // namespace mf
