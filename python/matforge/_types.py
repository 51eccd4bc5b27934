"""matforge's results as typed, read-only objects, made from the library's own JSON (the manifest
of docs/interface.md, the validate report's findings, the plan of docs/plan.schema.json). Every
object keeps that JSON as `raw`: a field a later matforge adds is there before it has a name here.
"""

from __future__ import annotations

import enum
import os
from dataclasses import dataclass, field
from typing import Any, Mapping, Optional, Sequence, Tuple, Union

# A measured value behind a finding: a flag, a count (int), a measure (float), a word, or a list
# of counts, measures or words, as the JSON reports hold it.
Figure = Union[bool, int, float, str, Tuple[int, ...], Tuple[float, ...], Tuple[str, ...]]


class Severity(str, enum.Enum):
    """A finding's severity; compares equal to its name ("error") and orders info < warning < error."""

    info = "info"
    warning = "warning"
    error = "error"

    @property
    def rank(self) -> int:
        return ("info", "warning", "error").index(self.value)

    def __lt__(self, other: object) -> bool:
        if not isinstance(other, Severity):
            return NotImplemented
        return self.rank < other.rank

    def __le__(self, other: object) -> bool:
        if not isinstance(other, Severity):
            return NotImplemented
        return self.rank <= other.rank

    def __gt__(self, other: object) -> bool:
        if not isinstance(other, Severity):
            return NotImplemented
        return self.rank > other.rank

    def __ge__(self, other: object) -> bool:
        if not isinstance(other, Severity):
            return NotImplemented
        return self.rank >= other.rank

    def __str__(self) -> str:
        return self.value


def _figure(v: Any) -> Figure:
    return tuple(v) if isinstance(v, list) else v


@dataclass(frozen=True)
class Finding:
    """One coded result (docs/rules.md: every code, its figures and thresholds)."""

    code: str
    severity: Severity
    message: str
    file: Optional[str] = None  # the image file, relative to the set's source; None for set-wide findings
    role: Optional[str] = None
    figures: Mapping[str, Figure] = field(default_factory=dict)
    material: Optional[str] = None  # the set it is about
    raw: Mapping[str, Any] = field(default_factory=dict, repr=False, compare=False)

    @staticmethod
    def from_json(j: Mapping[str, Any], material: Optional[str] = None) -> "Finding":
        return Finding(code=j["code"], severity=Severity(j["severity"]), message=j["message"], file=j.get("file"),
                       role=j.get("role"), figures={k: _figure(v) for k, v in j.get("figures", {}).items()},
                       material=material, raw=j)

    def __str__(self) -> str:
        where = f"{self.material}: " if self.material else ""
        return f"{self.severity.value} {self.code} {where}{self.message}"


@dataclass(frozen=True)
class InputFailure:
    """An input that could not be processed at all (an unreadable archive, a folder without a set)."""

    source: str
    code: str
    message: str

    @staticmethod
    def from_json(j: Mapping[str, Any]) -> "InputFailure":
        return InputFailure(source=j["source"], code=j["code"], message=j["message"])


@dataclass(frozen=True)
class Input:
    """The file chosen for one role of a set (manifest `materials[].inputs.<role>`)."""

    role: str
    file: str
    family: str
    rule: str
    width: int
    height: int
    channels: int
    bit_depth: int
    color_space: str
    is_float: bool = False
    normal_convention: Optional[str] = None  # normal inputs: gl, dx or unknown
    normal_convention_source: Optional[str] = None  # "name" or "content"
    normal_convention_confidence: Optional[float] = None
    unused: bool = False
    stored_as_depth: bool = False
    raw: Mapping[str, Any] = field(default_factory=dict, repr=False, compare=False)

    @staticmethod
    def from_json(role: str, j: Mapping[str, Any]) -> "Input":
        return Input(role=role, file=j["file"], family=j.get("family", ""), rule=j.get("rule", ""),
                     width=j.get("width", 0), height=j.get("height", 0), channels=j.get("channels", 0),
                     bit_depth=j.get("bit_depth", 0), color_space=j.get("color_space", ""),
                     is_float=j.get("float", False), normal_convention=j.get("normal_convention"),
                     normal_convention_source=j.get("normal_convention_source"),
                     normal_convention_confidence=j.get("normal_convention_confidence"),
                     unused=j.get("unused", False), stored_as_depth=j.get("stored_as_depth", False), raw=j)


@dataclass(frozen=True)
class Level:
    """One mip level of a block-compressed output and its error against the level it encodes."""

    width: int
    height: int
    psnr_db: Optional[float] = None
    mean_angle_deg: Optional[float] = None
    max_angle_deg: Optional[float] = None
    coverage: Optional[float] = None

    @staticmethod
    def from_json(j: Mapping[str, Any]) -> "Level":
        return Level(width=j["width"], height=j["height"], psnr_db=j.get("psnr_db"),
                     mean_angle_deg=j.get("mean_angle_deg"), max_angle_deg=j.get("max_angle_deg"),
                     coverage=j.get("coverage"))


