#include <gtest/gtest.h>

#include <cstdlib>
#include <vector>

#include "core/allocator.hpp"

// Sanitizer builds replace malloc (mallopt and mallinfo2 are no-ops there).
#if defined(__GLIBC__) && !defined(MATFORGE_SANITIZE_BUILD)
#include <malloc.h>

TEST(Allocator, LargeBlocksComeFromTheHeapAndAreReused) {
    mf::prefer_heap_reuse_for_large_images();
    const auto mapped_before = mallinfo2().hblks;
    for (int i = 0; i < 3; ++i) {  // a 4K RGB float map's size, three times over
        std::vector<float> map(4096u * 4096u * 3u, 1.f);
        // Read through volatile: clang elides an allocation whose contents nothing reads.
        const volatile float* touched = map.data();
        EXPECT_EQ(touched[map.size() - 1], 1.f);
        EXPECT_EQ(mallinfo2().hblks, mapped_before) << "the block was mmap'd";
    }
    // Freed, not trimmed: the next map reuses these pages instead of faulting in fresh ones.
    EXPECT_GE(mallinfo2().fordblks, 4096u * 4096u * 3u * sizeof(float));
}
#endif
