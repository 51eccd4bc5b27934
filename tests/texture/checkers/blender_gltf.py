"""Blender's own glTF importer on an empty scene: shared by blender_open.py and blender_render.py
(run with the virtual environment of scripts/py-checkers.sh, where PyPI's bpy is)."""
import bpy


def import_gltf(path, before=None):
    """Empties the scene (unless `before` runs first on the empty scene: another import to keep),
    imports `path`; returns "" or the importer's error."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    try:
        if before is not None:
            error = before()
            if error:
                return error
        result = bpy.ops.import_scene.gltf(filepath=path)
    except RuntimeError as e:
        return str(e).strip()
    return "" if "FINISHED" in result else "the importer returned " + str(result)
