# Blender (3.4) script: renders one scene of scenes.json with Cycles on the CPU to a linear float
# EXR. Run headless:
#   blender -b --factory-startup --python cycles_scene.py -- SCENES.json SCENE VARIANT SAMPLES SEED OUT.exr [ETABLE_DIR]
# VARIANT (how the dielectric's diffuse is built; metals are the same in all three):
#   principled      Cycles' own Principled BSDF (Burley diffuse with retro-reflection, not weighted
#                   by the specular), Multiscatter GGX
#   lambert_add     Diffuse BSDF (Lambert) + the Principled specular lobe alone, added (no coupling)
#   lambert_scaled  Diffuse BSDF (Lambert) x (1 - E_s(n.v)) + the Principled specular lobe: albedo
#                   scaling by the specular lobe's directional albedo (Multiscatter GGX, Fresnel of
#                   IOR 1.5), tabulated per roughness by brdf_tables.py as ETABLE_DIR/escale_rR.exr
# The camera, lights, sphere mesh (three.js SphereGeometry: same vertices and (u, v)) and units
# (Sun strength S = irradiance S, as matforge's directional intensity) follow the scene entry.
import json
import math
import os
import sys
import time

import bpy
from mathutils import Vector

argv = sys.argv[sys.argv.index("--") + 1:]
scenes_path, scene_name, variant, samples, seed, out_path = argv[:6]
etable_dir = argv[6] if len(argv) > 6 else None
samples, seed = int(samples), int(seed)
doc = json.load(open(scenes_path))
common, sc = doc["common"], next(s for s in doc["scenes"] if s["name"] == scene_name)
base_dir = os.path.dirname(os.path.abspath(scenes_path))
assert variant in ("principled", "lambert_add", "lambert_scaled"), variant

# ---- empty scene ----
for o in list(bpy.data.objects):
    bpy.data.objects.remove(o, do_unlink=True)
scene = bpy.context.scene
scene.render.engine = "CYCLES"
cy = scene.cycles
cy.device = "CPU"
cy.samples = samples
cy.use_adaptive_sampling = False
cy.use_denoising = False
cy.seed = seed
cy.use_animated_seed = False
cy.pixel_filter_type = "BOX"   # box over the pixel: what N x N supersampling computes
cy.filter_width = 1.0
cy.sample_clamp_direct = 0.0
cy.sample_clamp_indirect = 0.0
cy.max_bounces = 4
cy.caustics_reflective = True
cy.caustics_refractive = True
scene.render.threads_mode = "AUTO"
scene.render.resolution_x = common["size"]
scene.render.resolution_y = common["size"]
scene.render.resolution_percentage = 100
scene.render.film_transparent = False
scene.view_settings.view_transform = "Standard"
scene.view_settings.look = "None"
scene.view_settings.exposure = 0.0
scene.view_settings.gamma = 1.0
scene.sequencer_colorspace_settings.name = "Linear"
im = scene.render.image_settings
im.file_format = "OPEN_EXR"
im.color_mode = "RGB"
im.color_depth = "32"
im.exr_codec = "ZIP"

# ---- world: constant background (black) ----
world = bpy.data.worlds.new("world")
world.use_nodes = True
bg = world.node_tree.nodes["Background"]
bg.inputs["Color"].default_value = (*common["background"], 1.0)
bg.inputs["Strength"].default_value = 1.0
scene.world = world

# ---- camera: perspective, vertical FOV, looking from position to target with up ----
cam_data = bpy.data.cameras.new("cam")
cam_data.type = "PERSP"
cam_data.sensor_fit = "VERTICAL"
cam_data.angle_y = math.radians(common["camera"]["yfov_deg"])
cam_data.clip_start = 0.01
cam_data.clip_end = 100.0
cam = bpy.data.objects.new("cam", cam_data)
bpy.context.collection.objects.link(cam)
pos, tgt = Vector(common["camera"]["position"]), Vector(common["camera"]["target"])
cam.location = pos
# Blender cameras look along local -Z with local +Y up.
cam.rotation_euler = (tgt - pos).to_track_quat("-Z", "Y").to_euler()
scene.camera = cam

# ---- lights: Sun lamps, angle 0 (a point-like sun), strength = irradiance ----
for i, l in enumerate(common["lights"]):
    ld = bpy.data.lights.new(f"sun{i}", "SUN")
    ld.energy = l["intensity"]          # W/m^2: irradiance on a surface facing it
    ld.angle = 0.0
    ld.color = tuple(l.get("color", [1, 1, 1]))
    ld.cycles.cast_shadow = True
    lo = bpy.data.objects.new(f"sun{i}", ld)
    bpy.context.collection.objects.link(lo)
    d = Vector(l["direction"]).normalized()   # direction of travel; a Sun emits along its local -Z
    lo.rotation_euler = d.to_track_quat("-Z", "Y").to_euler()

# ---- the sphere: three.js SphereGeometry(radius, W, H), exact normals ----
W, H, r = common["sphere_segments"][0], common["sphere_segments"][1], common["radius"]
verts, uvs, grid = [], [], []
for iy in range(H + 1):
    v = iy / H
    u_off = 0.5 / W if iy == 0 else (-0.5 / W if iy == H else 0.0)
    row = []
    for ix in range(W + 1):
        u = ix / W
        phi, theta = u * 2 * math.pi, v * math.pi
        verts.append((-r * math.cos(phi) * math.sin(theta), r * math.cos(theta),
                      r * math.sin(phi) * math.sin(theta)))
        uvs.append((u + u_off, 1 - v))
        row.append(len(verts) - 1)
    grid.append(row)
