// A content-addressed cache of ingest results (the design of Bazel's remote cache and Unreal's
// derived-data cache): outputs are stored by their SHA-256 (`cas/<aa>/<sha256>`), and an action
// record (`ac/<aa>/<id>.json`) maps a set's action key (process/work.hpp), material name and the
// build of matforge that computed it (core/version.hpp code_identity: its build-id) to its
// manifest entry and the outputs it lists. An unchanged set re-ingested by the same build is
// restored from the cache: no decoding, no encoding, the same bytes.
//
// Conventions of this module (decided once here):
//  - safe for several processes and machines at once (a shared file system): every file is
//    written aside and renamed into place; a reader trusts nothing it has not hash-checked;
//  - a corrupt or truncated blob is never used: the set is recomputed and the caller told;
//  - the cache never fails an ingest: an unwritable cache (a full disk) turns itself off with
//    one warning;
//  - file digests are remembered by (device, inode, size, mtime, ctime) in `stat/`: a changed
//    file always changes its ctime, so it is always read and hashed again;
//  - eviction is least recently used: a record's mtime is its last use; prune() keeps the most
//    recent records within the size limit and the blobs they name;
//  - a record is its build's own (two builds of one version may write other bytes: a
//    developer's tree, a patched package); the build is named here, not in the action key,
//    which manifests record and the CLI and the Python extension (two objects, two build-ids)
//    must write alike. Blobs are shared: equal bytes, one blob;
//  - a cache is known by its marker (`version`, "matforge cache 1"): nothing is written into or
//    removed from a folder without it (a user's folder named by mistake), and prune() removes
//    only files named as this cache names them (`ac/<aa>/<sha256>.json`, `cas/<aa>/<sha256>`).
#pragma once
#include <cstdint>
#include <filesystem>
#include <functional>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "image/image.hpp"
#include "manifest/manifest.hpp"

namespace mf {

class Cache {
public:
    // ingest's: the cache in `dir`, made there when `dir` does not exist or is an empty folder,
    // whose records are those of the build `code` names (code_identity's form; by default this
    // process's: tests name another build). nullopt + `error` when `dir` is a folder that holds
    // something but no cache marker (it is not a cache: nothing is written there), cannot be
    // created or written, or the running build cannot be named.
    static std::optional<Cache> create(const std::filesystem::path& dir, std::string& error,
                                       std::optional<std::string> code = std::nullopt);
    // `matforge cache`'s: the cache that is in `dir` already, for stats() and prune() (every
    // build's records); nothing is created, restore() misses and store() refuses. nullopt +
    // `error` when `dir` holds no cache marker.
    static std::optional<Cache> open(const std::filesystem::path& dir, std::string& error);
    // "" when `dir` may be a cache (absent, an empty folder, or a cache), else why not.
    static std::string unusable(const std::filesystem::path& dir);

    const std::filesystem::path& dir() const { return dir_; }

    // The SHA-256 of an input file (hex): remembered by its stat for files on disk, computed for
    // zip entries. nullopt + `error` when it cannot be read.
    std::optional<std::string> digest(const InputFile& in, std::string& error) const;

    struct Hit {
        manifest::Material entry;  // source and archive are the caller's (they depend on -o)
    };
    // The record of (key, name) with every output restored under `out_dir` (a file already
    // holding the recorded bytes is left alone). nullopt on a miss; a blob that fails its hash
    // check is removed and reported in `corrupt` (the set must be recomputed).
    // Files are written through `write` (relative to `out_dir`: the run's output folder, which
    // journals them and refuses files that are not ours).
    using Write = std::function<bool(const std::string& rel, std::span<const unsigned char> bytes, std::string& error)>;
    std::optional<Hit> restore(const std::string& key, const std::string& name, const std::filesystem::path& out_dir,
                               const Write& write, std::vector<std::string>& corrupt) const;

    // Stores a computed set: each output and material file (read back from `out_dir`,
    // hash-checked against the entry) as a blob (a hard link to the output where the file system
    // allows: no second copy on disk; outputs are replaced by rename, never rewritten in place,
    // so the blob keeps its bytes), then the record. False + `error` when the cache cannot be written.
    bool store(const std::string& key, const manifest::Material& entry, const std::filesystem::path& out_dir,
               std::string& error) const;

    struct Stats {
        uint64_t records = 0, blobs = 0, blob_bytes = 0, other_bytes = 0;
        // prune(): files it had to remove and could not (a read-only cache), and the first error.
        uint64_t failed = 0;
        std::string error;
    };
    Stats stats() const;
    // Least recently used records go first until the blobs of the rest fit in `max_bytes`;
    // blobs no kept record names are removed (those younger than `grace` are left: a writer may
    // be about to name them). Returns what was removed, counting only what is gone.
    Stats prune(uint64_t max_bytes, std::chrono::seconds grace = std::chrono::seconds(60)) const;

private:
    Cache(std::filesystem::path dir, std::string code) : dir_(std::move(dir)), code_(std::move(code)) {}
    std::filesystem::path blob_path(const std::string& sha) const;
    std::filesystem::path record_path(const std::string& key, const std::string& name) const;
    std::filesystem::path stat_path(const std::filesystem::path& file) const;
    std::filesystem::path dir_;
    std::string code_;  // the build whose records restore() and store() use; "" for open()'s
};

}  // namespace mf
