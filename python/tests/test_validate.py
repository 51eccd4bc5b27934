"""matforge.validate against `matforge validate --report json` on real vendor downloads: the same
findings (code, severity, role, file, message, figures with their int/float types), the same
verdict, rules given as a file or an object alike, and progress once per set."""

from __future__ import annotations

import json
import threading
import time

import matforge
import pytest
from conftest import same_typed, set_paths

# Sets with warnings and infos of several rules (albedo, normal convention, packed maps, a flat
# folder of two sets, a sidecar-named set).
SETS = ["ambientcg_Net004A_1K-JPG", "flat_folder_two_sets", "godot_tps-demo_container1",
        "polyhaven_rubberized_track_1k", "3dtextures_Metal_Rusted_010"]


def finding_json(f: matforge.Finding) -> dict:
    """A finding as the JSON report writes it (absent members left out)."""
    j = {"code": f.code, "severity": f.severity.value, "message": f.message,
         "figures": {k: list(v) if isinstance(v, tuple) else v for k, v in f.figures.items()}}
    if f.role is not None:
        j["role"] = f.role
    if f.file is not None:
        j["file"] = f.file
    return j


def test_findings_equal_the_cli_json(cli, corpus):
    inputs = set_paths(corpus, SETS)
    report = cli.validate_json(*inputs)
    v = matforge.validate(inputs)
    assert isinstance(v, matforge.Validation)
    by_name = {m["name"]: m for m in report["materials"]}
    assert sorted(m.name for m in v.materials) == sorted(by_name)
    assert len(v.materials) == 6  # the flat folder holds two sets
    total = 0
    for m in v.materials:
        expected = by_name[m.name]
        assert m.source == expected["source"]
        got = [finding_json(f) for f in m.findings]
        want = [{k: f[k] for k in ("code", "severity", "message", "figures", "role", "file") if k in f}
                for f in expected["findings"]]
        assert len(got) == len(want), m.name
        for g, w in zip(got, want):
            assert same_typed(g, w), (m.name, g, w)
        assert all(f.material == m.name for f in m.findings)
        total += len(got)
    assert total >= 10
    assert not v.failures and report["failures"] == []
    s = v.summary
    assert (s.error, s.warning, s.info, s.failures) == tuple(
        report["summary"][k] for k in ("error", "warning", "info", "failures"))
    assert s.warning > 0
    # The verdicts of --fail-on warning / error, as the exit codes say them.
    for fail_on in ("error", "warning"):
        code = cli.run("validate", *inputs, "--fail-on", fail_on, ok=(0, 1)).returncode
        assert v.passed(fail_on) == (code == 0), fail_on
    assert not v.passed("warning")


def test_rules_as_object_or_file_raise_a_severity_like_the_cli(cli, corpus, tmp_path):
    inputs = set_paths(corpus, ["ambientcg_Net004A_1K-JPG"])
    rules = {"rules": {"ALBEDO_TOO_DARK": "error"}}
    rules_file = tmp_path / "rules.json"
    rules_file.write_text(json.dumps(rules))
    plain = matforge.validate(inputs)
    dark = [f for f in plain.findings if f.code == "ALBEDO_TOO_DARK"]
    assert dark and all(f.severity == matforge.Severity.warning for f in dark)
    assert plain.passed()
    for given in (rules, rules_file, str(rules_file)):
        raised = matforge.validate(inputs, rules=given)
        assert [f.severity for f in raised.findings if f.code == "ALBEDO_TOO_DARK"] == [matforge.Severity.error] * len(dark)
        assert not raised.passed()
    report = cli.validate_json(*inputs, "--rules", str(rules_file))
    cli_severities = [f["severity"] for m in report["materials"] for f in m["findings"]]
    assert cli_severities == [f.severity.value for f in matforge.validate(inputs, rules=rules).findings]


def test_progress_once_per_set_in_order(corpus):
    inputs = set_paths(corpus, SETS[:3])
    calls = []
    v = matforge.validate(inputs, progress=lambda done, total, name: calls.append((done, total, name)))
    assert [c[0] for c in calls] == [1, 2, 3, 4]
    assert all(c[1] == 4 for c in calls)
    assert sorted(c[2] for c in calls) == sorted(m.name for m in v.materials)


def test_the_gil_is_released_while_it_runs(corpus):
    # A Python thread keeps counting while validate runs: it could not if the call held the GIL.
    counts = []
    stop = threading.Event()

    def count():
        n = 0
        while not stop.is_set():
            n += 1
            if n % 1000 == 0:
                counts.append(time.monotonic())

    t = threading.Thread(target=count)
    t.start()
    try:
        start = time.monotonic()
        v = matforge.validate(corpus, jobs=1)  # every corpus set, one at a time: about a second
        end = time.monotonic()
    finally:
        stop.set()
        t.join()
    assert len(v.materials) > 15
    during = [c for c in counts if start + 0.05 < c < end - 0.05]
    assert len(during) > 20 * (end - start), f"{len(during)} thousands counted during {end - start:.2f} s"


def test_sample_materials_print(samples):
    v = matforge.validate(samples)
    text = str(v)
    assert text.startswith("4 material(s), 0 input(s) not processed")
    assert "PASS" in text or "FAIL" in text
    assert [m.name for m in v.materials] == sorted(m.name for m in v.materials)


def test_a_figure_keeps_its_type(corpus):
    v = matforge.validate(set_paths(corpus, ["ambientcg_Net004A_1K-JPG"]))
    dark = next(f for f in v.findings if f.code == "ALBEDO_TOO_DARK")
    assert isinstance(dark.figures["pixels"], int) and not isinstance(dark.figures["pixels"], bool)
    assert isinstance(dark.figures["share"], float)
    assert 0.0 < dark.figures["share"] <= 1.0
    assert isinstance(dark.figures["metalness_mask"], bool)


if __name__ == "__main__":
    raise SystemExit(pytest.main([__file__]))
