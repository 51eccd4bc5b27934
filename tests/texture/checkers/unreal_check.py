#!/usr/bin/env python3
"""Runs matforge's Unreal import scripts against a recording stand-in of the editor's `unreal`
module (no Unreal Editor runs here): every class, function, property and enum value the stand-in
offers is one the Unreal Python API reference documents (AssetImportTask, AssetTools,
AssetToolsHelpers, EditorAssetLibrary, MaterialEditingLibrary, Texture, TextureCompressionSettings,
MaterialSamplerType, MaterialProperty, BlendMode), and anything else fails the script:

    python3 unreal_check.py [--session] SCRIPT.py...

(--session: the scripts run one after the other in one project, as an editor session runs them;
else each in a fresh project)

prints one JSON line per script: {file, ok, error, parses, imports: [{filename, exists,
destination_path, automated, replace_existing}], textures: {asset path: {srgb, compression}},
parent: {created, samplers: {parameter: sampler}, connections: [[parameter, output, property]]},
instance: {path, parent, textures: {parameter: asset path}, scalars: {name: value}, overrides}}."""
import ast
import json
import os
import runpy
import sys
import types


def enum(name, values):
    cls = type(name, (), {})
    for v in values:
        setattr(cls, v, name + "." + v)
    return cls


class Recorder:
    def __init__(self):
        self.reset()

    def reset(self, keep_assets=False):
        """A fresh project, or with keep_assets the same project (its assets and parent) for the
        next script: --session runs scripts one after the other as an editor session does."""
        self.imports, self.textures, self.instance = [], {}, {}
        if keep_assets:
            self.parent["created"] = False
            return
        self.assets = {p: Texture2D(p) for p in ENGINE_CONTENT}
        self.parent = {"created": False, "samplers": {}, "connections": [], "scalars": {}, "defaults": {}}


# Textures every Unreal project has (the engine's content): the flat normal map and black.
ENGINE_CONTENT = ("/Engine/EngineMaterials/FlatNormal", "/Engine/EngineResources/Black")



class Object:
    """An editor object: properties only through set/get_editor_property, names checked."""
    PROPERTIES = ()

    def __init__(self, path=""):
        object.__setattr__(self, "_props", {})
        object.__setattr__(self, "path", path)

    def set_editor_property(self, name, value):
        if name not in self.PROPERTIES:
            raise AttributeError(type(self).__name__ + " has no editor property " + name)
        self._props[name] = value

    def get_editor_property(self, name):
        if name not in self.PROPERTIES:
            raise AttributeError(type(self).__name__ + " has no editor property " + name)
        return self._props.get(name)


class AssetImportTask(Object):
    PROPERTIES = ("filename", "destination_path", "destination_name", "automated", "replace_existing", "save",
                  "imported_object_paths", "options", "factory")


class Texture2D(Object):
    PROPERTIES = ("srgb", "compression_settings", "flip_green_channel", "lod_group")

    def set_editor_property(self, name, value):
        super().set_editor_property(name, value)
        R.textures.setdefault(self.path, {})[name] = value


class MaterialInstanceBasePropertyOverrides(Object):
    PROPERTIES = ("override_blend_mode", "blend_mode", "override_opacity_mask_clip_value", "opacity_mask_clip_value",
                  "override_two_sided", "two_sided", "override_shading_model", "shading_model")


class Material(Object):
    PROPERTIES = ("blend_mode", "two_sided", "opacity_mask_clip_value")


class MaterialInstanceConstant(Object):
    PROPERTIES = ("base_property_overrides", "parent")

    def __init__(self, path=""):
        super().__init__(path)
        self._props["base_property_overrides"] = MaterialInstanceBasePropertyOverrides()


class MaterialExpressionTextureSampleParameter2D(Object):
    PROPERTIES = ("parameter_name", "sampler_type", "texture", "group")

    def set_editor_property(self, name, value):
        super().set_editor_property(name, value)
        if name == "texture":
            R.parent["defaults"][self._props.get("parameter_name")] = value.path


class MaterialExpressionScalarParameter(Object):
    PROPERTIES = ("parameter_name", "default_value", "group")


class MaterialExpressionMultiply(Object):
    PROPERTIES = ("const_a", "const_b")


class MaterialFactoryNew(Object):
    pass


class MaterialInstanceConstantFactoryNew(Object):
    PROPERTIES = ("initial_parent",)


class AssetTools:
    def import_asset_tasks(self, tasks):
        for t in tasks:
            if not isinstance(t, AssetImportTask):
                raise TypeError("import_asset_tasks takes AssetImportTask objects")
            p = t._props
            R.imports.append({k: p.get(k) for k in ("filename", "destination_path", "automated", "replace_existing")})
            R.imports[-1]["exists"] = os.path.isfile(p.get("filename") or "")
            path = p["destination_path"] + "/" + os.path.splitext(os.path.basename(p["filename"]))[0]
            R.assets[path] = Texture2D(path)
            p["imported_object_paths"] = [path]

    def create_asset(self, asset_name, package_path, asset_class, factory):
        path = package_path + "/" + asset_name
        if asset_class is Material and isinstance(factory, MaterialFactoryNew):
            R.parent["created"] = True
            R.parent["path"] = path
        elif not (asset_class is MaterialInstanceConstant and isinstance(factory, MaterialInstanceConstantFactoryNew)):
            raise TypeError("create_asset: " + asset_class.__name__ + " with " + type(factory).__name__)
        R.assets[path] = asset_class(path)
        return R.assets[path]


class AssetToolsHelpers:
    @staticmethod
    def get_asset_tools():
        return AssetTools()


