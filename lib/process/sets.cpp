#include "process/sets.hpp"

#include <zip.h>

#include <algorithm>
#include <map>
#include <set>

#include "material/discovery.hpp"

namespace mf {
namespace fs = std::filesystem;
namespace {

bool hidden(const std::string& name) { return name.empty() || name[0] == '.' || name == "__MACOSX"; }

// Folder -> its files, for a zip archive's entries.
std::map<std::string, std::vector<std::string>> zip_folders(const fs::path& zip_path, std::string& error) {
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
        // they are no part of a material set either.
        bool skip = name.front() == '/';
        size_t start = 0;
        for (size_t p = 0; p <= name.size(); ++p) {
            if (p == name.size() || name[p] == '/') {
                const std::string part = name.substr(start, p - start);
                if (part == ".." || hidden(part)) skip = true;
                start = p + 1;
            }
        }
        if (skip) continue;
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

void scan_zip(const fs::path& zip, std::vector<MaterialSource>& out, std::vector<SourceFailure>& failures) {
    std::string error;
    auto folders = zip_folders(zip, error);
    if (!error.empty()) {
        failures.push_back({zip.string(), std::string(code::unreadable_file), zip.string() + ": not a readable .zip (" + error + ")"});
        return;
    }
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

void scan_folder(const fs::path& dir, std::vector<MaterialSource>& out, std::vector<SourceFailure>& failures) {
    std::vector<std::string> files;
    std::error_code ec;
    for (fs::directory_iterator it(dir, fs::directory_options::skip_permission_denied, ec), end; !ec && it != end;
         it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (hidden(name)) continue;
        std::error_code fec;
        if (it->is_regular_file(fec)) {  // follows file symlinks; a dangling one is not regular
            if (name.size() > 4 && fs::path(name).extension() == ".zip") scan_zip(it->path(), out, failures);
            else files.push_back(name);
        }
    }
    std::sort(files.begin(), files.end());
    MaterialSource proto;
    proto.root = dir;
    proto.display = dir.string();
    add_groups(dir.filename().string(), files, proto, out);
}

void walk(const fs::path& root, const fs::path& exclude, std::vector<MaterialSource>& out,
          std::vector<SourceFailure>& failures) {
    scan_folder(root, out, failures);
    std::vector<fs::path> subdirs;
    std::error_code ec;
    for (fs::directory_iterator it(root, fs::directory_options::skip_permission_denied, ec), end; !ec && it != end;
         it.increment(ec)) {
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
    if (zip_t* z = zip_open(root.c_str(), ZIP_RDONLY, &err)) {
        zip_stat_t st;
        if (zip_stat(z, entry.c_str(), 0, &st) == 0 && (st.valid & ZIP_STAT_SIZE) &&
            st.size <= static_cast<zip_uint64_t>(1) << 31) {  // 2 GiB cap on one entry
            if (zip_file_t* f = zip_fopen(z, entry.c_str(), 0)) {
                bytes->resize(st.size);
                const zip_int64_t got = zip_fread(f, bytes->data(), st.size);
                if (got < 0 || static_cast<zip_uint64_t>(got) != st.size) bytes->clear();
                zip_fclose(f);
            }
        }
        zip_close(z);
    }
    in.bytes = std::move(bytes);  // empty bytes read as "empty file"
    return in;
}

std::vector<MaterialSource> find_material_sets(const std::vector<fs::path>& inputs, const fs::path& exclude,
                                               std::vector<SourceFailure>& failures) {
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
