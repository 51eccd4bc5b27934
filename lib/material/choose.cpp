// One set: classify every file, rank the candidates of each role, explain every choice.
#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <tuple>

#include "core/text.hpp"
#include "findings/catalog.hpp"
#include "material/classify.hpp"
#include "material/discovery.hpp"
#include "material/families.hpp"
#include "material/provenance.hpp"
#include "material/routing.hpp"

namespace mf {
namespace {

using naming::extension_of;
using naming::lower_copy;
using naming::RoleTag;

// Lossless first, then lossy; the order of the header's contract (exr tif png tga bmp jpg webp),
// with the other readable formats placed by how much they lose. WebP after JPEG: no vendor ships
// WebP (ambientCG, Poly Haven, 3dtextures.me, Textures.com: JPEG or PNG), so a WebP beside a JPEG
// of the same map is a copy someone re-encoded from it.
int format_rank(std::string_view file) {
    static constexpr std::array<std::string_view, 12> kOrder{"exr", "tif", "tiff", "png",  "tga",  "bmp",
                                                             "psd", "hdr", "jpg",  "jpeg", "webp", "dds"};
    const auto ext = lower_copy(extension_of(file));
    const auto it = std::find(kOrder.begin(), kOrder.end(), ext);
    int rank = static_cast<int>(it - kOrder.begin());
    if (ext == "tiff") rank -= 1;  // same rank as tif
    if (ext == "jpeg") rank -= 1;  // same rank as jpg
    return rank;
}

struct Ranked {
    Candidate cand;
    bool stray = false;   // another material's map beside the one a sidecar names for the role
    int normal_rank = 0;  // 0 policy's convention, 1 other known, 2 unknown
    // A bump map as the height: a displacement map of the set comes first, whatever its size
    // (Poliigon's BUMP is detail for bump mapping, its DISP the surface's height).
    bool bump = false;
    bool over_limit = false;
    int size = 0;  // longest side, header else name hint; 0 unknown
    int format = 0;
    int depth = 0;

    // Smaller is better.
    auto key() const {
        return std::make_tuple(stray, normal_rank, bump, over_limit, over_limit ? size : -size, format, -depth,
                               std::string_view(cand.file));
    }
};

Ranked rank_candidate(const Candidate& c, const ChoicePolicy& policy) {
    Ranked r;
    r.cand = c;
    if (c.match.role == Role::normal) {
        const auto n = c.match.normal;
        const bool preferred = n != NormalConvention::unknown && n == policy.preferred_normal;
        r.normal_rank = preferred ? 0 : n != NormalConvention::unknown ? 1 : 2;
    }
    if (c.match.role == Role::height) {
        const std::string rule = lower_copy(c.match.rule);
        r.bump = rule.find("bump", rule.find(':') + 1) != std::string::npos;
    }
    r.size = c.header.width > 0 || c.header.height > 0 ? std::max(c.header.width, c.header.height)
                                                       : resolution_hint(c.file);
    r.over_limit = policy.max_size > 0 && r.size > policy.max_size;
    r.format = format_rank(c.file);
    r.depth = c.header.bit_depth > 0 ? c.header.bit_depth : naming::name_bit_depth(naming::analyse(c.file).tokens);
    return r;
}

// Why `a` ranks before `b`: the first criterion that separates them.
std::string why_first(const Ranked& a, const Ranked& b, const ChoicePolicy& policy) {
    const auto conv = [](const Ranked& r) { return std::string(convention_name(r.cand.match.normal)); };
    if (a.stray != b.stray)
        return "the sidecar " + a.cand.match.sidecar + " names it, and " + b.cand.file +
               " is a map of another material name";
    if (a.normal_rank != b.normal_rank)
        return a.normal_rank == 0 ? "its normal convention (" + conv(a) + ") is the preset's"
                                  : "its name states a normal convention (" + conv(a) + ")";
    if (a.bump != b.bump) return "a displacement map is the height; a bump map is detail for bump mapping";
    if (a.over_limit != b.over_limit) return "it fits the size limit of " + std::to_string(policy.max_size) + " px";
    if (a.size != b.size)
        return a.over_limit
                   ? "it is the smallest above the size limit (" + std::to_string(a.size) + " px vs " +
                         std::to_string(b.size) + " px)"
                   : "it is the largest (" + std::to_string(a.size) + " px vs " + std::to_string(b.size) + " px)";
    if (a.format != b.format) {
        const std::string fa = lower_copy(extension_of(a.cand.file)), fb = lower_copy(extension_of(b.cand.file));
        return "its format (" + fa + ") ranks above " + fb +
               (fb == "webp" && (fa == "jpg" || fa == "jpeg")
                    ? " (the vendor's own: no vendor ships WebP, so a WebP twin is a re-encoded copy)"
                    : " (lossless first)");
    }
    if (a.depth != b.depth)
        return "higher bit depth (" + std::to_string(a.depth) + " vs " + std::to_string(b.depth) + ")";
    return "equal otherwise; first by name";
}

std::string why_provider(Role out, const Route& a, const Route& b) {
    const auto name = [](Role r) { return std::string(role_name(r)); };
    if (a.from == out && traits(b.from).packed)
        return "a dedicated " + name(out) + " map beats the packed " + name(b.from) + " map";
    if (a.from == out && b.from == Role::gloss) return "a roughness map beats a gloss map";
    if (traits(a.from).packed && b.from == Role::gloss)
        return "the packed " + name(a.from) + " map's roughness beats a gloss map (no inversion)";
    return "the " + name(a.from) + " map comes before the " + name(b.from) + " map";
}

// Everything one AMBIGUOUS_MAP says; built up per role, emitted once.
struct Ambiguity {
    std::vector<std::string> candidates;  // chosen first
    std::string chosen;
    std::vector<std::string> reasons;

