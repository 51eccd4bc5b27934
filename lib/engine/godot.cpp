// Godot 4: <material>/<material>.tres (ORMMaterial3D) and a .import beside each texture.
//
// Sources (docs/engines.md lists them with the real projects' files they were checked against):
// Godot's class reference (BaseMaterial3D, ORMMaterial3D: orm_texture R occlusion, G roughness,
// B metallic), its text resource format (format=3; ext_resource needs path, type and id; a
// relative path is resolved against the .tres's own folder; uid optional) and
// editor/import/resource_importer_texture.cpp's options.
//  - Godot 4 has no sRGB import flag: the material's shader samples albedo_texture and
//    emission_texture as colour (source_color) and the ORM, normal and height textures as data,
//    which is what the slot table says of them;
//  - the .import carries [remap] and [params] only: Godot reimports a file whose .import has no
//    uid and rewrites it whole (uid, paths, every option), mixing missing options with the
//    importer's built-in defaults, which are Lossless without mipmaps; so every option that
//    matters is written: VRAM compression, mipmaps, no 3D auto-detection, the normal map
//    imported as one (compress/normal_map=1: RGTC, Z rebuilt) and every other map not;
//  - ORMMaterial3D reads AO only with ao_enabled; its roughness and metallic numbers are not
//    applied to the ORM texture; emission adds the emission colour (left black) to the texture;
//  - the material's credit (manifest/attribution.hpp material_credit) as the resource's metadata
//    `copyright` (Object.set_meta, saved in the .tres as `metadata/copyright`, shown in the
//    Inspector's Metadata section; Godot has no licence field); none where the licence is unknown.
#include <filesystem>

#include "core/identifier.hpp"
#include "core/text.hpp"
#include "core/version.hpp"
#include "engine/engine.hpp"
#include "manifest/attribution.hpp"

namespace mf::engine {
namespace {

namespace fs = std::filesystem;

std::string import_file(const manifest::Output& o, const EngineSlot& slot) {
    const bool normal = slot.reads_role(Role::normal);
    return std::string("[remap]\n\nimporter=\"texture\"\ntype=\"CompressedTexture2D\"\n\n[params]\n\n") +
           "compress/mode=2\ncompress/high_quality=false\ncompress/lossy_quality=0.7\ncompress/hdr_compression=1\n"
           "compress/normal_map=" +
           (normal ? "1" : "2") +
           "\ncompress/channel_pack=0\nmipmaps/generate=true\nmipmaps/limit=-1\nroughness/mode=0\n"
           "roughness/src_normal=\"\"\nprocess/fix_alpha_border=true\nprocess/premult_alpha=false\n"
           "process/normal_map_invert_y=false\nprocess/hdr_as_srgb=false\nprocess/hdr_clamp_exposure=false\n"
           "process/size_limit=0\ndetect_3d/compress_to=0\n" +
           "; " + std::string(kGenerator) + ": " + std::string(slot.slot) + " (" + (slot.srgb ? "colour" : "data") +
           ")" + (o.bit_depth > 8 ? ", 16-bit: Godot loads PNGs as 8-bit" : "") + "\n";
}

}  // namespace

std::vector<File> godot_files(const EngineMaterial& e, const manifest::Material& m, const std::vector<Bound>& bound) {
    std::vector<File> files;
    files.reserve(bound.size() + 1);
    const fs::path tres = fs::path(m.name) / (m.name + ".tres");
    std::string ext, res;
    int id = 0;
    for (const Bound& b : bound)
        files.push_back({b.output->file + ".import", "import", import_file(*b.output, *b.slot)});
    res += "resource_name = " + string_literal(m.name) + "\n";
    // One ext_resource per slot's texture, in the table's order, each with the property that turns
    // its slot on.
    using manifest::AlphaMode;
    for (const EngineSlot& s : e.slots) {
        if (const manifest::Output* o = texture_of(bound, s.slot)) {
            const std::string rid = std::to_string(++id);
            ext += "[ext_resource type=\"Texture2D\" path=" +
                   string_literal(fs::path(o->file).lexically_relative(tres.parent_path()).generic_string()) +
                   " id=\"" + rid + "\"]\n";
            const std::string enable = s.enable.empty() ? "" : std::string(s.enable) + " = true\n";
            if (!s.enable_after) res += enable;
            res += std::string(s.slot) + " = ExtResource(\"" + rid + "\")\n";
            if (s.enable_after) res += enable;
            if (s.reads_role(Role::emissive) && m.emissive_strength != 1.f)
                res += "emission_energy_multiplier = " + scene_number(m.emissive_strength) + "\n";
        }
        // How the slot reading opacity is used, after it (whether or not the set has a texture).
        if (s.reads_role(Role::opacity) && m.alpha_mode && *m.alpha_mode != AlphaMode::opaque) {
            res += *m.alpha_mode == AlphaMode::mask
                       ? "transparency = 2\nalpha_scissor_threshold = " + scene_number(m.alpha_cutoff) + "\n"
                       : "transparency = 1\n";
            if (manifest::double_sided(m.alpha_mode)) res += "cull_mode = 2\n";
        }
    }
    res += "texture_filter = 5\n";  // linear, mipmaps, anisotropic: what Godot's own demo materials use
    if (const auto credit = m.provenance ? manifest::material_credit(*m.provenance) : std::nullopt)
        res += "metadata/copyright = " + string_literal(credit->line) + "\n";
    // load_steps: the external resources + 1 (Godot 4.0-4.5 write it; 4.6 reads and ignores it).
    files.push_back({tres.generic_string(), "tres",
                     "[gd_resource type=\"ORMMaterial3D\" load_steps=" + std::to_string(id + 1) + " format=3]\n\n" +
                         ext + "\n[resource]\n" + res});
    return files;
}

}  // namespace mf::engine