@dataclass(frozen=True)
class Output:
    """A texture an ingest wrote (manifest `materials[].outputs[]`); `file` relative to the manifest."""

    file: str
    format: str
    color_space: str  # "sRGB" or "linear"
    channels: Mapping[str, Union[str, float]]
    width: int
    height: int
    bit_depth: int
    sha256: str
    normal_convention: Optional[str] = None
    block_format: Optional[str] = None
    gpu_format: Optional[str] = None
    levels: Tuple[Level, ...] = ()
    raw: Mapping[str, Any] = field(default_factory=dict, repr=False, compare=False)

    @staticmethod
    def from_json(j: Mapping[str, Any]) -> "Output":
        return Output(file=j["file"], format=j.get("format", ""), color_space=j.get("color_space", ""),
                      channels=dict(j.get("channels", {})), width=j.get("width", 0), height=j.get("height", 0),
                      bit_depth=j.get("bit_depth", 0), sha256=j.get("sha256", ""),
                      normal_convention=j.get("normal_convention"), block_format=j.get("block_format"),
                      gpu_format=j.get("gpu_format"), levels=tuple(Level.from_json(x) for x in j.get("levels", [])),
                      raw=j)


@dataclass(frozen=True)
class MaterialFile:
    """A file describing a material (or the library) for an engine: .gltf, .bin, .mtlx, .usda, .tres, ..."""

    file: str
    format: str
    sha256: str

    @staticmethod
    def from_json(j: Mapping[str, Any]) -> "MaterialFile":
        return MaterialFile(file=j["file"], format=j["format"], sha256=j.get("sha256", ""))


@dataclass(frozen=True)
class Material:
    """One material set as a manifest (ingest) or a validate report records it."""

    name: str
    source: str
    convention: str
    status: str  # "ok" or "partial"
    inputs: Tuple[Input, ...]
    findings: Tuple[Finding, ...]
    constants: Mapping[str, Union[float, Tuple[float, ...]]] = field(default_factory=dict)
    outputs: Tuple[Output, ...] = ()
    material_files: Tuple[MaterialFile, ...] = ()
    archive: Optional[str] = None
    key: Optional[str] = None
    alpha_mode: Optional[str] = None
    alpha_cutoff: Optional[float] = None
    emissive_strength: Optional[float] = None
    raw: Mapping[str, Any] = field(default_factory=dict, repr=False, compare=False)

    @staticmethod
    def from_json(j: Mapping[str, Any]) -> "Material":
        name = j["name"]
        return Material(
            name=name, source=j.get("source", ""), convention=j.get("convention", ""), status=j.get("status", "ok"),
            inputs=tuple(Input.from_json(r, x) for r, x in j.get("inputs", {}).items()),
            findings=tuple(Finding.from_json(f, name) for f in j.get("findings", [])),
            constants={k: _figure(v) for k, v in j.get("constants", {}).items()},
            outputs=tuple(Output.from_json(o) for o in j.get("outputs", [])),
            material_files=tuple(MaterialFile.from_json(f) for f in j.get("material_files", [])),
            archive=j.get("archive"), key=j.get("key"), alpha_mode=j.get("alpha_mode"),
            alpha_cutoff=j.get("alpha_cutoff"), emissive_strength=j.get("emissive_strength"), raw=j)

    def input(self, role: str) -> Optional[Input]:
        """The input of `role` ("albedo", "normal", ...), or None."""
        return next((i for i in self.inputs if i.role == role), None)


@dataclass(frozen=True)
class Summary:
    """Findings counted by severity over every material, the inputs not processed, and the materials
    with a map not read or an output not written (UNREADABLE_FILE, OUTPUT_WRITE_FAILED)."""

    error: int
    warning: int
    info: int
    failures: int
    incomplete: int = 0

    def fails(self, fail_on: str = "error") -> bool:
        """What the commands exit 1 for under `--fail-on FAIL_ON` (docs/interface.md, "Exit codes"):
        a finding at or above it, an input not processed, a material incomplete."""
        from . import _core  # the library's rule, its one owner

        return _core.run_fails(self.error, self.warning, self.info, self.failures, self.incomplete, fail_on)


def _summary(materials: Sequence["Material"], failures: Sequence[InputFailure]) -> Summary:
    from . import _core

    counts = _core.summary([[(f.code, f.severity.value) for f in m.findings] for m in materials], len(failures))
    return Summary(**counts)