faces = []
for iy in range(H):
    for ix in range(W):
        a, b, c, d = grid[iy][ix + 1], grid[iy][ix], grid[iy + 1][ix], grid[iy + 1][ix + 1]
        if iy != 0:
            faces.append((a, b, d))
        if iy != H - 1:
            faces.append((b, c, d))
mesh = bpy.data.meshes.new("sphere")
mesh.from_pydata(verts, [], faces)
uv_layer = mesh.uv_layers.new(name="UVMap")
for poly in mesh.polygons:
    poly.use_smooth = True
    for li in poly.loop_indices:
        uv_layer.data[li].uv = uvs[mesh.loops[li].vertex_index]
mesh.use_auto_smooth = True
mesh.normals_split_custom_set_from_vertices([Vector(p).normalized() for p in verts])
mesh.update()
sphere = bpy.data.objects.new("sphere", mesh)
bpy.context.collection.objects.link(sphere)
sphere.cycles.shadow_terminator_geometry_offset = 0.0
sphere.cycles.shadow_terminator_offset = 0.0

# ---- material ----
m = sc["material"]
metal = float(m.get("metalness", 0.0))
assert metal in (0.0, 1.0), "metalness must be 0 or 1 (a spec-only lobe is built from it)"
rough = float(m["roughness"])
mat = bpy.data.materials.new("mat")
mat.use_nodes = True
nt = mat.node_tree
nodes, links = nt.nodes, nt.links
for n in list(nodes):
    nodes.remove(n)
outn = nodes.new("ShaderNodeOutputMaterial")
albedo_socket = None
if "albedo_map" in m:
    tex = nodes.new("ShaderNodeTexImage")
    tex.image = bpy.data.images.load(os.path.join(base_dir, m["albedo_map"]))
    tex.image.colorspace_settings.name = "sRGB"
    tex.interpolation = "Linear"
    tex.extension = "REPEAT"
    uvn = nodes.new("ShaderNodeUVMap")
    uvn.uv_map = "UVMap"
    links.new(uvn.outputs["UV"], tex.inputs["Vector"])
    albedo_socket = tex.outputs["Color"]
albedo = tuple(m.get("albedo", [1, 1, 1])) + (1.0,)


def principled(base_from_albedo):
    p = nodes.new("ShaderNodeBsdfPrincipled")
    p.distribution = "MULTI_GGX"
    p.subsurface_method = "BURLEY"
    p.inputs["Metallic"].default_value = metal
    p.inputs["Specular"].default_value = 0.5          # F0 = 0.08 * 0.5 = 0.04, IOR 1.5
    p.inputs["Specular Tint"].default_value = 0.0
    p.inputs["Roughness"].default_value = rough        # perceptual: alpha = r^2, as ours
    p.inputs["Sheen"].default_value = 0.0
    p.inputs["Clearcoat"].default_value = 0.0
    p.inputs["Subsurface"].default_value = 0.0
    p.inputs["Transmission"].default_value = 0.0
    if base_from_albedo:
        if albedo_socket is not None:
            links.new(albedo_socket, p.inputs["Base Color"])
        else:
            p.inputs["Base Color"].default_value = albedo
    else:
        p.inputs["Base Color"].default_value = (0, 0, 0, 1)
    return p


if variant == "principled" or metal == 1.0:
    shader = principled(True).outputs["BSDF"]
else:
    spec = principled(False)        # black base, dielectric: the specular lobe alone
    diff = nodes.new("ShaderNodeBsdfDiffuse")
    diff.inputs["Roughness"].default_value = 0.0   # Lambert (Oren-Nayar with sigma 0)
    colour = albedo_socket
    if variant == "lambert_scaled":
        geo = nodes.new("ShaderNodeNewGeometry")
        dot = nodes.new("ShaderNodeVectorMath")
        dot.operation = "DOT_PRODUCT"
        links.new(geo.outputs["Normal"], dot.inputs[0])
        links.new(geo.outputs["Incoming"], dot.inputs[1])
        comb = nodes.new("ShaderNodeCombineXYZ")
        links.new(dot.outputs["Value"], comb.inputs["X"])
        comb.inputs["Y"].default_value = 0.5
        et = nodes.new("ShaderNodeTexImage")
        et.image = bpy.data.images.load(os.path.join(etable_dir, f"escale_r{rough:.2f}.exr"))
        et.image.colorspace_settings.name = "Non-Color"
        et.interpolation = "Linear"
        et.extension = "EXTEND"
        links.new(comb.outputs["Vector"], et.inputs["Vector"])
        mul = nodes.new("ShaderNodeMixRGB")
        mul.blend_type = "MULTIPLY"
        mul.inputs["Fac"].default_value = 1.0
        if albedo_socket is not None:
            links.new(albedo_socket, mul.inputs["Color1"])
        else:
            mul.inputs["Color1"].default_value = albedo
        links.new(et.outputs["Color"], mul.inputs["Color2"])
        colour = mul.outputs["Color"]
    if colour is not None:
        links.new(colour, diff.inputs["Color"])
    else:
        diff.inputs["Color"].default_value = albedo
    add = nodes.new("ShaderNodeAddShader")
    links.new(diff.outputs["BSDF"], add.inputs[0])
    links.new(spec.outputs["BSDF"], add.inputs[1])
    shader = add.outputs["Shader"]
links.new(shader, outn.inputs["Surface"])
sphere.data.materials.append(mat)

scene.render.filepath = out_path
t0 = time.time()
bpy.ops.render.render(write_still=True)
print(f"CYCLES_DONE {scene_name} {variant} spp={samples} seed={seed} {time.time() - t0:.1f}s")
