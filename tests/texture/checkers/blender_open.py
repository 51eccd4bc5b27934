"""Imports glTF files with Blender itself (PyPI bpy 4.5: Blender as a Python module, installed by
scripts/py-checkers.sh; run with that environment's python) through Blender's own glTF importer
(io_import_scene_gltf2), and reports the material Blender made of each: which image feeds each
input of its Principled BSDF, through which channel, in which colour space, and whether Blender
loaded the image's pixels. It shares no code with matforge's writer (lib/engine/gltf.cpp).

    blender_open.py FILE...

prints one JSON line per file:
  {"file", "ok", "error", "materials": [{"name", "blend", "inputs": {
      "<Principled input>": {"image": absolute path, "colorspace", "size": [w, h], "loaded",
                             "channel": "RGB" | "A" | "R" | "G" | "B", "via": [node types]}}}]}
"""
import json
import os
import sys

import bpy

from blender_gltf import import_gltf

INPUTS = ("Base Color", "Alpha", "Metallic", "Roughness", "Normal", "Emission Color")


def image_source(socket, via):
    """The Image Texture feeding `socket` (through Separate Color, Normal Map and the like), with
    the channel it is read from."""
    if not socket.is_linked:
        return None
    link = socket.links[0]
    node, out = link.from_node, link.from_socket
    if node.type == "TEX_IMAGE":
        return node, ("A" if out.name == "Alpha" else "RGB")
    via.append(node.type)
    if node.type == "SEPARATE_COLOR":
        found = image_source(node.inputs[0], via)
        return (found[0], {"Red": "R", "Green": "G", "Blue": "B"}[out.name]) if found else None
    for i in node.inputs:  # Normal Map's Color, a Math or Mix node's inputs
        if i.is_linked:
            found = image_source(i, via)
            if found:
                return found
    return None


def open_one(path):
    rep = {"file": path, "ok": False, "error": import_gltf(path), "materials": []}
    if rep["error"]:
        return rep
    rep["ok"] = True
    for mat in bpy.data.materials:
        if not mat.use_nodes:
            continue
        bsdf = next((n for n in mat.node_tree.nodes if n.type == "BSDF_PRINCIPLED"), None)
        m = {"name": mat.name, "blend": getattr(mat, "surface_render_method", ""), "inputs": {}}
        for name in INPUTS:
            if bsdf is None or name not in bsdf.inputs:
                continue
            via = []
            found = image_source(bsdf.inputs[name], via)
            if not found:
                continue
            node, channel = found
            image = node.image
            m["inputs"][name] = {
                "image": os.path.realpath(bpy.path.abspath(image.filepath)) if image else "",
                "colorspace": image.colorspace_settings.name if image else "",
                "size": list(image.size) if image else [0, 0],
                "loaded": bool(image) and (image.has_data or len(image.pixels) > 0),
                "channel": channel,
                "via": via,
            }
        if bsdf is not None:
            m["emission_strength"] = bsdf.inputs["Emission Strength"].default_value
        rep["materials"].append(m)
    return rep


def main():
    for path in sys.argv[1:]:
        print(json.dumps(open_one(os.path.realpath(path))), flush=True)


if __name__ == "__main__":
    main()
