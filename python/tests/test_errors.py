"""Errors are typed exceptions carrying their code, raised before anything is written."""

from __future__ import annotations

import shutil

import matforge
import pytest
from conftest import set_paths


def test_a_missing_input_is_input_not_found(tmp_path):
    missing = tmp_path / "no_such_folder"
    for call in (lambda: matforge.validate(missing), lambda: matforge.discover(missing),
                 lambda: matforge.ingest(missing, tmp_path / "out"), lambda: matforge.plan(missing)):
        with pytest.raises(matforge.InputError) as e:
            call()
        assert e.value.code == "INPUT_NOT_FOUND"
        assert str(missing) in str(e.value) and "no such folder" in e.value.message
        assert isinstance(e.value, matforge.Error)
    assert not (tmp_path / "out").exists()  # nothing created


def test_usage_errors(corpus, tmp_path):
    one = set_paths(corpus, ["ambientcg_Net004A_1K-JPG"])
    with pytest.raises(matforge.UsageError) as e:
        matforge.validate(one, preset="no-such-preset")
    assert e.value.code == "usage" and "no-such-preset" in str(e.value)
    with pytest.raises(matforge.UsageError) as e:
        matforge.validate(one, rules={"rules": {"NO_SUCH_CODE": "error"}})
    assert "NO_SUCH_CODE" in str(e.value)
    copy = tmp_path / "in" / "Net004A"  # never the corpus itself as an output folder
    shutil.copytree(one[0], copy)
    with pytest.raises(matforge.UsageError):  # an output folder that holds the input
        matforge.ingest(copy, tmp_path / "in", cache=False)
    assert sorted(p.name for p in (tmp_path / "in").iterdir()) == ["Net004A"]
    with pytest.raises(matforge.UsageError):
        matforge.ingest(one, tmp_path / "o", tiers=[512, 512], cache=False)
    with pytest.raises(matforge.UsageError):
        matforge.ingest(one, tmp_path / "o", normal_convention="up", cache=False)
    with pytest.raises(matforge.UsageError):
        matforge.validate(one, jobs=-1)
    assert not (tmp_path / "o").exists()


def test_a_foreign_manifest_is_refused_without_force(corpus, tmp_path):
    out = tmp_path / "o"
    out.mkdir()
    (out / "manifest.json").write_text("{}")
    one = set_paths(corpus, ["ambientcg_Net004A_1K-JPG"])
    with pytest.raises(matforge.UsageError):
        matforge.ingest(one, out, cache=False)
    assert (out / "manifest.json").read_text() == "{}"
    m = matforge.ingest(one, out, cache=False, force=True)
    assert [x.name for x in m.materials] == ["Net004A"]


def test_the_libraries_in_use():
    # OpenImageIO comes from the image module the package carries (or the build tree's): loaded here.
    libs = matforge.libraries()
    assert libs[0].startswith("OpenImageIO 2.") and "formats:" in libs[0]
    assert any(lib.startswith("OpenColorIO") for lib in libs)
    assert matforge.__version__ == "0.1.0" or matforge.__version__[0].isdigit()
    assert "gltf" in matforge.presets() and "unity-hdrp" in matforge.presets()


def test_an_unreadable_manifest_is_a_manifest_error(tmp_path):
    bad = tmp_path / "manifest.json"
    bad.write_text('{"manifest_version": 1, "materials": [{"name": 3}]}')
    with pytest.raises(matforge.ManifestError) as e:
        matforge.read_manifest(bad)
    assert e.value.code == "manifest"


if __name__ == "__main__":
    raise SystemExit(pytest.main([__file__]))
