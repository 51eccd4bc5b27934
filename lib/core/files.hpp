// Output files: content hashes and atomic writes (written aside, flushed, then renamed, so an
// interrupted run never leaves a half-written file under a final name).
#pragma once
#include <filesystem>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace mf {

std::string sha256_hex(std::span<const unsigned char> bytes);

// SHA-256 of bytes that arrive in pieces (a file streamed to disk): update() each, then hex().
class Sha256 {
public:
    Sha256();
    ~Sha256();
    Sha256(const Sha256&) = delete;
    Sha256& operator=(const Sha256&) = delete;
    void update(std::string_view bytes);
    std::string hex();  // of everything given so far; once

private:
    void* ctx_;  // EVP_MD_CTX (OpenSSL stays out of this header)
};

// Files too large to hold as one buffer (the manifest or library of 100,000 sets) are produced
// in pieces: `produce` is called once with a sink, hands it the file's bytes in order and returns
// false to abandon the write (nothing is renamed into place; `error` is left to the producer).
// The sink returns false when the disk refused a piece (the producer should stop).
using ByteSink = std::function<bool(std::string_view)>;
using ByteProducer = std::function<bool(const ByteSink&)>;

// Writes `bytes` to `dest` atomically: a temporary file beside it (named by temp_marker()),
// fsync, rename over `dest`, fsync of the folder. Creates missing parent folders. When `dest`
// already holds exactly these bytes it is left untouched. False + `error` on failure.
bool write_file_atomic(const std::filesystem::path& dest, std::span<const unsigned char> bytes, std::string& error);
// The same from a producer; the file is written even when it already holds these bytes.
bool write_file_atomic(const std::filesystem::path& dest, const ByteProducer& produce, std::string& error);

// The substring every temporary file of ours carries. A temporary is named exactly
// "." + <final name> + kTempMarker + <host> + "-" + <pid> + "-" + <counter>: temp_name() makes
// one, temp_owner() recognizes one (the writer's host and pid; nullopt for any other name, e.g. a
// user's "a.matforge-tmp-b"). The host is there because a farm's nodes write into one shared
// folder: a pid says whether a writer lives only on the host that wrote it. (Names of earlier
// releases, without a host, are read as this host's.)
inline constexpr const char* kTempMarker = ".matforge-tmp-";
struct TempOwner {
    std::string host;  // this_host() of the writer ("" in names of earlier releases)
    long pid = 0;
};
std::string temp_name(const std::string& final_name);
std::optional<TempOwner> temp_owner(std::string_view name);
// Who may ask whether a writer's pid lives: the host name, this boot (a pid of an earlier boot is
// no one), and the pid namespace (pods on one node, containers). The first 16 of the host name's
// [A-Za-z0-9._-] for people, "~", then 16 hex digits of SHA-256 of all three whole: Kubernetes'
// indexed-job pods share far longer prefixes than any cut of the name (issue 45: with 32 bytes,
// one shard's sweep deleted another pod's live temporary).
std::string host_identity(std::string_view host_name, std::string_view boot_id, std::string_view pid_namespace);
// host_identity() of this process (gethostname(), /proc/sys/kernel/random/boot_id,
// /proc/self/ns/pid): what temp_name() records.
const std::string& this_host();
// Removes, in `dir` (not recursive), our temporaries whose writer no longer exists: a killed
// run's, never a running one's (another set of this run, another shard) nor a user's file. A
// writer on this host is gone when its pid is; one on another host cannot be asked, so its
// temporaries are kept unless `other_hosts` (a folder only the caller writes, such as a set's
// folder its shard owns: a temporary there from another host is a lost node's). Returns how many
// were removed.
int remove_stale_temps(const std::filesystem::path& dir, bool other_hosts = false);

// Writes root/rel atomically (as write_file_atomic) without following a symbolic link anywhere
// below `root`: each folder of `rel` is created when missing and opened with O_NOFOLLOW, the
// temporary is created with O_EXCL in the final folder and renamed over the final name there (a
// link at the final name is replaced, never written through). `rel` is relative, without "..".
// `before_write(exists)` is called once the destination is known to need writing (absent, or
// holding other bytes: exists = true) and may refuse with a reason (then nothing is written and
// `error` is "rel: reason"). Identical bytes leave the file untouched. False + `error` on failure.
bool write_file_under(const std::filesystem::path& root, const std::string& rel, std::span<const unsigned char> bytes,
                      std::string& error, const std::function<std::string(bool exists)>& before_write = {});
