"""matforge from Python: the library the `matforge` command runs, called in-process.

    import matforge
    print(matforge.validate("sample_materials"))            # findings, as `matforge validate` reports them
    m = matforge.ingest("sample_materials", "out", presets="unity-hdrp")  # the manifest written, typed

Each function does what its command does (docs/interface.md) and returns typed, read-only
objects (matforge._types). Work runs with the GIL released, on every core (`jobs`); `progress`
is called as (done, total, set name) after each set (from a worker thread, holding the GIL:
return False to cancel); a Cancel token, or Ctrl-C, stops a run at its next set as SIGINT stops
the command: every file written is complete, no temporary is left, no manifest is written, and
matforge.Cancelled is raised (KeyboardInterrupt for Ctrl-C). Errors are matforge.Error subclasses
carrying a `code`. One run at a time per process: a second call waits for the first.
"""

from __future__ import annotations

import json
import os
from typing import Any, Callable, Dict, Mapping, Optional, Sequence, Tuple, Union

from . import _core
from ._core import Cancel
from ._errors import Cancelled, Error, InputError, ManifestError, MergeError, OutputError, UsageError
from ._types import (Candidate, DiscoveredSet, Discovery, Figure, Finding, Input, InputFailure, Level, Manifest,
                     MapChoice, Material, MaterialFile, Output, Plan, PlannedSet, Severity, Summary, Validation)

__all__ = [
    "Cancel", "Cancelled", "Candidate", "DiscoveredSet", "Discovery", "Error", "Figure", "Finding", "Input",
    "InputError", "InputFailure", "Level", "Manifest", "ManifestError", "MapChoice", "Material", "MaterialFile",
    "MergeError", "Output", "OutputError", "Plan", "PlannedSet", "Severity", "Summary", "UsageError", "Validation",
    "discover", "ingest", "libraries", "merge", "plan", "presets", "read_manifest", "validate", "__version__",
]

__version__: str = _core.version().split(" ", 1)[1]

PathLike = Union[str, "os.PathLike[str]"]
Inputs = Union[PathLike, Sequence[PathLike]]
Rules = Union[None, PathLike, Mapping[str, Any]]
Progress = Callable[[int, int, str], Optional[bool]]


def _inputs(inputs: Inputs) -> list:
    if isinstance(inputs, (str, os.PathLike)):
        return [os.fspath(inputs)]
    return [os.fspath(i) for i in inputs]


def _jobs(jobs: int) -> int:
    if not 0 <= jobs <= 1024:  # the commands' --jobs range
        raise UsageError(f"jobs must be 0 (all cores) to 1024, not {jobs}", "usage")
    return jobs


def _choice(name: str, value: str, allowed: Sequence[str]) -> str:
    if value not in allowed:
        raise UsageError(f"{name} must be one of {', '.join(allowed)}, not {value!r}", "usage")
    return value


def _rules(rules: Rules) -> Tuple[str, str]:
    """(rules file, rules JSON text): a file's path, or a rules object (docs/rules.md, "Configuration")."""
    if rules is None:
        return "", ""
    if isinstance(rules, Mapping):
        return "", json.dumps(rules)
    return os.fspath(rules), ""


def presets() -> list:
    """The shipped presets' names."""
    return list(_core.presets())


def libraries() -> list:
    """The libraries that read inputs and decide output bytes, with their versions, as loaded
    (what `matforge --version` lists): OpenImageIO (with its formats), OpenColorIO, the encoders,
    libzip, OpenSSL."""
    return list(_core.libraries())


def discover(inputs: Inputs, rules: Rules = None, *, preset: str = "gltf") -> Discovery:
    """Every material set under `inputs` (folders, .zip files, folders of many) with its files, the
    file chosen for each role, the rule or sidecar that decided it, and the other candidates.
    Reads names, sidecars and headers; decodes nothing (but where only the pixels tell a name's role)."""
    rules_file, rules_text = _rules(rules)
    return Discovery.from_json(_core.discover(_inputs(inputs), preset, rules_file, rules_text))


def validate(inputs: Inputs, rules: Rules = None, *, preset: str = "gltf", jobs: int = 0,
             progress: Optional[Progress] = None, cancel: Optional[Cancel] = None) -> Validation:
    """`matforge validate`: discovery and every rule over each set, writing nothing. The findings
    are those of `matforge validate --report json`. `rules`: a rules file or a rules object;
    `preset`: whose needs (MISSING_MAP) and validate block apply."""
    rules_file, rules_text = _rules(rules)
    return Validation.from_json(
        _core.validate(_inputs(inputs), preset, rules_file, rules_text, _jobs(jobs), progress, cancel))


