#!/usr/bin/env python3
"""Reads Unity material (.mat) and importer (.meta) files with PyYAML, as YAML 1.1 documents
(Unity's `%TAG !u! tag:unity3d.com,2011:` class tags read as plain mappings), not with
matforge's writer:

    python3 unity_check.py ROOT FILE.mat...

ROOT: the folder whose .meta files the materials' guids are looked up in (a Unity project's
Assets folder is searched the same way). Prints one JSON line per .mat: {file, ok, error,
shader_guid, name, keywords, floats, colors, textures: {slot: {guid, file (the texture whose
.meta holds that guid, relative to ROOT) or null, importer: {the TextureImporter's fields}}},
mat_meta: the .mat's own .meta guid and importer, guids_unique: no two .meta files of ROOT
share a guid}."""
import json
import os
import re
import sys

import yaml


class UnityLoader(yaml.SafeLoader):
    pass


def unity_object(loader, suffix, node):  # !u!21 &2100000 -> a plain mapping
    return loader.construct_mapping(node, deep=True)


UnityLoader.add_multi_constructor("tag:unity3d.com,2011:", unity_object)


def load(path):
    """Every object of a Unity file. Unity states its %TAG once for the whole stream and starts
    each object with `--- !u!<class> &<id>` (a material beside HDRP's AssetVersion is two); YAML
    scopes a %TAG to the first document, so the shorthand is written out in full for the rest."""
    with open(path, encoding="utf-8") as f:
        text = re.sub(r"!u!(\d+)", r"!<tag:unity3d.com,2011:\1>", f.read())
    return list(yaml.load_all(text, Loader=UnityLoader))


def metas(root):
    by_guid, dupes = {}, []
    for d, _, files in os.walk(root):
        for f in files:
            if f.endswith(".meta"):
                p = os.path.join(d, f)
                doc = load(p)[0]
                g = str(doc["guid"])
                if g in by_guid:
                    dupes.append(g)
                by_guid[g] = (os.path.relpath(p[:-len(".meta")], root), doc)
    return by_guid, dupes


def check(root, path, by_guid, dupes):
    out = {"file": path, "ok": False, "error": ""}
    try:
        docs = load(path)
        mat = docs[0]["Material"]
        out["name"] = mat["m_Name"]
        out["shader_guid"] = mat["m_Shader"]["guid"]
        out["shader_file_id"] = mat["m_Shader"]["fileID"]
        out["keywords"] = mat.get("m_ValidKeywords") or []
        props = mat["m_SavedProperties"]
        out["floats"] = {k: v for d in props.get("m_Floats") or [] for k, v in d.items()}
        out["colors"] = {k: v for d in props.get("m_Colors") or [] for k, v in d.items()}
        out["textures"] = {}
        for d in props.get("m_TexEnvs") or []:
            for slot, env in d.items():
                t = env["m_Texture"]
                if t.get("fileID", 0) == 0:
                    out["textures"][slot] = None
                    continue
                g = str(t["guid"])
                hit = by_guid.get(g)
                out["textures"][slot] = {"guid": g, "file_id": t["fileID"], "file": hit[0] if hit else None,
                                         "importer": hit[1].get("TextureImporter") if hit else None}
        # The other objects of the file: HDRP's AssetVersion MonoBehaviour (its script's guid, version).
        out["asset_versions"] = [{"script_guid": str(d["MonoBehaviour"]["m_Script"]["guid"]),
                                  "version": d["MonoBehaviour"]["version"]} for d in docs[1:] if "MonoBehaviour" in d]
        own = load(path + ".meta")[0]
        out["mat_meta"] = {"guid": str(own["guid"]), "importer": list(k for k in own if k.endswith("Importer"))}
        out["guids_unique"] = not dupes
        out["ok"] = True
    except Exception as e:  # noqa: BLE001 - every failure is the file's verdict
        out["error"] = type(e).__name__ + ": " + str(e)
    return out


if __name__ == "__main__":
    root = sys.argv[1]
    by_guid, dupes = metas(root)
    for f in sys.argv[2:]:
        print(json.dumps(check(root, f, by_guid, dupes), sort_keys=True, default=str))
