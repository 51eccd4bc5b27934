#include "core/spool.hpp"

#include <cerrno>
#include <cstring>
#include <limits>

#include <fcntl.h>
#include <unistd.h>

namespace mf {

std::unique_ptr<TextSpool> TextSpool::open(const std::filesystem::path& dir, std::string& error) {
    int fd = ::open(dir.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
    if (fd < 0 && (errno == EOPNOTSUPP || errno == EISDIR || errno == EINVAL)) {  // no O_TMPFILE there
        std::string name = (dir / ".matforge-spool-XXXXXX").string();
        fd = ::mkostemp(name.data(), O_CLOEXEC);
        if (fd >= 0) ::unlink(name.c_str());
    }
    if (fd < 0) {
        error = dir.string() + ": cannot create a temporary file (" + std::strerror(errno) + ")";
        return nullptr;
    }
    return std::unique_ptr<TextSpool>(new TextSpool(fd, dir.string()));
}

TextSpool::~TextSpool() { ::close(fd_); }

std::optional<uint32_t> TextSpool::append(std::string_view text, std::string& error) {
    std::lock_guard lock(mutex_);
    if (text.size() > std::numeric_limits<uint32_t>::max() || pieces_.size() >= std::numeric_limits<uint32_t>::max()) {
        error = dir_ + ": a temporary file's piece is too large";
        return std::nullopt;
    }
    for (size_t done = 0; done < text.size();) {
        const ssize_t n = ::pwrite(fd_, text.data() + done, text.size() - done, static_cast<off_t>(end_ + done));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            error = dir_ + ": cannot write a temporary file (" + std::strerror(n < 0 ? errno : ENOSPC) + ")";
            return std::nullopt;
        }
        done += static_cast<size_t>(n);
    }
    pieces_.push_back({end_, static_cast<uint32_t>(text.size())});
    end_ += text.size();
    return static_cast<uint32_t>(pieces_.size() - 1);
}

size_t TextSpool::size() const {
    std::lock_guard lock(mutex_);
    return pieces_.size();
}

std::optional<std::string> TextSpool::read(uint32_t i, std::string& error) const {
    Piece p{};
    {
        std::lock_guard lock(mutex_);
        if (i >= pieces_.size()) {
            error = dir_ + ": no piece " + std::to_string(i) + " in a temporary file";
            return std::nullopt;
        }
        p = pieces_[i];
    }
    std::string text(p.size, '\0');
    for (size_t done = 0; done < text.size();) {  // pread: no shared file position, no lock
        const ssize_t n = ::pread(fd_, text.data() + done, text.size() - done, static_cast<off_t>(p.offset + done));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            error = dir_ + ": cannot read a temporary file back (" + std::strerror(n < 0 ? errno : EIO) + ")";
            return std::nullopt;
        }
        done += static_cast<size_t>(n);
    }
    return text;
}

bool TextSpool::copy(uint32_t i, const ByteSink& sink, std::string& error) const {
    const auto text = read(i, error);
    return text && sink(*text);
}

}  // namespace mf
