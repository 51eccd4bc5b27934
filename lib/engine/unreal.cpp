// Unreal Engine: <material>/import_<material>.py, an editor Python script (Tools > Execute
// Python Script, or `UnrealEditor-Cmd Project.uproject -run=pythonscript -script=...`) that
// imports the set's textures with unreal.AssetImportTask, sets each one's sRGB flag and
// compression (TC_MASKS on the ORM, TC_NORMALMAP on the normal map, TC_GRAYSCALE on the height),
// and makes MI_<material>, an instance of /Game/Matforge/M_MatforgeORM (made by the script when
// the project has none: BaseColor RGB to Base Color and A to Opacity / Opacity Mask, ORM R to
// Ambient Occlusion, G to Roughness, B to Metallic, Normal to Normal, Emissive times
// EmissiveStrength to Emissive Color). Every instance sets every parameter (the engine's flat
// normal and black where its set has no map, strength 0 without emission), so no instance shows
// the parent's defaults, which are whichever set made it. import_all.py (a folder file) runs
// every material's script.
//
// Checked against the Unreal Python API reference (AssetImportTask, AssetTools,
// EditorAssetLibrary, MaterialEditingLibrary, Texture.srgb / compression_settings) and parsed
// and run against a recording stand-in of the `unreal` module in the tests
// (tests/texture/checkers/unreal_check.py); not run in Unreal here (no Unreal Editor on Linux CI).
#include "core/identifier.hpp"
#include "core/version.hpp"
#include "engine/engine.hpp"

#include <algorithm>
#include <filesystem>

