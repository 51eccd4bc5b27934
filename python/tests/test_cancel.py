"""Stopping a run from Python: a progress callback returning False, a Cancel token, an exception in
the callback, Ctrl-C. A cancelled ingest leaves nothing torn: every file is complete (the bytes a
whole run writes) or absent, no temporary is left and no manifest is written, only the stopped
run's journal listing each file it wrote (docs/interface.md: the next run knows them as its own);
running it again finishes it, byte for byte the CLI's."""

from __future__ import annotations

import json
import os
import signal

import matforge
import pytest
from conftest import set_paths, tree

SETS = ["3dtextures_Crystal_003_SD", "3dtextures_Obsidian_001", "3dtextures_Sci-Fi_Wall_014",
        "handnamed_crystal_tutorial"]


@pytest.fixture(scope="module")
def whole(cli, corpus, tmp_path_factory):
    """What a whole run writes (the CLI's), at the depth of each test's `tmp_path / "o"` (the
    manifest names the sources relative to itself)."""
    out = tmp_path_factory.mktemp("whole") / "o"
    cli.run("ingest", *set_paths(corpus, SETS), "-o", out, "--no-cache", "-q", "-j", "1", ok=(0, 1))
    return tree(out)


JOURNAL = ".manifest.json.journal"


def assert_nothing_torn(out, whole):
    written = tree(out)
    assert "manifest.json" not in written
    journal = written.pop(JOURNAL).decode().splitlines()
    assert journal[0] == "matforge journal 1"
    assert {json.loads(line)["wrote"] for line in journal[1:]} == set(written)
    for name, data in written.items():
        assert name in whole, f"{name}: no file of a whole run (a temporary?)"
        assert data == whole[name], f"{name}: torn"
    return written


def test_progress_returning_false_cancels_after_the_first_set(corpus, tmp_path, whole):
    seen = []

    def progress(done, total, name):
        seen.append((done, total, name))
        return False

    with pytest.raises(matforge.Cancelled) as e:
        matforge.ingest(set_paths(corpus, SETS), tmp_path / "o", cache=False, jobs=1, progress=progress)
    assert e.value.code == "INTERRUPTED"
    assert isinstance(e.value, matforge.Error)
    assert len(seen) == 1 and seen[0][:2] == (1, 4)
    written = assert_nothing_torn(tmp_path / "o", whole)
    first = seen[0][2]
    assert any(n.startswith(first + "/") for n in written), "the first set's outputs are complete"
    assert len([n for n in whole if n.endswith(".png")]) > len([n for n in written if n.endswith(".png")])
    # Run again: it finishes, and the folder is what a whole run writes.
    m = matforge.ingest(set_paths(corpus, SETS), tmp_path / "o", cache=False, jobs=1)
    assert len(m.materials) == 4
    assert tree(tmp_path / "o") == whole


def test_a_cancel_token_stops_the_run(corpus, tmp_path, whole):
    token = matforge.Cancel()
    assert not token.cancelled

    def progress(done, total, name):
        token.cancel()  # any thread may: here a worker's

    with pytest.raises(matforge.Cancelled):
        matforge.ingest(set_paths(corpus, SETS), tmp_path / "o", cache=False, jobs=1, progress=progress, cancel=token)
    assert token.cancelled
    assert_nothing_torn(tmp_path / "o", whole)
    # A cancelled token stops a validate before it has judged every set.
    with pytest.raises(matforge.Cancelled):
        matforge.validate(set_paths(corpus, SETS), cancel=token)


def test_an_exception_in_the_callback_stops_the_run_and_is_raised(corpus, tmp_path, whole):
    class Stop(Exception):
        pass

    def progress(done, total, name):
        raise Stop(name)

    with pytest.raises(Stop):
        matforge.ingest(set_paths(corpus, SETS), tmp_path / "o", cache=False, jobs=1, progress=progress)
    assert_nothing_torn(tmp_path / "o", whole)


def test_ctrl_c_stops_the_run_as_keyboard_interrupt(corpus, tmp_path, whole):
    def progress(done, total, name):
        os.kill(os.getpid(), signal.SIGINT)  # as the terminal's Ctrl-C: Python's handler marks it

    with pytest.raises(KeyboardInterrupt):
        matforge.ingest(set_paths(corpus, SETS), tmp_path / "o", cache=False, jobs=1, progress=progress)
    assert_nothing_torn(tmp_path / "o", whole)


if __name__ == "__main__":
    raise SystemExit(pytest.main([__file__]))
