"""Numeric twin of the BRDFs compared in docs/accuracy/pathtracer.md (numpy, double precision).

- matforge `standard` and `accurate` punctual-light BRDFs, as lib/render/shaders/brdf.glsl and
  tests/stability/brdf_reference.hpp define them (used here to check the harness against the
  renderer's EXRs, and as the base of the candidate diffuse terms);
- directional albedos E(mu) of the specular lobe by deterministic quadrature over visible normals
  (Heitz 2018), for F = 1 (the accurate model's compensation) and for the exact Fresnel of a
  dielectric of IOR 1.5 (the Cycles reference's albedo-scaled diffuse);
- candidate diffuse couplings for the accurate model (diagnose.py).
"""
import math

import numpy as np

MIN_R = 0.045
MIN_NOV = 1e-4


# ---- microfacet terms ----
def D_ggx(NoH, alpha):
    a2 = alpha * alpha
    d = NoH * NoH * (a2 - 1.0) + 1.0
    return a2 / (math.pi * d * d)


def lambda_ggx(cos, alpha):
    cos = np.clip(cos, 1e-9, 1.0)
    t2 = (1.0 - cos * cos) / (cos * cos)
    return 0.5 * (np.sqrt(1.0 + alpha * alpha * t2) - 1.0)


def G1_smith(cos, alpha):
    return 1.0 / (1.0 + lambda_ggx(cos, alpha))


def V_smith_correlated(NoV, NoL, alpha):
    a2 = alpha * alpha
    lv = NoL * np.sqrt(NoV * NoV * (1.0 - a2) + a2)
    ll = NoV * np.sqrt(NoL * NoL * (1.0 - a2) + a2)
    return 0.5 / (lv + ll)


def V_schlick_ggx(NoV, NoL, r):
    k = (r + 1.0) ** 2 / 8.0
    return 0.25 / ((NoL * (1.0 - k) + k) * (NoV * (1.0 - k) + k))


def F_schlick(f0, VoH):
    m = 1.0 - VoH
    return f0 + (1.0 - f0) * m ** 5


def F_dielectric(cos, eta=1.5):
    """Exact unpolarized Fresnel reflectance from outside (Cycles' fresnel_dielectric_cos)."""
    c = np.abs(cos)
    g = eta * eta - 1.0 + c * c
    g = np.sqrt(np.maximum(g, 0.0))
    A = (g - c) / (g + c)
    B = (c * (g + c) - 1.0) / (c * (g - c) + 1.0)
    return 0.5 * A * A * (1.0 + B * B)


# ---- directional albedo by quadrature over visible normals ----
def _vndf_grid(NoV, alpha, n=128):
    """Half vectors sampled by Heitz 2018 listing 1 on an n x n midpoint grid; returns (h, l, v)."""
    v = np.array([math.sqrt(max(0.0, 1.0 - NoV * NoV)), 0.0, NoV])
    vh = np.array([alpha * v[0], alpha * v[1], v[2]])
    vh /= np.linalg.norm(vh)
    lensq = vh[0] ** 2 + vh[1] ** 2
    T1 = np.array([-vh[1], vh[0], 0.0]) / math.sqrt(lensq) if lensq > 0 else np.array([1.0, 0, 0])
    T2 = np.cross(vh, T1)
    u1, u2 = np.meshgrid((np.arange(n) + 0.5) / n, (np.arange(n) + 0.5) / n, indexing="ij")
    r = np.sqrt(u1)
    phi = 2.0 * math.pi * u2
    t1, t2 = r * np.cos(phi), r * np.sin(phi)
    s = 0.5 * (1.0 + vh[2])
    t2 = (1.0 - s) * np.sqrt(np.maximum(0.0, 1.0 - t1 * t1)) + s * t2
    nh = (t1[..., None] * T1 + t2[..., None] * T2
          + np.sqrt(np.maximum(0.0, 1.0 - t1 * t1 - t2 * t2))[..., None] * vh)
    h = np.stack([alpha * nh[..., 0], alpha * nh[..., 1], np.maximum(1e-9, nh[..., 2])], -1)
    h /= np.linalg.norm(h, axis=-1, keepdims=True)
    VoH = h @ v
    l = 2.0 * VoH[..., None] * h - v
    return h, l, v, VoH


