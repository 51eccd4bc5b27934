#!/usr/bin/python3
"""Validates manifests and validate reports against the committed JSON Schemas.

Usage: check-schemas.py [--allow-empty] DOCS_DIR PATH...   (a folder PATH is searched for *.json)
A file with "manifest_version" is checked against DOCS_DIR/manifest.schema.json, one with
"report_version" against DOCS_DIR/validate-report.schema.json, one with "plan_version" against
DOCS_DIR/plan.schema.json; any other JSON file is an error.
Exits 1 naming every file that does not validate, and when no file was found (unless
--allow-empty: a subset of the suite may write none; a missing folder counts as empty). Uses
Debian's python3-jsonschema (draft 2020-12).
"""
import json
import pathlib
import sys

import jsonschema


def main():
    args = sys.argv[1:]
    allow_empty = bool(args) and args[0] == "--allow-empty"
    if allow_empty:
        args = args[1:]
    if len(args) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    docs = pathlib.Path(args[0])
    schemas = {name: json.loads((docs / name).read_text())
               for name in ("manifest.schema.json", "validate-report.schema.json", "plan.schema.json")}
    # The report and plan schemas refer to the manifest's definitions by file name.
    store = {name: s for name, s in schemas.items()}
    store.update({s["$id"]: s for s in schemas.values()})
    files = []
    for arg in args[1:]:
        p = pathlib.Path(arg)
        if p.is_dir():
            files += sorted(p.rglob("*.json"))
        elif p.exists() or not allow_empty:
            files.append(p)
    if not files:
        print("check-schemas: no file to check", file=sys.stderr)
        return 0 if allow_empty else 1
    bad = 0
    counts = {"manifest": 0, "report": 0, "plan": 0}
    for f in files:
        doc = json.loads(f.read_text(encoding="utf-8"))
        kinds = {"manifest_version": "manifest", "report_version": "report", "plan_version": "plan"}
        kind = next((k for v, k in kinds.items() if v in doc), None)
        if kind is None:
            print(f"{f}: neither a manifest, a validate report nor a plan", file=sys.stderr)
            bad += 1
            continue
        schema = schemas[{"manifest": "manifest.schema.json", "report": "validate-report.schema.json",
                          "plan": "plan.schema.json"}[kind]]
        resolver = jsonschema.RefResolver(base_uri=schema["$id"], referrer=schema, store=store)
        validator = jsonschema.Draft202012Validator(schema, resolver=resolver)
        errors = sorted(validator.iter_errors(doc), key=lambda e: list(e.absolute_path))
        for e in errors[:5]:
            where = "/".join(str(x) for x in e.absolute_path)
            print(f"{f}: {kind} at /{where}: {e.message}", file=sys.stderr)
        bad += bool(errors)
        counts[kind] += 1
    print(f"check-schemas: {counts['manifest']} manifests, {counts['report']} reports, {counts['plan']} plans, "
          f"{bad} invalid")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
