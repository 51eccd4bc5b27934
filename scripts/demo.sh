#!/usr/bin/env bash
# The main job on sample_materials/ (four real CC0 sets, sample_materials/SOURCES.md), from a
# fresh Debian 12 machine: installs what building and running matforge needs (no test tools),
# builds the matforge binary alone, then
#   ingest (glTF preset)  -> OUT/<material>/..., OUT/manifest.json
#   validate              -> OUT/validate.json (JSON report; its summary line on the terminal)
#   preview               -> OUT/preview/<material>.png and OUT/contact_sheet.png
#                            (a GPU when there is one, else Mesa's lavapipe on the CPU)
#   report                -> OUT/report/index.html (one static page: previews, maps, findings,
#                            each material turned in WebGL2 with --viewer)
# Usage: scripts/demo.sh [OUT]   (default: out/ in the clone, ignored by git). The ingest cache
# goes where it always does (~/.cache/matforge, or $MATFORGE_CACHE), never into the clone.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
out=${1:-$root/out}
t_start=$SECONDS
# shellcheck source=bootstrap.sh
source "$root/scripts/bootstrap.sh"
install_set build
build=$root/build
# A build folder of scripts/test.sh is reused as it is; a new one gets the binary alone, built
# fast (bootstrap.sh configure_release; scripts/test.sh reconfigures it with the tests).
[[ -f $build/CMakeCache.txt ]] || configure_release "$build"
build_quietly "$build" matforge
mf=$build/tools/matforge/matforge

step() {
  local what=$1 t0=$SECONDS
  shift
  echo "demo: $what" >&2
  "$@"
  echo "demo:   done in $((SECONDS - t0)) s" >&2
}
step "ingest sample_materials/ -> ${out/#"$root"\//} (glTF preset)" "$mf" ingest "$root/sample_materials" -o "$out" --preset gltf
step "validate sample_materials/ -> validate.json" \
  "$mf" validate "$root/sample_materials" --report json --report-file "$out/validate.json" --fail-on never
"$mf" validate "$root/sample_materials" --report text --fail-on never | tail -n 1 | sed 's/^/demo:   /' >&2
step "preview every material (Cook-Torrance, look-dev studio) -> preview/, contact_sheet.png" \
  "$mf" preview "$out/manifest.json" -o "$out/preview" --contact-sheet "$out/contact_sheet.png"
step "report -> report/index.html" "$mf" report "$out/manifest.json" -o "$out/report" --previews "$out/preview" --viewer
echo "demo: all done in $((SECONDS - t_start)) s. Open $out/report/index.html in a browser;" \
  "the glTF materials are $out/<material>/<material>.gltf and $out/library.gltf" >&2
