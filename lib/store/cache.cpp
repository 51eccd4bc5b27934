#include "store/cache.hpp"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "base/file_identity.hpp"
#include "core/files.hpp"
#include "core/json.hpp"
#include "core/version.hpp"

namespace mf {
namespace fs = std::filesystem;
namespace {

std::span<const unsigned char> as_bytes(const std::string& s) {
    return {reinterpret_cast<const unsigned char*>(s.data()), s.size()};
}

std::string sha_of(const std::string& s) { return sha256_hex(as_bytes(s)); }

bool is_sha(const std::string& s) {
    return s.size() == 64 &&
           std::all_of(s.begin(), s.end(), [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); });
}

// What a file's digest is remembered by: its settled identity (base/file_identity.hpp, the rule
// lib/image keeps header reads by). A file changed within the last seconds has none: it is
// hashed, and no hint is written for it (its times may not move at its next change).
std::string stat_line(const fs::path& file) { return settled_identity(file); }

std::optional<std::string> read_text(const fs::path& p) {
    std::vector<unsigned char> bytes;
    std::string error;
    if (!read_file(p, bytes, error)) return std::nullopt;
    return std::string(bytes.begin(), bytes.end());
}

// A digest hint (stat/): written aside and renamed, but not fsynced. A hint lost to a crash
// costs one re-hash; it is only trusted while the file's stat still matches.
void write_hint(const fs::path& file, const std::string& text) {
    std::error_code ec;
    fs::create_directories(file.parent_path(), ec);
    const fs::path aside = file.parent_path() / temp_name(file.filename().string());
    {
        std::ofstream o(aside, std::ios::binary | std::ios::trunc);
        o << text;
        if (!o.flush()) {
            fs::remove(aside, ec);
            return;
        }
    }
    fs::rename(aside, file, ec);
    if (ec) fs::remove(aside, ec);
}

// The digest of `file`, remembered under `stat_file` ("<stat line>\n<sha>"): hashed only when
// the file's stat changed since.
std::optional<std::string> remembered_digest(const fs::path& file, const fs::path& stat_file, std::string& error) {
    const std::string now = stat_line(file);
    if (!now.empty())
        if (const auto rec = read_text(stat_file)) {
            const auto nl = rec->find('\n');
            if (nl != std::string::npos && rec->substr(0, nl) == now && is_sha(rec->substr(nl + 1)))
                return rec->substr(nl + 1);
        }
    std::optional<std::string> sha = sha256_of_file(file, error);  // in pieces, never held
    if (!sha) return std::nullopt;
    // Written only when the stat did not move while we read (else the next run hashes again).
    if (!now.empty() && stat_line(file) == now) {
        write_hint(stat_file, now + "\n" + *sha);
    }
    return sha;
}

// The files a set's entry lists: its outputs and its material files (glTF + bin).
struct FileRef {
    std::string file, sha256;
};
std::vector<FileRef> files_of(const manifest::Material& m) {
    std::vector<FileRef> out;
    for (const auto& o : m.outputs) out.push_back({o.file, o.sha256});
    for (const auto& f : m.material_files) out.push_back({f.file, f.sha256});
    return out;
}

// `blob` as a hard link to `file` (no second copy), put aside and renamed into place; a copy of
// `bytes` where links are not possible (another file system, a file system without links).
bool link_or_write(const fs::path& file, const fs::path& blob, std::span<const unsigned char> bytes,
                   std::string& error) {
    std::error_code ec;
    fs::create_directories(blob.parent_path(), ec);
    const fs::path aside = blob.parent_path() / temp_name(blob.filename().string());
    fs::create_hard_link(file, aside, ec);
    if (!ec) {
        fs::rename(aside, blob, ec);
        if (!ec) return true;
        fs::remove(aside, ec);
    }
    return write_file_atomic(blob, bytes, error);
}

// Version 2 records carry the SHA-256 of their entry's JSON text (`entry_sha256`): a record cut
// short or altered is detected like a blob, never trusted. Version 3 entries record a flipped
// normal's convention (normal_converted_from). Version 4: albedo checks weighted by metalness,
// MaterialX sidecars read, inputs' `unused`, and the gltf preset's .mtlx material files.
// Version 5: materials' alpha_mode and the engines' material files. Version 6: a JPEG cut short
// is unreadable (it decoded grey), a name's "--" kept apart in the .mtlx comment. Version 7:
// materials' provenance and the vendor's preview input (LICENCE_UNKNOWN). Version 8: a record
// names the build that computed it (`code`), which its file name includes. Records of other
// versions miss.
constexpr int kRecordVersion = 8;

// The digest of a record's entry: its compact JSON text, invalid UTF-8 in names replaced as the
// manifest writer does (a file name is any bytes; dump() would throw on them).
std::string entry_digest(const nlohmann::json& entry) {
    return sha_of(entry.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
}

// The manifest entry an action record holds, checked: nullopt + `error` naming the problem when
// it does not parse, is of another version, is for another key than `key` or another build than
// `code` (when given), or does not hash to its `entry_sha256`. `outdated`: the record is a
// well-formed one of another cache_version (an earlier matforge wrote it), no fault of the cache.
std::optional<manifest::Material> read_record(const fs::path& rec, std::string& error, const std::string* key = nullptr,
                                              const std::string* code = nullptr, bool* outdated = nullptr) {
    const auto j = read_json_file(rec, error);
    if (!j) return std::nullopt;
    const auto mj = j->find("entry");
    if (!j->is_object() || j->value("cache_version", 0) != kRecordVersion || mj == j->end() || !mj->is_object()) {
        if (outdated && j->is_object() && j->value("cache_version", 0) > 0 &&
            j->value("cache_version", 0) != kRecordVersion)
            *outdated = true;
        error = "not an action record of this cache version";
        return std::nullopt;
    }
    if (key && j->value("key", "") != *key) {
        error = "a record of another action key";
        return std::nullopt;
    }
    if (code && j->value("code", "") != *code) {
        error = "a record of another build of matforge";
        return std::nullopt;
    }
    if (j->value("entry_sha256", "") != entry_digest(*mj)) {
        error = "its entry does not hash to its entry_sha256 (truncated or altered)";
        return std::nullopt;
    }
    nlohmann::json wrapped{{"manifest_version", manifest::kVersion}, {"materials", nlohmann::json::array({*mj})}};
    auto m = manifest::manifest_from_json(wrapped, error);
    if (!m || m->materials.size() != 1) {
        if (error.empty()) error = "its entry is not one manifest material";
        return std::nullopt;
    }
    return std::move(m->materials[0]);
}

}  // namespace

namespace {

constexpr std::string_view kMarker = "matforge cache 1\n";
constexpr const char* kMarkerName = "version";

bool has_marker(const fs::path& dir) {
    const fs::path marker = dir / kMarkerName;
    std::error_code ec;
    if (fs::is_symlink(marker, ec) || !fs::is_regular_file(marker, ec) || fs::file_size(marker, ec) != kMarker.size())
        return false;
    const auto text = read_text(marker);
    return text && *text == kMarker;
}

// Our own name for a record (`ac/<aa>/<64 hex>.json`) or a blob (`cas/<aa>/<64 hex>`), relative
// to the cache: prune() removes nothing else.
bool our_file(const fs::path& rel, std::string_view top) {
    std::vector<std::string> parts;
    for (const auto& p : rel) parts.push_back(p.string());
    if (parts.size() != 3 || parts[0] != top) return false;
    std::string name = parts[2];
    if (top == "ac") {
        if (name.size() < 5 || name.substr(name.size() - 5) != ".json") return false;
        name.resize(name.size() - 5);
    }
    return is_sha(name) && parts[1] == name.substr(0, 2);
}

}  // namespace

std::string Cache::unusable(const fs::path& dir) {
    std::error_code ec;
    const auto st = fs::symlink_status(dir, ec);
    if (!fs::exists(st)) return {};
    if (!fs::is_directory(fs::status(dir, ec)))
        return dir.string() + ": not a folder; a cache is a folder matforge makes";
    if (has_marker(dir)) return {};
    // Empty, or holding only the marker another run is writing: a cache being made, by us or by
    // a concurrent shard. create() writes the marker before anything else, so anything else in
    // the folder with the marker now present was made by such a run after our first look.
    fs::directory_iterator it(dir, ec);
    if (ec) return dir.string() + ": cannot list it (" + ec.message() + ")";
    for (; it != fs::directory_iterator(); it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (name.starts_with("." + std::string(kMarkerName) + kTempMarker) && temp_owner(name)) continue;
        if (has_marker(dir)) return {};
        return dir.string() + ": not a matforge cache (it holds " + name +
               " and no cache marker): matforge writes and removes nothing there; name an empty or new folder";
    }
    return {};
}

std::optional<Cache> Cache::create(const fs::path& dir, std::string& error, std::optional<std::string> code) {
    if (std::string why = unusable(dir); !why.empty()) {
        error = std::move(why);
        return std::nullopt;
    }
    // Never records without a build: they would be every build's.
    if (!code) {
        std::string why;
        code = code_identity(why);
        if (!code) {
            error = "cannot tell which build of matforge this is (" + why + ")";
            return std::nullopt;
        }
    }
    // The marker first: a concurrent run (another shard on the same new cache) must never see
    // our folders without it and take the cache for a user's folder.
    if (!write_file_atomic(dir / kMarkerName, as_bytes(std::string(kMarker)), error)) return std::nullopt;
    std::error_code ec;
    for (const char* sub : {"cas", "ac", "stat"}) {
        fs::create_directories(dir / sub, ec);
        if (ec) {
            error = (dir / sub).string() + ": cannot create the cache folder (" + ec.message() + ")";
            return std::nullopt;
        }
    }
    return Cache(fs::absolute(dir, ec), std::move(*code));
}

std::optional<Cache> Cache::open(const fs::path& dir, std::string& error) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) {
        error = dir.string() + ": no such cache folder";
        return std::nullopt;
    }
    if (!has_marker(dir)) {
        error = dir.string() +
                ": not a matforge cache (no cache marker 'version' in it); nothing is read or removed there";
        return std::nullopt;
    }
    return Cache(fs::absolute(dir, ec), {});
}