    void add(const std::string& file) {
        if (std::find(candidates.begin(), candidates.end(), file) == candidates.end()) candidates.push_back(file);
    }
    void put_first(const std::string& file) {
        std::erase(candidates, file);
        candidates.insert(candidates.begin(), file);
    }
};

std::string join(const std::vector<std::string>& parts, std::string_view sep) {
    std::string out;
    for (size_t i = 0; i < parts.size(); ++i) out += (i ? std::string(sep) : "") + parts[i];
    return out;
}

Finding ambiguity_finding(Role role, const Ambiguity& a) {
    const std::string r(role_name(role));
    const auto reason = join(a.reasons, "; ");
    return finding(code::ambiguous_map, r, a.chosen,
                   std::to_string(a.candidates.size()) + " files could be the " + r + " map (" +
                       join(a.candidates, ", ") + "); chose " + a.chosen + ": " + reason,
                   {{"candidates", a.candidates}, {"chosen", a.chosen}, {"reason", reason}});
}

Finding unrecognized_finding(const std::string& file, std::string_view reason) {
    return finding(code::unrecognized_file, "", file, std::string(reason) + "; not used as a map",
                   {{"reason", std::string(reason)}});
}

// The set's convention: the family compatible with the most files; ties go to the family more
// files name distinctively (only it has the rule), then to the one whose layout more names
// follow, then to priority order. A family that is not compatible with a strict majority of the
// maps means a mixed set: "generic".
std::string vote_convention(const std::vector<RoleTag>& tags) {
    std::tuple<int, int, int> best{0, 0, 0};
    std::string_view winner = "generic";
    for (size_t fi = 0; fi < naming::kGenericFamily; ++fi) {
        const auto name = naming::kFamilies[fi].name;
        int votes = 0, distinct = 0, fitting = 0;
        for (const auto& t : tags) {
            const bool in = std::find(t.families.begin(), t.families.end(), name) != t.families.end();
            votes += in;
            distinct += in && t.families.size() == 1;
            fitting += std::find(t.fitting.begin(), t.fitting.end(), name) != t.fitting.end();
        }
        const std::tuple<int, int, int> score{votes, distinct, fitting};
        if (score > best) {
            best = score;
            winner = name;
        }
    }
    const auto votes = static_cast<size_t>(std::get<0>(best));
    return votes * 2 > tags.size() ? std::string(winner) : "generic";
}

// The role every file of the set named by a sidecar takes. A Megascans JSON goes before a glTF
// (it describes the maps themselves, a glTF one use of them), then the order given; the first
// sidecar to name a file decides. A path that is not a file of the set matches the one file
// with that base name, if exactly one has it (a JSON written beside "Textures/…" may name the
// maps without the folder).
std::map<std::string, NameMatch> sidecar_matches(const std::vector<std::string>& set_files,
                                                 const std::vector<SidecarRoles>& sidecars,
                                                 std::set<std::string>& used) {
    std::set<std::string> in_set(set_files.begin(), set_files.end());
    std::map<std::string, std::vector<std::string>> by_base;
    for (const auto& f : set_files) by_base[std::string(naming::base_name(f))].push_back(f);
    std::vector<const SidecarRoles*> order;
    order.reserve(sidecars.size());
    for (const auto& s : sidecars) order.push_back(&s);
    const auto rank = [](SidecarKind k) { return k == SidecarKind::megascans ? 0 : k == SidecarKind::gltf ? 1 : 2; };
    std::stable_sort(order.begin(), order.end(),
                     [&](const SidecarRoles* a, const SidecarRoles* b) { return rank(a->kind) < rank(b->kind); });
    std::map<std::string, NameMatch> out;
    for (const SidecarRoles* s : order)
        for (const auto& m : s->maps) {
            std::string file = m.file;
            if (!in_set.count(file)) {
                const auto it = by_base.find(std::string(naming::base_name(file)));
                if (it == by_base.end() || it->second.size() != 1) continue;
                file = it->second.front();
            }
            if (!is_image_file(file)) continue;
            used.insert(s->source);
            out.try_emplace(file, m.match);
        }
    return out;
}

// The family's name with static storage (RoleTag keeps views), "generic" when unknown.
std::string_view family_view(std::string_view name) {
    for (const auto& f : naming::kFamilies)
        if (f.name == name) return f.name;
    return naming::kFamilies[naming::kGenericFamily].name;
}

// Unreal-style letters whose meaning differs between families: Epic's style guide has "_D" base
// colour and "_A" opacity, Megascans' own export "_A" albedo and "_D" displacement. The pixels
// decide: a colour "_A" is the albedo (an opacity mask is never a colour image), and a grey
// "_D" beside it is then the displacement.
void decide_by_pixels(std::map<Role, std::vector<Ranked>>& by_role, const PixelProbe& colour) {
    if (!colour) return;
    const auto letter = [](const Ranked& r, std::string_view rule) { return r.cand.match.rule == rule; };
    auto take = [&](Role from, std::string_view rule, Role to, const char* new_rule, bool want_colour) {
        bool moved = false;
        auto it = by_role.find(from);
        if (it == by_role.end()) return false;
        auto& list = it->second;
        for (size_t i = 0; i < list.size();) {
            if (!letter(list[i], rule) || colour(list[i].cand.file) != want_colour) {
                ++i;
                continue;
            }
            Ranked r = std::move(list[i]);
            list.erase(list.begin() + static_cast<std::ptrdiff_t>(i));
            r.cand.match.role = to;
            r.cand.match.family = "megascans";
            r.cand.match.rule = new_rule;
            by_role[to].push_back(std::move(r));
            moved = true;
        }
        if (list.empty()) by_role.erase(from);
        return moved;
    };
    if (take(Role::opacity, "unreal:_A", Role::albedo, "megascans:_A (a colour image: the albedo, not an opacity mask)",
             true))
        take(Role::albedo, "unreal:_D", Role::height,
             "megascans:_D (a grey image beside a colour _A albedo: the displacement)", false);
}

// A map named for a scalar role whose pixels are a tangent-space normal map, in a set without a
// normal map, is its normal map (Godot's demo material_testers: "rock_metal.jpg" is the
// normal_texture of its rock.tres; read as metalness, the rock was a shiny metal without relief).
// The first such file, in role then rank order; ROLE_FROM_PIXELS (warning) says so.
void normal_by_pixels(std::map<Role, std::vector<Ranked>>& by_role, const PixelProbe& normal,
                      std::vector<Finding>& findings) {
    if (!normal || by_role.count(Role::normal)) return;
    for (const Role from : {Role::metalness, Role::roughness, Role::gloss, Role::occlusion, Role::height, Role::opacity,
                            Role::specular, Role::cavity}) {
        const auto it = by_role.find(from);
        if (it == by_role.end()) continue;
        auto& list = it->second;
        for (size_t i = 0; i < list.size(); ++i) {
            if (!list[i].cand.match.sidecar.empty() || normal(list[i].cand.file) != true) continue;
            Ranked r = std::move(list[i]);
            list.erase(list.begin() + static_cast<std::ptrdiff_t>(i));
            if (list.empty()) by_role.erase(it);
            const std::string named(role_name(from));
            findings.push_back(finding(code::role_from_pixels, "normal", r.cand.file,
                                       r.cand.file + ": named " + named + " (" + r.cand.match.rule +
                                           ") but its pixels are a tangent-space normal map (X/Y centred, pointing "
                                           "up, not grey) and the set has no other: read as its normal map",
                                       {{"named", named}, {"rule", r.cand.match.rule}}));
            r.cand.match.role = Role::normal;
            r.cand.match.rule += " (its pixels: a tangent-space normal map)";
            by_role[Role::normal].push_back(std::move(r));
            return;
        }
    }
}

// Object-space normal maps (baked for one mesh) are never the material's tangent-space normal
// map: those the name calls object space, and, beside one the name calls tangent space, any
// other normal map whose name states no space or convention ("rock_nm" beside "rock_nm_tangent").
void keep_object_space_out(std::map<Role, std::vector<Ranked>>& by_role, std::vector<Finding>& unrecognized) {
    const auto it = by_role.find(Role::normal);
    if (it == by_role.end()) return;
    auto& list = it->second;
    const auto tangent = std::find_if(list.begin(), list.end(),
                                      [](const Ranked& r) { return r.cand.match.space == NormalSpace::tangent; });
    const std::string tangent_file = tangent == list.end() ? std::string() : tangent->cand.file;
    std::erase_if(list, [&](const Ranked& r) {
        const NameMatch& m = r.cand.match;
        std::string why;
        if (m.space == NormalSpace::object) why = "an object-space normal map (its name says so)";
        else if (!tangent_file.empty() && m.space == NormalSpace::unknown && m.normal == NormalConvention::unknown)
            why = "taken as the object-space normal map beside the tangent-space " + tangent_file;
        if (why.empty()) return false;
        unrecognized.push_back(unrecognized_finding(
            r.cand.file, why + "; kept out of the normal slot (the material's normal map is tangent space)"));
        return true;
    });
    if (list.empty()) by_role.erase(it);
}

// Where a sidecar names a file for a role, a candidate of another material name for that role
// is a stray (another id's map left in the folder): it ranks after every named one.
void mark_strays(std::map<Role, std::vector<Ranked>>& by_role) {
    for (auto& [role, list] : by_role) {
        std::set<std::string> named_stems;
        for (const auto& r : list)
            if (!r.cand.match.sidecar.empty()) named_stems.insert(fold_case(material_stem(r.cand.file)));
        if (named_stems.empty()) continue;
        for (auto& r : list)
            r.stray = r.cand.match.sidecar.empty() && !named_stems.count(fold_case(material_stem(r.cand.file)));
    }
}

// A picture of the material its vendor ships (discovery.hpp SetDiscovery::preview).
struct PreviewCandidate {
    std::string file;
    int rank = 0;      // -1 a sidecar lists it, else preview_rank's word (0: ambientCG's "<id>.png")
    std::string stem;  // the material name the file names ("" none)
    std::string family, rule;
};

// The set's preview among `found`: a candidate that names the set's material (a stem of its
// maps), or no material where the folder is the set's alone; the plainest, then the largest.
std::optional<Candidate> choose_preview(const std::vector<PreviewCandidate>& found,
                                        const std::set<std::string>& map_stems, const ChoicePolicy& policy,
                                        const std::function<std::optional<HeaderInfo>(const std::string&)>& header) {
    std::optional<Candidate> best;
    std::tuple<int, int, std::string> best_key;
    for (const PreviewCandidate& p : found) {
        const bool named = !p.stem.empty();
        if (p.rank >= 0 && (named ? !map_stems.count(naming::normalized_key(p.stem)) : policy.shared_folder)) continue;
        Candidate c;
        c.file = p.file;
        c.match.role = Role::preview;
        c.match.family = p.family;
        c.match.rule = p.rule;
        if (header)
            if (auto h = header(p.file)) c.header = *h;
        const std::tuple<int, int, std::string> key{p.rank, -std::max(c.header.width, c.header.height), p.file};
        if (!best || key < best_key) {
            best = std::move(c);
            best_key = key;
        }
    }
    return best;
}

}  // namespace

SetDiscovery discover_set(const std::vector<std::string>& files,
                          const std::function<std::optional<HeaderInfo>(const std::string&)>& header,
                          const ChoicePolicy& policy, const std::vector<SidecarRoles>& sidecars,
                          const PixelProbe& colour, const PixelProbe& normal) {
    SetDiscovery out;
    std::vector<std::string> sorted = files;  // directory order must not change the result
    std::sort(sorted.begin(), sorted.end());
    sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());