def spec_albedo(NoV, r, model="accurate", fresnel=None, n=128):
    """E(mu) = integral of f_spec (n.l) over l. model: 'accurate' (height-correlated Smith) or
    'standard' (Schlick-GGX V); fresnel: None (F = 1) or a function of v.h."""
    r = max(r, MIN_R)
    alpha = r * r
    NoV = max(NoV, MIN_NOV)
    h, l, v, VoH = _vndf_grid(NoV, alpha, n)
    NoL = l[..., 2]
    ok = NoL > 0
    NoLc = np.clip(NoL, 1e-9, 1.0)
    if model == "accurate":
        V = V_smith_correlated(NoV, NoLc, alpha)
    else:
        V = V_schlick_ggx(NoV, NoLc, r)
    # f (n.l) / pdf(l), pdf(l) = G1(v) D(h) / (4 n.v)  ->  4 V (n.l)(n.v) / G1(v)
    w = 4.0 * V * NoLc * NoV / G1_smith(NoV, alpha)
    if fresnel is not None:
        w = w * fresnel(np.clip(VoH, 0.0, 1.0))
    return float(np.mean(np.where(ok, w, 0.0)))


def albedo_table(r, model="accurate", fresnel=None, nmu=64, n=128):
    """E at mu = (i + 0.5)/nmu, i < nmu."""
    mus = (np.arange(nmu) + 0.5) / nmu
    return mus, np.array([spec_albedo(m, r, model, fresnel, n) for m in mus])


def average(mus, E):
    """Cosine-weighted hemispherical average 2 integral E(mu) mu dmu (midpoint rule)."""
    return float(np.sum(2.0 * E * mus) / len(mus))


def dielectric_ms_albedo(r, eta=1.5, nmu=64, n=128):
    """E_s(mu) of a rough dielectric's reflection lobe with multiple scattering: the single-
    scattering albedo with the exact Fresnel of IOR eta, plus Kulla & Conty's multiple-scattering
    lobe (albedo 1 - E_1(mu) for F = 1) scaled by F_ms = F_avg^2 E_avg / (1 - F_avg (1 - E_avg))."""
    mus, E1 = albedo_table(r, "accurate", None, nmu, n)
    _, EF = albedo_table(r, "accurate", lambda c: F_dielectric(c, eta), nmu, n)
    Eavg = average(mus, E1)
    Favg = average(mus, F_dielectric(mus, eta))
    Fms = Favg * Favg * Eavg / (1.0 - Favg * (1.0 - Eavg))
    return mus, EF + (1.0 - E1) * Fms


# ---- per-pixel evaluation of a scene ----
def camera_rays(common):
    """Unit primary rays of every sub-sample: (size*ss, size*ss, 3), rows top to bottom."""
    size, ss = common["size"], common["supersample"]
    N = size * ss
    t = math.tan(math.radians(common["camera"]["yfov_deg"]) / 2.0)
    c = (np.arange(N) + 0.5) / N
    x = (2.0 * c - 1.0) * t
    y = (1.0 - 2.0 * c) * t
    X, Y = np.meshgrid(x, y)
    pos = np.array(common["camera"]["position"], float)
    tgt = np.array(common["camera"]["target"], float)
    up = np.array(common["camera"].get("up", [0, 1, 0]), float)
    f = tgt - pos
    f /= np.linalg.norm(f)
    rgt = np.cross(f, up)
    rgt /= np.linalg.norm(rgt)
    u = np.cross(rgt, f)
    d = X[..., None] * rgt + Y[..., None] * u + f
    return pos, d / np.linalg.norm(d, axis=-1, keepdims=True)


def sphere_hits(common):
    """Per sub-sample: hit mask, normal n and view vector v on the analytic sphere."""
    o, d = camera_rays(common)
    R = common["radius"]
    b = d @ o
    c = o @ o - R * R
    disc = b * b - c
    hit = disc > 0
    t = -b - np.sqrt(np.maximum(disc, 0.0))
    p = o + t[..., None] * d
    n = p / R
    return hit, n, -d


def F_avg_schlick(f0):
    """Cosine-weighted hemispherical average of Schlick's Fresnel: F0 + (1 - F0)/21."""
    return f0 + (1.0 - f0) / 21.0


