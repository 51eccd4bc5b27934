"""Opens USD layers with OpenUSD itself (PyPI usd-core: Pixar's pxr modules, installed by
scripts/py-checkers.sh; run with that environment's python) and reports what USD makes of them.
It shares no code with matforge's writer (lib/engine/usd.cpp).

    usd_open.py FILE...

prints one JSON line per file:
  {"file", "ok", "error",           ok: Usd.Stage.Open composed the layer without an error
   "metadata": {"defaultPrim", "upAxis", "metersPerUnit"},
   "customLayerData": {key: value},  the root layer's, as Sdf.Layer reads it ({} none)
   "prims": {"/Path": {"type", "references": [asset path as written],
                       "attributes": {"name": {"type", "uniform", "value"?, "connect"?: {"path"}}}}},
   "unresolved": [connection targets that are no attribute of the stage],
   "assets": {"/Path.inputs:file": {"path", "resolved"}},   resolved: the file Ar found ("" none)
   "validation": ["validator name: message", ...]}          UsdValidation's errors (below)

Validation runs every validator OpenUSD registers for a stage of shading prims (the checks
`usdchecker` runs: the UsdPreviewSurface rules — a normal map's scale and bias, an input's type
as the shader's Sdr definition declares it —, composition errors, missing references, stage
metadata, material binding and encapsulation rules); the package (usdz) validators are left out:
these are plain text layers.
"""
import json
import sys

from pxr import Sdf, Tf, Usd, UsdShade, UsdValidation

# Validators of packaged (.usdz) assets: a .usda beside its textures is not one.
SKIPPED = ("usdUtilsValidators:UsdzPackageValidator", "usdUtilsValidators:PackageEncapsulationValidator",
           "usdUtilsValidators:RootPackageValidator", "usdUtilsValidators:FileExtensionValidator")


def value_json(v):
    if isinstance(v, Sdf.AssetPath):
        return {"asset": v.path}
    if isinstance(v, (bool, int, float, str)):
        return v
    if hasattr(v, "__len__"):  # Gf vectors, Vt arrays
        return [value_json(x) for x in v]
    return str(v)


def references(prim):
    out = []
    for spec in prim.GetPrimStack():
        op = spec.referenceList
        for items in (op.explicitItems, op.prependedItems, op.appendedItems):
            out += [r.assetPath for r in items]
    return out


def open_one(path, validators):
    rep = {"file": path, "ok": False, "error": "", "metadata": {}, "customLayerData": {}, "prims": {},
           "unresolved": [], "assets": {}, "validation": []}
    mark = Tf.Error.Mark()
    try:
        stage = Usd.Stage.Open(path)
        errors = [e.commentary for e in mark.GetErrors()] if not mark.IsClean() else []
    except Tf.ErrorException as e:
        rep["error"] = str(e).strip()
        return rep
    if stage is None or errors:
        rep["error"] = "; ".join(errors) or "Usd.Stage.Open returned nothing"
        return rep
    root = stage.GetRootLayer()
    rep["ok"] = True
    rep["metadata"] = {"defaultPrim": root.defaultPrim, "upAxis": stage.GetMetadata("upAxis"),
                       "metersPerUnit": stage.GetMetadata("metersPerUnit")}
    rep["customLayerData"] = {k: value_json(v) for k, v in root.customLayerData.items()}
    for prim in stage.Traverse():
        attrs = {}
        for a in prim.GetAttributes():
            entry = {"type": str(a.GetTypeName()), "uniform": a.GetVariability() == Sdf.VariabilityUniform}
            if a.HasAuthoredValue():
                entry["value"] = value_json(a.Get())
            targets = a.GetConnections()
            if targets:
                entry["connect"] = {"path": str(targets[0])}
                for t in targets:
                    if not stage.GetAttributeAtPath(t):
                        rep["unresolved"].append(str(t))
            if a.GetTypeName() == Sdf.ValueTypeNames.Asset and a.HasAuthoredValue():
                asset = a.Get()
                rep["assets"][str(a.GetPath())] = {"path": asset.path, "resolved": asset.resolvedPath}
            attrs[a.GetName()] = entry
        rep["prims"][str(prim.GetPath())] = {"type": str(prim.GetTypeName()), "references": references(prim),
                                             "attributes": attrs}
        # Every shader input's source is a shader output the stage holds (UsdShade's own view).
        shader = UsdShade.Shader(prim)
        if shader:
            for i in shader.GetInputs():
                for source in i.GetConnectedSources()[0]:
                    if not source.source.GetPrim().IsValid():
                        rep["unresolved"].append(str(source.source.GetPath()))
    context = UsdValidation.ValidationContext(validators)
    for e in context.Validate(stage):
        if e.GetType() == UsdValidation.ValidationErrorType.Error:
            rep["validation"].append(e.GetValidator().GetMetadata().name + ": " + e.GetMessage())
    return rep


def main():
    registry = UsdValidation.ValidationRegistry()
    validators = [v for v in registry.GetOrLoadAllValidators() if v.GetMetadata().name not in SKIPPED]
    for path in sys.argv[1:]:
        print(json.dumps(open_one(path, validators)), flush=True)


if __name__ == "__main__":
    main()
