// An allocation failure while decoding is said as one (not "malformed data"), names the file, and
// is an error returned, never a crash. The failure is made deterministic by this program's
// operator new, which throws std::bad_alloc for large requests while a test asks it to (every
// other test of the program allocates normally).
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <new>

#include <unistd.h>

#include "core/files.hpp"
#include "image/image.hpp"
#include "test_dirs.hpp"

namespace {
std::atomic<size_t> g_fail_above{0};  // 0: never fail
}

void* operator new(size_t n) {
    const size_t limit = g_fail_above.load(std::memory_order_relaxed);
    if (limit != 0 && n > limit) throw std::bad_alloc();
    if (void* p = std::malloc(n ? n : 1)) return p;
    throw std::bad_alloc();
}
void* operator new[](size_t n) { return operator new(n); }
// These replace the global operators: free() is their own malloc's match, which GCC cannot see.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, size_t) noexcept { std::free(p); }
void operator delete[](void* p, size_t) noexcept { std::free(p); }
#pragma GCC diagnostic pop

namespace {

namespace fs = std::filesystem;

TEST(AllocationFailure, DecodingSaysOutOfMemoryAndNamesTheFile) {
    const fs::path dir = mf::testdirs::fresh("matforge-alloc-", "decode");
    const fs::path file = dir / "Big_Color.png";
    mf::Image img(512, 512, 3, 0.5f);
    std::vector<unsigned char> bytes;
    std::string error;
    ASSERT_TRUE(mf::encode_image(img, {mf::FileFormat::png, 8}, bytes, error)) << error;
    ASSERT_TRUE(mf::write_file_atomic(file, bytes, error)) << error;
    mf::InputFile in;
    in.path = file;
    in.display = file.string();
    mf::Image out;
    mf::ImageInfo info;
    ASSERT_TRUE(mf::read_image(in, out, info, error)) << error;  // enough memory: read
    g_fail_above = 256 * 1024;  // no allocation above 256 KiB: the 512² pixels cannot be held
    const bool read = mf::read_image(in, out, info, error);
    g_fail_above = 0;
    EXPECT_FALSE(read);
    EXPECT_NE(error.find(file.string() + ": decoding it needed more memory than could be allocated"), std::string::npos)
        << error;
    EXPECT_EQ(error.find("malformed"), std::string::npos) << error;
    fs::remove_all(dir);
}

}  // namespace
