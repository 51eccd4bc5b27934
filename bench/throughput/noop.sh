#!/usr/bin/env bash
# noop.sh: a re-ingest with nothing to do against the cold run it repeats (issue 28, item 2:
# at most 5 % of cold, start-up included).
#
#   bench/throughput/noop.sh [BUILD_DIR (build)] [--library DIR (tests/data/corpus/real)]
#                            [--preset NAME (gltf)] [--jobs N (2)] [--repeat N (3)]
#
# Each round: a cold ingest (a fresh output folder and a fresh cache: every set decoded,
# validated, encoded and stored), then the same command three times with nothing changed (the
# same folder, the same cache), then once into a new folder from that cache; plus
# `matforge --help` and `--version` (which loads OpenImageIO to name its format libraries).
# Medians of --repeat rounds of /usr/bin/time's wall seconds and peak memory. Checks that every
# re-ingest's manifest is byte-identical to the cold one's and that the no-op loaded no image
# library (glibc's LD_DEBUG=files log).
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
# shellcheck source=common.sh
source "$repo/bench/throughput/common.sh"
build=build library=$repo/tests/data/corpus/real preset=gltf jobs=2 repeat=3
while [[ $# -gt 0 ]]; do
  case $1 in
    --library) library=$2; shift 2 ;;
    --preset) preset=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    -*) echo "usage: noop.sh [BUILD_DIR] [--library DIR] [--preset NAME] [--jobs N] [--repeat N]" >&2; exit 2 ;;
    *) build=$1; shift ;;
  esac
done
[[ $build = /* ]] || build=$repo/$build
matforge=$build/tools/matforge/matforge
[[ -x $matforge ]] || { echo "noop.sh: $matforge not built" >&2; exit 1; }
work=$(mktemp -d /tmp/matforge-noop.XXXXXX)
trap 'rm -rf "$work"' EXIT
find "$library" -type f -exec cat {} + >/dev/null  # a warm page cache for every run

# `timed NAME ARGS...`: appends NAME's wall seconds and peak KB to $work/NAME.{times,kb}.
timed() {
  local name=$1
  shift
  /usr/bin/time -f '%e %M' -o "$work/t" "$matforge" "$@" >"$work/$name.log" 2>&1 || {
    local rc=$?
    ((rc == 1)) || { echo "noop.sh: $name failed ($rc)" >&2; cat "$work/$name.log" >&2; exit 1; }  # 1: findings
  }
  tail -n 1 "$work/t" | awk '{ print $1 }' >>"$work/$name.times"
  tail -n 1 "$work/t" | awk '{ print $2 }' >>"$work/$name.kb"
}
ingest() { timed "$1" ingest "$library" -o "$2" --preset "$preset" --jobs "$jobs" --cache "$work/cache"; }
for ((r = 0; r < repeat; r++)); do
  rm -rf "$work/out" "$work/new" "$work/cache"
  ingest cold "$work/out"
  cp "$work/out/manifest.json" "$work/cold.json"
  for _ in 1 2 3; do ingest noop "$work/out"; done
  cmp -s "$work/out/manifest.json" "$work/cold.json" || { echo "noop.sh: the no-op changed the manifest" >&2; exit 1; }
  ingest newfolder "$work/new"
  cmp -s "$work/new/manifest.json" "$work/cold.json" || { echo "noop.sh: the new folder's manifest differs" >&2; exit 1; }
  timed help --help
  timed version --version
done
LD_DEBUG=files "$matforge" ingest "$library" -o "$work/out" --preset "$preset" --jobs "$jobs" --cache "$work/cache" \
  >"$work/ld.log" 2>&1 || true
if grep -q 'matforge_oiio\|libOpenImageIO' "$work/ld.log"; then echo "noop.sh: the no-op loaded OpenImageIO" >&2; exit 1; fi
grep -q 'restored, 0 computed' "$work/noop.log" || { echo "noop.sh: the no-op computed sets" >&2; cat "$work/noop.log" >&2; exit 1; }

sets=$(python3 -c 'import json, sys; print(len(json.load(open(sys.argv[1]))["materials"]))' "$work/cold.json")
cold=$(median "$work/cold.times")
row() { echo "| $1 | $(median "$work/$2.times") s | $(( $(median "$work/$2.kb") / 1024 )) MB | $(awk -v a="$(median "$work/$2.times")" -v b="$cold" 'BEGIN { printf "%.1f %%", 100 * a / b }') |"; }
echo "| run | wall (median of $repeat) | peak memory | of cold |"
echo "|---|---:|---:|---:|"
row "cold: new folder, new cache" cold
row "nothing changed, the same folder" noop
row "nothing changed, a new folder, the same cache" newfolder
row '`matforge --help`' help
row '`matforge --version` (loads OpenImageIO)' version
echo
echo "$sets sets in $library; --preset $preset --jobs $jobs; $(nproc) cores; manifests byte-identical to the cold run's; the no-op loaded no image library (LD_DEBUG=files)."
