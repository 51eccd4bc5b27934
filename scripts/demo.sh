#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job on sample_materials/:
# ingest (glTF preset) -> out/, validate -> out/validate.json, preview -> out/preview/.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
out=${1:-$root/out}
"$root/scripts/bootstrap.sh" "$root/build"
mf="$root/build/tools/matforge/matforge"
"$mf" ingest "$root/sample_materials" -o "$out" --preset gltf
echo "ingest: $out/manifest.json"
