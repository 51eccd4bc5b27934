// Output files: content hashes and atomic writes (written aside, flushed, then renamed, so an
// interrupted run never leaves a half-written file under a final name).
#pragma once
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace mf {

std::string sha256_hex(std::span<const unsigned char> bytes);

// Writes `bytes` to `dest` atomically: a temporary file beside it (named by temp_marker()),
// fsync, rename over `dest`, fsync of the folder. Creates missing parent folders. When `dest`
// already holds exactly these bytes it is left untouched. False + `error` on failure.
bool write_file_atomic(const std::filesystem::path& dest, std::span<const unsigned char> bytes,
                       std::string& error);

// The substring every temporary file of ours carries; remove_stale_temps() deletes such files
// left by a killed run in `dir` (not recursive). Returns how many were removed.
inline constexpr const char* kTempMarker = ".matforge-tmp-";
int remove_stale_temps(const std::filesystem::path& dir);

// The whole file. Only a regular file is opened (a FIFO would block, a device never end): every
// reader of the project (JSON documents, sidecars) comes through here or through lib/image.
bool read_file(const std::filesystem::path& path, std::vector<unsigned char>& bytes, std::string& error);
// Why `path` must not be opened (broken link, folder, FIFO, socket, device), nullopt when it is a
// regular file (following symbolic links).
std::optional<std::string> not_a_regular_file(const std::filesystem::path& path);

}  // namespace mf
