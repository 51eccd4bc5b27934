#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job on sample_materials/:
# ingest (glTF preset) -> out/, validate -> out/validate.json.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
out=${1:-$root/out}
"$root/scripts/bootstrap.sh" "$root/build"
mf="$root/build/tools/matforge/matforge"
"$mf" ingest "$root/sample_materials" -o "$out" --preset gltf
"$mf" validate "$root/sample_materials" --report json --report-file "$out/validate.json"
echo "demo: outputs and manifest in $out, validation report in $out/validate.json"
