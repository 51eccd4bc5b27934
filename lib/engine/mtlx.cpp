#include "engine/mtlx.hpp"

#include <algorithm>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <vector>

#include "core/identifier.hpp"
#include "core/text.hpp"
#include "core/version.hpp"
#include "manifest/attribution.hpp"

namespace mf::mtlx {
namespace {

namespace fs = std::filesystem;

// One row of gltf::kSurfaceInputs as gltf_pbr names it: the input, its MaterialX type, the role,
// whether the map is colour (sRGB).
struct Slot {
    const char* input;
    const char* type;
    Role role;
    bool color;
};

int channel_index(const std::string& key) {
    return key == "R" ? 0 : key == "G" ? 1 : key == "B" ? 2 : key == "A" ? 3 : -1;
}

// The elements of one material: its nodes, its gltf_pbr and its surfacematerial. Element names
// derive from `id` (the material, "<id>_shader", "<id>_normalmap", "<id>_<role>") and, for the
// image nodes, from `image_prefix` + "img_<file stem>"; names() lists them all.
class Writer {
public:
    Writer(const manifest::Material& m, fs::path base, std::string id, std::string image_prefix)
        : m_(m), name_(std::move(id)), base_(std::move(base)), image_prefix_(std::move(image_prefix)) {}

    std::string body() {
        std::set<std::string> connected;  // gltf_pbr inputs read from a texture
        std::string s = "  <gltf_pbr name=\"" + name_ + "_shader\" type=\"surfaceshader\">\n";
        for (const gltf::SurfaceInput& row : gltf::kSurfaceInputs) {
            const Slot slot{row.mtlx.input, row.mtlx.type, row.role, row.color};
            const gltf::RoleSource src = gltf::role_source(m_, slot.role);
            const auto node = src.output ? read(*src.output, *src.channel, slot) : std::nullopt;
            const std::string head = "    <input name=\"" + std::string(slot.input) + "\" type=\"" + slot.type + "\" ";
            if (node) {
                connected.insert(slot.input);
                s += head + "nodename=\"" + *node + "\" />\n";
            } else if (src.constant) {
                const auto& v = *src.constant;
                s += head + "value=\"" +
                     (std::string(slot.type) == "color3"
                          ? scene_number(v[0]) + ", " + scene_number(v[1]) + ", " + scene_number(v[2])
                          : scene_number(v[0])) +
                     "\" />\n";
            }
        }
        if (connected.count("emissive") && m_.emissive_strength != 1.f)
            s += "    <input name=\"emissive_strength\" type=\"float\" value=\"" + scene_number(m_.emissive_strength) +
                 "\" />\n";
        using manifest::AlphaMode;
        if (connected.count("alpha") && m_.alpha_mode) {
            s += "    <input name=\"alpha_mode\" type=\"integer\" value=\"" +
                 std::to_string(*m_.alpha_mode == AlphaMode::mask    ? 1
                                : *m_.alpha_mode == AlphaMode::blend ? 2
                                                                     : 0) +
                 "\" />\n";
            if (*m_.alpha_mode == AlphaMode::mask)
                s += "    <input name=\"alpha_cutoff\" type=\"float\" value=\"" + scene_number(m_.alpha_cutoff) +
                     "\" />\n";
        }
        s += "  </gltf_pbr>\n";
        // The material's credit as its `doc`, the attribute MaterialX gives every element for
        // human text (a description, a UI's tooltip); none where the licence is unknown.
        const auto credit = m_.provenance ? manifest::material_credit(*m_.provenance) : std::nullopt;
        s += "  <surfacematerial name=\"" + name_ + "\" type=\"material\"" +
             (credit ? " doc=\"" + markup_escape(credit->line) + "\"" : "") + ">\n";
        s += "    <input name=\"surfaceshader\" type=\"surfaceshader\" nodename=\"" + name_ + "_shader\" />\n";
        s += "  </surfacematerial>\n";
        names_.insert(names_.end(), {name_ + "_shader", name_});
        return nodes_ + s;
    }

