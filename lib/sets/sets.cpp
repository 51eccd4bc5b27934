#include "sets/sets.hpp"

#include <zip.h>

#include <sys/stat.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <functional>
#include <list>
#include <map>
#include <mutex>
#include <set>

#include "core/files.hpp"
#include "core/json.hpp"
#include "core/text.hpp"
#include "findings/catalog.hpp"
#include "material/discovery.hpp"

namespace mf {
namespace fs = std::filesystem;

// ---- the archive, opened once

class ZipArchive {
public:
    struct Entry {
        zip_uint64_t index = 0;
        bool symlink = false;  // stored as a Unix symbolic link: its data is the target's name
        int copies = 1;        // entries of this name (the first is used)
    };

    explicit ZipArchive(fs::path path) : path_(std::move(path)) {}
    ~ZipArchive() {
        std::lock_guard reg(registry_mutex());
        auto& open = registry();
        open.remove(this);
        if (z_) zip_discard(z_);
    }
    ZipArchive(const ZipArchive&) = delete;
    ZipArchive& operator=(const ZipArchive&) = delete;

    const fs::path& path() const { return path_; }
    std::map<std::string, Entry> entries;  // by name, filled by scan (not changed afterwards)

    // Opens the archive (or reuses the handle); `error` names libzip's reason.
    bool with_handle(std::string& error, const std::function<void(zip_t*)>& fn) {
        std::lock_guard lock(mutex_);
        if (!z_) {
            int err = 0;
            z_ = zip_open(path_.c_str(), ZIP_RDONLY, &err);
            if (!z_) {
                zip_error_t ze;
                zip_error_init_with_code(&ze, err);
                error = zip_error_strerror(&ze);
                zip_error_fini(&ze);
                return false;
            }
            remember_open();
        }
        fn(z_);
        return true;
    }

private:
    // At most kMaxOpen archives hold a descriptor at once (a library of 10,000 zips would run out
    // of them): opening one more closes the least recently opened one not in use.
    static constexpr size_t kMaxOpen = 32;
    static std::mutex& registry_mutex() {
        static std::mutex m;
        return m;
    }
    static std::list<ZipArchive*>& registry() {
        static std::list<ZipArchive*> open;
        return open;
    }
    void remember_open() {  // mutex_ held
        std::lock_guard reg(registry_mutex());
        auto& open = registry();
        open.push_back(this);
        for (auto it = open.begin(); open.size() > kMaxOpen && it != open.end();) {
            ZipArchive* a = *it;
            // try_lock: never waits on another archive while holding our own lock (no deadlock).
            if (a != this && a->mutex_.try_lock()) {
                zip_discard(a->z_);
                a->z_ = nullptr;
                a->mutex_.unlock();
                it = open.erase(it);
            } else {
                ++it;
            }
        }
    }