fs::path Cache::blob_path(const std::string& sha) const { return dir_ / "cas" / sha.substr(0, 2) / sha; }
fs::path Cache::record_path(const std::string& key, const std::string& name) const {
    const std::string id = sha_of(key + "\n" + name + "\n" + code_);
    return dir_ / "ac" / id.substr(0, 2) / (id + ".json");
}
fs::path Cache::stat_path(const fs::path& file) const {
    std::error_code ec;
    const std::string id = sha_of(fs::absolute(file, ec).lexically_normal().string());
    return dir_ / "stat" / id.substr(0, 2) / id;
}

std::optional<std::string> Cache::digest(const InputFile& in, std::string& error) const {
    if (in.bytes) return sha256_hex(*in.bytes);  // a zip entry: already in memory
    if (!in.open_error.empty()) {
        error = in.display + ": " + in.open_error;
        return std::nullopt;
    }
    return remembered_digest(in.path, stat_path(in.path), error);
}

std::optional<Cache::Hit> Cache::restore(const std::string& key, const std::string& name, const fs::path& out_dir,
                                         const Write& write, std::vector<std::string>& corrupt) const {
    if (code_.empty()) return std::nullopt;  // open()'s: no build's records
    const fs::path rec = record_path(key, name);
    std::error_code ec;
    if (!fs::exists(fs::symlink_status(rec, ec))) return std::nullopt;  // never stored, or evicted
    std::string error;
    bool outdated = false;
    auto entry = read_record(rec, error, &key, &code_, &outdated);
    if (!entry || entry->name != name) {
        // An earlier matforge's record: a plain miss, replaced when the set is stored again
        // (a version upgrade is no problem to report).
        if (!outdated)
            corrupt.push_back(rec.string() + ": " + (entry ? "a record of another material" : error) + "; removed");
        fs::remove(rec, ec);
        return std::nullopt;
    }
    Hit hit{std::move(*entry)};
    // Every blob is read and checked before the first file is written: a miss half-way would
    // leave a set with some outputs of the cached run and the rest to recompute.
    const std::vector<FileRef> files = files_of(hit.entry);
    std::vector<std::pair<const FileRef*, std::vector<unsigned char>>> todo;
    for (const FileRef& f : files) {
        const fs::path dest = out_dir / f.file;
        // Already in place (the stat of what this cache last wrote or read there): nothing to do.
        std::string ignored;
        if (const auto have = remembered_digest(dest, stat_path(dest), ignored); have && *have == f.sha256) continue;
        std::vector<unsigned char> bytes;
        const fs::path blob = blob_path(f.sha256);
        if (!is_sha(f.sha256) || !read_file(blob, bytes, error)) return std::nullopt;  // evicted: a miss
        if (sha256_hex(bytes) != f.sha256) {
            corrupt.push_back(blob.string() +
                              ": its content does not hash to its name (truncated or altered); removed");
            fs::remove(blob, ec);
            return std::nullopt;
        }
        todo.emplace_back(&f, std::move(bytes));
    }
    for (const auto& [f, bytes] : todo) {
        if (!write(f->file, bytes, error)) return std::nullopt;  // the caller recomputes and reports
        const fs::path dest = out_dir / f->file;
        const std::string now = stat_line(dest);
        if (!now.empty()) write_hint(stat_path(dest), now + "\n" + f->sha256);
    }
    // Used now: least recently used eviction keeps it.
    fs::last_write_time(rec, fs::file_time_type::clock::now(), ec);
    return hit;
}

