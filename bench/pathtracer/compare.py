"""Compares every renderer's linear radiance with the Cycles references and writes
WORK/results.json and WORK/results.md (the table of docs/accuracy/pathtracer.md).

Metrics, over the mask (pixels whose 4 x 4 sub-samples all hit the analytic sphere, eroded by
one pixel so that no renderer's silhouette coverage enters):
  psnr_lin   10 log10(1 / MSE) on linear RGB radiance: peak 1 = the radiance of a white Lambertian
             surface facing the key light (E / pi); highlights exceed it and are not clipped (a
             fixed peak, since the reference's maximum moves with Cycles' fireflies; the ranking of
             the renderers depends on the MSE only)
  psnr_srgb  PSNR on 8-bit sRGB codes (radiance clipped to [0, 1], exact sRGB curve, rounded):
             what `--tonemap none` shows
  ratio      sum(renderer) / sum(reference) over the mask, RGB summed: a systematic "5 % too dark"
             is ratio 0.95
Cycles' own noise: each reference is the mean of two renders with seeds 1 and 2; the MSE of that
mean against its expectation is estimated as mean((a - b)^2) / 4, reported as psnr_lin/psnr_srgb of
the noise, and the ratio's noise as |sum a - sum b| / (sum a + sum b).
usage: python3 compare.py WORK
"""
import json
import math
import os
import sys

import numpy as np
import OpenImageIO as oiio

import brdf_model as bm

work = sys.argv[1]
doc = json.load(open(os.path.join(work, "scenes.json")))
common = doc["common"]
size, ss = common["size"], common["supersample"]
REFS = ["lambert_scaled", "lambert_add", "principled"]
RENDERERS = ["mf_standard", "mf_accurate", "three", "filament"]


def read_exr(p):
    buf = oiio.ImageBuf(p)
    if buf.has_error:
        raise SystemExit(f"cannot read {p}: {buf.geterror()}")
    return buf.get_pixels(oiio.FLOAT)[..., :3].astype(np.float64)


def read_any(p):
    if p.endswith(".f32"):
        return np.fromfile(p, np.float32).reshape(size, size, 3).astype(np.float64)
    return read_exr(p)


def srgb8(x):
    x = np.clip(x, 0.0, 1.0)
    y = np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)
    return np.round(y * 255.0)


def psnr(mse, peak):
    return float("inf") if mse <= 0 else 10.0 * math.log10(peak * peak / mse)


hit = bm.sphere_hits(common)[0].reshape(size, ss, size, ss).all(axis=(1, 3))
mask = hit.copy()
for dy in (-1, 0, 1):
    for dx in (-1, 0, 1):
        mask &= np.roll(np.roll(hit, dy, 0), dx, 1)

paths = {
    "mf_standard": lambda s: f"{work}/out/matforge/{s}__mf_standard.exr",
    "mf_accurate": lambda s: f"{work}/out/matforge/{s}__mf_accurate.exr",
    "three": lambda s: f"{work}/out/web/{s}__three.f32",
    "filament": lambda s: f"{work}/out/web/{s}__filament.f32",
}
results = {"mask_pixels": int(mask.sum()), "scenes": {}}
for sc in doc["scenes"]:
    name = sc["name"]
    metal = float(sc["material"].get("metalness", 0.0)) == 1.0
    entry = {"refs": {}, "renderers": {}}
    refs = {}
    for ref in REFS:
        v = "principled" if metal else ref
        a = read_exr(f"{work}/out/cycles/{name}__{v}__s1.exr")
        b = read_exr(f"{work}/out/cycles/{name}__{v}__s2.exr")
        m = 0.5 * (a + b)
        refs[ref] = m
        peak = 1.0
        noise_mse = float(np.mean((a[mask] - b[mask]) ** 2)) / 4.0
        noise_mse8 = float(np.mean((srgb8(a[mask]) - srgb8(b[mask])) ** 2)) / 4.0
        entry["refs"][ref] = {
            "peak": peak,
            "noise_mse": noise_mse,
            "noise_psnr_lin": psnr(noise_mse, peak),
            "noise_psnr_srgb": psnr(noise_mse8, 255.0),
            "noise_ratio": float(abs(a[mask].sum() - b[mask].sum()) / (a[mask].sum() + b[mask].sum())),
        }
    for r in RENDERERS:
        p = paths[r](name)
        if not os.path.exists(p):
            print(f"missing {p}", file=sys.stderr)
            continue
        img = read_any(p)
        row = {}
        for ref, m in refs.items():
            peak = entry["refs"][ref]["peak"]
            d = img[mask] - m[mask]
            mse = float(np.mean(d * d))
            excess = mse - entry["refs"][ref]["noise_mse"]
            row[ref] = {
                "psnr_lin": psnr(mse, peak),
                "psnr_lin_excess": psnr(excess, peak) if excess > 0 else None,
                "psnr_srgb": psnr(float(np.mean((srgb8(img[mask]) - srgb8(m[mask])) ** 2)), 255.0),
                "ratio": float(img[mask].sum() / m[mask].sum()),
            }
        entry["renderers"][r] = row
    results["scenes"][name] = entry
json.dump(results, open(os.path.join(work, "results.json"), "w"), indent=1)

# ---- markdown ----
NAMES = {"mf_standard": "matforge standard", "mf_accurate": "matforge accurate", "three": "three.js",
         "filament": "Filament"}
lines = []
hdr = "| scene | renderer | " + " | ".join(
    f"{ref}: PSNR lin / sRGB8 (dB) | {ref}: ratio" for ref in REFS) + " |"
lines.append(hdr)
lines.append("|" + " --- |" * (2 + 2 * len(REFS)))
for name, e in results["scenes"].items():
    best = {}
    for ref in REFS:
        cands = {r: e["renderers"][r][ref]["psnr_lin"] for r in e["renderers"]}
        top = max(cands.values())
        best[ref] = {r for r, v in cands.items() if v > top - 0.05}   # ties within 0.05 dB
    for r, row in e["renderers"].items():
        cells = []
        for ref in REFS:
            x = row[ref]
            b = "**" if r in best[ref] else ""
            cells.append(f"{b}{x['psnr_lin']:.2f}{b} / {x['psnr_srgb']:.1f}")
            cells.append(f"{x['ratio']:.3f}")
        lines.append(f"| {name} | {NAMES[r]} | " + " | ".join(cells) + " |")
    cells = []
    for ref in REFS:
        n = e["refs"][ref]
        cells.append(f"{n['noise_psnr_lin']:.2f} / {n['noise_psnr_srgb']:.1f}")
        cells.append(f"±{n['noise_ratio']:.4f}")
    lines.append(f"| {name} | *Cycles noise* | " + " | ".join(cells) + " |")
open(os.path.join(work, "results.md"), "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
print(f"mask: {results['mask_pixels']} pixels")