    fs::path path_;
    std::mutex mutex_;
    zip_t* z_ = nullptr;
};

namespace {

bool hidden(const std::string& name) { return name.empty() || name[0] == '.' || name == "__MACOSX"; }

// The real path of a folder or archive, to read each once however many inputs reach it.
fs::path real_path(const fs::path& p) {
    std::error_code ec;
    fs::path r = fs::canonical(p, ec);
    return ec ? fs::absolute(p, ec).lexically_normal() : r;
}

// Image formats matforge does not read: a file named like a map in one of them is not silently
// nothing ("Wood_Color.gif").
bool unread_image_format(const std::string& file) {
    static const std::set<std::string> kExt{"gif", "jp2", "j2k",  "j2c",  "jpx",  "jpf",   "ppm", "pgm", "pbm", "pnm",
                                            "pam", "pfm", "heic", "heif", "avif", "jxl",   "ico", "sgi", "rgb", "iff",
                                            "pcx", "ktx", "ktx2", "astc", "pvr",  "basis", "dpx", "cin", "fits"};
    const auto dot = file.rfind('.');
    if (dot == std::string::npos || dot == 0 || !kExt.count(ascii_lower(file.substr(dot + 1)))) return false;
    return classify_name(file.substr(0, dot) + ".png").has_value();
}

// The file that marks `dir` as an output folder of matforge ("" when none): a manifest or a
// stopped run's journal that matforge wrote, or a report's index.html. Only the start of a file
// is read: a manifest of 100,000 sets is hundreds of MB.
std::string matforge_output_marker(const fs::path& dir) {
    std::error_code ec;
    auto starts_with_ours = [](const fs::path& f, std::string_view needle) {
        std::ifstream in(f, std::ios::binary);
        std::string head(size_t{1} << 20, '\0');
        in.read(head.data(), static_cast<std::streamsize>(head.size()));
        head.resize(static_cast<size_t>(in.gcount()));
        return head.find(needle) != std::string::npos;
    };
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        std::string n = it->path().filename().string();
        std::error_code fec;
        if (!it->is_regular_file(fec) || it->is_symlink(fec)) continue;
        if (n.rfind(".manifest", 0) == 0 && n.size() > 8 && n.substr(n.size() - 8) == ".journal") return n;
        if (n.rfind("manifest", 0) == 0 && it->path().extension() == ".json" &&
            starts_with_ours(it->path(), "\"generator\": \"matforge "))
            return n;
        if (n == "index.html" && starts_with_ours(it->path(), "<meta name=\"generator\" content=\"matforge ")) return n;
    }
    return {};
}

struct Scan {
    const std::vector<fs::path>& exclude;
    std::vector<MaterialSource>& out;
    std::vector<InputFailure>& failures;
    std::string* output_conflict;
    std::vector<std::string>* skipped;             // output folders of matforge met in the walk, said once each
    std::map<fs::path, std::vector<size_t>> seen;  // real path of a folder/archive -> its sets
    std::string input;                             // the input being walked, for DUPLICATE_INPUT
    size_t reached_again = 0;                      // folders and archives met a second time
    std::vector<std::string> lone;                 // lone maps that made no set, one line each
};

// A folder or archive already read: its sets are noted, not found again.
bool already_seen(Scan& scan, const fs::path& p) {
    const auto it = scan.seen.find(real_path(p));
    if (it == scan.seen.end()) return false;
    ++scan.reached_again;
    for (size_t i : it->second) {
        MaterialSource& s = scan.out[i];
        const std::string msg = s.display + " is also reached through the input " + scan.input +
                                "; it is read once (overlapping inputs)";
        const bool known = std::any_of(s.findings.begin(), s.findings.end(),
                                       [&](const Finding& f) { return f.message == msg; });
        if (!known) s.findings.push_back(finding(code::duplicate_input, "", "", msg, {{"input", scan.input}}));
    }
    return true;
}

// Why a group of files is no material ("" when it is one): a lone map whose name carries no
// material name ("normal_map_tutorial.png", "alpha.webp": a tag and nothing of a material) is a
// stray image, not a material with grey albedo. A colour map, two maps, an untagged image
// beside the map, or a lone map named for a material ("Rock_Roughness.png") make a set.
std::string lone_map(const std::vector<std::string>& files, bool billboards) {
    int maps = 0;
    std::string only, role;
    for (const auto& f : files) {
        const auto m = classify_name(f, billboards);
        // An untagged image beside it may be its colour map (discover_set: "Platform2.jpg").
        if (!m && is_image_file(f) && !is_clutter(f)) return {};
        if (!m) continue;
        if (m->role == Role::albedo) return {};
        ++maps;
        only = f;
        role = role_name(m->role);
    }
    if (maps != 1 || !material_stem(only).empty()) return {};
    return only + " (" + role +
           "): a lone map whose name holds no material name, not a material set (a set needs a colour map, "
           "two maps of one material, or a material name); not used";
}

void add_groups(const std::string& fallback, const std::vector<std::string>& files, const MaterialSource& proto,
                std::vector<MaterialSource>& out, std::vector<std::string>* notes = nullptr) {
    const bool billboards = billboards_only(files);
    for (auto& g : group_files(files, fallback)) {
        const bool any_role = std::any_of(g.files.begin(), g.files.end(), [&](const std::string& f) {
            return classify_name(f, billboards).has_value();
        });
        if (!any_role) continue;
        if (const std::string why = lone_map(g.files, billboards); !why.empty()) {
            if (notes) notes->push_back(proto.display + "/" + why);
            continue;
        }
        MaterialSource s = proto;
        s.name = g.name.empty() ? fallback : g.name;
        s.files = g.files;
        s.shared_folder = g.shared;
        std::sort(s.files.begin(), s.files.end());
        if (g.merge) {
            // Spellings that differ only in resolution/format tags are one material at several
            // sizes (info); a difference of case or separators may be two materials (warning).
            Figures figures{{"spellings", g.merge->spellings}, {"files", g.merge->files}};
            Finding f = finding(code::names_merged, "", g.merge->files.empty() ? "" : g.merge->files.front(),
                                g.merge->message, std::move(figures));
            if (!g.merge->spelling_differs) f.severity = Severity::info;  // the catalog's one exception (its title)
            s.findings.push_back(std::move(f));
        }
        out.push_back(std::move(s));
    }
}

// Folder -> its files, for a zip archive's entries (recorded in `zip.entries`). Entries named to
// climb out of the archive ("../x", "/abs/x") go to `unsafe`.
std::map<std::string, std::vector<std::string>> zip_folders(ZipArchive& zip, std::string& error,
                                                            std::vector<std::string>& unsafe) {
    std::map<std::string, std::vector<std::string>> folders;
    zip.with_handle(error, [&](zip_t* z) {
        const zip_int64_t n = zip_get_num_entries(z, 0);
        for (zip_int64_t i = 0; i < n; ++i) {
            const auto index = static_cast<zip_uint64_t>(i);
            const char* raw = zip_get_name(z, index, ZIP_FL_ENC_GUESS);
            if (!raw) continue;
            const std::string name = raw;
            if (name.empty() || name.back() == '/') continue;
            // Entries are only ever read into memory, so "../" names cannot escape anywhere, but
            // they are no part of a material set either: reported (a crafted archive), then skipped.
            bool escapes = name.front() == '/', skip = false;
            size_t start = 0;
            for (size_t p = 0; p <= name.size(); ++p) {
                if (p == name.size() || name[p] == '/') {
                    const std::string part = name.substr(start, p - start);
                    if (part == "..") escapes = true;
                    else if (hidden(part)) skip = true;
                    start = p + 1;
                }
            }
            if (escapes) unsafe.push_back(name);
            if (escapes || skip) continue;
            zip_uint8_t opsys = 0;
            zip_uint32_t attributes = 0;
            const bool link = zip_file_get_external_attributes(z, index, 0, &opsys, &attributes) == 0 &&
                              opsys == ZIP_OPSYS_UNIX && ((attributes >> 16) & S_IFMT) == S_IFLNK;
            auto [it, first] = zip.entries.try_emplace(name, ZipArchive::Entry{index, link, 1});
            if (!first) {
                ++it->second.copies;  // one name twice: the first entry is used, and said so
                continue;
            }
            const auto slash = name.rfind('/');
            const std::string folder = slash == std::string::npos ? "" : name.substr(0, slash);
            folders[folder].push_back(slash == std::string::npos ? name : name.substr(slash + 1));
        }
    });
    return folders;
}

void scan_zip(Scan& scan, const fs::path& zip_path) {
    if (already_seen(scan, zip_path)) return;
    auto zip = std::make_shared<ZipArchive>(zip_path);
    std::string error;
    std::vector<std::string> unsafe;
    auto folders = zip_folders(*zip, error, unsafe);
    const std::string shown = zip_path.string();
    if (!error.empty()) {
        scan.failures.push_back({shown, std::string(code::unreadable_file),
                                 shown + ": not a readable .zip (" + error + ")"});
        scan.seen[real_path(zip_path)];
        return;
    }
    for (const auto& name : unsafe)
        scan.failures.push_back({shown, std::string(code::unsafe_path),
                                 shown + ": entry '" + name + "' points outside the archive; skipped"});
    const size_t before = scan.out.size();
    for (auto& [folder, files] : folders) {
        MaterialSource proto;
        proto.root = zip_path;
        proto.is_zip = true;
        proto.zip_folder = folder;
        proto.archive = zip;
        proto.display = shown + (folder.empty() ? "" : "/" + folder);
        const std::string fallback = folder.empty() ? zip_path.stem().string() : fs::path(folder).filename().string();
        add_groups(fallback, files, proto, scan.out, &scan.lone);
    }
    auto& mine = scan.seen[real_path(zip_path)];
    for (size_t i = before; i < scan.out.size(); ++i) {
        mine.push_back(i);
        MaterialSource& s = scan.out[i];
        for (const std::string& f : s.files) {
            const std::string entry = s.zip_folder.empty() ? f : s.zip_folder + "/" + f;
            const auto it = zip->entries.find(entry);
            if (it == zip->entries.end() || it->second.copies < 2) continue;
            s.findings.push_back(finding(code::duplicate_entry, "", f,
                                         shown + ": " + std::to_string(it->second.copies) + " entries are named '" +
                                             entry + "'; the first is used, the others are ignored",
                                         {{"entries", it->second.copies}}));
        }
    }
    if (scan.out.size() == before)
        scan.failures.push_back({shown, std::string(code::unrecognized_file),
                                 shown + ": the archive holds no recognizable material maps"});
}

// Whether a sidecar in the folder names one of its images: then its maps are the set's whatever
// their names say (file names need no role tag), and the folder is one set. A MaterialX
// document whose maps the names already group as one material (ambientCG's downloads) leaves
// the grouping, and so the material's name, to the names.
bool sidecar_names_a_map(const fs::path& dir, const std::vector<std::string>& files) {
    for (const std::string& f : files) {
        if (!is_sidecar_name(f)) continue;
        std::error_code ec;
        if (!fs::is_regular_file(dir / f, ec) || fs::file_size(dir / f, ec) > kSidecarMaxBytes) continue;
        std::vector<unsigned char> bytes;
        std::string error;
        if (!read_file(dir / f, bytes, error)) continue;
        const SidecarRoles roles = sidecar_roles(f, std::string_view(reinterpret_cast<const char*>(bytes.data()),
                                                                     bytes.size()));
        std::vector<std::string> named;
        for (const SidecarMap& m : roles.maps)
            if (std::binary_search(files.begin(), files.end(), m.file)) named.push_back(m.file);
        if (named.empty()) continue;
        if (roles.kind != SidecarKind::materialx) return true;
        // Its maps all in one group of the names (another id's set beside it, or a stray map of
        // another id, is a group of its own): the names decide. ambientCG's downloads put one
        // document beside each set, two sets side by side are two materials.
        std::vector<MaterialSource> groups;
        add_groups(dir.filename().string(), files, MaterialSource{}, groups);
        const bool one_group = std::any_of(groups.begin(), groups.end(), [&](const MaterialSource& g) {
            return std::all_of(named.begin(), named.end(), [&](const std::string& n) {
                return std::binary_search(g.files.begin(), g.files.end(), n);
            });
        });
        if (!one_group) return true;
    }
    return false;
}

// Why a folder that made no set is still not nothing (issue 45: it vanished from a library
// run): images whose names state no role beside a material document (MaterialX, glTF) that
// cannot be read (not well-formed, too deep, too large) or names none of them (an entity left
// unexpanded), so the maps it would have named are named by nothing. Empty when the folder has
// no such document or no image. Called only for a folder that made no set.
std::string unreadable_sidecar(const fs::path& dir, const std::vector<std::string>& files) {
    std::string images;
    int count = 0;
    for (const std::string& f : files)
        if (is_image_file(f) && count++ < 3) images += (images.empty() ? "" : ", ") + f;
    if (count == 0) return {};
    if (count > 3) images += ", … (" + std::to_string(count) + " images)";
    for (const std::string& f : files) {
        // MaterialX and glTF documents only: a .json beside images may be anything.
        const std::string ext = ascii_lower(fs::path(f).extension().string());
        if (!is_sidecar_name(f) || (ext != ".mtlx" && ext != ".gltf" && ext != ".glb")) continue;
        std::error_code ec;
        std::string error;
        std::vector<unsigned char> bytes;
        if (!fs::is_regular_file(dir / f, ec)) continue;
        if (fs::file_size(dir / f, ec) > kSidecarMaxBytes)
            error = "larger than " + std::to_string(kSidecarMaxBytes) + " bytes";
        else if (!read_file(dir / f, bytes, error)) error = "cannot be read (" + error + ")";
        else {
            const SidecarRoles roles = sidecar_roles(f, std::string_view(reinterpret_cast<const char*>(bytes.data()),
                                                                         bytes.size()));
            error = roles.error;
            // Read, but naming none of these images (an entity left unexpanded, another folder's
            // file names): as unusable to this folder.
            if (error.empty()) error = "it names none of them";
        }
        return dir.string() + ": " + images + " name no map role, and the sidecar " + f +
               " that could name them is unusable (" + error +
               "); no set is made of them — repair the sidecar, or name the maps by role (_Color, _Normal, ...)";
    }
    return {};
}

// The files of `dir` that are not folders (hidden ones left out), sorted; zips go to `zips`.
bool list_folder(const fs::path& dir, std::vector<std::string>& files, std::vector<fs::path>* zips,
                 std::string& error) {
    std::error_code ec;
    fs::directory_iterator it(dir, ec);
    for (fs::directory_iterator end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (hidden(name)) continue;
        std::error_code fec;
        const fs::file_status st = it->status(fec);  // follows symlinks
        if (fs::is_directory(st)) continue;          // walk() decides about folders
        // Everything else is a candidate file, also FIFOs, sockets and broken or looping links:
        // they get a coded error naming them when read (never opened, so a FIFO cannot hang us).
        if (zips && fs::is_regular_file(st) && name.size() > 4 &&
            ascii_lower(fs::path(name).extension().string()) == ".zip")
            zips->push_back(it->path());
        else files.push_back(name);
    }
    if (ec) {
        error = ec.message();
        return false;
    }
    std::sort(files.begin(), files.end());
    if (zips) std::sort(zips->begin(), zips->end());
    return true;
}

void scan_folder(Scan& scan, const fs::path& dir) {
    std::vector<std::string> files;
    std::vector<fs::path> zips;
    std::string error;
    if (!list_folder(dir, files, &zips, error)) {  // unreadable, beyond PATH_MAX, I/O error: reported
        scan.failures.push_back({dir.string(), std::string(code::unreadable_file),
                                 dir.string() + ": cannot list the folder (" + error + ")"});
        return;
    }
    for (const fs::path& z : zips) scan_zip(scan, z);
    MaterialSource proto;
    proto.root = dir;
    proto.display = dir.string();
    const size_t before = scan.out.size();
    if (sidecar_names_a_map(dir, files)) {  // the sidecar defines the set: one material, the folder's
        MaterialSource s = proto;
        s.name = dir.filename().string();
        s.files = files;
        scan.out.push_back(std::move(s));
    } else {
        add_groups(dir.filename().string(), files, proto, scan.out, &scan.lone);
    }
    auto& mine = scan.seen[real_path(dir)];
    for (size_t i = before; i < scan.out.size(); ++i) mine.push_back(i);
    if (scan.out.size() > before) return;
    if (std::string why = unreadable_sidecar(dir, files); !why.empty()) {
        scan.failures.push_back({dir.string(), std::string(code::unrecognized_file), std::move(why)});
        return;
    }
    std::string unread;
    for (const std::string& f : files)
        if (unread_image_format(f)) unread += (unread.empty() ? "" : ", ") + f;
    if (!unread.empty())
        scan.failures.push_back(
            {dir.string(), std::string(code::unrecognized_file),
             dir.string() + ": " + unread +
                 " name material maps in a format matforge does not read "
                 "(it reads PNG, JPEG, TIFF, EXR, HDR, TGA, BMP, WebP, DDS and PSD); no set is made of them"});
}

// Whether the output folder `dir` (met while walking an input) holds a set's maps of its own,
// and no manifest or journal of ours says they are outputs of an earlier run.
std::string set_in_output_folder(const fs::path& dir) {
    std::vector<std::string> files;
    std::string error;
    if (!list_folder(dir, files, nullptr, error)) return {};
    if (!matforge_output_marker(dir).empty()) return {};
    std::vector<MaterialSource> sets;
    add_groups(dir.filename().string(), files, MaterialSource{}, sets);
    if (sets.empty()) return {};
    std::string first;
    for (const auto& f : sets.front().files)
        if (classify_name(f)) {
            first = f;
            break;
        }
    return "the output folder " + dir.string() + " is the folder of the material set '" + sets.front().name + "' (" +
           first +
           " …): its outputs would be written among its sources and the set left out; choose an output folder "
           "that holds no material";
}

void walk(Scan& scan, const fs::path& root) {
    if (already_seen(scan, root)) return;
    // An output folder of an earlier run (or a report) is never read as material sets: its
    // outputs would come back as new materials and rename the real ones ("<name>_2").
    if (const std::string marker = matforge_output_marker(root); !marker.empty()) {
        scan.seen[real_path(root)];
        if (scan.skipped)
            scan.skipped->push_back(root.string() + ": skipped, an output folder of matforge (it holds its " + marker +
                                    "), not material sets");
        return;
    }
    scan_folder(scan, root);
    std::vector<fs::path> subdirs;
    std::error_code ec;
    for (fs::directory_iterator it(root, ec), end; !ec && it != end; it.increment(ec)) {
        std::error_code fec;
        // Real folders only: a symlink to a folder could loop back to an ancestor.
        if (it->is_directory(fec) && !it->is_symlink(fec) && !hidden(it->path().filename().string())) {
            if (std::any_of(scan.exclude.begin(), scan.exclude.end(),
                            [&](const fs::path& x) { return !x.empty() && fs::equivalent(it->path(), x, fec); })) {
                if (scan.output_conflict && scan.output_conflict->empty())
                    *scan.output_conflict = set_in_output_folder(it->path());
                continue;
            }
            subdirs.push_back(it->path());
        }
    }
    std::sort(subdirs.begin(), subdirs.end());
    for (auto& d : subdirs) walk(scan, d);
}

}  // namespace

