"""A farm from Python: plan() writes `matforge plan`'s work list byte for byte, each shard's ingest
writes its part, and merge() joins them into the manifest one unsharded run writes (the CLI's)."""

from __future__ import annotations

import matforge
import pytest
from conftest import set_paths, tree

SETS = ["3dtextures_Crystal_003_SD", "3dtextures_Obsidian_001", "handnamed_crystal_tutorial"]


def test_plan_shards_and_merge_as_one_run(cli, corpus, tmp_path):
    inputs = set_paths(corpus, SETS)
    cli.run("plan", *inputs, "-o", tmp_path / "cli-plan.json", "--shards", "2")
    p = matforge.plan(inputs, shards=2, out=tmp_path / "plan.json")
    assert (tmp_path / "plan.json").read_bytes() == (tmp_path / "cli-plan.json").read_bytes()
    assert p.shards == 2 and len(p.sets) == 3 and p.path == str(tmp_path / "plan.json")
    assert sorted(s.shard for s in p.sets) in ([0, 0, 1], [0, 1, 1])
    assert all(s.key and len(s.key) == 64 for s in p.sets)

    out = tmp_path / "farm"
    parts = []
    for i in range(2):
        m = matforge.ingest(inputs, out, shard=(i, 2), cache=False)
        assert m.shard is not None and m.shard["index"] == i and m.shard["plan"] == p.digest
        assert sorted(x.name for x in m.materials) == sorted(s.name for s in p.shard(i))
        parts.append(out / f"manifest.shard-{i}-of-2.json")
    merged = matforge.merge(parts, out / "manifest.json")
    assert merged.shard is None and len(merged.materials) == 3

    cli.run("ingest", *inputs, "-o", tmp_path / "one", "--no-cache", "-q", ok=(0, 1))
    one, farm = tree(tmp_path / "one"), tree(out)
    for name, data in one.items():
        assert farm.get(name) == data, name
    assert sorted(set(farm) - set(one)) == [p.name for p in parts]


def test_a_failed_shard_is_refused(corpus, tmp_path):
    inputs = set_paths(corpus, SETS)
    out = tmp_path / "farm"
    parts = []
    for i in range(2):
        matforge.ingest(inputs, out, shard=(i, 2), cache=False, rules={"rules": {"MISSING_MAP": "error"}})
        parts.append(out / f"manifest.shard-{i}-of-2.json")
    with pytest.raises(matforge.MergeError) as e:
        matforge.merge(parts, out / "manifest.json")
    assert e.value.code == "shard_failed" and "MISSING_MAP" in str(e.value)
    assert not (out / "manifest.json").exists()
    merged = matforge.merge(parts, out / "manifest.json", keep_errors=True)
    assert not merged.passed()


if __name__ == "__main__":
    raise SystemExit(pytest.main([__file__]))