namespace mf::engine {
namespace {

namespace fs = std::filesystem;

// The parent material and the instance, shared by every script (each script stands alone).
constexpr const char* kBody = R"PY(

def import_textures():
    """Imports TEXTURES into DEST and sets their sRGB flag and compression; returns {parameter: texture}."""
    tasks = []
    for file, _, _, _ in TEXTURES:
        task = unreal.AssetImportTask()
        task.set_editor_property("filename", os.path.join(HERE, file))
        task.set_editor_property("destination_path", DEST)
        task.set_editor_property("automated", True)
        task.set_editor_property("replace_existing", True)
        task.set_editor_property("save", False)
        tasks.append(task)
    unreal.AssetToolsHelpers.get_asset_tools().import_asset_tasks(tasks)
    textures = {}
    for task, (file, parameter, srgb, compression) in zip(tasks, TEXTURES):
        paths = task.get_editor_property("imported_object_paths")
        if not paths:
            raise RuntimeError("matforge: " + file + " was not imported")
        texture = unreal.EditorAssetLibrary.load_asset(paths[0])
        texture.set_editor_property("srgb", srgb)
        texture.set_editor_property("compression_settings", getattr(unreal.TextureCompressionSettings, compression))
        unreal.EditorAssetLibrary.save_loaded_asset(texture)
        textures[parameter] = texture
    return textures


def texture_for(textures, parameter):
    """This set's texture for `parameter`, else the engine's neutral one (a flat normal, black)."""
    if parameter in textures:
        return textures[parameter]
    return unreal.EditorAssetLibrary.load_asset(ENGINE_DEFAULTS[parameter])


def parent_material(textures):
    """/Game/Matforge/M_MatforgeORM, made when missing. Every parameter has a default texture (this
    set's, or the engine's neutral one where the set has none), so it compiles whichever set
    makes it; each instance sets all of them (material_instance), so none shows another's."""
    if unreal.EditorAssetLibrary.does_asset_exist(PARENT):
        return unreal.EditorAssetLibrary.load_asset(PARENT)
    folder, name = PARENT.rsplit("/", 1)
    tools = unreal.AssetToolsHelpers.get_asset_tools()
    material = tools.create_asset(name, folder, unreal.Material, unreal.MaterialFactoryNew())
    mel = unreal.MaterialEditingLibrary
    for row, (parameter, sampler, feeds) in enumerate(PARAMETERS):
        node = mel.create_material_expression(material, unreal.MaterialExpressionTextureSampleParameter2D, -600, row * 300)
        node.set_editor_property("parameter_name", parameter)
        node.set_editor_property("sampler_type", getattr(unreal.MaterialSamplerType, sampler))
        node.set_editor_property("texture", texture_for(textures, parameter))
        for output, prop in feeds:
            if prop != "MP_EMISSIVE_COLOR":
                mel.connect_material_property(node, output, getattr(unreal.MaterialProperty, prop))
                continue
            # Emissive colour is the texture times EmissiveStrength (HDR emission, normalized).
            strength = mel.create_material_expression(material, unreal.MaterialExpressionScalarParameter, -600,
                                                      len(PARAMETERS) * 300)
            strength.set_editor_property("parameter_name", "EmissiveStrength")
            strength.set_editor_property("default_value", 1.0)
            emissive = mel.create_material_expression(material, unreal.MaterialExpressionMultiply, -250, row * 300)
            mel.connect_material_expressions(node, output, emissive, "A")
            mel.connect_material_expressions(strength, "", emissive, "B")
            mel.connect_material_property(emissive, "", unreal.MaterialProperty.MP_EMISSIVE_COLOR)
    mel.recompile_material(material)
    unreal.EditorAssetLibrary.save_loaded_asset(material)
    return material


def material_instance(textures, parent):
    """MI_<material> in DEST: every imported texture on its parameter, the blend mode of the set."""
    tools = unreal.AssetToolsHelpers.get_asset_tools()
    path = DEST + "/" + INSTANCE
    if unreal.EditorAssetLibrary.does_asset_exist(path):
        instance = unreal.EditorAssetLibrary.load_asset(path)
    else:
        instance = tools.create_asset(INSTANCE, DEST, unreal.MaterialInstanceConstant,
                                      unreal.MaterialInstanceConstantFactoryNew())
    mel = unreal.MaterialEditingLibrary
    mel.set_material_instance_parent(instance, parent)
    # Every parameter, whatever the parent's defaults are (another set's, if it made the parent).
    for parameter, _, _ in PARAMETERS:
        mel.set_material_instance_texture_parameter_value(instance, parameter, texture_for(textures, parameter))
    mel.set_material_instance_scalar_parameter_value(instance, "EmissiveStrength", EMISSIVE_STRENGTH)
    overrides = instance.get_editor_property("base_property_overrides")
    overrides.set_editor_property("override_blend_mode", True)
    overrides.set_editor_property("blend_mode", getattr(unreal.BlendMode, BLEND_MODE))
    overrides.set_editor_property("override_opacity_mask_clip_value", True)
    overrides.set_editor_property("opacity_mask_clip_value", OPACITY_MASK_CLIP_VALUE)
    overrides.set_editor_property("override_two_sided", True)
    overrides.set_editor_property("two_sided", BLEND_MODE != "BLEND_OPAQUE")
    instance.set_editor_property("base_property_overrides", overrides)
    mel.update_material_instance(instance)
    unreal.EditorAssetLibrary.save_loaded_asset(instance)
    return instance


textures = import_textures()
material_instance(textures, parent_material(textures))
)PY";

// The folder's script: every material's import script under it, each on its own.
constexpr const char* kImportAll = R"PY(# matforge: imports every material of this folder into /Game/Matforge: runs each
# <material>/import_<material>.py under it, in name order. Each stands alone (its textures, its
# instance, every parameter set), so the order changes nothing.
# Run in the Unreal Editor (Tools > Execute Python Script) or
#   UnrealEditor-Cmd Project.uproject -run=pythonscript -script=<this file>
import os
import runpy

HERE = os.path.dirname(os.path.abspath(__file__))
for name in sorted(os.listdir(HERE)):
    script = os.path.join(HERE, name, "import_" + name + ".py")
    if os.path.isfile(script):
        runpy.run_path(script, run_name="__main__")
)PY";

}  // namespace

