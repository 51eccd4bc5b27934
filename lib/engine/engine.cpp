#include "engine/engine.hpp"

#include <nlohmann/json.hpp>

#include "core/files.hpp"

namespace mf::engine {

std::vector<Bound> bind(const EngineMaterial& e, const manifest::Material& m) {
    std::vector<Bound> out;
    for (const manifest::Output& o : m.outputs)
        if (const EngineSlot* s = slot_of(e, o.channels)) out.push_back({&o, s});
    return out;
}

const manifest::Output* texture_of(const std::vector<Bound>& bound, std::string_view slot) {
    for (const Bound& b : bound)
        if (b.slot->slot == slot) return b.output;
    return nullptr;
}

std::vector<File> material_files(const EngineMaterial& e, const manifest::Material& m) {
    const std::vector<Bound> bound = bind(e, m);
    switch (e.kind) {
        case MaterialFileKind::godot: return godot_files(e, m, bound);
        case MaterialFileKind::unity_hdrp:
        case MaterialFileKind::unity_urp: return unity_files(e, m, bound);
        case MaterialFileKind::unreal: return unreal_files(e, m, bound);
        default: return {};
    }
}

std::vector<File> folder_files(const EngineMaterial& e) {
    if (e.kind == MaterialFileKind::d3d11) return {hlsl_include()};
    if (e.kind == MaterialFileKind::unreal) return {unreal_import_all()};
    return {};
}

std::string_view how_to_open(std::string_view format) {
    static constexpr std::pair<std::string_view, std::string_view> kHow[] = {
        {"gltf", "any glTF 2.0 viewer or engine: three.js GLTFLoader, Babylon.js, Blender (File > Import > glTF 2.0)"},
        {"bin", "the glTF's buffer, opened with it"},
        {"mtlx", "a MaterialX host: Houdini, Maya, Omniverse, MaterialX Viewer (load as a material)"},
        {"usda", "a USD host: usdview, Omniverse, Houdini Solaris, Blender (reference the layer)"},
        {"tres", "Godot 4: copy the folder into the project, drag the .tres onto a mesh's material"},
        {"import", "Godot 4 imports the texture beside it with these settings"},
        {"meta", "Unity imports the asset beside it with these settings (copy the folder into Assets/)"},
        {"mat", "Unity: copy the folder into Assets/, drag the .mat onto a renderer"},
        {"py", "Unreal Editor: Tools > Execute Python Script (imports the textures, makes the instance)"},
        {"hlsli", "Direct3D 11: #include it in the engine's HLSL (mf_sample, mf_brdf_light)"},
    };
    for (const auto& [f, how] : kHow)
        if (f == format) return how;
    return "";
}

std::string string_literal(const std::string& s) {
    return nlohmann::json(s).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::string guid_of(const std::string& what) {
    Sha256 h;
    h.update("matforge unity guid\n" + what);
    return h.hex().substr(0, 32);
}

}  // namespace mf::engine