    const bool billboards = billboards_only(sorted);  // a billboard's own folder: its maps are maps
    std::set<std::string> used_sidecars;
    const auto from_sidecar = sidecar_matches(sorted, sidecars, used_sidecars);
    std::map<std::string, const SidecarRoles*> sidecar_files;
    for (const auto& s : sidecars) sidecar_files.try_emplace(s.source, &s);

    std::vector<Finding> unrecognized;
    std::vector<std::pair<std::string, size_t>> untagged;  // images whose names state no role, their finding
    std::vector<PreviewCandidate> previews;
    std::vector<RoleTag> tags;
    std::map<Role, std::vector<Ranked>> by_role;
    auto add_candidate = [&](Candidate c) {
        if (header)
            if (auto h = header(c.file)) c.header = *h;
        by_role[c.match.role].push_back(rank_candidate(c, policy));
    };
    for (const auto& file : sorted) {
        if (const auto sc = sidecar_files.find(file); sc != sidecar_files.end()) {
            if (used_sidecars.count(file)) continue;  // read for its roles: recognized
            const auto& err = sc->second->error;
            unrecognized.push_back(unrecognized_finding(file, err.empty() ? "sidecar naming no map of this set"
                                                                          : "sidecar not read (" + err + ")"));
            continue;
        }
        if (is_licence_file_name(file)) continue;  // read for the set's provenance (provenance.hpp)
        if (!is_image_file(file)) {
            unrecognized.push_back(unrecognized_finding(file, "not an image"));
            continue;
        }
        auto a = naming::analyse(file);
        if (billboards && a.clutter && a.clutter->kind == naming::ClutterKind::billboard) a.clutter.reset();
        const auto sc = from_sidecar.find(file);
        if (sc != from_sidecar.end() && !(a.clutter && a.clutter->kind == naming::ClutterKind::billboard)) {
            // A sidecar of no naming family (MaterialX) that agrees with the name adds its evidence
            // to the name's tag: the name still names the material and votes for its convention.
            if (sc->second.family.empty() && a.tag && a.tag->match.role == sc->second.role) {
                RoleTag t = std::move(*a.tag);
                t.match.rule += " + " + sc->second.rule;
                t.match.sidecar = sc->second.sidecar;
                if (sc->second.normal != NormalConvention::unknown) t.match.normal = sc->second.normal;
                add_candidate({file, t.match, {}});
                tags.push_back(std::move(t));
                continue;
            }
            RoleTag t;
            t.match = sc->second;
            if (t.match.family.empty()) t.match.family = naming::kFamilies[naming::kGenericFamily].name;
            // Where the name agrees on the role, what else it states stays ("_B-O": opacity in A).
            if (a.tag && a.tag->match.role == t.match.role) {
                t.match.opacity_in_alpha = t.match.opacity_in_alpha || a.tag->match.opacity_in_alpha;
                if (t.match.normal == NormalConvention::unknown) t.match.normal = a.tag->match.normal;
            }
            t.families = {family_view(t.match.family)};
            t.fitting = t.families;
            add_candidate({file, t.match, {}});
            tags.push_back(std::move(t));
            continue;
        }
        if (a.clutter) {
            if (const auto rank = naming::preview_rank(a)) {
                const bool render = a.clutter->kind == naming::ClutterKind::render;
                previews.push_back({file, *rank, naming::join_name(a.tokens, a.clutter->token), "generic",
                                    render ? "generic:Material_NNNN (a preview render)"
                                           : "generic:_" + a.tokens[a.clutter->token].text + " (a preview image)"});
            }
            unrecognized.push_back(unrecognized_finding(file, naming::clutter_reason(a.clutter->kind)));
            continue;
        }
        if (!a.tag) {
            untagged.emplace_back(file, unrecognized.size());
            unrecognized.push_back(unrecognized_finding(file, "no role tag in the name"));
            continue;
        }
        add_candidate({file, a.tag->match, {}});
        tags.push_back(std::move(*a.tag));
    }
    out.convention = vote_convention(tags);
    decide_by_pixels(by_role, colour);
    normal_by_pixels(by_role, normal, out.findings);
    keep_object_space_out(by_role, unrecognized);
    mark_strays(by_role);
    // The engine's normal convention where the name states none (the pixels still decide first).
    const NormalConvention engine = out.convention == "unity"    ? NormalConvention::gl
                                    : out.convention == "unreal" ? NormalConvention::dx
                                                                 : NormalConvention::unknown;
    if (const auto n = by_role.find(Role::normal); n != by_role.end())
        for (auto& r : n->second) r.cand.match.engine_normal = engine;
    // An untagged image named as the set beside tagged maps of that name ("Platform2.jpg" beside
    // "PLatform2_Normal.jpg" and "Platform2_disp.jpg": tutorial and hand-made game folders) is
    // the colour map, when the set has no other and it is the only file so named (other untagged
    // files may sit beside it: Godot's "texture_bricks.jpg" beside "texture_bricks_depth.jpg").
    // Names compare as case-insensitive file systems compare them. Not in an ambientCG download:
    // its untagged "<id>.png" beside "<id>_1K-JPG_*" is the vendor's preview render, at the maps' size.
    auto sibling = [&](const std::string& file) {
        const std::string stem = fold_case(material_stem(file));
        return !stem.empty() && std::any_of(by_role.begin(), by_role.end(), [&](const auto& role_ranked) {
            return std::any_of(role_ranked.second.begin(), role_ranked.second.end(), [&](const Ranked& r) {
                return r.cand.match.sidecar.empty() && fold_case(material_stem(r.cand.file)) == stem;
            });
        });
    };
    std::vector<size_t> named_as_set;  // indices into `untagged`
    for (size_t i = 0; i < untagged.size(); ++i)
        if (sibling(untagged[i].first)) named_as_set.push_back(i);
    if (!by_role.count(Role::albedo) && named_as_set.size() == 1 && out.convention != "ambientcg") {
        const auto& [file, finding_at] = untagged[named_as_set.front()];
        NameMatch m;
        m.role = Role::albedo;
        m.family = "untagged";
        m.rule = "untagged:the set's name, beside its tagged maps";
        add_candidate({file, m, {}});
        unrecognized.erase(unrecognized.begin() + static_cast<std::ptrdiff_t>(finding_at));
    }

