#!/usr/bin/env bash
# multi_preset.sh: what `ingest --preset a,b` saves over one run per preset (issue 28, item 1:
# at most 0.8x the time of the separate runs).
#
#   bench/throughput/multi_preset.sh [BUILD_DIR (build)] [--library DIR (tests/data/corpus/real)]
#                                    [--presets "gltf unity-hdrp"] [--jobs N (2)] [--repeat N (3)]
#
# Times, with /usr/bin/time, every run computing (--no-cache) into a fresh folder: each preset
# alone, then all of them in one `--preset a,b` run; --repeat rounds, the runs alternating within
# a round (a drift in the machine's speed hits all alike); each keeps its median wall time.
# Checks that each preset's folder of the one run is byte-identical to its own run's (diff -r),
# and prints a Markdown table: each preset's run with its time over the first preset's (issue 28,
# item 4: `--presets "gltf vulkan-ktx2"`, at most 3x), the separate runs' sum, the one run, and
# their ratio.
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
# shellcheck source=common.sh
source "$repo/bench/throughput/common.sh"
build=build library=$repo/tests/data/corpus/real presets="gltf unity-hdrp" jobs=2 repeat=3
while [[ $# -gt 0 ]]; do
  case $1 in
    --library) library=$2; shift 2 ;;
    --presets) presets=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    -*) echo "usage: multi_preset.sh [BUILD_DIR] [--library DIR] [--presets \"a b\"] [--jobs N] [--repeat N]" >&2; exit 2 ;;
    *) build=$1; shift ;;
  esac
done
[[ $build = /* ]] || build=$repo/$build
matforge=$build/tools/matforge/matforge
[[ -x $matforge ]] || { echo "multi_preset.sh: $matforge not built" >&2; exit 1; }
work=$(mktemp -d /tmp/matforge-multi.XXXXXX)
trap 'rm -rf "$work"' EXIT
read -ra list <<<"$presets"
joined=$(IFS=,; echo "${list[*]}")
find "$library" -type f -exec cat {} + >/dev/null  # a warm page cache for every contender

# wall: `timed NAME OUT ARGS...` appends NAME's wall seconds to $work/NAME.times.
timed() {
  local name=$1 out=$2
  shift 2
  rm -rf "$out"
  /usr/bin/time -f %e -o "$work/t" "$matforge" ingest "$library" -o "$out" -q --no-cache --jobs "$jobs" "$@" || {
    local rc=$?
    ((rc == 1)) || { echo "multi_preset.sh: $name failed ($rc)" >&2; exit 1; }  # 1: findings, still written
  }
  tail -n 1 "$work/t" >>"$work/$name.times"  # (time notes a non-zero exit on a line before)
}
for ((r = 0; r < repeat; r++)); do
  for p in "${list[@]}"; do timed "$p" "$work/alone/$p" --preset "$p"; done
  timed together "$work/together" --preset "$joined"
done
for p in "${list[@]}"; do
  diff -r "$work/alone/$p" "$work/together/$p" >/dev/null || { echo "multi_preset.sh: $p differs between the runs" >&2; exit 1; }
done
sets=$(python3 -c 'import json, sys; print(len(json.load(open(sys.argv[1]))["materials"]))' "$work/together/${list[0]}/manifest.json")
sum=0
first=$(median "$work/${list[0]}.times")
echo "| run | wall (median of $repeat) | × \`${list[0]}\` |"
echo "|---|---|---|"
for p in "${list[@]}"; do
  t=$(median "$work/$p.times")
  sum=$(awk -v a="$sum" -v b="$t" 'BEGIN { print a + b }')
  echo "| \`--preset $p\` | $t s | $(awk -v a="$t" -v b="$first" 'BEGIN { printf "%.2f", a / b }') |"
done
t=$(median "$work/together.times")
echo "| separate runs, sum | $sum s | |"
echo "| \`--preset $joined\` (one run) | $t s | |"
echo "| one run / separate runs | $(awk -v a="$t" -v b="$sum" 'BEGIN { printf "%.2f", a / b }') | |"
echo
echo "$sets sets in $library; --jobs $jobs; $(nproc) cores; every run --no-cache into a fresh folder; each preset's folder of the one run byte-identical to its own run's."