@dataclass(frozen=True)
class _Findings:
    materials: Tuple[Material, ...]
    failures: Tuple[InputFailure, ...]

    @property
    def findings(self) -> Tuple[Finding, ...]:
        """Every material's findings, material by material."""
        return tuple(f for m in self.materials for f in m.findings)

    @property
    def summary(self) -> Summary:
        return _summary(self.materials, self.failures)

    def passed(self, fail_on: str = "error") -> bool:
        """What `matforge validate --fail-on FAIL_ON` exits 0 for: no finding at or above it, every
        input read, every material complete."""
        return not self.summary.fails(fail_on)

    def material(self, name: str) -> Material:
        """The material named `name` (KeyError when none is)."""
        for m in self.materials:
            if m.name == name:
                return m
        raise KeyError(name)


@dataclass(frozen=True)
class Validation(_Findings):
    """`matforge validate`'s run: each set's findings (its JSON report's content), no file written."""

    preset: str = "gltf"
    skipped: Tuple[str, ...] = ()  # output folders of earlier runs found under the inputs, left out
    raw: Mapping[str, Any] = field(default_factory=dict, repr=False, compare=False)

    @staticmethod
    def from_json(j: Mapping[str, Any]) -> "Validation":
        return Validation(materials=tuple(Material.from_json(m) for m in j.get("materials", [])),
                          failures=tuple(InputFailure.from_json(f) for f in j.get("failures", [])),
                          preset=j.get("preset", ""), skipped=tuple(j.get("skipped", [])), raw=j)

    def __str__(self) -> str:
        s = self.summary
        verdict = "PASS" if self.passed() else "FAIL"
        lines = [f"{len(self.materials)} material(s), {s.failures} input(s) not processed: {s.error} error(s), "
                 f"{s.warning} warning(s), {s.info} info — {verdict} (fail_on error)"]
        lines += [f"  {f}" for f in self.findings if f.severity != Severity.info]
        lines += [f"  failure {f.code} {f.message}" for f in self.failures]
        return "\n".join(lines)


@dataclass(frozen=True)
class Manifest(_Findings):
    """manifest.json (version 1) as an ingest wrote it (docs/interface.md)."""

    manifest_version: int = 1
    generator: str = ""
    preset: str = ""
    normal_convention: str = "gl"
    library: Tuple[MaterialFile, ...] = ()
    thresholds: Mapping[str, Mapping[str, float]] = field(default_factory=dict)
    shard: Optional[Mapping[str, Any]] = None  # only in a shard's manifest (ingest shard=(i, n))
    path: Optional[str] = None  # the file it was read from
    notes: Tuple[str, ...] = ()  # the ingest's notes: outputs of earlier runs removed or kept
    raw: Mapping[str, Any] = field(default_factory=dict, repr=False, compare=False)

    @staticmethod
    def from_json(j: Mapping[str, Any], path: Optional[str] = None, notes: Sequence[str] = ()) -> "Manifest":
        return Manifest(materials=tuple(Material.from_json(m) for m in j.get("materials", [])),
                        failures=tuple(InputFailure.from_json(f) for f in j.get("failures", [])),
                        manifest_version=j.get("manifest_version", 1), generator=j.get("generator", ""),
                        preset=j.get("preset", ""), normal_convention=j.get("normal_convention", "gl"),
                        library=tuple(MaterialFile.from_json(f) for f in j.get("library", [])),
                        thresholds=j.get("thresholds", {}), shard=j.get("shard"),
                        path=os.fspath(path) if path is not None else None, notes=tuple(notes), raw=j)

    @property
    def folder(self) -> Optional[str]:
        """The folder the manifest's paths are relative to."""
        return os.path.dirname(self.path) if self.path else None

    def __str__(self) -> str:
        s = self.summary
        return (f"{self.path or 'manifest'}: {len(self.materials)} material(s) ({self.preset}), {s.failures} failed; "
                f"findings: {s.error} error, {s.warning} warning, {s.info} info")


@dataclass(frozen=True)
class Candidate:
    """A file discovery considered for a role: the name rule (or sidecar) that matched, its header."""

    file: str
    family: str
    rule: str
    sidecar: str  # the sidecar that stated the role ("" when the name did)
    normal_convention: str  # what the name says: gl, dx or unknown
    width: int
    height: int
    channels: int
    bit_depth: int
    is_float: bool
    opacity_in_alpha: bool
    unused: Tuple[str, ...]  # output roles this map must not feed (a glTF factor of 0)

    @staticmethod
    def _fields(j: Mapping[str, Any]) -> dict:
        return dict(file=j["file"], family=j["family"], rule=j["rule"], sidecar=j["sidecar"],
                    normal_convention=j["normal_convention"], width=j["width"], height=j["height"],
                    channels=j["channels"], bit_depth=j["bit_depth"], is_float=j["is_float"],
                    opacity_in_alpha=j["opacity_in_alpha"], unused=tuple(j["unused"]))

    @property
    def evidence(self) -> str:
        """What decided the role: the sidecar's path, else "name"."""
        return self.sidecar or "name"