// The same from a producer; the file is written even when it already holds these bytes.
bool write_file_under(const std::filesystem::path& root, const std::string& rel, const ByteProducer& produce,
                      std::string& error, const std::function<std::string(bool exists)>& before_write = {});

// An atomic write's first half: the bytes in a temporary beside the destination (their
// writeback started), for a caller that finishes the write elsewhere (OutputFolder's committer
// thread: fsyncs off the workers, one journal flush and one folder fsync a group). sync() then
// rename() finish it; the folder's fsync is the caller's. A staged file that is never renamed
// removes its temporary when destroyed. Move-only; not thread-safe.
class StagedFile {
public:
    // The bytes `produce` gives, as a temporary (temp_name) for `name` in folder `dir` (taken:
    // closed when the staged file goes). nullopt + `error` (naming `shown`) on failure.
    static std::optional<StagedFile> write(int dir, const std::string& name, const ByteProducer& produce,
                                           const std::string& shown, std::string& error);
    StagedFile(StagedFile&& o) noexcept;
    StagedFile& operator=(StagedFile&& o) noexcept;
    StagedFile(const StagedFile&) = delete;
    StagedFile& operator=(const StagedFile&) = delete;
    ~StagedFile();

    const std::string& shown() const { return shown_; }
    int folder() const { return dir_; }  // the destination's folder (for the caller's fsync)
    bool sync(std::string& error);       // fsync of the bytes; false: the temporary removed
    // Whether something is at the destination now (never follows a link).
    bool destination_exists() const;
    bool rename(std::string& error);  // over the destination; false: the temporary removed

private:
    StagedFile() = default;
    void release();
    int dir_ = -1, fd_ = -1;
    std::string temp_, name_, shown_;
};

// write_file_under up to a StagedFile: the same checks, folders, `before_write` and the
// identical-bytes case (true with `staged` empty: nothing to write). False + `error` on failure.
bool stage_file_under(const std::filesystem::path& root, const std::string& rel, std::span<const unsigned char> bytes,
                      std::optional<StagedFile>& staged, std::string& error,
                      const std::function<std::string(bool exists)>& before_write = {});

// An exclusive lock on a folder: flock(2) on the file `name` inside it, held until destroyed
// (then the file is removed). The lock file holds the holder's pid, so a second writer can say
// who is there: acquire() returns nullopt + `error` "another matforge (pid N) is writing in DIR"
// without waiting. A lock whose holder died is free again (the kernel drops it with the process).
class FolderLock {
public:
    static std::optional<FolderLock> acquire(const std::filesystem::path& dir, const std::string& name,
                                             std::string& error);
    FolderLock(FolderLock&& o) noexcept;
    FolderLock& operator=(FolderLock&&) = delete;
    FolderLock(const FolderLock&) = delete;
    FolderLock& operator=(const FolderLock&) = delete;
    ~FolderLock();

private:
    FolderLock(int fd, std::filesystem::path file) : fd_(fd), file_(std::move(file)) {}
    int fd_ = -1;
    std::filesystem::path file_;
};

// The whole file. Only a regular file is opened (a FIFO would block, a device never end): every
// reader of the project (JSON documents, sidecars) comes through here or through lib/image.
bool read_file(const std::filesystem::path& path, std::vector<unsigned char>& bytes, std::string& error);
// The same in 64 KB pieces handed to `sink` in order (a false from the sink stops the read with an
// error): a file is hashed or copied without holding it.
bool read_file(const std::filesystem::path& path, const ByteSink& sink, std::string& error);
// SHA-256 (hex) of the file's bytes, read in pieces. nullopt + `error` as read_file.
std::optional<std::string> sha256_of_file(const std::filesystem::path& path, std::string& error);
// Why `path` must not be opened (broken link, folder, FIFO, socket, device), nullopt when it is a
// regular file (following symbolic links).
std::optional<std::string> not_a_regular_file(const std::filesystem::path& path);

// `rel` normalized ('/'-separated) when it names a path inside a folder: relative, not empty,
// no ".." component. nullopt otherwise: a path a manifest, journal or record names that is not
// inside its folder (a crafted "../x" or "/etc/x") is never read, written or removed.
std::optional<std::string> path_inside(const std::string& rel);

// For `matforge --version`: the OpenSSL library behind sha256 (every output's and cache blob's).
std::string crypto_library_version();

}  // namespace mf