def ingest(inputs: Inputs, out: PathLike, presets: Union[str, Sequence[str]] = "gltf", *,
           tiers: Optional[Sequence[int]] = None, jobs: int = 0, normal_convention: Optional[str] = None,
           rules: Rules = None, shard: Optional[Tuple[int, int]] = None, cache: Union[None, bool, PathLike] = None,
           force: bool = False, replace: bool = False, progress: Optional[Progress] = None,
           cancel: Optional[Cancel] = None) -> Union[Manifest, Dict[str, Manifest]]:
    """`matforge ingest`: the sets under `inputs` converted into `out` for a preset (a shipped name
    or a preset file), its manifest.json written last; the same bytes as the command writes.

    Several presets ("gltf,unity-hdrp" or a list) or `tiers` write one folder each in one pass
    (out/<preset>, out/<tier>, out/<preset>/<tier>) and return {folder: Manifest}; one returns
    its Manifest. `shard=(i, n)`: only shard i of n (see plan()), its manifest
    manifest.shard-i-of-n.json for merge(). `cache`: None the CLI's default ($MATFORGE_CACHE, else
    ~/.cache/matforge), False none, or a folder. `force`, `replace`, `normal_convention` ("gl",
    "dx"), `rules`, `jobs`: as the command's options. Sets that fail are in `failures`, not raised."""
    names = [p for p in presets.split(",")] if isinstance(presets, str) else [os.fspath(p) for p in presets]
    if cache is None:
        cache_dir = _core.default_cache()
        named = bool(os.environ.get("MATFORGE_CACHE"))
    elif cache is False:
        cache_dir, named = "", False
    elif cache is True:
        cache_dir, named = _core.default_cache(), bool(os.environ.get("MATFORGE_CACHE"))
    else:
        cache_dir, named = os.fspath(cache), True
    rules_file, rules_text = _rules(rules)
    if normal_convention is not None:
        _choice("normal_convention", normal_convention, ("gl", "dx"))
    runs = _core.ingest(_inputs(inputs), os.fspath(out), names, list(tiers) if tiers is not None else None,
                        _jobs(jobs), normal_convention or "", rules_file, rules_text, tuple(shard) if shard else None,
                        cache_dir, named, force, replace, progress, cancel)
    manifests = {r["folder"]: Manifest.from_json(_core.read_manifest(r["manifest"]), r["manifest"], r["notes"])
                 for r in runs}
    if len(manifests) == 1 and "" in manifests:
        return manifests[""]
    return manifests


def read_manifest(path: PathLike) -> Manifest:
    """A manifest.json, checked as every matforge reader checks it."""
    return Manifest.from_json(_core.read_manifest(os.fspath(path)), os.fspath(path))


def plan(inputs: Inputs, shards: int = 1, *, preset: str = "gltf", rules: Rules = None,
         changed_since: Optional[PathLike] = None, out: Optional[PathLike] = None) -> Plan:
    """`matforge plan`: the deterministic work list (every set, its size, action key and shard);
    each machine of a farm then runs ingest(..., shard=(i, shards)) and one merge() joins them.
    `changed_since`: an earlier run's manifest: only the sets whose key changed. `out`: also
    written there (docs/plan.schema.json)."""
    rules_file, rules_text = _rules(rules)
    j = _core.plan(_inputs(inputs), preset, rules_file, rules_text, shards,
                   os.fspath(changed_since) if changed_since else "", os.fspath(out) if out else "")
    return Plan.from_json(j, os.fspath(out) if out else None)


def merge(parts: Sequence[PathLike], out: PathLike, *, fail_on: str = "error", keep_errors: bool = False) -> Manifest:
    """`matforge merge`: the shards' manifests as the manifest (and library) one run writes,
    beside them. A part whose shard's run failed (a set not processed, a finding at `fail_on`)
    raises MergeError naming it, unless `keep_errors`."""
    _choice("fail_on", fail_on, ("error", "warning", "info", "never"))
    r = _core.merge([os.fspath(p) for p in parts], os.fspath(out), fail_on, keep_errors)
    return read_manifest(r["manifest"])
