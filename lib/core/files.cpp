#include "core/files.hpp"

#include <openssl/crypto.h>
#include <openssl/evp.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>
#include <utility>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace mf {
namespace fs = std::filesystem;

std::string sha256_hex(std::span<const unsigned char> bytes) {
    Sha256 h;
    h.update({reinterpret_cast<const char*>(bytes.data()), bytes.size()});
    return h.hex();
}

Sha256::Sha256() : ctx_(EVP_MD_CTX_new()) {
    if (!ctx_ || EVP_DigestInit_ex(static_cast<EVP_MD_CTX*>(ctx_), EVP_sha256(), nullptr) != 1) throw std::bad_alloc();
}

Sha256::~Sha256() { EVP_MD_CTX_free(static_cast<EVP_MD_CTX*>(ctx_)); }

void Sha256::update(std::string_view bytes) {
    EVP_DigestUpdate(static_cast<EVP_MD_CTX*>(ctx_), bytes.data(), bytes.size());
}

std::string Sha256::hex() {
    unsigned char digest[EVP_MAX_MD_SIZE];
    unsigned int len = 0;
    EVP_DigestFinal_ex(static_cast<EVP_MD_CTX*>(ctx_), digest, &len);
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
           (fs::is_directory(st) ? "a folder"
            : fs::is_fifo(st)    ? "a FIFO"
            : fs::is_socket(st)  ? "a socket"
                                 : "a device or special file") +
           ")";
}

bool read_file(const fs::path& path, const ByteSink& sink, std::string& error) {
    // Checked before opening (a FIFO blocks open() until a writer comes, a device may never end),
    // and again on the descriptor, opened non-blocking: a FIFO swapped in between cannot hang us.
    if (const auto why = not_a_regular_file(path)) {
        error = path.string() + ": " + *why;
        return false;
    }
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        error = path.string() + ": cannot open (" + std::strerror(errno) + ")";
        return false;
    }
    struct stat st {};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        ::close(fd);
        error = path.string() + ": not a regular file";
        return false;
    }
    char buf[1 << 16];
    for (;;) {
        const ssize_t n = ::read(fd, buf, sizeof buf);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
            const int e = errno;
            ::close(fd);
            error = path.string() + ": read error (" + std::strerror(e) + ")";
            return false;
        }
        if (n == 0) break;
        if (!sink({buf, static_cast<size_t>(n)})) {
            ::close(fd);
            error = path.string() + ": reading stopped";
            return false;
        }
    }
    ::close(fd);
    return true;
}

bool read_file(const fs::path& path, std::vector<unsigned char>& bytes, std::string& error) {
    bytes.clear();
    std::error_code ec;
    if (const auto size = fs::file_size(path, ec); !ec) bytes.reserve(static_cast<size_t>(size));
    return read_file(
        path,
        [&](std::string_view piece) {
            bytes.insert(bytes.end(), piece.begin(), piece.end());
            return true;
        },
        error);
}

