#include "core/allocator.hpp"

#include <cstdlib>  // defines __GLIBC__ on glibc (through <features.h>)
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace mf {

void prefer_heap_reuse_for_large_images() {
#if defined(__GLIBC__)
    mallopt(M_ARENA_MAX, 1);             // one heap for all threads: freed maps serve the next set
    mallopt(M_MMAP_MAX, 0);              // large blocks from the heap, not fresh mmap'd pages
    mallopt(M_TRIM_THRESHOLD, 1 << 30);  // keep up to 1 GiB freed for reuse instead of trimming
#endif
}

}  // namespace mf
