// lib/image remembers a file's header for the run (while a ReadScope is alive) by its identity
// and change times (image.cpp, file_key): an unchanged file is not opened again, a changed one is
// read anew even when its size and modification time are kept, a file changed within the last
// two seconds is never remembered (its times may not have moved), and nothing is remembered once
// the run's last scope is gone.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "image/image.hpp"
#include "test_dirs.hpp"

namespace {
namespace fs = std::filesystem;

std::vector<unsigned char> png(int w, int h) {
    std::vector<unsigned char> bytes;
    std::string error;
    EXPECT_TRUE(mf::encode_image(mf::Image(w, h, 3, 0.5f), {mf::FileFormat::png, 8}, bytes, error)) << error;
    return bytes;
}

// Written in place (the same inode), as an editor saving over the file would.
void overwrite(const fs::path& file, const std::vector<unsigned char>& bytes) {
    std::ofstream(file, std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

int width_of(const fs::path& file) {
    mf::InputFile in;
    in.display = file.filename().string();
    in.path = file;
    std::string error;
    const auto info = mf::read_info(in, error);
    EXPECT_TRUE(info) << error;
    return info ? info->width : -1;
}

// Bytes this process has read through read(2) and its kind (/proc/self/io rchar): a header
// served from the memo reads none of the file.
long long bytes_read() {
    std::ifstream io("/proc/self/io");
    std::string key;
    long long value = 0;
    while (io >> key >> value)
        if (key == "rchar:") return value;
    ADD_FAILURE() << "no rchar in /proc/self/io";
    return -1;
}

TEST(HeaderMemo, HeadersAreRememberedWhileARunIsOpenAndForgottenAfter) {
    const fs::path dir = mf::testdirs::fresh("matforge-header-scope-", "png");
    const fs::path file = dir / "Map_Color.png";
    overwrite(file, png(16, 8));
    std::this_thread::sleep_for(std::chrono::milliseconds(2100));  // settled: may be remembered
    // What a read of the header adds to the bytes read, less what reading /proc/self/io costs
    // (which varies by a byte or two as its numbers gain digits). Opening the PNG reads at least
    // its signature and IHDR (33 bytes); a remembered header reads nothing.
    const long long io0 = bytes_read();
    const long long itself = bytes_read() - io0;
    auto read_costs = [&] {
        const long long before = bytes_read();
        EXPECT_EQ(width_of(file), 16);
        return bytes_read() - before - itself;
    };
    constexpr long long kSlack = 8, kHeader = 33;
    EXPECT_GE(read_costs(), kHeader) << "no run open: read";
    EXPECT_GE(read_costs(), kHeader) << "no run open: read again, nothing remembered";
    {
        const mf::ReadScope run;
        EXPECT_GE(read_costs(), kHeader) << "first read of the run";
        EXPECT_LE(read_costs(), kSlack) << "remembered for the run";
        const mf::ReadScope copy = run;  // a batch moved or copied keeps the run open
        EXPECT_LE(read_costs(), kSlack);
    }
    EXPECT_GE(read_costs(), kHeader) << "the run is over: its memo was dropped";
    const mf::ReadScope next;
    EXPECT_GE(read_costs(), kHeader) << "a new run starts with nothing remembered";
}

TEST(HeaderMemo, AFileChangedInPlaceIsReadAgainEvenWithItsSizeAndMtimeKept) {
    const mf::ReadScope run;
    const fs::path dir = mf::testdirs::fresh("matforge-header-memo-", "png");
    const fs::path file = dir / "Map_Color.png";
    auto wide = png(8, 4), tall = png(4, 8);
    // One length for both: bytes after IEND, which decoders ignore.
    const size_t n = std::max(wide.size(), tall.size());
    wide.resize(n);
    tall.resize(n);
    overwrite(file, wide);
    EXPECT_EQ(width_of(file), 8);  // fresh: read, not remembered
    overwrite(file, tall);
    EXPECT_EQ(width_of(file), 4);
    // Old enough to be remembered (a file changed in the last two seconds never is).
    std::this_thread::sleep_for(std::chrono::milliseconds(2100));
    EXPECT_EQ(width_of(file), 4);
    EXPECT_EQ(width_of(file), 4);  // remembered
    // The same inode, size and modification time, other pixels: only the change time, which no
    // one can set back, tells it apart.
    const auto mtime = fs::last_write_time(file);
    overwrite(file, wide);
    fs::last_write_time(file, mtime);
    EXPECT_EQ(width_of(file), 8);
}

}  // namespace