std::string safe_name(const std::string& name) {
    std::string s;
    for (unsigned char c : name)
        s += (std::isalnum(c) || c == '_' || c == '-' || c == '.') ? static_cast<char>(c) : '_';
    while (!s.empty() && s.front() == '.') s.erase(0, 1);
    if (s.size() > kMaxNameBytes) s.resize(kMaxNameBytes);
    if (s.empty()) s = "material";
    return s;
}

std::vector<std::string> unique_names(const std::vector<std::string>& wanted,
                                      const std::vector<std::string>& reserved) {
    std::vector<std::string> names;
    std::map<std::string, int> holders;  // lower-case safe name -> how many sets want it
    for (const auto& w : wanted) {
        names.push_back(safe_name(w));
        ++holders[ascii_lower(names.back())];
    }
    std::set<std::string> taken(reserved.begin(), reserved.end());
    // First come, first kept: the first set of each name keeps it, unless reserved.
    std::vector<bool> kept(names.size(), false);
    for (size_t i = 0; i < names.size(); ++i)
        kept[i] = !taken.count(ascii_lower(names[i])) && taken.insert(ascii_lower(names[i])).second;
    for (size_t i = 0; i < names.size(); ++i) {
        if (kept[i]) continue;
        const std::string base = names[i];
        for (int n = 2;; ++n) {
            const std::string suffix = "_" + std::to_string(n);
            std::string candidate = base.substr(0, std::min(base.size(), kMaxNameBytes - suffix.size())) + suffix;
            // A name another set holds as its own is never handed out, even before that set's turn.
            if (holders.count(ascii_lower(candidate)) || !taken.insert(ascii_lower(candidate)).second) continue;
            names[i] = candidate;
            break;
        }
    }
    return names;
}