def shade(common, mat, model="accurate", diffuse="one_minus_F", etab=None, pix=None, ms="turquin"):
    """Radiance of every pixel (box-averaged sub-samples) for a constant material.
    diffuse: 'one_minus_F' (matforge standard, and accurate before proposal 1: (1 - F(v.h))), 'none'
    (additive), 'one_minus_Eo' (albedo scaling by the lobe's albedo at the view, (1 - E_F(n.v)):
    matforge accurate since proposal 1), 'kc' (Kulla & Conty's
    reciprocal (1 - E_F(n.v))(1 - E_F(n.l))/(1 - E_F,avg)), 'burley' (Disney 2015 as Cycles 3.x).
    etab: {'E1': (mus, E(mu) with F = 1), 'EF': (mus, the specular lobe's albedo with its Fresnel)}.
    ms (accurate model only): 'turquin' (matforge today: the lobe scaled by 1 + F0 (1/E - 1)) or
    'kc_lobe' (Kulla & Conty 2017's separate multiple-scattering lobe
    F_ms (1 - E(n.v))(1 - E(n.l)) / (pi (1 - E_avg)), F_ms = F_avg^2 E_avg / (1 - F_avg (1 - E_avg)))."""
    hit, n, v = pix if pix is not None else sphere_hits(common)
    albedo = np.array(mat["albedo"], float)
    metal = float(mat.get("metalness", 0.0))
    r = max(float(mat["roughness"]), MIN_R)
    alpha = r * r
    f0 = 0.04 * (1 - metal) + albedo * metal
    dcol = albedo * (1 - metal)
    NoV = np.clip(np.sum(n * v, -1), MIN_NOV, 1.0)
    out = np.zeros(n.shape)
    if model == "accurate" or diffuse in ("one_minus_Eo", "kc"):
        mus, E1 = etab["E1"]
        E1v = np.interp(NoV, mus, E1)
    for L in common["lights"]:
        l = -np.array(L["direction"], float)
        l /= np.linalg.norm(l)
        E = np.array(L.get("color", [1, 1, 1]), float) * L["intensity"]
        NoL = n @ l
        lit = NoL > 0
        NoL = np.clip(NoL, 0.0, 1.0)
        h = v + l
        h /= np.maximum(np.linalg.norm(h, axis=-1, keepdims=True), 1e-30)
        NoH = np.clip(np.sum(n * h, -1), 0, 1)
        VoH = np.clip(np.sum(v * h, -1), 0, 1)
        F = F_schlick(f0, VoH[..., None])
        D = D_ggx(NoH, alpha)
        if model == "accurate":
            V = V_smith_correlated(NoV, NoL, alpha)
            if ms == "turquin":
                comp = 1.0 + f0 * (1.0 / np.maximum(E1v, 1e-4) - 1.0)[..., None]
            else:
                comp = 1.0
        else:
            V = V_schlick_ggx(NoV, NoL, r)
            comp = 1.0
        spec = (D * V)[..., None] * F * comp
        if model == "accurate" and ms == "kc_lobe":
            mus, E1 = etab["E1"]
            Eavg = average(mus, E1)
            Favg = F_avg_schlick(f0)
            Fms = Favg * Favg * Eavg / (1.0 - Favg * (1.0 - Eavg))
            E1l = np.interp(NoL, mus, E1)
            spec = spec + Fms * ((1.0 - E1v) * (1.0 - E1l) / (math.pi * (1.0 - Eavg)))[..., None]
        if diffuse == "one_minus_F":
            kd = 1.0 - F
        elif diffuse == "none":
            kd = np.ones_like(F)
        elif diffuse in ("one_minus_Eo", "kc"):
            mus, EF = etab["EF"]
            Eo = np.interp(NoV, mus, EF)
            if diffuse == "one_minus_Eo":
                kd = np.repeat((1.0 - Eo)[..., None], 3, -1)
            else:
                Ei = np.interp(NoL, mus, EF)
                kd = np.repeat(((1.0 - Eo) * (1.0 - Ei) / (1.0 - average(mus, EF)))[..., None], 3, -1)
        elif diffuse == "burley":
            FL, FV = (1 - NoL) ** 5, (1 - NoV) ** 5
            LoH = np.clip(np.sum(l * h, -1), 0, 1)
            RR = 2 * r * LoH * LoH
            kd = np.repeat(((1 - 0.5 * FL) * (1 - 0.5 * FV) + RR * (FL + FV + FL * FV * (RR - 1)))[..., None], 3, -1)
        else:
            raise ValueError(diffuse)
        fd = kd * dcol / math.pi
        out += np.where(lit[..., None], (fd + spec) * E * NoL[..., None], 0.0)
    out = np.where(hit[..., None], out, np.array(common["background"], float))
    ss = common["supersample"]
    N = out.shape[0] // ss
    return out.reshape(N, ss, N, ss, 3).mean(axis=(1, 3))
