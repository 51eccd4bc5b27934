#include "manifest/spool.hpp"

#include <algorithm>

#include "core/files.hpp"
#include "core/json.hpp"

namespace mf::manifest {

std::unique_ptr<MaterialSpool> MaterialSpool::open(const std::filesystem::path& dir, std::string& error) {
    auto text = TextSpool::open(dir, error);
    if (!text) return nullptr;
    return std::unique_ptr<MaterialSpool>(new MaterialSpool(std::move(text)));
}

bool MaterialSpool::add(const Material& m, std::string& error, int part) {
    const auto piece = text_->append(array_element_text(to_json(m)), error);
    if (!piece) return false;
    Entry e{m.name, "", *piece, part};
    for (const MaterialFile& f : m.material_files)
        if (f.format == "gltf") e.gltf = f.file;
    std::lock_guard lock(mutex_);
    entries_.push_back(std::move(e));
    return true;
}

size_t MaterialSpool::size() const {
    std::lock_guard lock(mutex_);
    return entries_.size();
}

std::optional<MaterialSpool::Duplicate> MaterialSpool::sort() {
    std::lock_guard lock(mutex_);
    // Stable: of two entries of one name, the one added first is named first.
    std::stable_sort(entries_.begin(), entries_.end(), [](const Entry& a, const Entry& b) { return a.name < b.name; });
    const auto dup = std::adjacent_find(entries_.begin(), entries_.end(),
                                        [](const Entry& a, const Entry& b) { return a.name == b.name; });
    if (dup == entries_.end()) return std::nullopt;
    return Duplicate{dup->name, dup->part, std::next(dup)->part};
}

bool MaterialSpool::for_each(const std::function<bool(Material&&)>& fn, std::string& error) const {
    for (size_t i = 0; i < entries_.size(); ++i) {
        const auto text = text_->read(entries_[i].piece, error);
        if (!text) return false;
        const auto j = parse_json(*text, "a spooled material", error);
        if (!j) return false;
        auto m = material_from_json(*j, "materials[" + std::to_string(i) + "]", error);
        if (!m || !fn(std::move(*m))) return false;
    }
    return true;
}

bool MaterialSpool::write_manifest(const Manifest& head, const ByteSink& sink, std::string& error) const {
    Manifest bare = head;  // the head's text never holds materials
    bare.materials.clear();
    return write_json_text(to_json(bare),
                           {{"materials", entries_.size(),
                             [&](size_t i, const ByteSink& out) {
                                 return text_->copy(entries_[i].piece, out, error);
                             }}},
                           sink);
}

namespace {

// A file a part lists: inside the output folder, a regular file (never through a link), and the
// bytes its sha256 says. "" or what is wrong.
std::string listed_file_problem(const std::filesystem::path& dir, const std::string& file, const std::string& sha) {
    const auto rel = path_inside(file);
    if (!rel) return "\"" + file + "\" is not a path inside the output folder";
    std::error_code ec;
    const auto st = std::filesystem::symlink_status(dir / *rel, ec);
    if (!std::filesystem::is_regular_file(st)) return *rel + ": not a regular file in the output folder";
    std::string error;
    const auto have = sha256_of_file(dir / *rel, error);
    if (!have) return error;
    if (*have != sha) return *rel + ": its bytes do not hash to the sha256 the part lists (changed or edited)";
    return {};
}

}  // namespace

std::optional<Manifest> merge_shards(const std::vector<std::string>& paths, const std::filesystem::path& dir,
                                     MaterialSpool& spool, std::string& error, const PartObserver& seen) {
    std::vector<Manifest> heads;
    for (size_t i = 0; i < paths.size(); ++i) {
        size_t materials = 0;
        auto head = read_manifest(
            paths[i],
            [&](Material&& m, std::string& e) {
                ++materials;
                if (seen.material) seen.material(i, m);
                return spool.add(m, e, static_cast<int>(i));
            },
            error);
        if (!head) return std::nullopt;
        // Each set of the shard is a material, or a failure when nothing of it could be read.
        if (head->shard && (materials > static_cast<size_t>(head->shard->sets) ||
                            materials + head->failures.size() < static_cast<size_t>(head->shard->sets))) {
            error = paths[i] + ": holds " + std::to_string(materials) + " materials and " +
                    std::to_string(head->failures.size()) + " failures for the " + std::to_string(head->shard->sets) +
                    " sets its shard was given (an incomplete or edited part); run that shard again";
            return std::nullopt;
        }
        if (seen.head) seen.head(i, *head);
        heads.push_back(std::move(*head));
    }
    auto merged = merge_heads(heads, paths, error);
    if (!merged) return std::nullopt;
    if (const auto dup = spool.sort()) {
        error = "material \"" + dup->name + "\" is in both " + paths[static_cast<size_t>(dup->first_part)] + " and " +
                paths[static_cast<size_t>(dup->second_part)];
        return std::nullopt;
    }
    // The parts make one run: every file they list must be there, as they list it.
    std::string problem;
    const bool listed_ok = spool.for_each(
        [&](Material&& m) {
            for (const Output& o : m.outputs)
                if (problem = listed_file_problem(dir, o.file, o.sha256); !problem.empty()) break;
            for (const MaterialFile& f : m.material_files)
                if (problem.empty()) problem = listed_file_problem(dir, f.file, f.sha256);
            if (!problem.empty()) problem = "material \"" + m.name + "\": " + problem;
            return problem.empty();
        },
        error);
    if (!problem.empty()) {
        error = problem;
        return std::nullopt;
    }
    if (!listed_ok) return std::nullopt;
    return merged;
}

}  // namespace mf::manifest
