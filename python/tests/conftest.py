"""What the Python tests share: the CLI of the same build (MATFORGE_BIN) to compare against, and
the real-material corpus (MATFORGE_CORPUS_DIR). ctest sets both (python/CMakeLists.txt)."""

from __future__ import annotations

import hashlib
import json
import os
import pathlib
import subprocess
from typing import Dict, List

import pytest


def _env_path(name: str) -> pathlib.Path:
    value = os.environ.get(name)
    if not value:
        raise RuntimeError(f"{name} is not set (run these tests through ctest: python/CMakeLists.txt)")
    return pathlib.Path(value)


@pytest.fixture(scope="session")
def corpus() -> pathlib.Path:
    real = _env_path("MATFORGE_CORPUS_DIR") / "real"
    assert real.is_dir(), f"the corpus is missing: {real}"
    return real


@pytest.fixture(scope="session")
def samples() -> pathlib.Path:
    return _env_path("MATFORGE_SOURCE_DIR") / "sample_materials"


class Cli:
    """The matforge binary of the same build."""

    def __init__(self, path: pathlib.Path) -> None:
        self.path = path

    def run(self, *args: str, ok=(0,)) -> subprocess.CompletedProcess:
        r = subprocess.run([str(self.path), *map(str, args)], capture_output=True, text=True)
        assert r.returncode in ok, f"matforge {' '.join(map(str, args))}: exit {r.returncode}\n{r.stderr}"
        return r

    def validate_json(self, *args: str) -> dict:
        """`matforge validate ARGS --report json`, the report parsed."""
        r = self.run("validate", *args, "--report", "json", "--fail-on", "never", ok=(0, 1))
        return json.loads(r.stdout)


@pytest.fixture(scope="session")
def cli() -> Cli:
    return Cli(_env_path("MATFORGE_BIN"))


def tree(folder: pathlib.Path) -> Dict[str, bytes]:
    """Every file under `folder` (hidden ones too), by '/'-separated relative path: its bytes."""
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


def sha256(path: pathlib.Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def same_typed(a, b) -> bool:
    """Equal values of equal types all the way down: 3 and 3.0 differ (a figure's int is a count)."""
    if type(a) is not type(b):
        return False
    if isinstance(a, dict):
        return a.keys() == b.keys() and all(same_typed(a[k], b[k]) for k in a)
    if isinstance(a, (list, tuple)):
        return len(a) == len(b) and all(same_typed(x, y) for x, y in zip(a, b))
    return a == b


def set_paths(corpus: pathlib.Path, names: List[str]) -> List[str]:
    return [str(corpus / n) for n in names]
