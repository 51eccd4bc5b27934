// A flat folder of several materials: split by material name, and say when different spellings
// of a name were merged.
#include <algorithm>
#include <map>

#include "material/classify.hpp"
#include "material/discovery.hpp"
#include "material/provenance.hpp"

namespace mf {
namespace {

using naming::Kind;

// How one file spells its material's name.
struct Spelling {
    std::string text;                     // as written, tags included ("Metal_1K")
    std::string words;                    // material_stem ("Metal")
    std::vector<std::string> tags;        // lower-case tags in the name part ("1k")
    std::vector<std::string> separators;  // between consecutive words with no tag between
};

Spelling spelling_of(std::string_view file, const naming::NameAnalysis& a) {
    Spelling s;
    s.text = naming::name_spelling(file, a);
    s.words = naming::join_name(a.tokens, a.name_end);
    const auto stem = naming::stem_of(file);
    std::optional<size_t> prev_word;
    bool tag_since = false;
    for (size_t i = 0; i < a.name_end && i < a.tokens.size(); ++i) {
        const auto& t = a.tokens[i];
        if (t.kind != Kind::word) {
            s.tags.push_back(t.low);
            tag_since = true;
            continue;
        }
        if (prev_word && !tag_since) {
            const auto& p = a.tokens[*prev_word];
            s.separators.emplace_back(stem.substr(p.end, t.begin - p.end));
        }
        prev_word = i;
        tag_since = false;
    }
    return s;
}

std::optional<StemMerge> merge_of(const std::string& name,
                                  const std::vector<std::pair<std::string, Spelling>>& members) {
    std::map<std::string, std::pair<std::string, const Spelling*>> by_text;  // text -> first file
    for (const auto& [file, sp] : members) {
        auto [it, inserted] = by_text.try_emplace(sp.text, file, &sp);
        if (!inserted && file < it->second.first) it->second = {file, &sp};
    }
    if (by_text.size() < 2) return std::nullopt;
    StemMerge m;
    const Spelling* first = by_text.begin()->second.second;
    std::string listed;
    for (const auto& [text, entry] : by_text) {
        m.spellings.push_back(text);
        m.files.push_back(entry.first);
        const Spelling& sp = *entry.second;
        m.tags_differ = m.tags_differ || sp.tags != first->tags;
        m.spelling_differs = m.spelling_differs || sp.words != first->words || sp.separators != first->separators;
        listed += (listed.empty() ? "" : ", ") + text + " (" + entry.first + ")";
    }
    std::string what;
    if (m.tags_differ) what = "resolution/format tags";
    if (m.spelling_differs) what += std::string(what.empty() ? "" : " and ") + "letter case or separators";
    m.message = std::to_string(m.spellings.size()) + " spellings of a material name were grouped as '" + name +
                "': " + listed + "; they differ in " + what;
    return m;
}

// The material's name without Unreal's texture prefix: "T_OilyCloth_A.png" is a texture of the
// material OilyCloth (its Unreal material instance is MI_OilyCloth; the unreal preset writes
// T_OilyCloth_BC, not T_T_OilyCloth_BC). Only where an Unreal-style rule read the tag.
std::string unprefixed(const std::string& stem, const naming::NameAnalysis& a) {
    const bool unreal = a.tag && (a.tag->match.family == "unreal" || a.tag->match.family == "megascans");
    if (!unreal || a.name_end < 2 || a.tokens.empty() || a.tokens.front().text != "T") return stem;
    const std::string rest = naming::join_name(std::vector<naming::Token>(a.tokens.begin() + 1, a.tokens.end()),
                                               a.name_end - 1);
    return rest.empty() ? stem : rest;
}

}  // namespace

std::vector<FileGroup> group_files(const std::vector<std::string>& files, const std::string& fallback_name) {
    std::map<std::string, FileGroup> groups;  // by case-insensitive stem, separators unified
    std::map<std::string, std::vector<std::pair<std::string, Spelling>>> spellings;
    std::vector<std::string> loose;
    const bool billboards = billboards_only(files);
    for (const auto& file : files) {
        const auto a = naming::analyse(file);
        const bool clutter = a.clutter && !(billboards && a.clutter->kind == naming::ClutterKind::billboard);
        const bool has_role = is_image_file(file) && !clutter && a.tag;
        const std::string stem = has_role ? naming::join_name(a.tokens, a.name_end) : std::string();
        if (stem.empty()) {
            loose.push_back(file);
            continue;
        }
        const auto key = naming::normalized_key(stem);
        auto [it, inserted] = groups.try_emplace(key);
        if (inserted) it->second.name = unprefixed(stem, a);
        it->second.files.push_back(file);
        spellings[key].emplace_back(file, spelling_of(file, a));
    }
    if (groups.empty()) {
        if (files.empty()) return {};
        groups.emplace("", FileGroup{fallback_name, {}, std::nullopt});
    }
    for (const auto& file : loose) {
        // Keys and names compare with separators unified: "Wood-Planks 2K.json" belongs to
        // the stem "Wood_Planks".
        const auto key = naming::normalized_key(naming::base_name(file));
        auto target = groups.end();
        size_t best = 0;
        for (auto it = groups.begin(); it != groups.end(); ++it) {
            const auto& stem = it->first;
            if (stem.size() > best && key.starts_with(stem)) {
                best = stem.size();
                target = it;
            }
        }
        if (target != groups.end()) target->second.files.push_back(file);
        else if (is_licence_file_name(file))  // the folder's licence: every set's
            for (auto& g : groups) g.second.files.push_back(file);
        else groups.begin()->second.files.push_back(file);
    }
    std::vector<FileGroup> out;
    for (auto& [key, group] : groups) {
        std::sort(group.files.begin(), group.files.end());
        if (const auto it = spellings.find(key); it != spellings.end()) group.merge = merge_of(group.name, it->second);
        group.shared = groups.size() > 1;
        out.push_back(std::move(group));
    }
    return out;
}

}  // namespace mf
