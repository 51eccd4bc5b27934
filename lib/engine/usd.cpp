#include "engine/usd.hpp"

#include <filesystem>
#include <map>
#include <optional>
#include <set>

#include "core/identifier.hpp"
#include "core/version.hpp"
#include "manifest/attribution.hpp"

namespace mf::usd {
namespace {

namespace fs = std::filesystem;

struct Slot {
    const char* input;  // UsdPreviewSurface input
    const char* type;   // its USD type
    Role role;
    bool color;
};

// USD string and asset literals: '"' and '\' escaped; '@' cannot be escaped in an @asset@ path.
std::string usd_string(const std::string& s) {
    std::string out = "\"";
    for (const char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        out += c;
    }
    return out + "\"";
}

class Writer {
public:
    Writer(const manifest::Material& m, const std::string& usda_file)
        : m_(m), name_(scene_identifier(m.name)), base_(fs::path(usda_file).parent_path()) {}

    std::string layer() {
        std::set<std::string> connected;  // UsdPreviewSurface inputs read from a texture
        std::string s = "    def Shader \"Surface\"\n    {\n        uniform token info:id = \"UsdPreviewSurface\"\n";
        for (const gltf::SurfaceInput& row : gltf::kSurfaceInputs) {
            const Slot slot{row.usd.input, row.usd.type, row.role, row.color};
            const gltf::RoleSource src = gltf::role_source(m_, slot.role);
            const std::string head = "        " + std::string(slot.type) + " inputs:" + slot.input;
            std::string out, tex;
            if (src.output && src.channel && !(out = output_of(*src.channel, slot)).empty())
                tex = texture(*src.output, slot.role);
            if (!tex.empty()) {
                connected.insert(slot.input);
                s += head + ".connect = </" + name_ + "/" + tex + ".outputs:" + out + ">\n";
            } else if (src.constant) {
                const auto& v = *src.constant;
                s += head + " = " +
                     (std::string(slot.type) == "float"
                          ? scene_number(v[0])
                          : "(" + scene_number(v[0]) + ", " + scene_number(v[1]) + ", " + scene_number(v[2]) + ")") +
                     "\n";
            }
        }
        using manifest::AlphaMode;
        if (connected.count("opacity") && m_.alpha_mode && *m_.alpha_mode != AlphaMode::opaque)
            s += "        float inputs:opacityThreshold = " +
                 (*m_.alpha_mode == AlphaMode::mask ? scene_number(m_.alpha_cutoff) : std::string("0")) + "\n";
        s += "        int inputs:useSpecularWorkflow = 0\n        token outputs:surface\n    }\n\n";
        s += "    def Shader \"TexCoord\"\n    {\n        uniform token info:id = \"UsdPrimvarReader_float2\"\n"
             "        string inputs:varname = \"st\"\n        float2 outputs:result\n    }\n";
        return "#usda 1.0\n(\n" + credit() + "    defaultPrim = " + usd_string(name_) +
               "\n    doc = " + usd_string(std::string(kGenerator) + ": " + m_.name) +
               "\n    metersPerUnit = 1\n    upAxis = \"Y\"\n)\n\n" + "def Material " + usd_string(name_) +
               "\n{\n    token outputs:surface.connect = </" + name_ + "/Surface.outputs:surface>\n\n" + s + textures_ +
               "}\n";
    }

private:
    // The layer's customLayerData with the material's credit, as ambientCG's own USD files carry
    // theirs ("author", "copyright": the licence, "url": the asset's page); OpenUSD names no
    // field of its own for it. "" when the licence is unknown.
    std::string credit() const {
        const auto c = m_.provenance ? manifest::material_credit(*m_.provenance) : std::nullopt;
        if (!c) return "";
        std::string s = "    customLayerData = {\n";
        if (!c->author.empty()) s += "        string author = " + usd_string(c->author) + "\n";
        s += "        string copyright = " + usd_string(c->licence) + "\n";
        if (!c->url.empty()) s += "        string url = " + usd_string(c->url) + "\n";
        return s + "    }\n";
    }

    // The reader output a channel goes through ("rgb", "r" ... "a"), "" when it cannot feed the
    // slot (three channels into a float input, one into a colour).
    static std::string output_of(const Channel& c, const Slot& slot) {
        const std::string out = c.key == "RGB" ? "rgb"
                                : c.key == "R" ? "r"
                                : c.key == "G" ? "g"
                                : c.key == "B" ? "b"
                                : c.key == "A" ? "a"
                                               : "";
        return out.empty() || (out == "rgb") != (std::string(slot.type) != "float") ? "" : out;
    }

    // The UsdUVTexture prim reading `o` (once per file), "" for a file whose path USD cannot hold.
    std::string texture(const manifest::Output& o, Role role) {
        if (const auto it = textures_of_.find(o.file); it != textures_of_.end()) return it->second;
        const std::string file = fs::path(o.file).lexically_relative(base_).generic_string();
        if (file.find('@') != std::string::npos) return textures_of_[o.file] = "";
        const std::string prim = "Tex_" + scene_identifier(fs::path(o.file).stem().string());
        std::string t = "\n    def Shader " + usd_string(prim) +
                        "\n    {\n        uniform token info:id = \"UsdUVTexture\"\n" +
                        "        asset inputs:file = @" + file + "@\n" + "        token inputs:sourceColorSpace = \"" +
                        (o.srgb ? "sRGB" : "raw") + "\"\n        float2 inputs:st.connect = </" + name_ +
                        "/TexCoord.outputs:result>\n        token inputs:wrapS = \"repeat\"\n"
                        "        token inputs:wrapT = \"repeat\"\n";
        if (role == Role::normal)
            t += "        float4 inputs:scale = (2, 2, 2, 1)\n        float4 inputs:bias = (-1, -1, -1, 0)\n";
        else if (role == Role::emissive && m_.emissive_strength != 1.f) {
            const std::string k = scene_number(m_.emissive_strength);
            t += "        float4 inputs:scale = (" + k + ", " + k + ", " + k + ", 1)\n";
        }
        t += "        float3 outputs:rgb\n        float outputs:r\n        float outputs:g\n        float outputs:b\n"
             "        float outputs:a\n    }\n";
        textures_ += t;
        return textures_of_[o.file] = prim;
    }

    const manifest::Material& m_;
    std::string name_;
    fs::path base_;
    std::string textures_;
    std::map<std::string, std::string> textures_of_;
};

}  // namespace

std::string material_usda(const manifest::Material& m, const std::string& usda_file) {
    return Writer(m, usda_file).layer();
}

bool library_usda(const std::vector<LibraryItem>& items, const ByteSink& sink) {
    if (!sink("#usda 1.0\n(\n    defaultPrim = \"Materials\"\n    doc = " +
              usd_string(std::string(kGenerator) + ": every material of the run") +
              "\n    metersPerUnit = 1\n    upAxis = \"Y\"\n)\n\ndef Scope \"Materials\"\n{\n"))
        return false;
    std::set<std::string> taken;
    for (const LibraryItem& item : items) {
        if (item.layer.find('@') != std::string::npos) continue;  // no @ in an asset path
        std::string prim = scene_identifier(item.name);
        for (int k = 2; !taken.insert(prim).second; ++k) prim = scene_identifier(item.name) + "_" + std::to_string(k);
        if (!sink("    def " + usd_string(prim) + " (\n        prepend references = @" + item.layer +
                  "@\n    )\n    {\n    }\n"))
            return false;
    }
    return sink("}\n");
}

}  // namespace mf::usd
