#include "text.hpp"

#include <filesystem>
#include <sstream>

namespace gen {

namespace fs = std::filesystem;

namespace {

std::string mtlx_sidecar(const SetDef& set) {
    std::ostringstream o;
    o << "<?xml version=\"1.0\"?>\n<materialx version=\"1.38\" fileprefix=\"./\">\n"
      << "  <nodegraph name=\"NG_" << set.name << "\">\n";
    for (const FileDef& f : set.files) {
        if (f.map == Map::preview) continue;
        const bool color = f.map == Map::albedo;
        const bool normal = f.map == Map::normal_gl || f.map == Map::normal_dx;
        o << "    <image name=\"" << fs::path(f.path).stem().string() << "\" type=\""
          << (color    ? "color3"
              : normal ? "vector3"
                       : "float")
          << "\">\n"
          << "      <input name=\"file\" type=\"filename\" value=\"" << f.path << "\""
          << (color ? " colorspace=\"srgb_texture\"" : "") << " />\n    </image>\n";
    }
    o << "  </nodegraph>\n</materialx>\n";
    return o.str();
}

std::string megascans_json(const SetDef& set) {
    std::ostringstream o;
    o << "{\n  \"id\": \"" << set.name << "\",\n  \"name\": \"Ivy Leaves\",\n  \"type\": \"atlas\",\n"
      << "  \"maps\": [\n";
    for (size_t i = 0; i < set.files.size(); ++i)
        o << "    {\"uri\": \"" << set.files[i].path << "\", \"resolution\": \"" << set.files[i].size << "x"
          << set.files[i].size << "\"}" << (i + 1 < set.files.size() ? "," : "") << "\n";
    o << "  ]\n}\n";
    return o.str();
}

std::string encoding_name(const FileDef& f) {
    std::string dim = std::to_string(f.size) + "²";
    switch (f.enc) {
        case Enc::png8: return dim + " PNG 8-bit";
        case Enc::png16: return dim + " PNG 16-bit";
        case Enc::jpg: return dim + " JPEG q90";
        case Enc::exr_half: return dim + " EXR half";
    }
    return dim;
}

std::string map_description(Map m) {
    switch (m) {
        case Map::albedo: return "albedo (sRGB)";
        case Map::normal_gl: return "normal, content OpenGL (+Y)";
        case Map::normal_dx: return "normal, content DirectX (-Y)";
        case Map::roughness: return "roughness";
        case Map::gloss: return "gloss (1 - roughness)";
        case Map::metalness: return "metalness (binary)";
        case Map::occlusion: return "ambient occlusion";
        case Map::height: return "height / displacement";
        case Map::opacity: return "opacity (cut-out)";
        case Map::emissive: return "emissive (sRGB)";
        case Map::arm: return "packed R=AO G=roughness B=metalness";
        case Map::ort: return "packed R=AO G=roughness B=translucency";
        case Map::metal_rough: return "packed R=0 G=roughness B=metalness";
        case Map::specular: return "specular level (REFL)";
        case Map::preview: return "clutter: preview render, not a map";
    }
    return "";
}

}  // namespace

std::string text_content(const SetDef& set, Text kind) {
    return kind == Text::mtlx ? mtlx_sidecar(set) : megascans_json(set);
}

std::string readme(const std::vector<SetDef>& sets) {
    std::ostringstream o;
    o << "# Synthetic material sets (tools/gen_samples)\n\n"
      << "Small procedural PBR material sets named the way vendors name them, for the cases the real\n"
      << "sets of sample_materials/ do not have (a .zip set, a gloss map, a Megascans ORT, a glTF\n"
      << "metallicRoughness map, an unnamed DirectX normal...). The tests generate them at test time.\n"
      << "Every map of a set comes from one procedural surface (height, albedo, roughness,\n"
      << "metalness...), so the maps agree: normals are derived from the height by central\n"
      << "differences (wrap-around, tileable), occlusion from its cavities, mortar and grout are low,\n"
      << "rough and occluded. Albedo is computed in linear and encoded with the IEC 61966-2-1 sRGB\n"
      << "curve; metal albedo uses physicallybased.info values.\n\n"
      << "Normal maps: with rows going down the image, OpenGL (+Y) maps store\n"
      << "n = normalize(-s dh/dx, +s dh/drow, 1) as n*0.5+0.5; DirectX (-Y) maps negate the green.\n\n"
      << "**Generated — do not edit by hand** (byte-identical with the same build):\n"
      << "`gen_samples <out-dir> [SET...]` replaces only the set folders and archives it writes and\n"
      << "this README. Names say 1K/2K as vendors do; the pixels are 64–256 px.\n\n"
      << "| set | convention | exercises |\n| --- | --- | --- |\n";
    for (const SetDef& s : sets) o << "| `" << s.root << "` | " << s.family << " | " << s.exercises << " |\n";
    for (const SetDef& s : sets) {
        o << "\n## " << s.root << " (" << s.family << ")\n\n";
        for (const FileDef& f : s.files)
            o << "- `" << f.path << "` — " << map_description(f.map) << ", " << encoding_name(f) << "\n";
        for (const TextDef& t : s.texts) o << "- `" << t.path << "` — clutter: text sidecar, not an image\n";
    }
    return o.str();
}

}  // namespace gen
