// File-name discovery: newline-separated names (one folder's listing; the first line is the
// folder name), optionally followed by a line "%%sidecar NAME" and the text of that sidecar
// (glTF or Megascans JSON, or anything). Every name is classified; grouping must place each file
// in exactly one group (a licence file naming no group in every group); choosing per role, the
// preview and the provenance's evidence must name files of the set only; a sidecar's maps and
// previews are relative paths that stay inside the set.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "material/discovery.hpp"
#include "material/provenance.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string input(reinterpret_cast<const char*>(data), size);
    std::string text = input;
    std::vector<mf::SidecarRoles> sidecars;
    constexpr std::string_view kMarker = "\n%%sidecar ";
    if (const auto at = input.find(kMarker); at != std::string::npos) {
        text = input.substr(0, at);
        const auto name_start = at + kMarker.size();
        const auto name_end = std::min(input.find('\n', name_start), input.size());
        const std::string name = input.substr(name_start, name_end - name_start);
        const std::string content = name_end < input.size() ? input.substr(name_end + 1) : std::string();
        sidecars.push_back(mf::sidecar_roles(name, content));
        const auto inside = [](const std::string& f) {
            if (f.empty() || f.front() == '/' || f.find('\\') != std::string::npos) __builtin_trap();
            if (f == ".." || f.starts_with("../") || f.find("/../") != std::string::npos || f.ends_with("/.."))
                __builtin_trap();
        };
        for (const auto& m : sidecars.back().maps) {
            inside(m.file);
            if (m.match.sidecar != name) __builtin_trap();
        }
        for (const auto& f : sidecars.back().facts.previews) inside(f);
        text += "\n" + name;  // the sidecar is a file of the set
    }
    std::vector<std::string> lines;
    size_t start = 0;
    for (size_t p = 0; p <= text.size(); ++p)
        if (p == text.size() || text[p] == '\n') {
            lines.push_back(text.substr(start, p - start));
            start = p + 1;
        }
    const std::string folder = lines.front();
    std::set<std::string> unique(lines.begin() + 1, lines.end());  // a folder lists a name once
    unique.erase("");
    const std::vector<std::string> files(unique.begin(), unique.end());

    for (const auto& f : files) {
        (void)mf::is_image_file(f);
        (void)mf::is_clutter(f);
        (void)mf::is_sidecar_name(f);
        (void)mf::classify_name(f);
        (void)mf::material_stem(f);
        if (mf::resolution_hint(f) < 0) __builtin_trap();
    }

    std::multiset<std::string> grouped;
    const auto groups = mf::group_files(files, folder);
    for (const auto& g : groups) {
        grouped.insert(g.files.begin(), g.files.end());
        if (g.merge && (g.merge->spellings.size() < 2 || g.merge->spellings.size() != g.merge->files.size()))
            __builtin_trap();
        if (g.shared != (groups.size() > 1)) __builtin_trap();
    }
    for (const auto& f : files) {
        const size_t n = grouped.count(f);
        if (n != 1 && !(mf::is_licence_file_name(f) && n == groups.size())) __builtin_trap();
    }
    if (std::set<std::string>(grouped.begin(), grouped.end()).size() != files.size()) __builtin_trap();

    // Header facts derived from the name, absent for some: the ranking must cope with both.
    auto header = [](const std::string& f) -> std::optional<mf::HeaderInfo> {
        if (f.size() % 3 == 0) return std::nullopt;
        const int s = 1 << (f.size() % 13);
        return mf::HeaderInfo{s, s, 1 + static_cast<int>(f.size() % 4), f.size() % 2 ? 8 : 16, f.size() % 5 == 0};
    };
    const mf::SetDiscovery d = mf::discover_set(files, header, mf::ChoicePolicy{mf::NormalConvention::gl, 2048},
                                                sidecars);
    for (const auto& c : d.choices) {
        if (!unique.count(c.chosen.file) || c.chosen.match.role != c.role) __builtin_trap();
        for (const auto& r : c.rejected)
            if (!unique.count(r.file) || r.match.role != c.role) __builtin_trap();
    }
    for (const auto& f : d.findings)
        if (!f.file.empty() && !unique.count(f.file)) __builtin_trap();
    if (d.preview && (!unique.count(d.preview->file) || d.preview->match.role != mf::Role::preview)) __builtin_trap();
    // The provenance of the set, its licence files holding the names' own text.
    std::vector<mf::SetText> texts;
    for (const auto& f : files)
        if (mf::is_licence_file_name(f)) texts.push_back({f, input, ""});
    const mf::ProvenanceResult p = mf::find_provenance({files, d, sidecars, texts, false});
    if (p.provenance.licence.has_value() == !p.unknown.empty()) __builtin_trap();  // a licence, or why none
    if (p.provenance.licence && !p.provenance.licence->evidence.file.empty() &&
        !unique.count(p.provenance.licence->evidence.file))
        __builtin_trap();
    return 0;
}
