"""The example publish validator (examples/publish_validator.py), without Pyblish: its verdicts are
`matforge validate`'s exit codes, it fails on the findings at or above its threshold and hands the
findings on in the instance's data."""

from __future__ import annotations

import json
import os
import pathlib
import subprocess
import sys

import pytest

sys.path.insert(0, str(pathlib.Path(__file__).parent))
import publish_validator  # noqa: E402

HERE = pathlib.Path(__file__).parent


def corpus_set(name: str) -> str:
    return str(pathlib.Path(os.environ["MATFORGE_CORPUS_DIR"]) / "real" / name)


def cli_exit(*args: str) -> int:
    return subprocess.run([os.environ["MATFORGE_BIN"], "validate", *args], capture_output=True).returncode


def test_the_plugin_passes_and_fails_as_validate_exits(tmp_path):
    folder = corpus_set("ambientcg_Net004A_1K-JPG")  # warnings (ALBEDO_TOO_DARK), no error
    plugin = publish_validator.ValidateMaterialSet()
    instance = publish_validator.Instance("Net004A", materialFolder=folder)
    assert cli_exit(folder, "--fail-on", "error") == 0
    plugin.process(instance)  # passes
    findings = instance.data["matforgeFindings"]
    assert any(f.code == "ALBEDO_TOO_DARK" and f.severity == "warning" for f in findings)

    assert cli_exit(folder, "--fail-on", "warning") == 1
    plugin.fail_on = "warning"
    with pytest.raises(publish_validator.MaterialSetInvalid) as e:
        plugin.process(instance)
    assert "ALBEDO_TOO_DARK" in str(e.value)
    assert {f.code for f in e.value.findings} == {f.code for f in findings if f.severity != "info"}

    rules = tmp_path / "rules.json"
    rules.write_text(json.dumps({"rules": {"ALBEDO_TOO_DARK": "error"}}))
    assert cli_exit(folder, "--rules", str(rules)) == 1
    strict = publish_validator.ValidateMaterialSet()
    with pytest.raises(publish_validator.MaterialSetInvalid):
        strict.process(publish_validator.Instance("Net004A", materialFolder=folder, matforgeRules=str(rules)))


def test_an_unreadable_folder_fails_the_publish(tmp_path):
    plugin = publish_validator.ValidateMaterialSet()
    with pytest.raises(publish_validator.MaterialSetInvalid) as e:
        plugin.process(publish_validator.Instance("gone", materialFolder=str(tmp_path / "gone")))
    assert "INPUT_NOT_FOUND" in str(e.value)


def test_standalone_exit_codes():
    folder = corpus_set("ambientcg_Net004A_1K-JPG")
    script = [sys.executable, str(HERE / "publish_validator.py"), folder]
    ok = subprocess.run(script, capture_output=True, text=True)
    assert ok.returncode == 0, ok.stderr
    assert json.loads(ok.stdout)["passed"] is True
    refused = subprocess.run(script + ["--fail-on", "warning"], capture_output=True, text=True)
    assert refused.returncode == 1 and "publish refused" in refused.stderr and "ALBEDO_TOO_DARK" in refused.stderr


if __name__ == "__main__":
    raise SystemExit(pytest.main([__file__]))