    // The vendor's preview: named by a sidecar, ambientCG's untagged "<id>.png" beside its
    // "<id>_<res>-<format>_*" maps, or an image the name calls a preview or render.
    if (!by_role.empty()) {
        std::set<std::string> map_stems;
        for (const auto& [role, ranked] : by_role)
            for (const Ranked& r : ranked) map_stems.insert(naming::normalized_key(material_stem(r.cand.file)));
        const std::set<std::string> in_set(sorted.begin(), sorted.end());
        for (const auto& s : sidecars)
            for (const std::string& file : s.facts.previews)
                if (in_set.count(file) && is_image_file(file))
                    previews.push_back({file, -1, "", "megascans", "megascans:previews.images[].uri"});
        // (The untagged-albedo rule above never applies in an ambientCG set.) Only beside maps of
        // ambientCG's own layout, "<id>_<res>-<FORMAT>_<Map>": its "_Color" tag alone is no download
        // of it ("Platform.jpg" beside "Platform_Color.jpg" stays unrecognized).
        std::set<std::string> ambientcg_ids;
        for (const auto& [role, ranked] : by_role)
            for (const Ranked& r : ranked) {
                const auto a = naming::analyse(r.cand.file);
                for (size_t i = 0; a.tag && i + 1 < a.tag->first_token; ++i)
                    if (a.tokens[i].kind == naming::Kind::resolution && a.tokens[i + 1].kind == naming::Kind::format)
                        ambientcg_ids.insert(naming::normalized_key(material_stem(r.cand.file)));
            }
        if (out.convention == "ambientcg")
            for (const auto& u : untagged)
                if (lower_copy(extension_of(u.first)) == "png" &&
                    ambientcg_ids.count(naming::normalized_key(material_stem(u.first))))
                    previews.push_back({u.first, 0, material_stem(u.first), "ambientcg",
                                        "ambientcg:<id>.png (the vendor's preview)"});
        out.preview = choose_preview(previews, map_stems, policy, header);
        if (out.preview) std::erase_if(unrecognized, [&](const Finding& f) { return f.file == out.preview->file; });
    }

