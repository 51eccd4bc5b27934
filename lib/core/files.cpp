#include "core/files.hpp"

#include <openssl/evp.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>

#include <fcntl.h>
#include <unistd.h>

namespace mf {
namespace fs = std::filesystem;

std::string sha256_hex(std::span<const unsigned char> bytes) {
    unsigned char digest[EVP_MAX_MD_SIZE];
    unsigned int len = 0;
    EVP_Digest(bytes.data(), bytes.size(), digest, &len, EVP_sha256(), nullptr);
    static constexpr char kHex[] = "0123456789abcdef";
    std::string out;
    out.reserve(len * 2);
    for (unsigned i = 0; i < len; ++i) {
        out += kHex[digest[i] >> 4];
        out += kHex[digest[i] & 15];
    }
    return out;
}

std::optional<std::string> not_a_regular_file(const fs::path& path) {
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (ec) {
        std::error_code lec;
        const bool link = fs::is_symlink(fs::symlink_status(path, lec));
        return std::string(link ? "broken symbolic link" : "cannot open") + " (" + ec.message() + ")";
    }
    if (fs::is_regular_file(st)) return std::nullopt;
    return std::string("not a regular file (") +
           (fs::is_directory(st) ? "a folder" : fs::is_fifo(st) ? "a FIFO" : fs::is_socket(st) ? "a socket" : "a device or special file") +
           ")";
}

bool read_file(const fs::path& path, std::vector<unsigned char>& bytes, std::string& error) {
    // Checked before opening: opening a FIFO blocks until a writer comes, a device may never end.
    if (const auto why = not_a_regular_file(path)) {
        error = path.string() + ": " + *why;
        return false;
    }
    std::ifstream f(path, std::ios::binary);
    if (!f) {
        error = path.string() + ": cannot open (" + std::strerror(errno) + ")";
        return false;
    }
    bytes.assign(std::istreambuf_iterator<char>(f), {});
    if (f.bad()) {
        error = path.string() + ": read error";
        return false;
    }
    return true;
}

namespace {
bool same_content(const fs::path& dest, std::span<const unsigned char> bytes) {
    std::error_code ec;
    if (!fs::is_regular_file(dest, ec) || fs::file_size(dest, ec) != bytes.size()) return false;
    std::vector<unsigned char> old;
    std::string ignored;
    return read_file(dest, old, ignored) && std::equal(old.begin(), old.end(), bytes.begin(), bytes.end());
}

bool write_all(int fd, std::span<const unsigned char> bytes) {
    size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0) {
            if (errno == EINTR) continue;
            return false;
        }
        done += static_cast<size_t>(n);
    }
    return true;
}
}  // namespace

bool write_file_atomic(const fs::path& dest, std::span<const unsigned char> bytes, std::string& error) {
    std::error_code ec;
    const fs::path dir = dest.parent_path().empty() ? fs::path(".") : dest.parent_path();
    fs::create_directories(dir, ec);
    if (ec) {
        error = dir.string() + ": cannot create folder (" + ec.message() + ")";
        return false;
    }
    if (same_content(dest, bytes)) return true;
    static std::atomic<unsigned> counter{0};
    // Appended, not `"." + name`: GCC 12 at -O3 takes that prepend into a temporary string for
    // an overlapping memcpy (a false -Wrestrict, a known bug of that release).
    std::string name = ".";
    name.append(dest.filename().string()).append(kTempMarker);
    name.append(std::to_string(::getpid())).append("-").append(std::to_string(counter++));
    const fs::path tmp = dir / name;
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) {
        error = dest.string() + ": cannot write (" + std::strerror(errno) + ")";
        return false;
    }
    const bool ok = write_all(fd, bytes) && ::fsync(fd) == 0;
    const int saved = errno;
    ::close(fd);
    if (!ok) {
        fs::remove(tmp, ec);
        error = dest.string() + ": cannot write (" + std::strerror(saved) + ")";
        return false;
    }
    if (::rename(tmp.c_str(), dest.c_str()) != 0) {
        const int e = errno;
        fs::remove(tmp, ec);
        error = dest.string() + ": cannot rename into place (" + std::strerror(e) + ")";
        return false;
    }
    // Make the rename itself durable.
    const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dfd >= 0) {
        ::fsync(dfd);
        ::close(dfd);
    }
    return true;
}

int remove_stale_temps(const fs::path& dir) {
    std::error_code ec;
    int removed = 0;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (name.find(kTempMarker) != std::string::npos && it->is_regular_file(ec)) {
            if (fs::remove(it->path(), ec)) ++removed;
        }
    }
    return removed;
}

}  // namespace mf
