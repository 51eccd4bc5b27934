#include "process/sets.hpp"

#include <zip.h>

#include <algorithm>
#include <map>
#include <set>

#include "core/files.hpp"
#include "material/discovery.hpp"

namespace mf {
namespace fs = std::filesystem;
namespace {

bool hidden(const std::string& name) { return name.empty() || name[0] == '.' || name == "__MACOSX"; }

// Folder -> its files, for a zip archive's entries. Entries named to climb out of the archive
// ("../x", "/abs/x") go to `unsafe`.
std::map<std::string, std::vector<std::string>> zip_folders(const fs::path& zip_path, std::string& error,
                                                            std::vector<std::string>& unsafe) {
    std::map<std::string, std::vector<std::string>> folders;
    int err = 0;
    zip_t* z = zip_open(zip_path.c_str(), ZIP_RDONLY, &err);
    if (!z) {
        zip_error_t ze;
        zip_error_init_with_code(&ze, err);
        error = zip_error_strerror(&ze);
        zip_error_fini(&ze);
        return folders;
    }
    const zip_int64_t n = zip_get_num_entries(z, 0);
    for (zip_int64_t i = 0; i < n; ++i) {
        const char* raw = zip_get_name(z, static_cast<zip_uint64_t>(i), ZIP_FL_ENC_GUESS);
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
        const auto slash = name.rfind('/');
        const std::string folder = slash == std::string::npos ? "" : name.substr(0, slash);
        folders[folder].push_back(slash == std::string::npos ? name : name.substr(slash + 1));
    }
    zip_close(z);
    return folders;
}

void add_groups(const std::string& fallback, const std::vector<std::string>& files,
                const MaterialSource& proto, std::vector<MaterialSource>& out) {
    for (auto& g : group_files(files, fallback)) {
        const bool any_role = std::any_of(g.files.begin(), g.files.end(),
                                          [](const std::string& f) { return classify_name(f).has_value(); });
        if (!any_role) continue;
        MaterialSource s = proto;
        s.name = g.name.empty() ? fallback : g.name;
        s.files = g.files;
        std::sort(s.files.begin(), s.files.end());
        out.push_back(std::move(s));
    }
}

void scan_zip(const fs::path& zip, std::vector<MaterialSource>& out, std::vector<InputFailure>& failures) {
    std::string error;
    std::vector<std::string> unsafe;
    auto folders = zip_folders(zip, error, unsafe);
    if (!error.empty()) {
        failures.push_back({zip.string(), std::string(code::unreadable_file), zip.string() + ": not a readable .zip (" + error + ")"});
        return;
    }
    for (const auto& name : unsafe)
        failures.push_back({zip.string(), std::string(code::unsafe_path),
                            zip.string() + ": entry '" + name + "' points outside the archive; skipped"});
    const size_t before = out.size();
    for (auto& [folder, files] : folders) {
        MaterialSource proto;
        proto.root = zip;
        proto.is_zip = true;
        proto.zip_folder = folder;
        proto.display = zip.string() + (folder.empty() ? "" : "/" + folder);
        const std::string fallback = folder.empty() ? zip.stem().string() : fs::path(folder).filename().string();
        add_groups(fallback, files, proto, out);
    }
    if (out.size() == before)
        failures.push_back({zip.string(), std::string(code::unrecognized_file), zip.string() + ": the archive holds no recognizable material maps"});
}

// Whether a glTF or Megascans sidecar in the folder names one of its images: then its maps are
// the set's whatever their names say (file names need no role tag), and the folder is one set.
bool sidecar_names_a_map(const fs::path& dir, const std::vector<std::string>& files) {
    for (const std::string& f : files) {
        if (!is_sidecar_name(f)) continue;
        std::error_code ec;
        if (!fs::is_regular_file(dir / f, ec) || fs::file_size(dir / f, ec) > kSidecarMaxBytes) continue;
        std::vector<unsigned char> bytes;
        std::string error;
        if (!read_file(dir / f, bytes, error)) continue;
        const SidecarRoles roles = sidecar_roles(f, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
        for (const SidecarMap& m : roles.maps)
            if (std::binary_search(files.begin(), files.end(), m.file)) return true;
    }
    return false;
}

void scan_folder(const fs::path& dir, std::vector<MaterialSource>& out, std::vector<InputFailure>& failures) {
    std::vector<std::string> files;
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
        if (fs::is_regular_file(st) && name.size() > 4 && fs::path(name).extension() == ".zip")
            scan_zip(it->path(), out, failures);
        else
            files.push_back(name);
    }
    if (ec) {  // unreadable folder, path beyond PATH_MAX, I/O error: reported, not silently lost
        failures.push_back({dir.string(), std::string(code::unreadable_file),
                            dir.string() + ": cannot list the folder (" + ec.message() + ")"});
        return;
    }
    std::sort(files.begin(), files.end());
    MaterialSource proto;
    proto.root = dir;
    proto.display = dir.string();
    if (sidecar_names_a_map(dir, files)) {  // the sidecar defines the set: one material, the folder's
        MaterialSource s = proto;
        s.name = dir.filename().string();
        s.files = files;
        out.push_back(std::move(s));
        return;
    }
    add_groups(dir.filename().string(), files, proto, out);
}

void walk(const fs::path& root, const fs::path& exclude, std::vector<MaterialSource>& out,
          std::vector<InputFailure>& failures) {
    scan_folder(root, out, failures);
    std::vector<fs::path> subdirs;
    std::error_code ec;
    for (fs::directory_iterator it(root, ec), end; !ec && it != end; it.increment(ec)) {
        std::error_code fec;
        // Real folders only: a symlink to a folder could loop back to an ancestor.
        if (it->is_directory(fec) && !it->is_symlink(fec) && !hidden(it->path().filename().string())) {
            if (!exclude.empty() && fs::equivalent(it->path(), exclude, fec)) continue;
            subdirs.push_back(it->path());
        }
    }
    std::sort(subdirs.begin(), subdirs.end());
    for (auto& d : subdirs) walk(d, exclude, out, failures);
}

}  // namespace

std::string safe_name(const std::string& name) {
    std::string s;
    for (unsigned char c : name) s += (std::isalnum(c) || c == '_' || c == '-' || c == '.') ? static_cast<char>(c) : '_';
    while (!s.empty() && s.front() == '.') s.erase(0, 1);
    if (s.size() > 96) s.resize(96);
    if (s.empty()) s = "material";
    return s;
}

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
    int err = 0;
    zip_t* z = zip_open(root.c_str(), ZIP_RDONLY, &err);
    if (!z) {
        in.open_error = "cannot open the archive";
    } else {
        constexpr zip_uint64_t kMaxEntry = zip_uint64_t{1} << 31;  // 2 GiB cap on one entry
        zip_stat_t st;
        zip_file_t* f = nullptr;
        if (zip_stat(z, entry.c_str(), 0, &st) != 0 || !(st.valid & ZIP_STAT_SIZE)) {
            in.open_error = "entry not found in the archive";
        } else if (st.size > kMaxEntry) {
            in.open_error = "entry declares " + std::to_string(st.size) + " bytes, more than the 2 GiB limit";
        } else if (!(f = zip_fopen(z, entry.c_str(), 0))) {
            in.open_error = std::string("cannot read the entry (") + zip_strerror(z) + ")";
        } else {
            // The declared size is the archive's claim, not a fact: read in chunks and grow, so a
            // forged header cannot make us allocate what the data does not hold.
            constexpr size_t kChunk = size_t{1} << 20;
            size_t got = 0;
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
            }
            bytes->resize(got);
            if (in.open_error.empty() && got != st.size)
                in.open_error = "entry holds " + std::to_string(got) + " bytes, its header declares " +
                                std::to_string(st.size);
            zip_fclose(f);
        }
        zip_close(z);
    }
    if (!in.open_error.empty()) bytes->clear();
    in.bytes = std::move(bytes);
    return in;
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

std::vector<MaterialSource> find_material_sets(const std::vector<fs::path>& inputs, const fs::path& exclude,
                                               std::vector<InputFailure>& failures) {
    std::vector<MaterialSource> sets;
    for (const auto& in : inputs) {
        std::error_code ec;
        if (fs::is_directory(in, ec)) {
            walk(in, exclude, sets, failures);
        } else if (fs::is_regular_file(in, ec) && in.extension() == ".zip") {
            scan_zip(in, sets, failures);
        } else {
            failures.push_back({in.string(), std::string(code::input_not_found),
                                in.string() + ": no such folder or .zip file"});
        }
    }
    // Unique, filesystem-safe names; order of discovery (sorted paths) decides the suffixes.
    std::map<std::string, int> seen;
    for (auto& s : sets) {
        std::string base = safe_name(s.name), name = base;
        std::string lower = name;
        std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
        if (int n = ++seen[lower]; n > 1) name = base + "_" + std::to_string(n);
        s.name = name;
    }
    return sets;
}

}  // namespace mf
