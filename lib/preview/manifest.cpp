// manifest.json (version 1) → renderer materials: textures as the manifest lists them, roles
// from each output's `channels`, whatever preset produced them.
#include <algorithm>
#include <fstream>
#include <limits>
#include <map>
#include <optional>

#include <nlohmann/json.hpp>

#include "core/json.hpp"
#include "preview/preview.hpp"

namespace mf::preview {

using nlohmann::json;

namespace {

// Manifest constants are texture values; the half-float range admits HDR emissive.
constexpr double kConstantMin = -65504.0, kConstantMax = 65504.0;

bool is_color_role(const std::string& r) { return r == "albedo" || r == "emissive"; }

render::ScalarRole* scalar_slot(render::Material& m, const std::string& role) {
    if (role == "roughness" || role == "smoothness") return &m.roughness;
    if (role == "metalness") return &m.metalness;
    if (role == "occlusion") return &m.occlusion;
    if (role == "opacity") return &m.opacity;
    return nullptr;
}

std::optional<render::Channel> channel_of(const std::string& key) {
    if (key == "R") return render::Channel::R;
    if (key == "G") return render::Channel::G;
    if (key == "B") return render::Channel::B;
    if (key == "A") return render::Channel::A;
    return std::nullopt;
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

// A string member of `o`: `fallback` when absent; any other type is the manifest's error.
std::string string_member(const json& o, const char* key, const std::string& fallback, const std::string& where) {
    const auto it = o.find(key);
    if (it == o.end()) return fallback;
    if (!it->is_string()) throw UsageError("manifest: " + where + ": \"" + key + "\" is not a string");
    return it->get<std::string>();
}

}  // namespace

// Every member is type-checked before use: a malformed manifest is a UsageError naming what is
// wrong, never a JSON type_error (the manifest fuzzer found `"materials": ["x/x.png", ...]`).
Manifest parse_manifest(const json& j, const std::filesystem::path& dir) {
    if (!j.is_object()) throw UsageError("manifest: expected a JSON object");
    const auto v = j.find("manifest_version");
    if (v == j.end() || !json_int(*v, 1, std::numeric_limits<int>::max()))
        throw UsageError("manifest: missing or invalid manifest_version");
    Manifest out;
    out.dir = dir;
    const auto it = j.find("materials");
    if (it == j.end() || !it->is_array()) throw UsageError("manifest: no \"materials\" array");
    for (size_t i = 0; i < it->size(); ++i) {
        const json& mj = (*it)[i];
        const std::string at = "materials[" + std::to_string(i) + "]";
        if (!mj.is_object()) throw UsageError("manifest: " + at + " is not an object");
        ManifestMaterial m;
        m.name = string_member(mj, "name", "", at);
        if (m.name.empty()) throw UsageError("manifest: a material has no name");
        if (const auto o = mj.find("outputs"); o != mj.end() && o->is_array()) {
            for (const json& oj : *o) {
                const std::string where = "material " + m.name + ": an output";
                if (!oj.is_object()) throw UsageError("manifest: " + where + " is not an object");
                ManifestOutput out_tex;
                const std::string file = string_member(oj, "file", "", where);
                if (file.empty()) throw UsageError("manifest: material " + m.name + " has an output without \"file\"");
                out_tex.file = dir / file;
                out_tex.color_space = string_member(oj, "color_space", "linear", where);
                out_tex.normal_convention = string_member(oj, "normal_convention", "", where);
                if (const auto ch = oj.find("channels"); ch != oj.end() && ch->is_object())
                    for (const auto& [k, val] : ch->items()) out_tex.channels.emplace_back(k, val);
                m.outputs.push_back(std::move(out_tex));
            }
        }
        if (const auto c = mj.find("constants"); c != mj.end() && c->is_object())
            for (const auto& [k, val] : c->items()) m.constants.emplace_back(k, val);
        out.materials.push_back(std::move(m));
    }
    return out;
}

Manifest read_manifest(const std::filesystem::path& file) {
    std::ifstream in(file);
    if (!in) throw UsageError("cannot read manifest " + file.string());
    json j;
    try {
        in >> j;
    } catch (const json::exception& e) {
        throw UsageError(file.string() + ": not valid JSON: " + e.what());
    }
    try {
        return parse_manifest(j, file.parent_path());
    } catch (const json::exception& e) {
        throw UsageError(file.string() + ": " + e.what());
    }
}

render::Material load_manifest_material(const ManifestMaterial& mm, std::vector<std::string>& notes) {
    render::Material m;
    m.name = mm.name;
    for (const ManifestOutput& o : mm.outputs) {
        // What this texture feeds; textures that feed nothing the preview shades are not read.
        const int index = static_cast<int>(m.textures.size());
        bool used = false, color_in_rgb = false;
        for (const auto& [key, value] : o.channels) {
            if (!value.is_string()) continue;  // a number: the channel holds a constant
            const std::string role = value.get<std::string>();
            if (role == "unused") continue;
            if (key == "RGB") {
                if (is_color_role(role)) {
                    (role == "albedo" ? m.albedo : m.emissive).texture = index;
                    color_in_rgb = used = true;
                } else if (role == "normal") {
                    m.normal.texture = index;
                    m.normal.green_down = lower(o.normal_convention) == "dx";
                    used = true;
                } else if (render::ScalarRole* s = scalar_slot(m, role)) {
                    *s = {index, render::Channel::R, role == "smoothness", s->value};
                    used = true;
                } else {
                    notes.push_back(mm.name + ": " + o.file.filename().string() + " holds " + role +
                                    ", which the preview does not simulate");
                }
                continue;
            }
            const auto ch = channel_of(key);
            if (!ch) {
                notes.push_back(mm.name + ": unknown channel key \"" + key + "\" in " + o.file.filename().string());
                continue;
            }
            if (render::ScalarRole* s = scalar_slot(m, role)) {
                *s = {index, *ch, role == "smoothness", s->value};
                used = true;
            } else {
                notes.push_back(mm.name + ": " + o.file.filename().string() + " " + key + " holds " + role +
                                ", which the preview does not simulate");
            }
        }
        if (!used) continue;
        if (m.textures.size() == render::kMaxTextures)
            throw std::runtime_error(mm.name + ": more than " + std::to_string(render::kMaxTextures) + " textures");
        render::Texture t = read_texture(o.file);
        // Only RGB that hold color are sRGB-decoded; a data texture tagged sRGB is a mistake of
        // the producer (COLOR_SPACE_MISMATCH), decoding it would change the data.
        const bool srgb_tag = lower(o.color_space) == "srgb";
        t.srgb = srgb_tag && color_in_rgb;
        if (srgb_tag && !color_in_rgb)
            notes.push_back(mm.name + ": " + o.file.filename().string() + " is tagged sRGB but holds data; read as linear");
        m.textures.push_back(std::move(t));
    }
    for (const auto& [role, value] : mm.constants) {
        if (role == "albedo" || role == "emissive") {
            // A constant is one number or [r, g, b]; anything else (or a non-finite, out-of-range
            // value) is ignored and the material keeps its default.
            std::optional<float> c[3];
            if (value.is_array() && value.size() == 3)
                for (size_t i = 0; i < 3; ++i) c[i] = json_float(value[i], kConstantMin, kConstantMax);
            else
                c[0] = c[1] = c[2] = json_float(value, kConstantMin, kConstantMax);
            if (!c[0] || !c[1] || !c[2]) continue;
            (role == "albedo" ? m.albedo : m.emissive).value = {*c[0], *c[1], *c[2]};
        } else if (render::ScalarRole* s = scalar_slot(m, role)) {
            if (const auto v = json_float(value, kConstantMin, kConstantMax))
                s->value = role == "smoothness" ? 1.f - *v : *v;
        }
    }
    return m;
}

void apply_scene_material(const SceneMaterial& s, render::Material& m) {
    std::map<std::pair<std::string, bool>, int> loaded;  // (file, sRGB) → texture index
    auto load = [&](const std::filesystem::path& file, bool srgb) {
        const auto key = std::make_pair(file.string(), srgb);
        if (const auto it = loaded.find(key); it != loaded.end()) return it->second;
        if (m.textures.size() == render::kMaxTextures) throw std::runtime_error("too many textures");
        render::Texture t = read_texture(file);
        t.srgb = srgb;
        m.textures.push_back(std::move(t));
        return loaded[key] = static_cast<int>(m.textures.size() - 1);
    };
    if (s.albedo_map) m.albedo.texture = load(s.albedo_map->file, true);
    if (s.emissive_map) m.emissive.texture = load(s.emissive_map->file, true);
    if (s.normal_map) {
        m.normal.texture = load(s.normal_map->file, false);
        m.normal.green_down = s.normal_dx;
    }
    auto scalar = [&](const std::optional<SceneMaterial::Map>& map, render::ScalarRole& role) {
        if (map) role = {load(map->file, false), map->channel.value_or(render::Channel::R), false, role.value};
    };
    scalar(s.roughness_map, m.roughness);
    scalar(s.metalness_map, m.metalness);
    scalar(s.occlusion_map, m.occlusion);
    scalar(s.opacity_map, m.opacity);
    // Constants apply only where the role has no map (spec).
    if (s.albedo && m.albedo.texture < 0) m.albedo.value = *s.albedo;
    if (s.emissive && m.emissive.texture < 0) m.emissive.value = *s.emissive;
    if (s.roughness && m.roughness.texture < 0) m.roughness.value = *s.roughness;
    if (s.metalness && m.metalness.texture < 0) m.metalness.value = *s.metalness;
}

}  // namespace mf::preview
