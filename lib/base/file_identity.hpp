// The one rule by which matforge remembers a fact about a file's bytes without reading them (a
// header read for the run: image.cpp; a digest across runs: store/cache.cpp), header-only.
#pragma once
#include <sys/stat.h>

#include <algorithm>
#include <ctime>
#include <filesystem>
#include <string>

namespace mf {

// How long a file must have been left alone before its times identify its bytes. File times
// advance by the kernel's coarse clock (milliseconds), so a file rewritten at the same size
// within one tick keeps them (git's "racily clean" rule, with a margin for clocks of other
// machines on a network file system).
inline constexpr std::time_t kSettledSeconds = 2;

// A regular file's identity as its file system states it (device, inode, size, modification and
// change times to the nanosecond: no one can set the change time back, and any write moves it),
// or empty: not a regular file, or changed within the last kSettledSeconds, whose bytes must be
// read. Equal identities, equal bytes.
inline std::string settled_identity(const std::filesystem::path& file) {
    struct stat st {};
    if (::stat(file.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return {};
    if (std::time(nullptr) - std::max(st.st_mtim.tv_sec, st.st_ctim.tv_sec) < kSettledSeconds) return {};
    return std::to_string(st.st_dev) + ' ' + std::to_string(st.st_ino) + ' ' + std::to_string(st.st_size) + ' ' +
           std::to_string(st.st_mtim.tv_sec) + '.' + std::to_string(st.st_mtim.tv_nsec) + ' ' +
           std::to_string(st.st_ctim.tv_sec) + '.' + std::to_string(st.st_ctim.tv_nsec);
}

}  // namespace mf
