// What validate holds of an 8K set, on real files: the bound docs/rules.md states. Maps are read
// in bands of 64 rows, but some decoders hold a whole image: a PNG is inflated whole (by matforge's
// direct reader up to 48 MiB of samples, by OpenImageIO beyond), and libjpeg keeps every DCT
// coefficient of a progressive JPEG (2 bytes each: 8192² RGB 4:2:0 is 192 MiB) until its last scan.
// A baseline JPEG streams. Measured with --jobs 1 (2026-12-06, release build): 178 MB for the
// baseline JPEG and two PNGs below, 398 MB with the progressive JPEG added; a reader that held
// the maps as floats (8192² RGB: 768 MiB each) fails both bounds.
#include <gtest/gtest.h>

#include <iostream>

#include "hostile_util.hpp"
#include "image/png_writer.hpp"
#include "test_jpeg.hpp"

namespace mfh {
namespace {

constexpr int kSide = 8192;

Bytes png8(int channels, int period) {
    std::vector<uint8_t> samples(static_cast<size_t>(kSide) * kSide * static_cast<size_t>(channels));
    for (size_t y = 0; y < kSide; ++y)
        for (size_t x = 0; x < kSide; ++x)
            for (int c = 0; c < channels; ++c)
                samples[(y * kSide + x) * static_cast<size_t>(channels) + static_cast<size_t>(c)] =
                    static_cast<uint8_t>(c == 2 ? 250 : 96 + (x + y * static_cast<size_t>(c)) % period);
    Bytes out;
    std::string error;
    EXPECT_TRUE(mf::png::write(samples.data(), kSide, kSide, channels, 8, out, error)) << error;
    return out;
}

long validate_peak_kb(const fs::path& in) {
    const Proc p = spawn({bin(), "validate", in.string(), "--jobs", "1", "--report", "json", "--report-file",
                          (in.parent_path() / "report.json").string(), "--fail-on", "never"},
                         300);
    EXPECT_EQ(p.code, 0) << p.output;
    return p.maxrss_kb;
}

TEST(Memory, ValidateOfAnEightKSetStaysWithinItsStatedBound) {
    const fs::path in = temp_dir("in");
    write_bytes(in / "Rock" / "Rock_Color.jpg", mf::testjpeg::make_jpeg(kSide, kSide, 3, false));
    write_bytes(in / "Rock" / "Rock_Normal.png", png8(3, 64));
    write_bytes(in / "Rock" / "Rock_Roughness.png", png8(1, 128));
    const long plain = validate_peak_kb(in);
    EXPECT_LT(plain, 256 * 1024) << "peak " << plain / 1024 << " MB; docs/rules.md states about 180 MB";
    write_bytes(in / "Rock" / "Rock_AO.jpg", mf::testjpeg::make_jpeg(kSide, kSide, 3, true));
    const long progressive = validate_peak_kb(in);
    EXPECT_LT(progressive, 512 * 1024) << "peak " << progressive / 1024 << " MB; docs/rules.md states about 400 MB";
    std::cout << "validate peak: " << plain / 1024 << " MB, with the progressive JPEG " << progressive / 1024
              << " MB\n";
    // The progressive file's coefficients are what it adds: most of 192 MiB, not a float copy.
    EXPECT_GT(progressive - plain, 96 * 1024) << plain / 1024 << " MB, then " << progressive / 1024 << " MB";
}

}  // namespace
}  // namespace mfh
