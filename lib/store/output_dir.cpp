#include "store/output_dir.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <set>
#include <utility>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/json.hpp"
#include "core/text.hpp"

namespace mf {
namespace fs = std::filesystem;
namespace {

constexpr const char* kJournalHeader = "matforge journal 1";

bool is_ours(const nlohmann::json& j) {
    return j.is_object() && j.contains("generator") && j["generator"].is_string() &&
           j["generator"].get<std::string>().rfind("matforge", 0) == 0;
}

// [{file, sha256}, ...] of a manifest (leniently: a later version's manifest too) into `out`.
void add_files(const nlohmann::json& list, std::map<std::string, std::string>& out) {
    if (!list.is_array()) return;
    for (const auto& o : list) {
        if (!o.is_object() || !o.contains("file") || !o["file"].is_string()) continue;
        const auto rel = path_inside(o["file"].get<std::string>());
        if (!rel) continue;
        out[*rel] = o.contains("sha256") && o["sha256"].is_string() ? o["sha256"].get<std::string>() : "";
    }
}

// A manifest file read one material at a time (core/json: a manifest of 100,000 sets is never a
// tree in memory): its head (materials empty), and when matforge wrote it, the files it lists
// (outputs, material files, the library: file -> sha256) added to `out`. nullopt + `why`.
std::optional<nlohmann::json> read_manifest_files(const fs::path& file, std::map<std::string, std::string>& out,
                                                  std::string& why) {
    std::map<std::string, std::string> found;
    auto j = read_json_file(
        file, "materials",
        [&](nlohmann::json& m, std::string&) {
            if (m.is_object()) {
                if (m.contains("outputs")) add_files(m["outputs"], found);
                if (m.contains("material_files")) add_files(m["material_files"], found);
            }
            return true;
        },
        why);
    if (j && is_ours(*j)) {
        if (j->contains("library")) add_files((*j)["library"], found);
        out.merge(found);
    }
    return j;
}

// A journal's files: "prev" lines keep the sha256 the manifest listed, "wrote" lines (files a
// stopped run replaced) have none. A torn last line (a crash mid-append) is skipped.
void journal_files(const fs::path& file, std::map<std::string, std::string>& out) {
    std::vector<unsigned char> bytes;
    std::string error;
    if (!read_file(file, bytes, error)) return;
    const std::string text(bytes.begin(), bytes.end());
    if (text.rfind(kJournalHeader, 0) != 0) return;
    std::set<std::string> rewritten;
    size_t start = 0;
    while (start < text.size()) {
        size_t end = text.find('\n', start);
        if (end == std::string::npos) break;  // no newline: torn
        const auto line = parse_json(std::string_view(text).substr(start, end - start), file.string(), error);
        start = end + 1;
        if (!line || !line->is_object()) continue;
        for (const char* key : {"prev", "wrote"}) {
            if (!line->contains(key) || !(*line)[key].is_string()) continue;
            const auto rel = path_inside((*line)[key].get<std::string>());
            if (!rel) continue;
            if (std::string(key) == "wrote") rewritten.insert(*rel);
            const std::string sha = line->contains("sha256") && (*line)["sha256"].is_string()
                                        ? (*line)["sha256"].get<std::string>()
                                        : "";
            out.emplace(*rel, sha);
        }
    }
    for (const auto& r : rewritten) out[r] = "";  // replaced since the manifest listed it
}

// Opens the folder holding `rel` under `root` without following links; -1 when any part of the
// way is missing or a link. `leaf` gets the last component.
int open_parent(const fs::path& root, const std::string& rel, std::string& leaf,
                std::vector<std::string>* parts_out = nullptr) {
    std::vector<std::string> parts;
    for (const auto& p : fs::path(rel)) parts.push_back(p.string());
    if (parts.empty()) return -1;
    int fd = ::open(root.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    for (size_t i = 0; fd >= 0 && i + 1 < parts.size(); ++i) {
        const int next = ::openat(fd, parts[i].c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
        ::close(fd);
        fd = next;
    }
    leaf = parts.back();
    if (parts_out) *parts_out = std::move(parts);
    return fd;
}

// sha256 of the regular file `leaf` in `dfd` (never through a link); nullopt when not one.
std::optional<std::string> file_sha(int dfd, const std::string& leaf) {
    const int fd = ::openat(dfd, leaf.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) return std::nullopt;
    struct stat st {};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        ::close(fd);
        return std::nullopt;
    }
    Sha256 sha;  // in pieces: an 8K output is not held to be hashed
    std::vector<char> buf(size_t{1} << 16);
    for (ssize_t n; (n = ::read(fd, buf.data(), buf.size())) > 0;) sha.update({buf.data(), static_cast<size_t>(n)});
    ::close(fd);
    return sha.hex();
}

}  // namespace

std::unique_ptr<OutputFolder> OutputFolder::open(const Options& opt, std::string& error, bool& usage) {
    usage = false;
    std::unique_ptr<OutputFolder> f(new OutputFolder(opt));
    auto lock = FolderLock::acquire(opt.dir, f->lock_name(), error);
    if (!lock) return nullptr;
    f->lock_.emplace(std::move(*lock));
    const fs::path manifest = opt.dir / opt.manifest_name;
    std::error_code ec;
    const fs::file_status st = fs::symlink_status(manifest, ec);
    if (fs::exists(st)) {
        std::string why;
        std::optional<nlohmann::json> j;
        if (fs::is_symlink(st)) why = "it is a symbolic link";
        else if (!fs::is_regular_file(st)) why = "it is not a regular file";
        else if (!(j = read_manifest_files(manifest, f->previous_, why))) why = "it is not a manifest: " + why;
        else if (!is_ours(*j))
            why = std::string("its generator is ") +
                  (j->is_object() && j->contains("generator") ? (*j)["generator"].dump() : std::string("not stated"));
        if (!why.empty() && !opt.force) {
            error = manifest.string() + " was not written by matforge (" + why +
                    "); it is not replaced: choose another output folder, or pass --force to replace it";
            usage = true;
            return nullptr;
        }
        const std::string earlier = why.empty() && j->is_object() && j->contains("preset") && (*j)["preset"].is_string()
                                        ? (*j)["preset"].get<std::string>()
                                        : std::string();
        if (!earlier.empty() && !opt.preset.empty() && earlier != opt.preset && !opt.replace) {
            error = opt.dir.string() + " holds the outputs of preset '" + earlier + "' (" + opt.manifest_name +
                    " says so); writing preset '" + opt.preset +
                    "' there would replace them and remove the rest (an engine project would lose every "
                    "reference to them): choose another output folder, or pass --replace to replace them";
            usage = true;
            return nullptr;
        }
    }
    journal_files(opt.dir / f->journal_name(), f->previous_);
    f->others_ = f->listed_elsewhere();
    return f;
}

std::set<std::string> OutputFolder::listed_elsewhere() const {
    std::map<std::string, std::string> files;
    std::error_code ec;
    for (fs::directory_iterator it(opt_.dir, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string n = it->path().filename().string();
        if (n == opt_.manifest_name || n == journal_name()) continue;
        std::error_code fec;
        if (!it->is_regular_file(fec) || it->is_symlink(fec)) continue;
        if (n.rfind("manifest", 0) == 0 && it->path().extension() == ".json") {
            std::string err;
            read_manifest_files(it->path(), files, err);
        } else if (n.size() > 8 && n.front() == '.' && n.substr(n.size() - 8) == ".journal") {
            journal_files(it->path(), files);
        }
    }
    std::set<std::string> out;
    for (const auto& [rel, sha] : files) out.insert(rel);
    return out;
}

OutputFolder::~OutputFolder() {
    stop_committer();
    if (journal_fd_ >= 0) ::close(journal_fd_);
}

bool OutputFolder::ours(const std::string& rel) const { return previous_.count(rel) > 0 || others_.count(rel) > 0; }

bool OutputFolder::begin(std::string& error) {
    std::string text = std::string(kJournalHeader) + "\n";  // then one JSON object per line
    for (const auto& [rel, sha] : previous_)
        text += nlohmann::json{{"prev", rel}, {"sha256", sha}}.dump(-1, ' ', false,
                                                                    nlohmann::json::error_handler_t::replace) +
                "\n";
    if (!write_file_under(opt_.dir, journal_name(),
                          std::span(reinterpret_cast<const unsigned char*>(text.data()), text.size()), error))
        return false;
    journal_fd_ = ::open((opt_.dir / journal_name()).c_str(), O_WRONLY | O_APPEND | O_NOFOLLOW | O_CLOEXEC);
    if (journal_fd_ < 0) {
        error = (opt_.dir / journal_name()).string() + ": cannot open (" + std::strerror(errno) + ")";
        return false;
    }
    // From here on no manifest describes the folder until finish() writes the new one.
    const fs::path manifest = opt_.dir / opt_.manifest_name;
    if (::unlink(manifest.c_str()) != 0 && errno != ENOENT) {
        error = manifest.string() + ": cannot remove the previous manifest (" + std::strerror(errno) + ")";
        return false;
    }
    if (const int dfd = ::open(opt_.dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC); dfd >= 0) {
        ::fsync(dfd);
        ::close(dfd);
    }
    return true;
}

std::string OutputFolder::claim(const std::string& rel, const std::string& owner) {
    const auto r = path_inside(rel);
    if (!r) return "the path leaves the output folder";
    const std::string key = ascii_lower(*r);
    auto held = [&](const std::string& by) {
        return by == owner ? std::string("another output of this material") : "material '" + by + "'";
    };
    if (const auto it = claimed_files_.find(key); it != claimed_files_.end())
        return "the file is also an output of " + held(it->second) +
               " (output names differ only in letter case, or a pattern leaves them equal)";
    if (const auto it = claimed_dirs_.find(key); it != claimed_dirs_.end())
        return "a folder of that name holds outputs of " + held(it->second);
    std::vector<std::string> ancestors;
    for (fs::path p = fs::path(key).parent_path(); !p.empty(); p = p.parent_path())
        ancestors.push_back(p.generic_string());
    for (const auto& a : ancestors)
        if (const auto it = claimed_files_.find(a); it != claimed_files_.end())
            return "its folder " + a + " is the file " +
                   (it->second.empty() ? std::string("of matforge's own") : "of " + held(it->second));
    claimed_files_.emplace(key, owner);
    for (const auto& a : ancestors) claimed_dirs_.emplace(a, owner);
    return {};
}

bool OutputFolder::write(const std::string& rel, std::span<const unsigned char> bytes, std::string& error) {
    const bool ok = write_file_under(opt_.dir, rel, bytes, error, [&](bool exists) { return may_write(rel, exists); });
    if (!ok) write_failed_ = true;
    return ok;
}

bool OutputFolder::write(const std::string& rel, const ByteProducer& produce, std::string& error) {
    const bool ok = write_file_under(opt_.dir, rel, produce, error,
                                     [&](bool exists) { return may_write(rel, exists); });
    if (!ok) write_failed_ = true;
    return ok;
}

std::string OutputFolder::refusal(const std::string& rel, bool exists) const {
    if (exists && !opt_.force && !ours(rel))
        return "a file matforge did not write is in the way (no earlier manifest of this folder lists it); "
               "move it away, or pass --force to replace it";
    return {};
}

std::string OutputFolder::journal(const std::vector<std::string>& rels) {
    std::string lines;
    for (const auto& rel : rels)
        lines += nlohmann::json{{"wrote", rel}}.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
    if (lines.empty()) return {};
    std::lock_guard lock(journal_mutex_);
    if (journal_fd_ >= 0 && (::write(journal_fd_, lines.data(), lines.size()) != static_cast<ssize_t>(lines.size()) ||
                             ::fdatasync(journal_fd_) != 0))
        return std::string("cannot record it in the journal (") + std::strerror(errno) + ")";
    return {};
}

std::string OutputFolder::may_write(const std::string& rel, bool exists) {
    if (std::string why = refusal(rel, exists); !why.empty()) return why;
    // Journaled before it is replaced: a run stopped after the rename still knows the file is ours.
    return journal({rel});
}

bool OutputFolder::Batch::write(const std::string& rel, std::span<const unsigned char> bytes, std::string& error) {
    std::optional<StagedFile> staged;
    if (!stage_file_under(folder_.opt_.dir, rel, bytes, staged, error,
                          [&](bool exists) { return folder_.refusal(rel, exists); })) {
        folder_.write_failed_ = true;
        return false;
    }
    if (!staged) return true;  // it already holds these bytes
    {
        std::lock_guard lock(mutex_);
        ++pending_;
    }
    folder_.enqueue({rel, std::move(*staged), this});
    return true;
}

std::map<std::string, std::string> OutputFolder::Batch::wait() {
    std::unique_lock lock(mutex_);
    cv_.wait(lock, [this] { return pending_ == 0; });
    return std::exchange(failed_, {});
}

void OutputFolder::Batch::done(const std::string& rel, std::string error) {
    std::lock_guard lock(mutex_);
    if (!error.empty()) {
        folder_.write_failed_ = true;
        failed_.emplace(rel, std::move(error));
    }
    --pending_;
    cv_.notify_all();
}

void OutputFolder::enqueue(Commit c) {
    std::lock_guard lock(commit_mutex_);
    if (!committer_.joinable()) committer_ = std::thread(&OutputFolder::commit_loop, this);
    commits_.push_back(std::move(c));
    commit_cv_.notify_one();
}

void OutputFolder::commit_loop() {
    for (;;) {
        std::vector<Commit> group;
        {
            std::unique_lock lock(commit_mutex_);
            commit_cv_.wait(lock, [this] { return stopping_ || !commits_.empty(); });
            if (commits_.empty()) return;  // stopping, and nothing left
            group.swap(commits_);
        }
        commit_group(group);
    }
}

// One group of staged files into place, in the order an atomic write takes: the bytes on disk,
// the journal line (one flush for the group), the rename, the folder.
void OutputFolder::commit_group(std::vector<Commit>& group) {
    std::vector<std::string> errors(group.size());
    for (size_t i = 0; i < group.size(); ++i) {
        if (!group[i].file.sync(errors[i])) continue;
        // The check write() made, again just before the rename: a file that is not ours and
        // appeared since the bytes were staged is never replaced.
        if (group[i].file.destination_exists() && !refusal(group[i].rel, true).empty())
            errors[i] = group[i].rel + ": a file matforge did not write appeared there while it was being written; "
                                       "not replaced";
    }
    std::vector<std::string> to_journal;
    for (size_t i = 0; i < group.size(); ++i)
        if (errors[i].empty()) to_journal.push_back(group[i].rel);
    if (const std::string why = journal(to_journal); !why.empty())
        for (size_t i = 0; i < group.size(); ++i)
            if (errors[i].empty()) errors[i] = group[i].rel + ": " + why;
    // Each folder's renames made durable by one fsync (folders told apart by device and inode).
    std::set<std::pair<dev_t, ino_t>> synced;
    for (size_t i = 0; i < group.size(); ++i) {
        if (!errors[i].empty() || !group[i].file.rename(errors[i])) continue;
        struct stat st {};
        const int dir = group[i].file.folder();
        if (::fstat(dir, &st) == 0 && synced.emplace(st.st_dev, st.st_ino).second) ::fsync(dir);
    }
    for (size_t i = 0; i < group.size(); ++i) {
        Batch* batch = group[i].batch;
        const std::string rel = group[i].rel;
        {  // descriptors closed (a temporary not renamed removed) before the batch hears
            const StagedFile gone = std::move(group[i].file);
        }
        batch->done(rel, std::move(errors[i]));
    }
}

void OutputFolder::stop_committer() {
    {
        std::lock_guard lock(commit_mutex_);
        stopping_ = true;
        commit_cv_.notify_all();
    }
    if (committer_.joinable()) committer_.join();
    std::lock_guard lock(commit_mutex_);
    stopping_ = false;  // a later Batch::write starts it again
}

bool OutputFolder::finish(const ByteProducer& manifest, const std::set<std::string>& produced,
                          std::vector<std::string>& notes, std::string& error) {
    stop_committer();  // every batch's files are in place before the manifest that lists them
    if (!write_file_under(opt_.dir, opt_.manifest_name, manifest, error)) {
        error = (opt_.dir / opt_.manifest_name).string() + ": " +
                error.substr(error.find(": ") == std::string::npos ? 0 : error.find(": ") + 2);
        return false;
    }
    // Outputs of earlier runs this one does not produce: removed when unchanged since we wrote
    // them, kept (and said so) when someone changed them. Files other manifests list are theirs.
    // A run with a failed write removes none of them and keeps its journal (header comment).
    size_t unproduced = 0;
    for (const auto& entry : previous_)
        unproduced += produced.count(entry.first) || entry.first == opt_.manifest_name ? 0 : 1;
    if (write_failed_ && unproduced > 0) {
        notes.push_back("kept " + std::to_string(unproduced) +
                        " earlier outputs this run does not produce: some of its own could not be written, so the "
                        "last good copies stay until a run writes all of its outputs");
        if (const int dfd = ::open(opt_.dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC); dfd >= 0) {
            ::fsync(dfd);
            ::close(dfd);
        }
        return true;
    }
    const std::set<std::string> elsewhere = listed_elsewhere();
    for (const auto& [rel, sha] : previous_) {
        if (produced.count(rel) || elsewhere.count(rel) || rel == opt_.manifest_name) continue;
        std::string leaf;
        std::vector<std::string> parts;
        const int dfd = open_parent(opt_.dir, rel, leaf, &parts);
        if (dfd < 0) continue;
        const auto now = file_sha(dfd, leaf);
        if (!now) {
            ::close(dfd);
            continue;
        }
        if (!sha.empty() && *now != sha) {
            notes.push_back(
                "kept " + rel +
                ": an earlier run wrote it, this one does not, and it has changed since; remove it by hand if it is not needed");
            ::close(dfd);
            continue;
        }
        if (::unlinkat(dfd, leaf.c_str(), 0) == 0)
            notes.push_back("removed " + rel + ": an earlier run's output that this run does not produce");
        ::close(dfd);
        // Its folders, when now empty (rmdir fails on any other).
        for (size_t n = parts.size() - 1; n > 0; --n) {
            std::string folder;
            for (size_t i = 0; i < n; ++i) folder += (i ? "/" : "") + parts[i];
            std::string last;
            const int parent = open_parent(opt_.dir, folder, last);
            if (parent < 0) break;
            const bool removed = ::unlinkat(parent, last.c_str(), AT_REMOVEDIR) == 0;
            ::close(parent);
            if (!removed) break;
        }
    }
    ::unlink((opt_.dir / journal_name()).c_str());
    if (journal_fd_ >= 0) {
        ::close(journal_fd_);
        journal_fd_ = -1;
    }
    if (const int dfd = ::open(opt_.dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC); dfd >= 0) {
        ::fsync(dfd);
        ::close(dfd);
    }
    return true;
}

}  // namespace mf