File unreal_import_all() { return {"import_all.py", "py", kImportAll}; }

std::vector<File> unreal_files(const EngineMaterial& e, const manifest::Material& m, const std::vector<Bound>& bound) {
    const fs::path script = fs::path(m.name) / ("import_" + m.name + ".py");
    const std::string id = scene_identifier(m.name);
    std::string list;
    bool emissive = false;
    for (const Bound& b : bound) {
        list += "    (" +
                string_literal(fs::path(b.output->file).lexically_relative(script.parent_path()).generic_string()) +
                ", " + string_literal(std::string(b.slot->slot)) + ", " + (b.slot->srgb ? "True" : "False") + ", " +
                string_literal(std::string(b.slot->compression)) + "),\n";
        emissive = emissive || b.slot->reads_role(Role::emissive);
    }
    // The engine's neutral texture of each slot that has one (the parent reads it where a set has
    // no map), and the parent's parameters: each slot with a sampler, the inputs its channels feed.
    std::string defaults, parameters;
    for (const EngineSlot& s : e.slots) {
        if (!s.fallback.empty())
            defaults += (defaults.empty() ? "" : ", ") + string_literal(std::string(s.slot)) + ": " +
                        string_literal(std::string(s.fallback));
        if (s.sampler.empty()) continue;
        std::string feeds;
        for (const SlotRead& r : s.reads) {
            std::string_view inputs = r.input;
            while (!inputs.empty()) {
                const size_t end = std::min(inputs.find(' '), inputs.size());
                feeds += std::string(feeds.empty() ? "" : ", ") + "(" + string_literal(std::string(r.key)) + ", " +
                         string_literal(std::string(inputs.substr(0, end))) + ")";
                inputs.remove_prefix(std::min(end + 1, inputs.size()));
            }
        }
        parameters += "    (" + string_literal(std::string(s.slot)) + ", " + string_literal(std::string(s.sampler)) +
                      ", [" + feeds + "]),\n";
    }
    using manifest::AlphaMode;
    const char* blend = !m.alpha_mode || *m.alpha_mode == AlphaMode::opaque ? "BLEND_OPAQUE"
                        : *m.alpha_mode == AlphaMode::mask                  ? "BLEND_MASKED"
                                                                            : "BLEND_TRANSLUCENT";
    std::string text = "# " + std::string(kGenerator) + ": imports the textures of " + string_literal(m.name) +
                       " into /Game/Matforge and makes its material instance.\n"
                       "# Run in the Unreal Editor (Tools > Execute Python Script) or\n"
                       "#   UnrealEditor-Cmd Project.uproject -run=pythonscript -script=<this file>\n"
                       "import os\n\nimport unreal\n\nHERE = os.path.dirname(os.path.abspath(__file__))\n"
                       "DEST = " +
                       string_literal("/Game/Matforge/" + id) +
                       "\nPARENT = \"/Game/Matforge/M_MatforgeORM\"\nINSTANCE = " + string_literal("MI_" + id) +
                       "\n# (file beside this script, parameter of the parent material, sRGB, compression)\n"
                       "TEXTURES = [\n" +
                       list + "]\nBLEND_MODE = \"" + blend +
                       "\"\nOPACITY_MASK_CLIP_VALUE = " + scene_number(m.alpha_cutoff) +
                       "\nEMISSIVE_STRENGTH = " + scene_number(emissive ? m.emissive_strength : 0.f) +
                       "\n# The engine's own neutral textures for a slot this set has no map for.\n"
                       "ENGINE_DEFAULTS = {" +
                       defaults +
                       "}\n# The parent's texture parameters: (parameter, sampler type, [(channel, material input)])\n"
                       "PARAMETERS = [\n" +
                       parameters + "]\n" + kBody;
    return {{script.generic_string(), "py", std::move(text)}};
}

}  // namespace mf::engine
