"""matforge.ingest against `matforge ingest`: the same files byte for byte (the manifest included:
it holds no time), the manifest returned as typed objects whose hashes are the files', and several
presets in one pass as the CLI writes them."""

from __future__ import annotations

import json

import matforge
import pytest
from conftest import sha256, tree, set_paths

SETS = ["ambientcg_Net004A_1K-JPG", "polyhaven_brown_planks_09_1k_jpg+webp"]


def test_ingest_is_byte_identical_to_the_cli(cli, corpus, tmp_path):
    inputs = set_paths(corpus, SETS)
    cli.run("ingest", *inputs, "-o", tmp_path / "cli", "--no-cache", "-q", ok=(0, 1))
    m = matforge.ingest(inputs, tmp_path / "py", cache=False)
    want, got = tree(tmp_path / "cli"), tree(tmp_path / "py")
    assert sorted(got) == sorted(want)
    assert "manifest.json" in got and len(got) > 10
    for name in want:
        assert got[name] == want[name], name
    # The manifest returned is the one written, typed.
    assert isinstance(m, matforge.Manifest)
    assert m.path == str(tmp_path / "py" / "manifest.json")
    raw = json.loads(want["manifest.json"])
    assert m.raw == raw
    assert [x.name for x in m.materials] == [x["name"] for x in raw["materials"]] == ["Net004A", "brown_planks_09"]
    assert m.preset == "gltf" and m.generator == f"matforge {matforge.__version__}"
    for material in m.materials:
        assert material.outputs
        for out in material.outputs:
            assert out.sha256 == sha256(tmp_path / "py" / out.file), out.file
            assert out.width > 0 and out.format == "png"
        albedo = material.input("albedo")
        assert albedo is not None and albedo.color_space == "sRGB" and albedo.width == 1024
    net = m.material("Net004A")
    assert net.alpha_mode == "mask"
    assert net.input("normal").normal_convention == "gl"
    assert [f.code for f in net.findings] == [f["code"] for f in raw["materials"][0]["findings"]]


def test_several_presets_in_one_pass_as_the_cli(cli, corpus, tmp_path):
    inputs = set_paths(corpus, SETS[:1])
    cli.run("ingest", *inputs, "-o", tmp_path / "cli", "--no-cache", "-q", "--preset", "gltf,unity-hdrp", ok=(0, 1))
    runs = matforge.ingest(inputs, tmp_path / "py", presets=["gltf", "unity-hdrp"], cache=False)
    assert sorted(runs) == ["gltf", "unity-hdrp"]
    assert runs["unity-hdrp"].preset == "unity-hdrp"
    assert runs["gltf"].path == str(tmp_path / "py" / "gltf" / "manifest.json")
    assert tree(tmp_path / "py") == tree(tmp_path / "cli")


def test_a_second_run_restores_from_the_cache_the_same_bytes(corpus, tmp_path):
    inputs = set_paths(corpus, SETS[:1])
    first = matforge.ingest(inputs, tmp_path / "a", cache=tmp_path / "cache")
    again = matforge.ingest(inputs, tmp_path / "b", cache=tmp_path / "cache")
    assert tree(tmp_path / "a") == tree(tmp_path / "b")
    assert first.raw == again.raw


def test_read_manifest_reads_what_ingest_wrote(corpus, tmp_path):
    m = matforge.ingest(set_paths(corpus, SETS[:1]), tmp_path / "o", cache=False, presets="separate")
    back = matforge.read_manifest(tmp_path / "o" / "manifest.json")
    assert back.raw == m.raw and back.preset == "separate"
    assert {o.file.rsplit("_", 1)[1] for o in back.materials[0].outputs} >= {"albedo.png", "normal.png"}


if __name__ == "__main__":
    raise SystemExit(pytest.main([__file__]))
