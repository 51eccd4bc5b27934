"""Why matforge's accurate BRDF is darker than the references on rough dielectrics, and what a
different diffuse coupling gives. Writes WORK/diagnosis.md.

1. Punctual-light white furnace: the directional albedo a(mu_o) = integral of (f_d + f_s)(n.l) over
   light directions for albedo 1, metalness 0, of the accurate model with each diffuse coupling.
   An energy-conserving, non-absorbing surface gives 1 (matforge's image-based lighting already
   does: its furnace test renders 1 +- 2e-3).
2. The same candidates rendered per pixel by the numeric twin (brdf_model.shade, which reproduces
   matforge's EXRs to 1e-3) and compared with each Cycles reference (PSNR lin / ratio, the mask and
   metrics of compare.py).
3. On the metals, the accurate model's multiple-scattering form: today's scaling of the single-
   scattering lobe by 1 + F0 (1/E - 1) (Turquin 2019) against Kulla & Conty's separate lobe
   F_ms (1 - E(n.v))(1 - E(n.l)) / (pi (1 - E_avg)), and single scattering alone.
Candidates (diffuse = albedo (1 - metalness) / pi x k):
  one_minus_F   k = 1 - F(v.h)                     matforge standard (accurate before proposal 1;
                                                   glTF's fresnel_mix), three.js
  none          k = 1                              Filament, Cycles `lambert_add`
  one_minus_Eo  k = 1 - E_spec(n.v)                albedo scaling by the specular lobe's albedo in
                                                   the view direction, E_spec = (F0 A + B)(1 + F0 (1/E - 1))
                                                   from matforge's own BRDF table (A, B, E = A + B):
                                                   matforge accurate since proposal 1
  kc            k = (1 - E_spec(n.v))(1 - E_spec(n.l)) / (1 - E_spec,avg)   reciprocal form
  burley        Cycles 3.4 Principled's diffuse (Burley 2015, retro-reflection), for the record
  one_minus_Eo+kc_lobe   one_minus_Eo with E_spec = F0 A + B + F_ms (1 - E), and Kulla & Conty's
                separate multiple-scattering lobe instead of the scaled one (both proposals)
usage: python3 diagnose.py WORK
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
tables = json.load(open(os.path.join(work, "etables", "tables.json")))
F0 = 0.04
CANDS = ["one_minus_F", "none", "one_minus_Eo", "kc"]


def etab(r, ms="turquin"):
    t = tables[f"{r:.2f}"]
    mu, E1, EFs = np.array(t["mu"]), np.array(t["E1"]), np.array(t["EF_schlick004"])
    if ms == "turquin":   # what matforge's table gives, F0 A + B, with today's compensation
        Espec = EFs * (1.0 + F0 * (1.0 / E1 - 1.0))
    else:                 # with Kulla & Conty's lobe: F0 A + B + F_ms (1 - E)
        Eavg, Favg = bm.average(mu, E1), bm.F_avg_schlick(F0)
        Espec = EFs + Favg * Favg * Eavg / (1.0 - Favg * (1.0 - Eavg)) * (1.0 - E1)
    return {"E1": (mu, E1), "EF": (mu, Espec)}


out = ["## Punctual white furnace (albedo 1, metalness 0, accurate specular lobe)", "",
       "a(mu_o) = directional albedo over all light directions; 1 = energy conserved.", "",
       "| roughness | mu_o | " + " | ".join(CANDS) + " |", "|" + " --- |" * (2 + len(CANDS))]
n = 600
ct = (np.arange(n) + 0.5) / n
ph = (np.arange(n) + 0.5) / n * 2 * math.pi
C, P = np.meshgrid(ct, ph, indexing="ij")
S = np.sqrt(1 - C * C)
L = np.stack([S * np.cos(P), S * np.sin(P), C], -1)
dw = (1.0 / n) * (2 * math.pi / n)
furnace = {}
for r in (0.2, 0.5, 0.9):
    et = etab(r)
    alpha = r * r
    mu, Es = et["EF"]
    Eavg = bm.average(mu, Es)
    for muo in (1.0, 0.7, 0.4, 0.1):
        v = np.array([math.sqrt(max(0, 1 - muo * muo)), 0.0, muo])
        h = L + v
        h /= np.linalg.norm(h, axis=-1, keepdims=True)
        NoH, VoH = h[..., 2], np.clip(h @ v, 0, 1)
        F = bm.F_schlick(F0, VoH)
        E1 = np.interp(muo, *et["E1"])
        fs = bm.D_ggx(NoH, alpha) * bm.V_smith_correlated(max(muo, 1e-4), C, alpha) * F * (1 + F0 * (1 / E1 - 1))
        Eo, Ei = np.interp(muo, mu, Es), np.interp(C, mu, Es)
        ks = {"one_minus_F": 1 - F, "none": np.ones_like(F), "one_minus_Eo": np.full_like(F, 1 - Eo),
              "kc": (1 - Eo) * (1 - Ei) / (1 - Eavg)}
        row = [float(np.sum((fs + ks[k] / math.pi) * C) * dw) for k in CANDS]
        furnace[(r, muo)] = row
        out.append(f"| {r} | {muo} | " + " | ".join(f"{x:.4f}" for x in row) + " |")

# ---- per-pixel candidates against the Cycles references ----
hit, nrm, vv = bm.sphere_hits(common)
pix = (hit, nrm, vv)
phit = hit.reshape(size, ss, size, ss).all(axis=(1, 3))
mask = phit.copy()
for dy in (-1, 0, 1):
    for dx in (-1, 0, 1):
        mask &= np.roll(np.roll(phit, dy, 0), dx, 1)


def read_ref(name, v):
    a = [oiio.ImageBuf(f"{work}/out/cycles/{name}__{v}__s{s}.exr").get_pixels(oiio.FLOAT)[..., :3].astype(float)
         for s in (1, 2)]
    return 0.5 * (a[0] + a[1])


REFS = ["lambert_scaled", "lambert_add", "principled"]
out += ["", "## Candidate diffuse couplings against the Cycles references (numeric twin, accurate specular)", "",
        "PSNR lin (dB, peak 1 as compare.py) / ratio (sum over the mask).", "",
        "| scene | candidate | " + " | ".join(REFS) + " |", "|" + " --- |" * (2 + len(REFS))]
res = {}
for sc in doc["scenes"]:
    m = sc["material"]
    if "albedo" not in m or float(m.get("metalness", 0)) != 0.0:
        continue
    name = sc["name"]
    refs = {v: read_ref(name, v) for v in REFS}
    for k in CANDS + ["burley", "one_minus_Eo+kc_lobe"]:
        if k == "one_minus_Eo+kc_lobe":   # both proposals together
            img = bm.shade(common, m, "accurate", "one_minus_Eo", etab(float(m["roughness"]), "kc_lobe"), pix, "kc_lobe")
        else:
            img = bm.shade(common, m, "accurate", k, etab(float(m["roughness"])), pix)
        cells = []
        for v in REFS:
            ref = refs[v]
            d = img[mask] - ref[mask]
            p = 10 * math.log10(1.0 / np.mean(d * d))
            q = img[mask].sum() / ref[mask].sum()
            res[(name, k, v)] = (p, q)
            cells.append(f"{p:.1f} / {q:.3f}")
        out.append(f"| {name} | {k} | " + " | ".join(cells) + " |")
# ---- metals: the multiple-scattering form against Cycles' Multiscatter GGX ----
out += ["", "## Multiple scattering on the metal: today's scaled lobe vs Kulla & Conty's separate lobe", "",
        "Against Cycles `principled` (Multiscatter GGX, a random walk): PSNR lin / PSNR lin with "
        "Cycles' noise removed / ratio / ratio per channel (R, G, B).", "",
        "| scene | multiple scattering | PSNR lin | PSNR excess | ratio | R, G, B |", "|" + " --- |" * 6]
for sc in doc["scenes"]:
    m = sc["material"]
    if float(m.get("metalness", 0)) != 1.0:
        continue
    name = sc["name"]
    a = [oiio.ImageBuf(f"{work}/out/cycles/{name}__principled__s{s}.exr").get_pixels(oiio.FLOAT)[..., :3].astype(float)
         for s in (1, 2)]
    ref = 0.5 * (a[0] + a[1])
    noise = float(np.mean((a[0][mask] - a[1][mask]) ** 2)) / 4.0
    for msf in ("single", "turquin", "kc_lobe"):
        et = etab(float(m["roughness"]))
        if msf == "single":
            et = {"E1": (et["E1"][0], np.ones_like(et["E1"][1])), "EF": et["EF"]}
        img = bm.shade(common, m, "accurate", "one_minus_F", et, pix, "kc_lobe" if msf == "kc_lobe" else "turquin")
        d = img[mask] - ref[mask]
        mse = float(np.mean(d * d))
        p, pe = 10 * math.log10(1 / mse), 10 * math.log10(1 / max(mse - noise, 1e-12))
        q, qc = img[mask].sum() / ref[mask].sum(), img[mask].sum(0) / ref[mask].sum(0)
        res[(name, msf, "principled")] = (p, q)
        out.append(f"| {name} | {msf} | {p:.2f} | {pe:.2f} | {q:.3f} | {qc[0]:.3f}, {qc[1]:.3f}, {qc[2]:.3f} |")

json.dump({"furnace": {f"{k[0]}@{k[1]}": v for k, v in furnace.items()},
           "candidates": {"|".join(k): v for k, v in res.items()}},
          open(os.path.join(work, "diagnosis.json"), "w"), indent=1)
open(os.path.join(work, "diagnosis.md"), "w").write("\n".join(out) + "\n")
print("\n".join(out))