namespace {

// An entry larger than one read piece is judged by its first piece before the rest is inflated
// (a 1 MiB zip can hold a 1 GiB entry of zeros named like a map): "" when it may be read, else
// why not. Its header must name an image whose pixels its size could encode (twice the raw size:
// no PNG, JPEG, TIFF or EXR of an image needs more), or, for a TIFF whose header is not in the
// first piece (it may keep its directory at the end), the entry must be within what a set's file
// of that kind holds in practice (kUnprobed). Bytes that begin no image are refused at once.
std::string entry_beyond_its_image(const std::string& display, const std::vector<unsigned char>& bytes, size_t got,
                                   uint64_t size) {
    constexpr uint64_t kUnprobed = uint64_t{256} << 20;
    InputFile head;
    head.display = display;
    head.bytes = std::make_shared<std::vector<unsigned char>>(bytes.begin(), bytes.begin() + static_cast<long>(got));
    std::string error;
    const auto info = read_info(head, error);
    if (!info) {
        // Only a TIFF may keep its header (its directory) past the first piece; bytes that begin
        // no image at all (a zip bomb's zeros) are refused here, however large.
        const bool tiff = got >= 4 &&
                          (std::memcmp(bytes.data(), "II*\0", 4) == 0 || std::memcmp(bytes.data(), "MM\0*", 4) == 0 ||
                           std::memcmp(bytes.data(), "II+\0", 4) == 0 || std::memcmp(bytes.data(), "MM\0+", 4) == 0);
        if (tiff && size <= kUnprobed) return {};
        if (error.rfind(display + ": ", 0) == 0) error.erase(0, display.size() + 2);  // the caller names it
        return "its first " + std::to_string(got) + " bytes hold no image header matforge can read (" + error +
               "); the rest of its " + std::to_string(size) + " bytes was not read";
    }
    const uint64_t raw = uint64_t(info->width) * uint64_t(info->height) * uint64_t(info->channels) *
                         uint64_t(std::max(1, info->bit_depth / 8));
    if (size <= 2 * raw + (uint64_t{1} << 20)) return {};
    return "holds " + std::to_string(size) + " bytes for a " + std::to_string(info->width) + "x" +
           std::to_string(info->height) + " image, more than any encoding of it needs; not read";
}

}  // namespace

