#include "generate.hpp"

#include <map>

#include "files.hpp"
#include "text.hpp"

namespace gen {

namespace fs = std::filesystem;

namespace {

// Writes one set's files under `dir`; bakes each resolution the set uses once.
bool write_set_files(const SetDef& set, const fs::path& dir, std::string& err) {
    std::map<int, Baked> bakes;
    auto baked = [&](int n) -> const Baked& {
        auto it = bakes.find(n);
        if (it == bakes.end()) it = bakes.emplace(n, bake(*set.material, n)).first;
        return it->second;
    };
    for (const FileDef& f : set.files) {
        const fs::path path = dir / f.path;
        fs::create_directories(path.parent_path());
        const Pixels px = f.map == Map::preview ? render_preview(baked(128), f.size) : extract(baked(f.size), f.map);
        if (!write_image(path, px, f.enc, is_color(f.map), err)) return false;
    }
    for (const TextDef& t : set.texts)
        if (!write_text(dir / t.path, text_content(set, t.kind), err)) return false;
    return true;
}

}  // namespace

bool generate_set(const fs::path& out, const SetDef& set, std::string& err) {
    const fs::path target = out / set.root;
    fs::remove_all(target);
    if (target.extension() != ".zip") {
        fs::create_directories(target);
        return write_set_files(set, target, err);
    }
    const fs::path staged = out / (".staging-" + target.stem().string());
    fs::remove_all(staged);
    fs::create_directories(staged);
    const bool ok = write_set_files(set, staged, err) && write_zip(staged, target, err);
    fs::remove_all(staged);
    return ok;
}

}  // namespace gen
