// The output folder of one ingest run: who may write there (a lock), which files in it are
// matforge's (the previous manifest, a stopped run's journal), which paths this run's outputs
// claim, and the manifest swapped in at the end.
//
// A run, in order: open() takes `.<manifest>.lock` (flock; a second run refuses at once, naming
// the holder's pid) and refuses a manifest that matforge did not write (unless force); begin()
// writes the journal `.<manifest>.journal` (every file an earlier run of ours left) and removes
// the previous manifest, so a run stopped from then on (SIGKILL, power loss, SIGINT) leaves no
// manifest describing files it has replaced; write() refuses files that are not ours (unless
// force), never follows a link, and journals each file before it is renamed into place;
// finish() writes the new manifest, removes the outputs of earlier runs this one no longer
// produces (reported in notes), then the journal, then the lock. A run that does not finish
// leaves the journal: the next run reads it and knows those files are its own.
//
// The shards of one run (`ingest --shard I/N`) each write their own manifest, hence hold their
// own lock and journal, and may share one folder at once; every matforge manifest and journal
// in the folder counts when deciding whether a file is ours or stale.
#pragma once
#include <atomic>
#include <condition_variable>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "core/files.hpp"

namespace mf {

class OutputFolder {
public:
    struct Options {
        std::filesystem::path dir;
        std::string manifest_name = "manifest.json";
        bool force = false;  // --force: replace a foreign manifest and files matforge did not write
        // The preset this run writes, and --replace: a manifest of ours that lists another
        // preset's outputs is refused without it (usage), naming that preset: this run would
        // replace them and remove the rest (inside an engine project, every reference to them).
        std::string preset;
        bool replace = false;
    };
    // nullopt + `error`; `usage` true when the refusal is about the choice of folder (a foreign
    // manifest: exit 2), false when the folder cannot be used now (locked, unwritable: exit 1).
    static std::unique_ptr<OutputFolder> open(const Options& opt, std::string& error, bool& usage);
    ~OutputFolder();
    OutputFolder(const OutputFolder&) = delete;
    OutputFolder& operator=(const OutputFolder&) = delete;

    const std::filesystem::path& dir() const { return opt_.dir; }
    std::string lock_name() const { return "." + opt_.manifest_name + ".lock"; }
    std::string journal_name() const { return "." + opt_.manifest_name + ".journal"; }

    // Before the first output: the journal, then the previous manifest removed.
    bool begin(std::string& error);
    // Reserves `rel` (a file path relative to the folder) for `owner`: "" when free, else why not
    // (another output's file, or a folder of it, compared without case). Not thread-safe: claim
    // every path before the sets run, in set order, so the same inputs give the same verdicts.
    std::string claim(const std::string& rel, const std::string& owner);
    // write_file_under(dir, rel): a file that is there and is not ours is refused (unless force).
    // Thread-safe.
    bool write(const std::string& rel, std::span<const unsigned char> bytes, std::string& error);
    // The same for a file made as it is written (it is written even when it holds these bytes).
    bool write(const std::string& rel, const ByteProducer& produce, std::string& error);
    // Writes whose last steps run on the folder's committer thread, so that a worker does not
    // wait on the disk: write() checks and writes the bytes aside as write() above does (its
    // refusals and failures are immediate); the committer then fsyncs them, journals a group of
    // them in one flush, renames each into place (unless a file that is not ours appeared there
    // meanwhile) and fsyncs each folder once. wait() returns once every write of the batch is
    // done, with those that failed since the last wait(): path -> error. Thread-safe.
    class Batch {
    public:
        explicit Batch(OutputFolder& folder) : folder_(folder) {}
        ~Batch() { wait(); }
        Batch(const Batch&) = delete;
        Batch& operator=(const Batch&) = delete;
        bool write(const std::string& rel, std::span<const unsigned char> bytes, std::string& error);
        std::map<std::string, std::string> wait();

    private:
        friend class OutputFolder;
        void done(const std::string& rel, std::string error);  // from the committer
        OutputFolder& folder_;
        std::mutex mutex_;
        std::condition_variable cv_;
        int pending_ = 0;
        std::map<std::string, std::string> failed_;
    };

    // The new manifest (made as it is written), stale outputs removed (`produced`: every output
    // file of this run), the journal removed. `notes`: one line per file removed or kept. When
    // any write of this run failed (a full disk, a refusal), no earlier output is removed: each
    // is the last good copy of a file this run may have failed to replace, and the journal stays
    // so the next run still knows them as ours (a run that writes all it should removes them).
    bool finish(const ByteProducer& manifest, const std::set<std::string>& produced, std::vector<std::string>& notes,
                std::string& error);
    // Whether a write of this run failed (write(), a batch's stage or commit).
    bool write_failed() const { return write_failed_.load(); }

private:
    explicit OutputFolder(Options opt) : opt_(std::move(opt)) {}
    bool ours(const std::string& rel) const;
    // write()'s check and journal line before `rel` is replaced: "" or why not.
    std::string may_write(const std::string& rel, bool exists);
    // "wrote" lines for `rels` appended to the journal in one flush: "" or why not.
    std::string journal(const std::vector<std::string>& rels);
    // may_write's check alone: "" or why `rel` may not be replaced.
    std::string refusal(const std::string& rel, bool exists) const;
    // The committer: Batch::write's files, finished in groups (Batch above).
    struct Commit {
        std::string rel;
        StagedFile file;
        Batch* batch;
    };
    void enqueue(Commit c);
    void commit_loop();
    void commit_group(std::vector<Commit>& group);
    void stop_committer();  // after every queued commit
    // Paths other manifests and journals of ours in the folder list now (other shards).
    std::set<std::string> listed_elsewhere() const;

    Options opt_;
    std::optional<FolderLock> lock_;
    // Files earlier runs of ours left: path -> sha256 the manifest lists ("" from a journal).
    std::map<std::string, std::string> previous_;
    std::set<std::string> others_;                      // listed by the folder's other manifests and journals
    std::map<std::string, std::string> claimed_files_;  // lower-case path -> owner
    std::map<std::string, std::string> claimed_dirs_;   // lower-case folder -> owner
    std::mutex journal_mutex_;
    std::atomic<bool> write_failed_{false};
    int journal_fd_ = -1;
    std::mutex commit_mutex_;
    std::condition_variable commit_cv_;
    std::vector<Commit> commits_;  // queued for the committer
    bool stopping_ = false;
    std::thread committer_;  // started by the first Batch::write
};

}  // namespace mf