std::optional<std::string> sha256_of_file(const fs::path& path, std::string& error) {
    Sha256 h;
    if (!read_file(
            path,
            [&](std::string_view piece) {
                h.update(piece);
                return true;
            },
            error))
        return std::nullopt;
    return h.hex();
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

std::string host_identity(std::string_view host_name, std::string_view boot_id, std::string_view pid_namespace) {
    std::string readable;
    for (const char c : host_name) {
        if (readable.size() == 16) break;
        if (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-') readable += c;
    }
    Sha256 sha;
    sha.update(host_name);
    sha.update(std::string_view("\n", 1));
    sha.update(boot_id);
    sha.update(std::string_view("\n", 1));
    sha.update(pid_namespace);
    return (readable.empty() ? std::string("host") : readable) + "~" + sha.hex().substr(0, 16);
}

const std::string& this_host() {
    static const std::string host = [] {
        char buf[256] = {};
        const std::string name = ::gethostname(buf, sizeof buf - 1) == 0 ? std::string(buf) : std::string();
        std::string boot;
        std::ifstream("/proc/sys/kernel/random/boot_id") >> boot;
        std::error_code ec;
        const std::string ns = std::filesystem::read_symlink("/proc/self/ns/pid", ec).string();
        return host_identity(name, boot, ns);
    }();
    return host;
}

std::string temp_name(const std::string& final_name) {
    static std::atomic<unsigned> counter{0};
    // Appended, not `"." + name`: GCC 12 at -O3 takes that prepend into a temporary string for
    // an overlapping memcpy (a false -Wrestrict, a known bug of that release).
    std::string name = ".";
    name.append(final_name).append(kTempMarker).append(this_host()).append("-");
    name.append(std::to_string(::getpid())).append("-").append(std::to_string(counter++));
    return name;
}

std::optional<TempOwner> temp_owner(std::string_view name) {
    const size_t at = name.rfind(kTempMarker);
    if (name.size() < 2 || name.front() != '.' || at == std::string_view::npos || at < 2) return std::nullopt;
    std::string_view tail = name.substr(at + std::strlen(kTempMarker));  // "[<host>-]<pid>-<counter>"
    auto digits = [](std::string_view d) {
        return !d.empty() && d.size() <= 18 &&
               std::all_of(d.begin(), d.end(), [](char c) { return c >= '0' && c <= '9'; });
    };
    // Read from the end: a host name may hold '-'.
    const size_t last = tail.rfind('-');
    if (last == std::string_view::npos || !digits(tail.substr(last + 1))) return std::nullopt;
    tail = tail.substr(0, last);  // "[<host>-]<pid>"
    const size_t dash = tail.rfind('-');
    const std::string_view pid = dash == std::string_view::npos ? tail : tail.substr(dash + 1);
    if (!digits(pid) || dash == 0) return std::nullopt;
    return TempOwner{dash == std::string_view::npos ? std::string() : std::string(tail.substr(0, dash)),
                     std::stol(std::string(pid))};
}

namespace {
bool process_alive(long pid) {
    if (pid <= 0 || pid > std::numeric_limits<pid_t>::max()) return false;
    return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;  // EPERM: alive, another user's
}

std::string errno_text(int e) {
    if (e == ENAMETOOLONG) return "the name is longer than the file system allows (255 bytes per name)";
    return std::strerror(e);
}

// Whether the regular file `name` in folder `dfd` holds exactly `bytes` (never follows a link).
bool same_content_at(int dfd, const char* name, std::span<const unsigned char> bytes) {
    const int fd = ::openat(dfd, name, O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) return false;
    struct stat st {};
    bool same = ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && static_cast<uint64_t>(st.st_size) == bytes.size();
    std::vector<unsigned char> buf(size_t{1} << 16);
    for (size_t done = 0; same && done < bytes.size();) {
        const ssize_t n = ::read(fd, buf.data(), std::min(buf.size(), bytes.size() - done));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            same = false;
            break;
        }
        same = std::equal(buf.begin(), buf.begin() + n, bytes.begin() + static_cast<std::ptrdiff_t>(done));
        done += static_cast<size_t>(n);
    }
    ::close(fd);
    return same;
}

// A folder descriptor closed on scope exit.
struct Fd {
    int fd = -1;
    explicit Fd(int f) : fd(f) {}
    ~Fd() {
        if (fd >= 0) ::close(fd);
    }
    Fd(const Fd&) = delete;
    Fd& operator=(const Fd&) = delete;
};

// StagedFile::write's file synced, renamed into place and the rename made durable (a folder
// fsync): the whole of an atomic write into folder `dir` (its descriptor goes to the staged file).
bool write_at(Fd& dir, const std::string& name, const ByteProducer& produce, const std::string& shown,
              std::string& error) {
    auto staged = StagedFile::write(std::exchange(dir.fd, -1), name, produce, shown, error);
    if (!staged || !staged->sync(error) || !staged->rename(error)) return false;
    ::fsync(staged->folder());  // make the rename itself durable
    return true;
}

ByteProducer producer_of(std::span<const unsigned char> bytes) {
    return [bytes](const ByteSink& sink) { return sink({reinterpret_cast<const char*>(bytes.data()), bytes.size()}); };
}
}  // namespace

std::optional<StagedFile> StagedFile::write(int dir, const std::string& name, const ByteProducer& produce,
                                            const std::string& shown, std::string& error) {
    StagedFile staged;
    staged.dir_ = dir;
    staged.name_ = name;
    staged.shown_ = shown;
    const std::string temp = temp_name(name);
    staged.fd_ = ::openat(dir, temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (staged.fd_ < 0) {
        error = shown + ": cannot write (" + errno_text(errno) + ")";
        return std::nullopt;  // closes `dir`; no temporary to remove
    }
    staged.temp_ = temp;
    const int fd = staged.fd_;
    // Small pieces (a JSON element) gather in a buffer; one write(2) each would cost more than them.
    constexpr size_t kBuffer = size_t{1} << 20;
    std::string buffer;
    int failed = 0;  // errno of the first failed write
    auto flush = [&] {
        if (!failed && !write_all(fd, {reinterpret_cast<const unsigned char*>(buffer.data()), buffer.size()}))
            failed = errno;
        buffer.clear();
        return !failed;
    };
    const ByteSink sink = [&](std::string_view piece) {
        if (buffer.size() + piece.size() > kBuffer && !flush()) return false;
        if (piece.size() < kBuffer) {
            buffer.append(piece);
            return true;
        }
        if (!write_all(fd, {reinterpret_cast<const unsigned char*>(piece.data()), piece.size()})) failed = errno;
        return !failed;
    };
    const bool produced = produce(sink);
    if (!produced || !flush()) {
        if (produced || failed) error = shown + ": cannot write (" + errno_text(failed ? failed : errno) + ")";
        else if (error.empty()) error = shown + ": not written";
        return std::nullopt;  // the temporary is removed
    }
#ifdef __linux__
    // Writeback starts now, without waiting: sync() then finds most of it done.
    ::sync_file_range(fd, 0, 0, SYNC_FILE_RANGE_WRITE);
#endif
    return staged;
}

StagedFile::StagedFile(StagedFile&& o) noexcept
    : dir_(std::exchange(o.dir_, -1)),
      fd_(std::exchange(o.fd_, -1)),
      temp_(std::exchange(o.temp_, {})),
      name_(std::move(o.name_)),
      shown_(std::move(o.shown_)) {}

StagedFile& StagedFile::operator=(StagedFile&& o) noexcept {
    if (this != &o) {
        release();
        dir_ = std::exchange(o.dir_, -1);
        fd_ = std::exchange(o.fd_, -1);
        temp_ = std::exchange(o.temp_, {});
        name_ = std::move(o.name_);
        shown_ = std::move(o.shown_);
    }
    return *this;
}

StagedFile::~StagedFile() { release(); }

void StagedFile::release() {
    if (fd_ >= 0) ::close(fd_);
    if (dir_ >= 0 && !temp_.empty()) ::unlinkat(dir_, temp_.c_str(), 0);
    if (dir_ >= 0) ::close(dir_);
    fd_ = dir_ = -1;
    temp_.clear();
}

bool StagedFile::sync(std::string& error) {
    const bool ok = fd_ >= 0 && ::fsync(fd_) == 0;
    const int e = fd_ >= 0 ? errno : EBADF;
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    if (!ok) {
        error = shown_ + ": cannot write (" + errno_text(e) + ")";
        release();
    }
    return ok;
}

bool StagedFile::destination_exists() const {
    struct stat st {};
    return dir_ >= 0 && ::fstatat(dir_, name_.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0;
}

bool StagedFile::rename(std::string& error) {
    if (dir_ < 0 || temp_.empty()) {
        error = shown_ + ": not written";
        return false;
    }
    if (::renameat(dir_, temp_.c_str(), dir_, name_.c_str()) != 0) {
        const int e = errno;
        error = shown_ + ": cannot rename into place (" +
                (e == EISDIR || e == ENOTEMPTY || e == EEXIST ? "a folder of that name is in the way" : errno_text(e)) +
                ")";
        release();
        return false;
    }
    temp_.clear();  // in place: nothing to remove
    return true;
}

namespace {
// write_file_atomic's steps; `same` (the bytes, when known in advance) leaves an identical file be.
bool write_atomic(const fs::path& dest, const ByteProducer& produce, const std::span<const unsigned char>* same,
                  std::string& error) {
    std::error_code ec;
    const fs::path dir = dest.parent_path().empty() ? fs::path(".") : dest.parent_path();
    fs::create_directories(dir, ec);
    if (ec) {
        error = dir.string() + ": cannot create folder (" + ec.message() + ")";
        return false;
    }
    if (same && same_content(dest, *same)) return true;
    Fd dfd(::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
    if (dfd.fd < 0) {
        error = dest.string() + ": cannot write (" + errno_text(errno) + ")";
        return false;
    }
    return write_at(dfd, dest.filename().string(), produce, dest.string(), error);
}

// write_file_under's steps; `same` as write_atomic's. With `staged`, the bytes are left in a
// temporary there (stage_file_under) and nothing is renamed.
bool write_under(const fs::path& root, const std::string& rel, const ByteProducer& produce,
                 const std::span<const unsigned char>* same, std::string& error,
                 const std::function<std::string(bool exists)>& before_write,
                 std::optional<StagedFile>* staged = nullptr) {
    const fs::path r = fs::path(rel).lexically_normal();
    std::vector<std::string> parts;
    for (const auto& p : r) parts.push_back(p.string());
    if (r.is_absolute() || parts.empty() || parts.front() == ".." || parts.back().empty() || parts.back() == "." ||
        std::find(parts.begin(), parts.end(), "..") != parts.end()) {
        error = rel + ": the path leaves the output folder";
        return false;
    }
    auto dfd = std::make_unique<Fd>(::open(root.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
    if (dfd->fd < 0) {
        error = root.string() + ": cannot open the output folder (" + errno_text(errno) + ")";
        return false;
    }
    std::string walked;
    for (size_t i = 0; i + 1 < parts.size(); ++i) {
        walked += (walked.empty() ? "" : "/") + parts[i];
        if (::mkdirat(dfd->fd, parts[i].c_str(), 0755) != 0 && errno != EEXIST) {
            error = rel + ": cannot create the folder " + walked + " (" + errno_text(errno) + ")";
            return false;
        }
        const int next = ::openat(dfd->fd, parts[i].c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
        if (next < 0) {
            const int e = errno;
            struct stat st {};
            const bool link = ::fstatat(dfd->fd, parts[i].c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 &&
                              S_ISLNK(st.st_mode);
            error = rel + ": " + walked +
                    (link ? " is a symbolic link; matforge never writes through links in the output folder (remove it)"
                     : e == ENOTDIR ? " is a file where a folder must be"
                                    : " cannot be opened (" + errno_text(e) + ")");
            return false;
        }
        dfd = std::make_unique<Fd>(next);
    }
    const std::string& name = parts.back();
    struct stat st {};
    bool exists = false;
    if (::fstatat(dfd->fd, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0) {
        if (S_ISDIR(st.st_mode)) {
            error = rel + ": cannot write (a folder of that name is in the way)";
            return false;
        }
        if (same && S_ISREG(st.st_mode) && same_content_at(dfd->fd, name.c_str(), *same)) return true;
        exists = true;
    } else if (errno != ENOENT) {
        error = rel + ": cannot write (" + errno_text(errno) + ")";
        return false;
    }
    if (before_write) {
        if (std::string why = before_write(exists); !why.empty()) {
            error = rel + ": " + why;
            return false;
        }
    }
    if (!staged) return write_at(*dfd, name, produce, rel, error);
    *staged = StagedFile::write(std::exchange(dfd->fd, -1), name, produce, rel, error);
    return staged->has_value();
}
}  // namespace

bool write_file_atomic(const fs::path& dest, std::span<const unsigned char> bytes, std::string& error) {
    return write_atomic(dest, producer_of(bytes), &bytes, error);
}

bool write_file_atomic(const fs::path& dest, const ByteProducer& produce, std::string& error) {
    return write_atomic(dest, produce, nullptr, error);
}

bool write_file_under(const fs::path& root, const std::string& rel, std::span<const unsigned char> bytes,
                      std::string& error, const std::function<std::string(bool exists)>& before_write) {
    return write_under(root, rel, producer_of(bytes), &bytes, error, before_write);
}

bool stage_file_under(const fs::path& root, const std::string& rel, std::span<const unsigned char> bytes,
                      std::optional<StagedFile>& staged, std::string& error,
                      const std::function<std::string(bool exists)>& before_write) {
    staged.reset();
    return write_under(root, rel, producer_of(bytes), &bytes, error, before_write, &staged);
}

bool write_file_under(const fs::path& root, const std::string& rel, const ByteProducer& produce, std::string& error,
                      const std::function<std::string(bool exists)>& before_write) {
    return write_under(root, rel, produce, nullptr, error, before_write);
}

int remove_stale_temps(const fs::path& dir, bool other_hosts) {
    std::error_code ec;
    int removed = 0;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const auto owner = temp_owner(it->path().filename().string());
        if (!owner) continue;
        const bool here = owner->host.empty() || owner->host == this_host();
        if (here ? process_alive(owner->pid) : !other_hosts) continue;
        std::error_code fec;
        if (!it->is_regular_file(fec) || it->is_symlink(fec)) continue;
        if (fs::remove(it->path(), fec)) ++removed;
    }
    return removed;
}

std::optional<FolderLock> FolderLock::acquire(const fs::path& dir, const std::string& name, std::string& error) {
    const fs::path file = dir / name;
    for (int attempt = 0; attempt < 100; ++attempt) {
        const int fd = ::open(file.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0644);
        if (fd < 0) {
            error = file.string() + ": cannot create the lock file (" + errno_text(errno) + ")";
            return std::nullopt;
        }
        if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
            const int e = errno;
            std::string pid(32, '\0');
            const ssize_t n = ::pread(fd, pid.data(), pid.size(), 0);
            pid.resize(n > 0 ? static_cast<size_t>(n) : 0);
            while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' ')) pid.pop_back();
            ::close(fd);
            if (e != EWOULDBLOCK) {
                error = file.string() + ": cannot lock (" + errno_text(e) + ")";
                return std::nullopt;
            }
            error = "another matforge" + (pid.empty() ? std::string() : " (pid " + pid + ")") + " is writing in " +
                    dir.string() + "; wait for it to finish or choose another output folder";
            return std::nullopt;
        }
        // The holder before us removes the file when it is done: a lock on a removed file locks
        // nothing, so the path must still name the file we locked.
        struct stat a {
        }, b{};
        if (::fstat(fd, &a) == 0 && ::lstat(file.c_str(), &b) == 0 && a.st_dev == b.st_dev && a.st_ino == b.st_ino) {
            const std::string pid = std::to_string(::getpid()) + "\n";
            if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, pid.data(), pid.size(), 0) < 0) {
                // The pid is only for the message of a second writer; the lock holds without it.
            }
            return FolderLock(fd, file);
        }
        ::close(fd);
    }
    error = file.string() + ": cannot take the lock (the file keeps being replaced)";
    return std::nullopt;
}

FolderLock::FolderLock(FolderLock&& o) noexcept : fd_(std::exchange(o.fd_, -1)), file_(std::move(o.file_)) {}

FolderLock::~FolderLock() {
    if (fd_ < 0) return;
    ::unlink(file_.c_str());  // while still holding it: a waiter that opened it retries (see acquire)
    ::close(fd_);
}

std::optional<std::string> path_inside(const std::string& rel) {
    const std::filesystem::path p = std::filesystem::path(rel).lexically_normal();
    if (rel.empty() || p.is_absolute() || p.empty() || p == ".") return std::nullopt;
    for (const auto& part : p)
        if (part == "..") return std::nullopt;
    return p.generic_string();
}

std::string crypto_library_version() { return OpenSSL_version(OPENSSL_VERSION); }

}  // namespace mf