class EditorAssetLibrary:
    @staticmethod
    def load_asset(path):
        if path not in R.assets:
            raise KeyError("load_asset: no asset " + path)
        return R.assets[path]

    @staticmethod
    def does_asset_exist(path):
        return path in R.assets

    @staticmethod
    def save_loaded_asset(asset, only_if_is_dirty=True):
        return isinstance(asset, Object)


def param_name(node):
    return node.get_editor_property("parameter_name")


class MaterialEditingLibrary:
    @staticmethod
    def create_material_expression(material, expression_class, node_pos_x=0, node_pos_y=0):
        if not isinstance(material, Material):
            raise TypeError("create_material_expression on a " + type(material).__name__)
        return expression_class()

    @staticmethod
    def connect_material_property(from_expression, from_output_name, material_property):
        if not str(material_property).startswith("MaterialProperty."):
            raise TypeError("connect_material_property: not a MaterialProperty")
        name = param_name(from_expression) if "parameter_name" in from_expression.PROPERTIES else \
            type(from_expression).__name__
        R.parent["connections"].append([name, from_output_name, material_property.split(".")[1]])
        return True

    @staticmethod
    def connect_material_expressions(from_expression, from_output_name, to_expression, to_input_name):
        return True

    @staticmethod
    def recompile_material(material):
        if not isinstance(material, Material):
            raise TypeError("recompile_material on a " + type(material).__name__)

    @staticmethod
    def set_material_instance_parent(instance, new_parent):
        R.instance["path"] = instance.path
        R.instance["parent"] = new_parent.path

    @staticmethod
    def set_material_instance_texture_parameter_value(instance, parameter_name, value, association=None):
        R.instance.setdefault("textures", {})[parameter_name] = value.path
        return True

    @staticmethod
    def set_material_instance_scalar_parameter_value(instance, parameter_name, value, association=None):
        R.instance.setdefault("scalars", {})[parameter_name] = float(value)
        return True

    @staticmethod
    def update_material_instance(instance):
        o = instance.get_editor_property("base_property_overrides")._props
        R.instance["overrides"] = dict(o)


R = Recorder()  # after the classes its reset() makes


def fake_unreal():
    m = types.ModuleType("unreal")
    for obj in (AssetImportTask, AssetToolsHelpers, EditorAssetLibrary, MaterialEditingLibrary, Material,
                MaterialInstanceConstant, MaterialFactoryNew, MaterialInstanceConstantFactoryNew,
                MaterialExpressionTextureSampleParameter2D, MaterialExpressionScalarParameter,
                MaterialExpressionMultiply, Texture2D):
        setattr(m, obj.__name__, obj)
    m.TextureCompressionSettings = enum("TextureCompressionSettings", [
        "TC_DEFAULT", "TC_NORMALMAP", "TC_MASKS", "TC_GRAYSCALE", "TC_DISPLACEMENTMAP", "TC_VECTOR_DISPLACEMENTMAP",
        "TC_HDR", "TC_EDITOR_ICON", "TC_ALPHA", "TC_DISTANCE_FIELD_FONT", "TC_HDR_COMPRESSED", "TC_BC7"])
    m.MaterialSamplerType = enum("MaterialSamplerType", [
        "SAMPLERTYPE_COLOR", "SAMPLERTYPE_GRAYSCALE", "SAMPLERTYPE_ALPHA", "SAMPLERTYPE_NORMAL", "SAMPLERTYPE_MASKS",
        "SAMPLERTYPE_DISTANCE_FIELD_FONT", "SAMPLERTYPE_LINEAR_COLOR", "SAMPLERTYPE_LINEAR_GRAYSCALE"])
    m.MaterialProperty = enum("MaterialProperty", [
        "MP_EMISSIVE_COLOR", "MP_OPACITY", "MP_OPACITY_MASK", "MP_BASE_COLOR", "MP_METALLIC", "MP_SPECULAR",
        "MP_ROUGHNESS", "MP_ANISOTROPY", "MP_NORMAL", "MP_TANGENT", "MP_WORLD_POSITION_OFFSET",
        "MP_AMBIENT_OCCLUSION", "MP_REFRACTION", "MP_PIXEL_DEPTH_OFFSET"])
    m.BlendMode = enum("BlendMode", ["BLEND_OPAQUE", "BLEND_MASKED", "BLEND_TRANSLUCENT", "BLEND_ADDITIVE",
                                     "BLEND_MODULATE", "BLEND_ALPHA_COMPOSITE", "BLEND_ALPHA_HOLDOUT"])
    return m


def check(path, session=False):
    R.reset(keep_assets=session)
    out = {"file": path, "ok": False, "error": "", "parses": False}
    try:
        tree = ast.parse(open(path, encoding="utf-8").read(), path)
        out["parses"] = True
        out["constants"] = {}
        for node in tree.body:
            if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name):
                try:
                    out["constants"][node.targets[0].id] = ast.literal_eval(node.value)
                except ValueError:
                    pass
        sys.modules["unreal"] = fake_unreal()
        runpy.run_path(path, run_name="__main__")
        out["ok"] = True
    except Exception as e:  # noqa: BLE001 - every failure is the script's verdict
        out["error"] = type(e).__name__ + ": " + str(e)
    out["imports"], out["textures"], out["parent"], out["instance"] = R.imports, R.textures, R.parent, R.instance
    return out


if __name__ == "__main__":
    args = sys.argv[1:]
    session = bool(args) and args[0] == "--session"
    if session:
        args = args[1:]
    for i, f in enumerate(args):
        print(json.dumps(check(f, session=session and i > 0), sort_keys=True, default=str))
