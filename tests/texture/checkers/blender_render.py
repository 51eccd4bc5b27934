"""Renders matforge's glTF materials with Blender itself (PyPI bpy 4.5, installed by
scripts/py-checkers.sh; run with that environment's python): each .gltf imported by Blender's own
glTF importer (the sphere it carries, with its material), or with `--usd`, the material of the
.usda beside it imported by Blender's own USD importer and put on that sphere; rendered by Cycles
on the CPU under the scene of `matforge preview --scene reference`: camera on +Z at four radii
looking at the centre, vertical field of view 35 degrees, one white sun travelling along
(0.577, -0.577, -0.577) (glTF axes) of irradiance 3, black world, direct light only, no tone
mapping (Standard view: the sRGB curve only), box pixel filter one pixel wide.

    blender_render.py [--usd] SIZE SAMPLES OUT_DIR FILE.gltf...

prints one JSON line per file: {"file", "ok", "error", "png": OUT_DIR/<stem>.blender(.usd).png,
"seconds"}. Sided as the glTF asks, as the preview draws it: a material the importer marks
single-sided (backface culling on: the glTF's doubleSided false) gets its back faces transparent
through the shader's Backfacing output (Cycles has no back-face culling); a double-sided one (a
cut-out) shows its far side. With `--usd`, the USD material is sided as the glTF beside it.
"""
import json
import math
import os
import sys
import time

import bpy
from mathutils import Vector

from blender_gltf import import_gltf

SUN_GLTF = (0.577, -0.577, -0.577)  # the reference scene's light, direction of travel
SUN_IRRADIANCE = 3.0                # the reference scene's intensity: E on a surface facing it
YFOV_DEG = 35.0
RADIUS = 0.5                        # the glTF's sphere (lib/engine/gltf.cpp); the preview's is 1


def to_blender(v):
    """glTF's Y-up axes to Blender's Z-up, as Blender's importer converts them."""
    return Vector((v[0], -v[2], v[1]))


def single_sided(mat):
    """Back faces transparent: mixes the surface with a Transparent BSDF on Backfacing."""
    nt = mat.node_tree
    out = next((n for n in nt.nodes if n.type == "OUTPUT_MATERIAL" and n.is_active_output), None)
    if out is None or not out.inputs["Surface"].is_linked:
        return
    link = out.inputs["Surface"].links[0]
    surface = link.from_socket
    nt.links.remove(link)
    geometry = nt.nodes.new("ShaderNodeNewGeometry")
    transparent = nt.nodes.new("ShaderNodeBsdfTransparent")
    mix = nt.nodes.new("ShaderNodeMixShader")
    nt.links.new(geometry.outputs["Backfacing"], mix.inputs["Fac"])
    nt.links.new(surface, mix.inputs[1])
    nt.links.new(transparent.outputs["BSDF"], mix.inputs[2])
    nt.links.new(mix.outputs["Shader"], out.inputs["Surface"])


def stage(size, samples):
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = samples
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.use_denoising = False
    scene.cycles.max_bounces = 0  # direct light only, as the preview's reference scene
    scene.cycles.pixel_filter_type = "BOX"
    scene.cycles.filter_width = 1.0
    scene.cycles.seed = 1
    scene.render.resolution_x = scene.render.resolution_y = size
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = False
    scene.render.image_settings.file_format = "PNG"
    scene.render.image_settings.color_mode = "RGB"
    scene.render.image_settings.color_depth = "8"
    scene.display_settings.display_device = "sRGB"
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    world = bpy.data.worlds.new("black")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    scene.world = world
    cam = bpy.data.cameras.new("camera")
    cam.sensor_fit = "VERTICAL"
    cam.angle_y = math.radians(YFOV_DEG)
    cam.clip_start, cam.clip_end = 0.01, 100.0
    cam_obj = bpy.data.objects.new("camera", cam)
    cam_obj.location = to_blender((0.0, 0.0, 4.0 * RADIUS))
    cam_obj.rotation_euler = (math.radians(90.0), 0.0, 0.0)  # looks along +Y (glTF -Z), Z up
    scene.collection.objects.link(cam_obj)
    scene.camera = cam_obj
    sun = bpy.data.lights.new("sun", type="SUN")
    sun.energy = SUN_IRRADIANCE
    sun.angle = 0.0
    sun_obj = bpy.data.objects.new("sun", sun)
    sun_obj.rotation_euler = to_blender(SUN_GLTF).normalized().to_track_quat("-Z", "Y").to_euler()
    scene.collection.objects.link(sun_obj)


def render_one(path, usd, size, samples, out_dir):
    stem = os.path.splitext(os.path.basename(path))[0]
    png = os.path.join(out_dir, stem + (".blender.usd.png" if usd else ".blender.png"))
    rep = {"file": path, "ok": False, "error": "", "png": png}
    t0 = time.monotonic()
    made = []

    def usd_material():
        bpy.ops.wm.usd_import(filepath=os.path.splitext(path)[0] + ".usda", import_materials=True,
                              import_all_materials=True)
        made.extend(bpy.data.materials)
        return "" if len(made) == 1 else "the USD importer made %d materials" % len(made)

    rep["error"] = import_gltf(path, usd_material if usd else None)
    if rep["error"]:
        return rep
    material = made[0] if usd else None
    meshes = [o for o in bpy.context.scene.objects if o.type == "MESH"]
    if len(meshes) != 1:
        rep["error"] = "%d meshes imported" % len(meshes)
        return rep
    # The preview's sphere turns the glTF's a quarter: its u = 0.25 faces the camera where the
    # glTF's u = 0 does (lib/render/geometry.cpp, lib/engine/gltf.cpp).
    meshes[0].rotation_mode = "XYZ"
    meshes[0].rotation_euler = (0.0, 0.0, math.radians(-90.0))
    if material is not None:
        # A USD mesh carries its texture coordinates as the primvar the layer's
        # UsdPrimvarReader_float2 names ("st"); the glTF's are Blender's "UVMap".
        meshes[0].data.uv_layers[0].name = "st"
    # The glTF's doubleSided, as Blender's importer keeps it (use_backface_culling = not doubleSided).
    culled = any(m.use_backface_culling for m in meshes[0].data.materials if m)
    if material is not None:
        meshes[0].data.materials.clear()
        meshes[0].data.materials.append(material)
    for mat in meshes[0].data.materials:
        if mat and mat.use_nodes and culled:
            single_sided(mat)
    stage(size, samples)
    bpy.context.scene.render.filepath = png
    bpy.ops.render.render(write_still=True)
    rep["ok"] = os.path.isfile(png)
    if not rep["ok"]:
        rep["error"] = "no picture written"
    rep["seconds"] = round(time.monotonic() - t0, 2)
    return rep


def main():
    args = sys.argv[1:]
    usd = bool(args) and args[0] == "--usd"
    if usd:
        args = args[1:]
    size, samples, out_dir, files = int(args[0]), int(args[1]), args[2], args[3:]
    os.makedirs(out_dir, exist_ok=True)
    for path in files:
        print(json.dumps(render_one(os.path.realpath(path), usd, size, samples, out_dir)), flush=True)


if __name__ == "__main__":
    main()
