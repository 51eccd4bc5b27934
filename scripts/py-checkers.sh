#!/usr/bin/env bash
# Installs the real implementations the tests open matforge's material files with, from PyPI,
# into a virtual environment of the build tree (never committed, never vendored):
#   usd-core   OpenUSD (Pixar's pxr modules): Usd.Stage.Open and the validators usdchecker runs
#              (UsdValidation) on every .usda and library.usda (tests/texture/checkers/usd_open.py)
#   bpy        Blender 4.5 as a Python module: every .gltf imported by Blender's own glTF importer,
#              each texture found in its Principled BSDF input (tests/texture/checkers/blender_open.py)
#   materialx  MaterialX 1.39 (the Academy Software Foundation's bindings): every .mtlx validated
#              with the standard libraries, GLSL generated for each material and compiled by
#              glslang (tests/texture/checkers/mtlx_open.py)
#   texture2ddecoder  K0lb3's BCn/ASTC/ETC decoders (C++ from AssetStudio's Texture2DDecoder, a
#              cp311-abi3 manylinux wheel): the independent decoder of every level of matforge's
#              BC1/BC3/BC4/BC5/BC7 .dds files and of the peers' (tests/texture/checkers/bc_decode.py,
#              bench/texture/bc7_vs_bc7e.sh)
#   numpy      1.26 (what bpy 4.5 requires anyway): the PSNR of bench/texture/psnr_rgba.py
#   pytest     runs the Python module's tests (python/tests, examples/: ctest's python.*), which
#              import the module the build made for this interpreter
# (PyPI's pyktx 4.4.2 is a source package that builds against an installed libktx, which Debian
# 12 does not package: the .ktx2 files are read by npm ktx-parse until libktx is built here.)
# Usage: scripts/py-checkers.sh [DIR]   (default build/py; the tests run DIR/bin/python)
# The interpreter is Debian's /usr/bin/python3 (3.11, with its venv module: package python3-venv)
# where it exists, else the python3 on PATH: each wheel above is built for CPython 3.11.
# Pinned versions: a new release must not change a test's verdict unnoticed.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
dir=${1:-$root/build/py}
packages=(usd-core==26.11 materialx==1.39.5 bpy==4.5.15 texture2ddecoder==1.0.6 numpy==1.26.4 pytest==8.4.2)
want=$(printf '%s\n' "${packages[@]}")
[[ -f $dir/installed.txt && $(cat "$dir/installed.txt") == "$want" && -x $dir/bin/python ]] && exit 0
mkdir -p "$dir"
# Test processes run in parallel and each may call this: one installs, the others wait.
exec 9>"$dir/.lock"
flock 9
[[ -f $dir/installed.txt && $(cat "$dir/installed.txt") == "$want" && -x $dir/bin/python ]] && exit 0
python=/usr/bin/python3
[[ -x $python ]] || python=$(command -v python3)
if [[ ! -x $dir/bin/python ]]; then
  "$python" -m venv "$dir" >&2 || {
    echo "py-checkers: $python cannot make a virtual environment (Debian: apt-get install python3-venv)" >&2
    exit 1
  }
fi
"$dir/bin/python" -m pip install --quiet --disable-pip-version-check --no-input "${packages[@]}" >&2
echo "$want" > "$dir/installed.txt"