    std::map<Role, Ambiguity> ambiguities;
    std::map<Role, std::string> chosen_file;
    for (auto& [role, ranked] : by_role) {
        std::sort(ranked.begin(), ranked.end(), [](const Ranked& a, const Ranked& b) { return a.key() < b.key(); });
        RoleChoice choice{role, ranked.front().cand, {}};
        for (size_t i = 1; i < ranked.size(); ++i) choice.rejected.push_back(ranked[i].cand);
        chosen_file[role] = choice.chosen.file;
        if (ranked.size() > 1) {
            auto& a = ambiguities[role];
            for (const auto& r : ranked) a.add(r.cand.file);
            a.chosen = choice.chosen.file;
            a.reasons.push_back(why_first(ranked[0], ranked[1], policy));
        }
        out.choices.push_back(std::move(choice));
    }

    std::vector<Role> targets;
    targets.reserve(kOutputRoleCount + 1);
    for (int i = 0; i < kOutputRoleCount; ++i) targets.push_back(static_cast<Role>(i));
    targets.push_back(Role::translucency);
    for (const Role target : targets) {
        // Which of the chosen files feeds the role is routing's (material/routing): here only
        // the choice among several is explained.
        std::vector<Route> available;
        for (const auto& p : route_candidates(target))
            if (chosen_file.count(p.from)) available.push_back(p);
        if (available.size() < 2) continue;
        const Route& best = available.front();
        auto& a = ambiguities[target];
        const std::string& file = chosen_file[best.from];
        a.put_first(file);
        for (const auto& p : available) a.add(chosen_file[p.from]);
        a.chosen = file;
        a.reasons.push_back(why_provider(target, best, available[1]));
    }

    for (const auto& [role, a] : ambiguities) out.findings.push_back(ambiguity_finding(role, a));
    for (auto& f : unrecognized) out.findings.push_back(std::move(f));
    return out;
}

}  // namespace mf
