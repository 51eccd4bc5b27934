"""Writes the inputs every renderer reads, into WORK (run.sh's scratch folder):
  WORK/scenes.json             copy of bench/pathtracer/scenes.json (paths are relative to it)
  WORK/albedo_grid.png         the textured scene's albedo (sRGB 8-bit, 512 x 256)
  WORK/matforge/<scene>.json   matforge scene files
  WORK/etables/escale_rR.exr   1 - E_s(mu) of the dielectric lobe (IOR 1.5, multiple scattering),
                               mu = (i + 0.5)/128, for the Cycles `lambert_scaled` reference
  WORK/etables/tables.json     the same tables, and E(mu) with F = 1, for diagnose.py
usage: python3 make_inputs.py SCENES.json WORK
"""
import json
import os
import shutil
import sys

import numpy as np
import OpenImageIO as oiio

import brdf_model as bm

src, work = sys.argv[1], sys.argv[2]
os.makedirs(os.path.join(work, "matforge"), exist_ok=True)
os.makedirs(os.path.join(work, "etables"), exist_ok=True)
shutil.copy(src, os.path.join(work, "scenes.json"))
doc = json.load(open(src))
common = doc["common"]


def write(path, a, fmt):
    spec = oiio.ImageSpec(a.shape[1], a.shape[0], a.shape[2], fmt)
    buf = oiio.ImageBuf(spec)
    buf.set_pixels(oiio.ROI(), a)
    if not buf.write(path):
        raise SystemExit(f"cannot write {path}: {buf.geterror()}")


# The texture: 8 x 4 cells (hue by column, value by row) and a white notch in the cell at
# u in [0, 1/8), v in [3/4, 1) so that a flipped or shifted (u, v) is visible; 8-bit sRGB.
W, H = 512, 256
u = (np.arange(W) + 0.5) / W
v = (np.arange(H) + 0.5) / H  # image row 0 = top = v 1 in GL's convention
col = np.floor(u * 8).astype(int)
row = np.floor(v * 4).astype(int)
hues = np.array([[0.85, 0.20, 0.15], [0.90, 0.60, 0.10], [0.80, 0.80, 0.20], [0.25, 0.70, 0.20],
                 [0.15, 0.65, 0.70], [0.20, 0.30, 0.85], [0.55, 0.25, 0.80], [0.75, 0.75, 0.75]])
value = np.array([1.0, 0.75, 0.5, 0.3])
img = hues[col][None, :, :] * value[row][:, None, None]
img[: H // 8, : W // 32] = 1.0
write(os.path.join(work, "albedo_grid.png"), np.round(img * 255).astype(np.uint8), oiio.UINT8)

for sc in doc["scenes"]:
    m = sc["material"]
    mat = {"roughness": m["roughness"], "metalness": m.get("metalness", 0.0)}
    if "albedo" in m:
        mat["albedo"] = m["albedo"]
    if "albedo_map" in m:
        mat["maps"] = {"albedo": os.path.join("..", m["albedo_map"])}
    j = {
        "image": {"width": common["size"], "height": common["size"], "supersample": common["supersample"]},
        "camera": {k: common["camera"][k] for k in ("position", "target", "up", "yfov_deg")},
        "shape": {"type": "sphere", "radius": common["radius"]},
        "background": common["background"],
        "lights": [{"type": "directional", "direction": l["direction"], "intensity": l["intensity"],
                    "color": l.get("color", [1, 1, 1])} for l in common["lights"]],
        "material": mat,
        "output": {"tonemap": "none", "exposure": 1},
    }
    json.dump(j, open(os.path.join(work, "matforge", sc["name"] + ".json"), "w"), indent=1)

tables = {}
for r in sorted({float(s["material"]["roughness"]) for s in doc["scenes"]}):
    mus, Es = bm.dielectric_ms_albedo(r, 1.5, nmu=128, n=128)
    _, E1 = bm.albedo_table(r, "accurate", None, nmu=128, n=128)
    _, EFs = bm.albedo_table(r, "accurate", lambda c: bm.F_schlick(0.04, c), nmu=128, n=128)
    tables[f"{r:.2f}"] = {"mu": mus.tolist(), "Es_ior15": Es.tolist(), "E1": E1.tolist(),
                          "EF_schlick004": EFs.tolist()}
    row = np.repeat((1.0 - Es)[None, :, None], 3, -1).astype(np.float32)
    write(os.path.join(work, "etables", f"escale_r{r:.2f}.exr"), row, oiio.FLOAT)
    print(f"r={r:.2f}: E_s(mu=1)={Es[-1]:.4f} E_s(mu=0.5)={Es[63]:.4f} E_s(mu~0)={Es[0]:.4f}  "
          f"E1 avg={bm.average(mus, E1):.4f}")
json.dump(tables, open(os.path.join(work, "etables", "tables.json"), "w"))
