// Manifest materials -> renderer materials: the textures the manifest lists, their channels
// mapped to the renderer's slots whatever preset produced them; scene-file materials on top.
#include <map>

#include "preview/preview.hpp"
#include "texture/texture.hpp"

namespace mf::preview {
namespace {

render::ScalarRole* scalar_slot(render::Material& m, Role role) {
    switch (role) {
        case Role::roughness: return &m.roughness;
        case Role::metalness: return &m.metalness;
        case Role::occlusion: return &m.occlusion;
        case Role::opacity: return &m.opacity;
        default: return nullptr;
    }
}

std::optional<render::Channel> channel_of(const std::string& key) {
    if (key == "R") return render::Channel::R;
    if (key == "G") return render::Channel::G;
    if (key == "B") return render::Channel::B;
    if (key == "A") return render::Channel::A;
    return std::nullopt;
}

// Inside `dir` lexically (no absolute path, no "..") — a manifest must not make the preview read
// files elsewhere unless its user allows it.
bool inside(const std::filesystem::path& rel) {
    const auto n = rel.lexically_normal();
    return !n.is_absolute() && !n.empty() && *n.begin() != "..";
}

}  // namespace

std::optional<render::Material> load_material(const manifest::Material& mm, const std::filesystem::path& dir,
                                              const MaterialOptions& opt, std::vector<std::string>& notes,
                                              std::string& error) {
    render::Material m;
    m.name = mm.name;
    for (const manifest::Output& o : mm.outputs) {
        const std::string shown = std::filesystem::path(o.file).filename().string();
        // What this texture feeds; textures that feed nothing the preview shades are not read.
        const int index = static_cast<int>(m.textures.size());
        bool used = false, color_in_rgb = false;
        for (const manifest::Channel& c : o.channels) {
            if (c.kind == manifest::Channel::Kind::constant || c.kind == manifest::Channel::Kind::unused) continue;
            const bool smooth = c.kind == manifest::Channel::Kind::smoothness;
            if (c.key == "RGB") {
                if (c.role == Role::albedo || c.role == Role::emissive) {
                    (c.role == Role::albedo ? m.albedo : m.emissive).texture = index;
                    color_in_rgb = used = true;
                } else if (c.role == Role::normal) {
                    m.normal.texture = index;
                    m.normal.green_down = o.normal_convention == NormalConvention::dx;
                    used = true;
                } else if (render::ScalarRole* s = scalar_slot(m, c.role)) {
                    *s = {index, render::Channel::R, smooth, s->value};
                    used = true;
                } else {
                    notes.push_back(mm.name + ": " + shown + " holds " + std::string(role_name(c.role)) +
                                    ", which the preview does not simulate");
                }
                continue;
            }
            if (render::ScalarRole* s = scalar_slot(m, c.role)) {
                *s = {index, *channel_of(c.key), smooth, s->value};
                used = true;
            } else {
                notes.push_back(mm.name + ": " + shown + " " + c.key + " holds " + std::string(role_name(c.role)) +
                                ", which the preview does not simulate");
            }
        }
        if (!used) continue;
        if (m.textures.size() == render::kMaxTextures) {
            error = mm.name + ": more than " + std::to_string(render::kMaxTextures) + " textures";
            return std::nullopt;
        }
        if (!opt.allow_outside && !inside(o.file)) {
            error = mm.name + ": output \"" + o.file +
                    "\" lies outside the manifest's folder (allow it with --allow-outside)";
            return std::nullopt;
        }
        const std::filesystem::path file = dir / o.file;
        auto t = texture::is_gpu_texture_name(file) ? read_gpu_texture(file, opt.samples, notes, error)
                                                    : read_texture(file, error);
        if (!t) return std::nullopt;
        // A normal stored as X, Y only (BC5): the shader rebuilds Z.
        if (index == m.normal.texture) m.normal.z_from_xy = o.normal_z_reconstructed;
        // Only RGB that hold color are sRGB-decoded; a data texture tagged sRGB is a mistake of
        // the producer (COLOR_SPACE_MISMATCH), decoding it would change the data.
        t->srgb = o.srgb && color_in_rgb;
        if (o.srgb && !color_in_rgb)
            notes.push_back(mm.name + ": " + shown + " is tagged sRGB but holds data; read as linear");
        m.textures.push_back(std::move(*t));
    }
    m.emissive.strength = mm.emissive_strength;  // an HDR emissive stored as emissive / strength
    // As the material files say (gltf.cpp: alphaMode, alphaCutoff, doubleSided): a cut-out is
    // cut at the preset's cutoff and its far side shows through, as in every engine.
    if (mm.alpha_mode) {
        using manifest::AlphaMode;
        m.alpha_mode = *mm.alpha_mode == AlphaMode::mask    ? render::AlphaMode::mask
                       : *mm.alpha_mode == AlphaMode::blend ? render::AlphaMode::blend
                                                            : render::AlphaMode::opaque;
        m.alpha_cutoff = mm.alpha_cutoff;
        m.double_sided = manifest::double_sided(mm.alpha_mode);
    }
    for (const manifest::Constant& c : mm.constants) {
        if (c.role == Role::albedo || c.role == Role::emissive) {
            const auto& v = c.value;
            const render::Vec3 rgb = v.size() == 3 ? render::Vec3{v[0], v[1], v[2]} : render::Vec3{v[0], v[0], v[0]};
            (c.role == Role::albedo ? m.albedo : m.emissive).value = rgb;
        } else if (render::ScalarRole* s = scalar_slot(m, c.role)) {
            if (c.value.size() == 1) s->value = c.value[0];
        }
    }
    return m;
}

bool apply_scene_material(const SceneMaterial& s, render::Material& m, std::string& error) {
    std::map<std::pair<std::string, bool>, int> loaded;  // (file, sRGB) → texture index
    auto load = [&](const std::filesystem::path& file, bool srgb) -> int {
        const auto key = std::make_pair(file.string(), srgb);
        if (const auto it = loaded.find(key); it != loaded.end()) return it->second;
        if (m.textures.size() == render::kMaxTextures) {
            error = "more than " + std::to_string(render::kMaxTextures) + " textures";
            return -1;
        }
        auto t = read_texture(file, error);
        if (!t) return -1;
        t->srgb = srgb;
        m.textures.push_back(std::move(*t));
        return loaded[key] = static_cast<int>(m.textures.size() - 1);
    };
    struct Want {
        const std::optional<SceneMaterial::Map>* map;
        bool srgb;
        int* slot;
    };
    int albedo = m.albedo.texture, emissive = m.emissive.texture, normal = m.normal.texture;
    for (const Want& w : {Want{&s.albedo_map, true, &albedo}, Want{&s.emissive_map, true, &emissive},
                          Want{&s.normal_map, false, &normal}}) {
        if (!*w.map) continue;
        *w.slot = load((*w.map)->file, w.srgb);
        if (*w.slot < 0) return false;
    }
    m.albedo.texture = albedo;
    m.emissive.texture = emissive;
    if (s.normal_map) {
        m.normal.texture = normal;
        m.normal.green_down = s.normal_convention == NormalConvention::dx;
    }
    for (const auto& [map, role] :
         {std::pair{&s.roughness_map, &m.roughness}, std::pair{&s.metalness_map, &m.metalness},
          std::pair{&s.occlusion_map, &m.occlusion}, std::pair{&s.opacity_map, &m.opacity}}) {
        if (!*map) continue;
        const int t = load((*map)->file, false);
        if (t < 0) return false;
        *role = {t, (*map)->channel.value_or(render::Channel::R), false, role->value};
    }
    // Constants apply only where the role has no map (docs/interface.md, scene file "material").
    if (s.albedo && m.albedo.texture < 0) m.albedo.value = *s.albedo;
    if (s.emissive && m.emissive.texture < 0) m.emissive.value = *s.emissive;
    if (s.roughness && m.roughness.texture < 0) m.roughness.value = *s.roughness;
    if (s.metalness && m.metalness.texture < 0) m.metalness.value = *s.metalness;
    return true;
}

}  // namespace mf::preview