InputFile MaterialSource::open(const std::string& file) const {
    InputFile in;
    if (!is_zip) {
        in.path = root / file;
        in.display = (root / file).string();
        return in;
    }
    const std::string entry = zip_folder.empty() ? file : zip_folder + "/" + file;
    in.display = root.string() + "/" + entry;
    auto bytes = std::make_shared<std::vector<unsigned char>>();
    const ZipArchive::Entry* e = nullptr;
    if (archive)
        if (const auto it = archive->entries.find(entry); it != archive->entries.end()) e = &it->second;
    std::string error;
    if (!e) {
        in.open_error = "entry not found in the archive";
    } else if (!archive->with_handle(error, [&](zip_t* z) {
                   constexpr zip_uint64_t kMaxEntry = zip_uint64_t{1} << 31;  // 2 GiB cap on one entry
                   zip_stat_t st;
                   zip_file_t* f = nullptr;
                   if (zip_stat_index(z, e->index, 0, &st) != 0 || !(st.valid & ZIP_STAT_SIZE)) {
                       in.open_error = "entry not found in the archive";
                   } else if (e->symlink) {
                       in.open_error =
                           "a symbolic link stored in the archive, not a file (links in archives are never followed)";
                   } else if (st.size > kMaxEntry) {
                       in.open_error = "entry declares " + std::to_string(st.size) +
                                       " bytes, more than the 2 GiB limit";
                   } else if (!(f = zip_fopen_index(z, e->index, 0))) {
                       in.open_error = std::string("cannot read the entry (") + zip_strerror(z) + ")";
                   } else {
                       // The declared size is the archive's claim, not a fact: read in chunks and
                       // grow, so a forged header cannot make us allocate what the data does not hold.
                       constexpr size_t kChunk = size_t{1} << 20;
                       size_t got = 0;
                       bool probed = false;
                       for (;;) {
                           bytes->resize(got + kChunk);
                           const zip_int64_t n = zip_fread(f, bytes->data() + got, kChunk);
                           if (n < 0) {
                               in.open_error = std::string("corrupt entry (") + zip_file_strerror(f) + ")";
                               break;
                           }
                           if (n == 0) break;
                           got += static_cast<size_t>(n);
                           if (got > kMaxEntry) {
                               in.open_error = "entry inflates beyond the 2 GiB limit";
                               break;
                           }
                           if (!probed && st.size > kChunk && got >= kChunk) {
                               probed = true;
                               in.open_error = entry_beyond_its_image(in.display, *bytes, got, st.size);
                               if (!in.open_error.empty()) break;
                               // Judged plausible: room for all of it at once, not doubled as it grows.
                               bytes->reserve(static_cast<size_t>(st.size) + kChunk);
                           }
                       }
                       bytes->resize(got);
                       if (in.open_error.empty() && got != st.size)
                           in.open_error = "entry holds " + std::to_string(got) + " bytes, its header declares " +
                                           std::to_string(st.size);
                       zip_fclose(f);
                   }
               })) {
        in.open_error = "cannot open the archive (" + error + ")";
    }
    if (!in.open_error.empty()) bytes->clear();
    in.bytes = std::move(bytes);
    return in;
}

