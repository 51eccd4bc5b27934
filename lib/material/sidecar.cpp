// Roles a set's own description states: glTF 2.0 materials (.gltf, .glb) and Megascans asset
// JSON here, MaterialX documents in materialx.cpp. Pure over the text; the caller reads the
// files (discovery.hpp says which and how much).
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cstdint>

#include "material/discovery.hpp"
#include "material/sidecar_util.hpp"
#include "material/tokens.hpp"

namespace mf {
namespace {

using nlohmann::json;
using sidecar::add_map;
using sidecar::read_materialx;
using sidecar::resolve;

const json* member(const json* j, const char* key) {
    if (!j || !j->is_object()) return nullptr;
    const auto it = j->find(key);
    return it == j->end() ? nullptr : &*it;
}

std::optional<size_t> index_of(const json* j) {
    if (!j || !j->is_number_integer()) return std::nullopt;
    const auto v = j->get<long long>();
    if (v < 0) return std::nullopt;
    return static_cast<size_t>(v);
}

bool is_zero_number(const json* j) { return j && j->is_number() && j->get<double>() == 0.0; }

// ---------------------------------------------------------------------------------------------
// glTF 2.0

// A .glb's JSON chunk (glTF 2.0 §4.4: 12-byte header "glTF", version, length; then chunk 0:
// length, type "JSON", data).
std::optional<std::string_view> glb_json(std::string_view bytes, std::string& error) {
    const auto u32 = [&](size_t at) {
        uint32_t v = 0;
        for (size_t k = 0; k < 4; ++k) v |= uint32_t{static_cast<unsigned char>(bytes[at + k])} << (8 * k);
        return v;
    };
    if (bytes.size() < 20 || bytes.substr(0, 4) != "glTF") {
        error = "not a binary glTF (.glb) file";
        return std::nullopt;
    }
    const uint32_t length = u32(12);
    if (bytes.substr(16, 4) != "JSON" || length > bytes.size() - 20) {
        error = "the .glb's JSON chunk is missing or truncated";
        return std::nullopt;
    }
    return bytes.substr(20, length);
}

std::string string_member(const json* j, const char* key) {
    const json* v = member(j, key);
    return v && v->is_string() ? v->get<std::string>() : std::string();
}

// glTF 2.0 §5.5 asset: "copyright", "a copyright message suitable for display to credit the
// content creator"; stores put their listing in `extras` (Sketchfab: license, author, title, source).
void read_gltf_asset(const json& root, SidecarFacts& facts) {
    const json* asset = member(&root, "asset");
    facts.copyright = string_member(asset, "copyright");
    const json* extras = member(asset, "extras");
    facts.author = string_member(extras, "author");
    facts.title = string_member(extras, "title");
    facts.source_url = string_member(extras, "source");
    for (const char* key : {"license", "licence"})
        if (std::string text = string_member(extras, key); !text.empty() && facts.licence.empty()) {
            facts.licence = std::move(text);
            facts.licence_field = std::string("asset.extras.") + key;
        }
}

void read_gltf(const json& root, std::string_view source, SidecarRoles& out) {
    read_gltf_asset(root, out.facts);
    const json* images = member(&root, "images");
    const json* textures = member(&root, "textures");
    const json* materials = member(&root, "materials");
    // The file a textureInfo ({"index": n}) samples: textures[n].source (or an extension's
    // source: KHR_texture_basisu, EXT_texture_webp) -> images[source].uri.
    const auto file_of = [&](const json* info) -> std::optional<std::string> {
        const auto ti = index_of(member(info, "index"));
        if (!ti || !textures || !textures->is_array() || *ti >= textures->size()) return std::nullopt;
        const json& tex = (*textures)[*ti];
        auto src = index_of(member(&tex, "source"));
        if (const json* ext = member(&tex, "extensions"); !src && ext && ext->is_object())
            for (const auto& e : *ext)
                if ((src = index_of(member(&e, "source")))) break;
        if (!src || !images || !images->is_array() || *src >= images->size()) return std::nullopt;
        const json* uri = member(&(*images)[*src], "uri");
        if (!uri || !uri->is_string()) return std::nullopt;  // embedded in a bufferView
        return resolve(source, uri->get_ref<const std::string&>(), true);
    };
    if (!materials || !materials->is_array()) return;
    for (size_t mi = 0; mi < materials->size(); ++mi) {
        const json& mat = (*materials)[mi];
        if (!mat.is_object()) continue;
        const std::string at = "gltf:materials[" + std::to_string(mi) + "].";
        const auto match = [&](Role role, const std::string& rule) {
            NameMatch m;
            m.role = role;
            m.family = "gltf";
            m.rule = at + rule;
            m.sidecar = std::string(source);
            return m;
        };
        const json* pbr = member(&mat, "pbrMetallicRoughness");
        const json* alpha = member(&mat, "alphaMode");
        const bool alpha_used = alpha && alpha->is_string() && (*alpha == "MASK" || *alpha == "BLEND");
        if (auto f = file_of(member(pbr, "baseColorTexture"))) {
            auto m = match(Role::albedo, "pbrMetallicRoughness.baseColorTexture");
            m.opacity_in_alpha = alpha_used;
            add_map(out, *f, std::move(m));
        }
        if (auto f = file_of(member(&mat, "normalTexture"))) {
            auto m = match(Role::normal, "normalTexture");
            m.normal = NormalConvention::gl;  // glTF 2.0 §3.9.3: +Y up (green up)
            add_map(out, *f, std::move(m));
        }
        const auto mr = file_of(member(pbr, "metallicRoughnessTexture"));
        const auto occ = file_of(member(&mat, "occlusionTexture"));
        if (mr) {
            // Occlusion in R of the same image: an ORM pack (glTF 2.0 §3.9.4 allows the sharing).
            const bool orm = occ && *occ == *mr;
            auto m = orm ? match(Role::orm, "pbrMetallicRoughness.metallicRoughnessTexture+occlusionTexture")
                         : match(Role::metallic_roughness, "pbrMetallicRoughness.metallicRoughnessTexture");
            // The texture's channel is multiplied by the factor (defaults 1): a factor of 0 means
            // the channel is not used.
            if (is_zero_number(member(pbr, "metallicFactor"))) m.unused.push_back(Role::metalness);
            if (is_zero_number(member(pbr, "roughnessFactor"))) m.unused.push_back(Role::roughness);
            add_map(out, *mr, std::move(m));
        }
        if (occ) add_map(out, *occ, match(Role::occlusion, "occlusionTexture"));
        if (auto f = file_of(member(&mat, "emissiveTexture"))) {
            auto m = match(Role::emissive, "emissiveTexture");
            // emissiveFactor defaults to [0, 0, 0]: without a non-zero factor the texture adds nothing.
            const json* factor = member(&mat, "emissiveFactor");
            bool lit = false;
            if (factor && factor->is_array())
                for (const auto& v : *factor) lit = lit || (v.is_number() && v.get<double>() != 0.0);
            if (!lit) m.unused.push_back(Role::emissive);
            add_map(out, *f, std::move(m));
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Megascans

std::optional<Role> megascans_role(std::string_view type) {
    static constexpr std::array<std::pair<std::string_view, Role>, 14> kTypes{{
        {"albedo", Role::albedo},
        {"diffuse", Role::albedo},
        {"normal", Role::normal},
        {"roughness", Role::roughness},
        {"gloss", Role::gloss},
        {"specular", Role::specular},
        {"displacement", Role::height},
        {"bump", Role::height},
        {"ao", Role::occlusion},
        {"cavity", Role::cavity},
        {"opacity", Role::opacity},
        {"translucency", Role::translucency},
        {"metalness", Role::metalness},
        {"metallic", Role::metalness},
    }};
    for (const auto& [name, role] : kTypes)
        if (name == type) return role;
    return std::nullopt;  // fuzz, thickness, curvature, brush, mask, transmission, …
}

bool read_megascans(const json& root, std::string_view source, SidecarRoles& out) {
    const json* maps = member(&root, "maps");
    const json* components = member(&root, "components");
    const bool shaped = (maps && maps->is_array()) || (components && components->is_array());
    if (!shaped) return false;
    const auto add = [&](const std::string& type, const json* uri, const std::string& where) {
        const auto role = megascans_role(naming::lower_copy(type));
        if (!role || !uri || !uri->is_string()) return;
        const auto file = resolve(source, uri->get_ref<const std::string&>(), false);
        if (!file) return;
        NameMatch m;
        m.role = *role;
        m.family = "megascans";
        m.rule = "megascans:" + where + ".type=" + type;
        m.sidecar = std::string(source);
        add_map(out, *file, std::move(m));
    };
    const auto type_of = [](const json& e) {
        const json* t = member(&e, "type");
        return t && t->is_string() ? t->get<std::string>() : std::string();
    };
    if (maps && maps->is_array())
        for (const auto& e : *maps) {
            // "uri" is the file; older exports give only "name" (a file name when it has a dot).
            const json* uri = member(&e, "uri");
            if (!uri) {
                const json* name = member(&e, "name");
                if (name && name->is_string() && name->get_ref<const std::string&>().find('.') != std::string::npos)
                    uri = name;
            }
            add(type_of(e), uri, "maps[]");
        }
    // The asset's own facts: its id (the one in its file names), its name, a licence member if
    // the file has one (Bridge exports have none), and the preview images it lists.
    out.facts.asset_id = string_member(&root, "id");
    out.facts.title = string_member(&root, "name");
    for (const char* key : {"license", "licence"})
        if (std::string text = string_member(&root, key); !text.empty() && out.facts.licence.empty()) {
            out.facts.licence = std::move(text);
            out.facts.licence_field = key;
        }
    if (const json* images = member(member(&root, "previews"), "images"); images && images->is_array())
        for (const auto& image : *images) {
            const json* uri = member(&image, "uri");
            if (!uri || !uri->is_string()) continue;
            if (auto file = resolve(source, uri->get_ref<const std::string&>(), false))
                out.facts.previews.push_back(std::move(*file));
        }
    if (components && components->is_array())
        for (const auto& c : *components) {
            const auto type = type_of(c);
            const json* uris = member(&c, "uris");
            if (!uris || !uris->is_array()) continue;
            for (const auto& u : *uris) {
                const json* res = member(&u, "resolutions");
                if (!res || !res->is_array()) continue;
                for (const auto& r : *res) {
                    const json* formats = member(&r, "formats");
                    if (!formats || !formats->is_array()) continue;
                    for (const auto& f : *formats) add(type, member(&f, "uri"), "components[]");
                }
            }
        }
    return true;
}

}  // namespace

bool is_sidecar_name(std::string_view filename) {
    const auto ext = naming::lower_copy(naming::extension_of(filename));
    return ext == "gltf" || ext == "glb" || ext == "json" || ext == "mtlx";
}

SidecarRoles sidecar_roles(std::string_view filename, std::string_view content) {
    SidecarRoles out;
    out.source = std::string(filename);
    const auto ext = naming::lower_copy(naming::extension_of(filename));
    std::string_view text = content;
    if (ext == "mtlx") {
        read_materialx(content, filename, out);
        return out;
    }
    if (ext == "glb") {
        const auto chunk = glb_json(content, out.error);
        if (!chunk) return out;
        text = *chunk;
    } else if (ext != "gltf" && ext != "json") {
        out.error = "not a .gltf, .glb, .json or .mtlx file";
        return out;
    }
    const json root = json::parse(text.begin(), text.end(), nullptr, false);
    if (root.is_discarded() || !root.is_object()) {
        out.error = "not a JSON object";
        return out;
    }
    // A .json is read as glTF when it says so (an "asset" with a "version"), else as Megascans.
    const json* asset = member(&root, "asset");
    const bool gltf = ext != "json" || (asset && member(asset, "version"));
    if (gltf) {
        out.kind = SidecarKind::gltf;
        read_gltf(root, filename, out);
        return out;
    }
    if (read_megascans(root, filename, out)) {
        out.kind = SidecarKind::megascans;
        return out;
    }
    out.error = "neither a glTF nor a Megascans asset file (no \"maps\" or \"components\")";
    return out;
}

}  // namespace mf
