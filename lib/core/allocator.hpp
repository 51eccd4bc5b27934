// Process-wide allocator settings for the image pipelines (ingest, validate).
#pragma once

namespace mf {

// Decoded maps are large (a 1K RGB float map is 12 MB, a 4K one 200 MB) and short-lived: one
// per input, freed when the set is done. glibc serves such blocks with mmap and returns them
// with munmap, so every map pays for page faults and zeroing of fresh pages; with two set
// threads each thread's arena also keeps its own free memory. This keeps large blocks in one
// heap and reuses them: measured on the throughput library, system time halves (1K-2K sets
// 0.49 -> 0.24 s, 4K sets 3.6 -> 1.8 s) for ~6 % more peak RSS (docs/throughput/results.md).
// Call once, before any worker thread starts. Does nothing on other C libraries.
void prefer_heap_reuse_for_large_images();

}  // namespace mf
