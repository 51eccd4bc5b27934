// PNG's row filters reversed (PNG spec 9.2: None, Sub, Up, Average, Paeth) for the plain-PNG
// reader (png_reader.hpp). On x86-64 with SSE2 (its baseline) and, where the CPU has it, SSE4.1
// for Paeth; elsewhere the byte-at-a-time form. Every form gives the same bytes:
// tests/image/png_unfilter_test.cpp holds the vector forms to the byte-at-a-time one for every
// filter, pixel size and width, and Paeth's for all 2^24 (left, above, upper left) triples.
#pragma once
#include <cstddef>
#include <cstdint>

namespace mf::png {

// The code that reverses the filters: byte at a time, SSE2's, or SSE2's with SSE4.1's byte
// blend in Paeth's chain (pblendvb: one instruction where SSE2 takes three).
enum class UnfilterIsa { scalar, sse2, sse41 };

// The fastest form this build runs on this CPU (asked once).
UnfilterIsa best_unfilter_isa();

// Whether this build runs `isa` on this CPU.
bool can_unfilter_with(UnfilterIsa isa);

// Reverses filter `type` (the byte before the row in the stream; 0-4) of the filtered row `in`:
// `width` pixels of `bpp` bytes (1, 2, 3, 4, 6 or 8: one to four samples of 8 or 16 bits),
// reconstructed into `out`, which is `in` (in place) or lies before it, overlapping or not: the
// reader moves each row over its filter byte as it goes. `up` is the row above, reconstructed,
// or zeros for a first row; it overlaps neither. False, nothing written, for any other type.
// `isa` must be one can_unfilter_with() takes.
bool unfilter_row(int type, const uint8_t* in, uint8_t* out, const uint8_t* up, size_t width, int bpp,
                  UnfilterIsa isa = best_unfilter_isa());

}  // namespace mf::png
