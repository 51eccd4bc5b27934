// File-name discovery: newline-separated names (one folder's listing; the first line is the
// folder name). Every name is classified; grouping must place each file in exactly one group;
// choosing per role must name files of the set only.
#include <cstddef>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "material/discovery.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
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
        (void)mf::classify_name(f);
        (void)mf::material_stem(f);
        if (mf::resolution_hint(f) < 0) __builtin_trap();
    }

    size_t grouped = 0;
    for (const auto& g : mf::group_files(files, folder)) grouped += g.files.size();
    if (grouped != files.size()) __builtin_trap();

    // Header facts derived from the name, absent for some: the ranking must cope with both.
    auto header = [](const std::string& f) -> std::optional<mf::HeaderInfo> {
        if (f.size() % 3 == 0) return std::nullopt;
        const int s = 1 << (f.size() % 13);
        return mf::HeaderInfo{s, s, 1 + static_cast<int>(f.size() % 4), f.size() % 2 ? 8 : 16, f.size() % 5 == 0};
    };
    const mf::SetDiscovery d = mf::discover_set(files, header, mf::ChoicePolicy{mf::NormalConvention::gl, 2048});
    for (const auto& c : d.choices) {
        if (!unique.count(c.chosen.file)) __builtin_trap();
        for (const auto& r : c.rejected)
            if (!unique.count(r.file)) __builtin_trap();
    }
    for (const auto& s : d.sources)
        if (!unique.count(s.file)) __builtin_trap();
    return 0;
}