namespace {
// `p` made absolute, its links and dots resolved as far as it exists.
fs::path resolved(const fs::path& p) {
    std::error_code ec;
    return fs::weakly_canonical(fs::absolute(p, ec), ec);
}
// Whether `a` is `b` or lies inside it (both resolved).
bool within(const fs::path& a, const fs::path& b) {
    const fs::path rel = a.lexically_relative(b);
    return !rel.empty() && *rel.begin() != "..";
}
}  // namespace

std::string input_problem(const fs::path& input) {
    std::error_code ec;
    const auto st = fs::status(input, ec);
    if (fs::is_directory(st)) return {};
    if (fs::is_regular_file(st) && ascii_lower(input.extension().string()) == ".zip") return {};
    if (!fs::exists(st)) return input.string() + ": no such folder or .zip file";
    if (fs::is_regular_file(st))
        return input.string() + ": a file, not a folder or a .zip file; give the folder that holds the set (" +
               input.parent_path().string() + ")";
    return input.string() + ": not a folder or a .zip file";
}

std::string no_usable_input(const std::vector<fs::path>& inputs) {
    std::string all;
    for (const auto& i : inputs) {
        const std::string why = input_problem(i);
        if (why.empty()) return {};
        all += (all.empty() ? "" : "; ") + why;
    }
    return all;
}

