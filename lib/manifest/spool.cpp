#include "manifest/spool.hpp"

#include <algorithm>

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

std::optional<Manifest> merge_shards(const std::vector<std::string>& paths, MaterialSpool& spool, std::string& error) {
    std::vector<Manifest> heads;
    for (size_t i = 0; i < paths.size(); ++i) {
        auto head = read_manifest(
            paths[i], [&](Material&& m, std::string& e) { return spool.add(m, e, static_cast<int>(i)); }, error);
        if (!head) return std::nullopt;
        heads.push_back(std::move(*head));
    }
    auto merged = merge_heads(heads, paths, error);
    if (!merged) return std::nullopt;
    if (const auto dup = spool.sort()) {
        error = "material \"" + dup->name + "\" is in both " + paths[static_cast<size_t>(dup->first_part)] + " and " +
                paths[static_cast<size_t>(dup->second_part)];
        return std::nullopt;
    }
    return merged;
}

}  // namespace mf::manifest