bool Cache::store(const std::string& key, const manifest::Material& entry, const fs::path& out_dir,
                  std::string& error) const {
    if (code_.empty()) {
        error = "a cache opened to be sized and pruned stores nothing";
        return false;
    }
    for (const FileRef& f : files_of(entry)) {
        const fs::path blob = blob_path(f.sha256);
        std::error_code ec;
        if (!is_sha(f.sha256)) {
            error = f.file + ": no sha256 recorded; not cached";
            return false;
        }
        if (fs::is_regular_file(blob, ec)) continue;  // content-addressed: the same bytes
        std::vector<unsigned char> bytes;
        if (!read_file(out_dir / f.file, bytes, error)) return false;
        if (sha256_hex(bytes) != f.sha256) {
            error = (out_dir / f.file).string() + ": changed since it was written; not cached";
            return false;
        }
        if (!link_or_write(out_dir / f.file, blob, bytes, error)) return false;
    }
    // What is in the output folder now is these bytes: the next restore checks their stat only.
    for (const FileRef& f : files_of(entry)) {
        const fs::path dest = out_dir / f.file;
        const std::string now = stat_line(dest);
        if (!now.empty()) write_hint(stat_path(dest), now + "\n" + f.sha256);
    }
    manifest::Material stored = entry;
    stored.source.clear();  // the caller's: relative to its output folder
    stored.archive.reset();
    const nlohmann::json ej = manifest::to_json(stored);
    const nlohmann::json rec{{"cache_version", kRecordVersion},
                             {"key", key},
                             {"code", code_},
                             {"entry", ej},
                             {"entry_sha256", entry_digest(ej)}};
    return write_file_atomic(record_path(key, entry.name), as_bytes(json_text(rec)), error);
}