std::string written_file_conflict(const fs::path& file, const std::vector<fs::path>& inputs,
                                  const std::vector<MaterialSource>& sets) {
    const fs::path f = resolved(file);
    const std::string rule = "; matforge never writes over what it reads: name a file outside the material sets";
    for (const auto& i : inputs)
        if (f == resolved(i)) return file.string() + " is the input " + i.string() + rule;
    for (const auto& s : sets) {
        const fs::path root = resolved(s.root);
        if (s.is_zip && f == root) return file.string() + " is the archive of the set '" + s.name + "'" + rule;
        if (!s.is_zip && f.parent_path() == root)
            return file.string() + " lies in the folder of the set '" + s.name + "' (" + s.display +
                   "), among its maps" + rule;
    }
    return {};
}

namespace {
// " is WHAT", " is inside WHAT SHOWN" or " holds WHAT SHOWN" for resolved paths `a` and `b` when
// one is within the other, else "".
std::string placement(const fs::path& a, const fs::path& b, const std::string& what, const std::string& shown) {
    if (a == b) return " is " + what;
    if (within(a, b)) return " is inside " + what + " " + shown;
    if (within(b, a)) return " holds " + what + " " + shown;
    return {};
}
}  // namespace

std::string cache_overlaps(const fs::path& cache, const fs::path& out_dir, const std::vector<fs::path>& inputs) {
    const fs::path c = resolved(cache);
    const std::string rule = "; the cache must be a folder of its own, outside the output folder and the inputs";
    if (std::string p = placement(c, resolved(out_dir), "the output folder", out_dir.string()); !p.empty())
        return "the cache " + cache.string() + p + rule;
    for (const auto& i : inputs) {
        const fs::path in = resolved(i);
        // Inside an input under a hidden folder (~/.cache/matforge in a walk of ~) is never read:
        // the walk skips hidden folders.
        bool hidden_below = false;
        if (within(c, in) && c != in)
            for (const auto& part : c.lexically_relative(in))
                hidden_below = hidden_below || part.string().front() == '.';
        if (hidden_below) continue;
        if (std::string p = placement(c, in, "the input", i.string()); !p.empty())
            return "the cache " + cache.string() + p + rule;
    }
    return {};
}

