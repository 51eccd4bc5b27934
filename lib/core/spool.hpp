// Text a run produces one piece at a time and needs again at its end (the manifest's materials,
// the library's glTF arrays), kept in an unlinked temporary file instead of memory: a library of
// 100,000 sets would otherwise hold every entry until the last set is done.
//
// The file is created with O_TMPFILE (no name: nothing is left behind however the process ends,
// SIGKILL included); where the file system lacks O_TMPFILE, a named temporary is created and
// unlinked at once. Memory: 12 bytes of index a piece.
#pragma once
#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/files.hpp"

namespace mf {

class TextSpool {
public:
    // In `dir` (the output folder: the disk the run writes to anyway, not a small /tmp).
    // nullptr + `error` naming the folder.
    static std::unique_ptr<TextSpool> open(const std::filesystem::path& dir, std::string& error);
    ~TextSpool();
    TextSpool(const TextSpool&) = delete;
    TextSpool& operator=(const TextSpool&) = delete;

    // Thread-safe. The piece's number (0, 1, ... in the order of the calls), or nullopt + `error`
    // when the disk refused it.
    std::optional<uint32_t> append(std::string_view text, std::string& error);
    size_t size() const;
    // Piece `i` handed to `sink` (false + `error` when it cannot be read back, or false when the
    // sink refused it).
    bool copy(uint32_t i, const ByteSink& sink, std::string& error) const;
    std::optional<std::string> read(uint32_t i, std::string& error) const;

private:
    TextSpool(int fd, std::string dir) : fd_(fd), dir_(std::move(dir)) {}
    struct Piece {
        uint64_t offset;
        uint32_t size;
    };
    int fd_;
    std::string dir_;  // for messages
    mutable std::mutex mutex_;
    std::vector<Piece> pieces_;
    uint64_t end_ = 0;
};

}  // namespace mf