    const std::vector<std::string>& names() const { return names_; }

private:
    // The image node reading `o` as `type` (once per file and type).
    std::string image(const manifest::Output& o, const std::string& type, bool color) {
        const std::string key = o.file + "|" + type;
        if (const auto it = images_.find(key); it != images_.end()) return it->second;
        std::string node = image_prefix_ + "img_" + scene_identifier(fs::path(o.file).stem().string()) +
                           (type == "vector4" ? "_rgba" : "");
        const std::string file = base_.empty() ? o.file : fs::path(o.file).lexically_relative(base_).generic_string();
        nodes_ += "  <image name=\"" + node + "\" type=\"" + type +
                  "\">\n    <input name=\"file\" type=\"filename\" value=\"" + markup_escape(file) + "\"" +
                  (color ? " colorspace=\"srgb_texture\"" : "") + " />\n  </image>\n";
        names_.push_back(node);
        return images_[key] = node;
    }

    // The node a gltf_pbr input connects to for channel `c` of `o`.
    std::optional<std::string> read(const manifest::Output& o, const Channel& c, const Slot& slot) {
        const std::string role(role_name(c.role));
        if (c.key == "RGB") {
            const std::string img = image(o, slot.type, slot.color);
            if (c.role != Role::normal) return img;
            std::string node = name_ + "_normalmap";
            nodes_ += "  <normalmap name=\"" + node +
                      "\" type=\"vector3\">\n    <input name=\"in\" type=\"vector3\" nodename=\"" + img +
                      "\" />\n  </normalmap>\n";
            names_.push_back(node);
            return node;
        }
        const int index = channel_index(c.key);
        if (index < 0 || std::string(slot.type) != "float") return std::nullopt;
        // A single channel of a packed (or RGBA) texture: read it whole as data (vector3, or
        // vector4 for A): a channel that is not colour has no colour space, the alpha of an sRGB
        // base colour included (sRGB encodes RGB only). Not color4: three.js's MaterialXLoader
        // reads color4 as a colour of three components and loses A.
        const bool rgba = index == 3;
        const std::string type = rgba ? "vector4" : "vector3";
        const std::string img = image(o, type, false);
        std::string node = name_ + "_" + role;
        nodes_ += "  <extract name=\"" + node + "\" type=\"float\">\n    <input name=\"in\" type=\"" + type +
                  "\" nodename=\"" + img + "\" />\n    <input name=\"index\" type=\"integer\" value=\"" +
                  std::to_string(index) + "\" />\n  </extract>\n";
        names_.push_back(node);
        return node;
    }

    const manifest::Material& m_;
    std::string name_;
    fs::path base_;
    std::string image_prefix_;
    std::string nodes_;
    std::map<std::string, std::string> images_;
    std::vector<std::string> names_;
};

// An XML comment may not hold "--" (XML 1.0, production 15): a name's dashes are kept apart.
// Built by appending: GCC 12 at -O3 warns -Wrestrict on an insert into a string it cannot size
// (its bug 105329), which a plain Release build shows to users.
std::string comment_text(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    for (const char c : text) {
        if (c == '-' && !out.empty() && out.back() == '-') out += ' ';
        out += c;
    }
    return out;
}

std::string head(const std::string& comment) {
    return "<?xml version=\"1.0\"?>\n<!-- " + markup_escape(std::string(kGenerator)) + ": " +
           comment_text(markup_escape(comment)) + " -->\n<materialx version=\"1.39\">\n";
}

}  // namespace

std::string material_mtlx(const manifest::Material& m, const std::string& mtlx_file) {
    return head(m.name) + Writer(m, fs::path(mtlx_file).parent_path(), scene_identifier(m.name), "").body() +
           "</materialx>\n";
}

bool library_mtlx(const std::function<bool(const MaterialVisitor&)>& materials, const ByteSink& sink,
                  std::string& error) {
    if (!sink(head("every material of the run"))) return false;
    std::set<std::string> taken;
    const bool ok = materials([&](const manifest::Material& m) {
        // The first of id, id_2, ... none of whose element names another material took.
        for (int k = 1;; ++k) {
            std::string id = scene_identifier(m.name);
            if (k > 1) id.append("_").append(std::to_string(k));
            Writer w(m, fs::path(), id, id + "_");
            std::string text = w.body();
            if (std::any_of(w.names().begin(), w.names().end(), [&](const auto& n) { return taken.count(n); }))
                continue;
            taken.insert(w.names().begin(), w.names().end());
            return sink(text);
        }
    });
    if (!ok) {
        if (error.empty()) error = "cannot write the document";
        return false;
    }
    return sink("</materialx>\n");
}

}  // namespace mf::mtlx
