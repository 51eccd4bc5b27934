#!/bin/bash
# Accuracy against a path tracer (docs/accuracy/pathtracer.md), end to end:
#   bench/pathtracer/run.sh BUILD_DIR [WORK]
# BUILD_DIR holds tools/matforge/matforge; WORK (default /tmp/matforge-pathtracer) receives the npm
# packages, the inputs, every render and the results (results.md: the table; diagnosis.md).
# Needs (Debian 12): blender (3.4.1), chromium, nodejs + npm, python3-numpy, python3-openimageio,
# and npm registry access for package.json's three packages. Cycles renders that already exist in
# WORK are kept (delete WORK/out/cycles to render them again). SPP=256 (per seed, two seeds; a scene's
# cycles_spp_scale multiplies it).
set -euo pipefail
[ $# -ge 1 ] || { echo "usage: $0 BUILD_DIR [WORK]" >&2; exit 2; }
build=$(cd "$1" && pwd)
here=$(cd "$(dirname "$0")" && pwd)
work=${2:-/tmp/matforge-pathtracer}
mkdir -p "$work"
work=$(cd "$work" && pwd)
spp=${SPP:-256}
mf=$build/tools/matforge/matforge
py=/usr/bin/python3
export PYTHONDONTWRITEBYTECODE=1
for t in blender /usr/bin/chromium node npm "$mf"; do
  command -v "$t" >/dev/null || { echo "missing $t (apt-get install blender chromium nodejs npm; or build matforge)" >&2; exit 2; }
done
$py -c 'import numpy, OpenImageIO' || { echo "apt-get install python3-numpy python3-openimageio" >&2; exit 2; }
log() { printf '[%s] %s\n' "$(date +%T)" "$*"; }
declare -A took

log "npm packages -> $work/node"
mkdir -p "$work/node"
cp "$here/package.json" "$work/node/package.json"
(cd "$work/node" && npm install --no-audit --no-fund --loglevel=error >/dev/null)

log "inputs (scene files, texture, E tables)"
cd "$here"
$py make_inputs.py "$here/scenes.json" "$work"

log "matforge (lavapipe, --aa via image.supersample)"
t0=$SECONDS
mkdir -p "$work/out/matforge"
for b in standard accurate; do
  for f in "$work"/matforge/*.json; do
    n=$(basename "$f" .json)
    tmp=$work/out/matforge/tmp
    rm -rf "$tmp"
    "$mf" preview --scene "$f" -o "$tmp" --format exr --device cpu --brdf "$b" >/dev/null
    mv "$tmp/$n.exr" "$work/out/matforge/${n}__mf_$b.exr"
  done
done
rm -rf "$work/out/matforge/tmp"
took[matforge]=$((SECONDS - t0))

log "three.js and Filament (headless Chromium, SwiftShader)"
t0=$SECONDS
nice -n 10 node "$here/render_web.mjs" "$work" "$work/node/node_modules" three filament | grep -v '^log' || true
[ -f "$work/out/web/textured_r050__filament.f32" ] || { echo "web renders failed" >&2; exit 1; }
took[web]=$((SECONDS - t0))

log "Cycles ($spp spp x 2 seeds per reference)"
t0=$SECONDS
"$here/render_cycles.sh" "$work" "$spp"
took[cycles]=$((SECONDS - t0))

log "compare, diagnose"
t0=$SECONDS
$py compare.py "$work" > /dev/null
$py diagnose.py "$work" > /dev/null
took[compare]=$((SECONDS - t0))
{
  echo "matforge_s=${took[matforge]} web_s=${took[web]} cycles_s=${took[cycles]} compare_s=${took[compare]}"
  blender --version 2>/dev/null | head -1
  /usr/bin/chromium --version 2>/dev/null || true
  node --version
} > "$work/timings.txt"
cat "$work/timings.txt"
log "done: $work/results.md, $work/diagnosis.md"