std::string output_overlaps_input(const fs::path& out_dir, const std::vector<fs::path>& inputs) {
    std::error_code ec;
    const fs::path out = fs::weakly_canonical(fs::absolute(out_dir, ec), ec);
    for (const auto& i : inputs) {
        const fs::path in = fs::weakly_canonical(fs::absolute(i, ec), ec);
        const fs::path rel = in.lexically_relative(out);
        if (!rel.empty() && *rel.begin() != "..")
            return "the output folder " + out_dir.string() + (rel == "." ? " is the input " : " holds the input ") +
                   i.string() + "; choose an output folder outside the inputs (or inside one)";
    }
    return {};
}

std::vector<MaterialSource> find_material_sets(const std::vector<fs::path>& inputs,
                                               const std::vector<fs::path>& exclude,
                                               std::vector<InputFailure>& failures, std::string* output_conflict,
                                               std::vector<std::string>* skipped) {
    std::vector<MaterialSource> sets;
    Scan scan{exclude, sets, failures, output_conflict, skipped, {}, {}, 0, {}};
    for (const auto& in : inputs) {
        scan.input = in.string();
        const size_t sets_before = sets.size(), failures_before = failures.size(), again = scan.reached_again;
        std::error_code ec;
        const bool seen_before = scan.seen.count(real_path(in)) > 0;
        if (fs::is_directory(in, ec)) {
            walk(scan, in);
        } else if (fs::is_regular_file(in, ec) && ascii_lower(in.extension().string()) == ".zip") {
            scan_zip(scan, in);
        } else {
            failures.push_back({in.string(), std::string(code::input_not_found), input_problem(in)});
            continue;
        }
        // Nothing found is not a pass: an input without a set fails, naming it (as a zip does).
        if (sets.size() == sets_before && failures.size() == failures_before && !seen_before &&
            scan.reached_again == again && fs::is_directory(in, ec)) {
            std::string why = "no file names a map role, e.g. _Color, _Normal, _Roughness, in a format matforge reads";
            if (!scan.lone.empty()) why = scan.lone.front();
            failures.push_back({in.string(), std::string(code::unrecognized_file),
                                in.string() + ": no material set found (" + why + ")"});
        } else if (skipped) {
            for (const auto& l : scan.lone) skipped->push_back(l);
        }
        scan.lone.clear();
    }
    std::vector<std::string> wanted;
    wanted.reserve(sets.size());
    for (const auto& s : sets) wanted.push_back(s.name);
    const std::vector<std::string> names = unique_names(wanted);
    for (size_t i = 0; i < sets.size(); ++i) sets[i].name = names[i];
    return sets;
}

std::string archive_library_version() { return std::string("libzip ") + zip_libzip_version(); }

}  // namespace mf
