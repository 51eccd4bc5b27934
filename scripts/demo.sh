#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job on sample_materials/ (four real CC0
# sets, sample_materials/SOURCES.md):
#   ingest (glTF preset)  -> out/<material>/..., out/manifest.json
#   validate              -> out/validate.json (JSON report; text summary on the terminal)
#   preview               -> out/preview/<material>.png and out/contact_sheet.png
#                            (a GPU when there is one, else Mesa's lavapipe on the CPU)
#   report                -> out/report/index.html (one static page: previews, maps, findings)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
out=${1:-$root/out}
"$root/scripts/bootstrap.sh" "$root/build"
mf="$root/build/tools/matforge/matforge"
"$mf" ingest "$root/sample_materials" -o "$out" --preset gltf
"$mf" validate "$root/sample_materials" --report json --report-file "$out/validate.json"
"$mf" validate "$root/sample_materials" --report text | tail -n 1
"$mf" preview "$out/manifest.json" -o "$out/preview" --contact-sheet "$out/contact_sheet.png"
"$mf" report "$out/manifest.json" -o "$out/report" --previews "$out/preview"
echo "demo: outputs + manifest.json, validate.json, preview/, contact_sheet.png and report/index.html in $out"
