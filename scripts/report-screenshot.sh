#!/usr/bin/env bash
# Makes docs/report.png: the sample report (ingest + preview + report of sample_materials) as a
# reader first sees it, 1280x1000, taken by scripts/browser-check.mjs in headless Chromium after
# its checks pass (a failed check leaves docs/report.png as it was and exits 1).
# Usage: scripts/report-screenshot.sh [BUILD_DIR] [OUT_PNG]
# Needs node and /usr/bin/chromium (scripts/bootstrap.sh installs it); previews render on the
# CPU (lavapipe), so no GPU is needed.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)  # absolute: the script runs from a scratch folder
png=${2:-$root/docs/report.png}
bin=${MATFORGE_BIN:-$build/tools/matforge/matforge}
work=$(mktemp -d "${TMPDIR:-/tmp}/matforge-report-shot.XXXXXX")
trap 'rm -rf "$work"' EXIT

# Relative paths from inside $work, and a copy of the sets beside the output: the page shows the
# manifest path as given and the sources relative to it, so no path of this machine is pictured.
cd "$work"
cp -r "$root/sample_materials" sample_materials
"$bin" ingest sample_materials -o out --preset gltf -q
"$bin" preview out/manifest.json -o out/preview --device cpu
"$bin" report out/manifest.json -o report --previews out/preview -q
node "$root/scripts/browser-check.mjs" --page report/index.html --manifest out/manifest.json \
  --width 1280 --height 1000 --screenshot shot.png
mkdir -p "$(dirname "$png")"
cp shot.png "$png"
echo "report-screenshot: wrote $png" >&2