@dataclass(frozen=True)
class MapChoice(Candidate):
    """The file chosen for one input role, and the other candidates for it, best first."""

    role: str = ""
    rejected: Tuple[Candidate, ...] = ()

    @staticmethod
    def from_json(j: Mapping[str, Any]) -> "MapChoice":
        return MapChoice(role=j["role"], rejected=tuple(Candidate(**Candidate._fields(r)) for r in j["rejected"]),
                         **Candidate._fields(j))


@dataclass(frozen=True)
class DiscoveredSet:
    """One material set as discovery sees it: its files, each role's file and why."""

    name: str
    source: str  # as messages name it: "path/to/set", or "path/to/x.zip/folder"
    root: str  # the folder holding the files, or the .zip
    archive: Optional[str]  # the .zip, for a set read from one
    files: Tuple[str, ...]  # relative to root (inside a .zip: to the set's folder)
    convention: str  # the naming family most maps follow
    maps: Tuple[MapChoice, ...]
    findings: Tuple[Finding, ...]  # AMBIGUOUS_MAP, UNRECOGNIZED_FILE, NAMES_MERGED, ...

    @staticmethod
    def from_json(j: Mapping[str, Any]) -> "DiscoveredSet":
        return DiscoveredSet(name=j["name"], source=j["source"], root=j["root"], archive=j["archive"],
                             files=tuple(j["files"]), convention=j["convention"],
                             maps=tuple(MapChoice.from_json(m) for m in j["maps"]),
                             findings=tuple(Finding.from_json(f, j["name"]) for f in j["findings"]))

    @property
    def roles(self) -> Mapping[str, str]:
        """role -> the chosen file."""
        return {m.role: m.file for m in self.maps}

    def role_of(self, file: str) -> Optional[str]:
        """The role `file` was chosen for, or None (a rejected candidate, clutter, not an image)."""
        return next((m.role for m in self.maps if m.file == file), None)


@dataclass(frozen=True)
class Discovery:
    """Every set under the inputs, as discovered (nothing decoded, nothing judged but names)."""

    sets: Tuple[DiscoveredSet, ...]
    failures: Tuple[InputFailure, ...]
    skipped: Tuple[str, ...]

    @staticmethod
    def from_json(j: Mapping[str, Any]) -> "Discovery":
        return Discovery(sets=tuple(DiscoveredSet.from_json(s) for s in j["sets"]),
                         failures=tuple(InputFailure.from_json(f) for f in j["failures"]), skipped=tuple(j["skipped"]))

    def __getitem__(self, name: str) -> DiscoveredSet:
        for s in self.sets:
            if s.name == name:
                return s
        raise KeyError(name)


@dataclass(frozen=True)
class PlannedSet:
    """One set of a plan (docs/plan.schema.json): its size, action key and shard."""

    name: str
    source: str
    bytes: int
    files: int
    shard: int
    key: Optional[str] = None
    error: Optional[str] = None  # why a file of the set could not be read

    @staticmethod
    def from_json(j: Mapping[str, Any]) -> "PlannedSet":
        return PlannedSet(name=j["name"], source=j["source"], bytes=j["bytes"], files=j["files"], shard=j["shard"],
                          key=j.get("key"), error=j.get("error"))


@dataclass(frozen=True)
class Plan:
    """`matforge plan`'s work list: every set with its shard, for ingest(..., shard=(i, shards)) on a farm."""

    preset: str
    shards: int
    context: str  # the digest of everything but the inputs that decides the outputs
    digest: str  # the digest of the split, which every shard's manifest records ("plan" in the file)
    sets: Tuple[PlannedSet, ...]
    failures: Tuple[InputFailure, ...]
    unchanged: int = 0  # with changed_since: the sets left out as unchanged
    path: Optional[str] = None  # where it was written
    raw: Mapping[str, Any] = field(default_factory=dict, repr=False, compare=False)

    @staticmethod
    def from_json(j: Mapping[str, Any], path: Optional[str] = None) -> "Plan":
        return Plan(preset=j["preset"], shards=j["shards"], context=j["context"], digest=j["plan"],
                    sets=tuple(PlannedSet.from_json(s) for s in j["sets"]),
                    failures=tuple(InputFailure.from_json(f) for f in j.get("failures", [])),
                    unchanged=j.get("unchanged", 0), path=path, raw=j)

    def shard(self, index: int) -> Tuple[PlannedSet, ...]:
        """The sets ingest(..., shard=(index, shards)) processes."""
        return tuple(s for s in self.sets if s.shard == index)