Cache::Stats Cache::stats() const {
    Stats s;
    std::error_code ec;
    for (fs::recursive_directory_iterator it(dir_, ec), end; !ec && it != end; it.increment(ec)) {
        if (!it->is_regular_file(ec) || it->is_symlink(ec)) continue;
        const auto size = it->file_size(ec);
        const fs::path rel = it->path().lexically_relative(dir_);
        if (our_file(rel, "cas")) ++s.blobs, s.blob_bytes += size;
        else if (our_file(rel, "ac")) ++s.records, s.other_bytes += size;
        else s.other_bytes += size;
    }
    return s;
}

Cache::Stats Cache::prune(uint64_t max_bytes, std::chrono::seconds grace) const {
    struct Record {
        fs::path path;
        fs::file_time_type used;
        std::vector<std::string> blobs;
    };
    std::vector<Record> records;
    Stats removed;
    // Only what is gone counts; a file that stays (a read-only cache) is a failure, said once.
    auto remove = [&](const fs::path& p) {
        std::error_code rec;
        if (fs::remove(p, rec)) return true;
        ++removed.failed;
        if (removed.error.empty()) removed.error = p.string() + ": " + (rec ? rec.message() : "not removed");
        return false;
    };
    std::error_code ec;
    for (fs::recursive_directory_iterator it(dir_ / "ac", ec), end; !ec && it != end; it.increment(ec)) {
        if (it->is_symlink(ec) || !it->is_regular_file(ec) || !our_file(it->path().lexically_relative(dir_), "ac"))
            continue;
        Record r{it->path(), it->last_write_time(ec), {}};
        std::string error;
        const auto entry = read_record(r.path, error);
        if (!entry) {  // unusable: restore() would remove it too
            if (remove(r.path)) ++removed.records;
            continue;
        }
        for (const FileRef& f : files_of(*entry)) r.blobs.push_back(f.sha256);  // outputs and material files
        records.push_back(std::move(r));
    }
    std::sort(records.begin(), records.end(), [](const Record& a, const Record& b) { return a.used > b.used; });
    std::map<std::string, uint64_t> blob_size;
    for (fs::recursive_directory_iterator it(dir_ / "cas", ec), end; !ec && it != end; it.increment(ec))
        if (!it->is_symlink(ec) && it->is_regular_file(ec) && our_file(it->path().lexically_relative(dir_), "cas"))
            blob_size[it->path().filename().string()] = it->file_size(ec);
    std::set<std::string> kept;
    uint64_t used = 0;
    for (const Record& r : records) {
        uint64_t extra = 0;
        for (const auto& b : r.blobs)
            if (!kept.count(b) && blob_size.count(b)) extra += blob_size[b];
        if (used + extra > max_bytes) {
            if (remove(r.path)) ++removed.records;
            else kept.insert(r.blobs.begin(), r.blobs.end());  // still there: its blobs stay usable
            continue;
        }
        used += extra;
        kept.insert(r.blobs.begin(), r.blobs.end());
    }
    const auto young = fs::file_time_type::clock::now() - grace;
    for (const auto& [sha, size] : blob_size) {
        if (kept.count(sha)) continue;
        const fs::path p = blob_path(sha);
        if (fs::last_write_time(p, ec) > young) continue;
        if (remove(p)) ++removed.blobs, removed.blob_bytes += size;
    }
    return removed;
}

}  // namespace mf
