#!/usr/bin/env bash
# preview_real.sh: `matforge preview` of a library made of real 1K sets (issue 49: the user's
# command at the device's pace), from the PNGs of a `gltf` ingest and from the BC blocks of a
# `vulkan-ktx2` ingest of the same sets, timed as users run it (the whole process).
# Runs where make_library cannot (it links OpenImageIO; the GPU machine has none): the sets are
# the corpus's 1K downloads (tests/data/corpus/real), each copied N times under a new folder name.
#
#   bench/throughput/preview_real.sh MATFORGE [--materials N (100)] [--repeat N (3)]
#        [--device cpu|gpu|auto (gpu)] [--also BIN]... [--lanes "0 1 2 4"] [--jobs "0 12"] [--corpus DIR]
#        [--timings]
#
# --corpus DIR: where the sets below are (default tests/data/corpus/real; those present are used).
# --also BIN: another matforge binary timed alternately with MATFORGE on the same outputs (the
# previous commit's, for a before/after in one run). --lanes, --jobs: MATFORGE's --lanes and --jobs
# values to try (every pair; 0: the command's own choice).
# Prints a Markdown table of every run (wall, CPU user + sys, materials/s) and the medians; checks
# each run wrote one picture a material. --timings: then one more run of MATFORGE and of each
# --also binary from each, with `preview --timings` (where its time went: the device's start, the
# renderers', reading, drawing).
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
# shellcheck source=common.sh
source "$repo/bench/throughput/common.sh"
matforge=${1:?usage: preview_real.sh MATFORGE [--materials N] [--repeat N] [--device D] [--also BIN]... [--lanes "L..."] [--jobs "J..."]}
shift
materials=100 repeat=3 device=gpu lanes=0 jobs=0 timings=0 corpus=$repo/tests/data/corpus/real
also=()
while [[ $# -gt 0 ]]; do
  case $1 in
    --materials) materials=$2; shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    --device) device=$2; shift 2 ;;
    --also) also+=("$2"); shift 2 ;;
    --lanes) lanes=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --corpus) corpus=$2; shift 2 ;;
    --timings) timings=1; shift ;;
    *) echo "preview_real.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
work=$(mktemp -d /tmp/matforge-preview-real.XXXXXX)
trap 'rm -rf "$work"' EXIT

# The corpus's 1K downloads of one material each (ambientCG, Poly Haven, 3dtextures.me).
sources=()
for s in ambientcg_Net004A_1K-JPG ambientcg_OfficeCeiling005_1K-JPG ambientcg_WoodFloor040_1K-JPG \
  polyhaven_brown_planks_09_1k_jpg+webp polyhaven_broken_wall_1k_jpg+webp polyhaven_rubberized_track_1k \
  3dtextures_Crystal_003_SD 3dtextures_Fabric_polyester_003_SD 3dtextures_Metal_Damaged_001_SD \
  3dtextures_Metal_Rusted_010; do
  [[ -d $corpus/$s ]] && sources+=("$s")
done
((${#sources[@]} > 0)) || { echo "preview_real.sh: none of the corpus's 1K sets in $corpus" >&2; exit 1; }
mkdir -p "$work/sets"
for ((i = 0; i < materials; i++)); do
  s=${sources[i % ${#sources[@]}]}
  cp -r "$corpus/$s" "$work/sets/$(printf '%03d' "$i")_$s"
done
for p in gltf vulkan-ktx2; do
  "$matforge" ingest "$work/sets" -o "$work/$p" --preset "$p" --no-cache -q || {
    rc=$?
    ((rc == 1)) || { echo "preview_real.sh: ingest --preset $p failed ($rc)" >&2; exit 1; }  # 1: findings, still written
  }
done
n_listed=$(grep -c '"source"' "$work/gltf/manifest.json" || true)

run() {  # run LABEL BIN FROM ARGS...: one timed preview
  local label=$1 bin=$2 from=$3
  shift 3
  rm -rf "$work/out"
  # bash's own timer (the GPU machine has no /usr/bin/time): wall, user, sys of the child
  local TIMEFORMAT='%R %U %S'
  { time "$bin" preview "$work/$from/manifest.json" -o "$work/out" --device "$device" "$@" >"$work/log" 2>&1; } \
    2>"$work/t" || { cat "$work/log" >&2; exit 1; }
  local n
  n=$(find "$work/out" -maxdepth 1 -name '*.png' | wc -l)
  ((n > 0)) || { echo "preview_real.sh: $label: no pictures" >&2; exit 1; }
  read -r wall user sys < <(tail -n 1 "$work/t")
  echo "$wall" >>"$work/$(echo "$label $from" | tr ' /' '__').wall"
  echo "| $r | $label | \`$from\` | $n | $wall s | $(awk -v u="$user" -v s="$sys" 'BEGIN { printf "%.1f", u + s }') s | $(awk -v n="$n" -v w="$wall" 'BEGIN { printf "%.0f", n / w }') |"
}

echo "$materials sets ($n_listed materials in the manifest), --device $device, $(nproc) cores, $(date -u +%F)"
echo
echo "| round | binary | from | pictures | wall | CPU (user + sys) | materials/s |"
echo "| ---: | --- | --- | ---: | ---: | ---: | ---: |"
for ((r = 1; r <= repeat; r++)); do
  for from in gltf vulkan-ktx2; do
    for b in "${also[@]}"; do run "$(basename "$b")" "$b" "$from"; done
    for l in $lanes; do
      for j in $jobs; do
        label="matforge --lanes $l"
        ((j == 0)) || label+=" -j $j"
        run "$label" "$matforge" "$from" --lanes "$l" --jobs "$j"
      done
    done
  done
done
echo
for f in "$work"/*.wall; do echo "median $(basename "$f" .wall): $(median "$f") s"; done
if ((timings)); then
  for b in "$matforge" "${also[@]}"; do
    for from in gltf vulkan-ktx2; do
      echo
      echo "\`$(basename "$b") preview --timings\` from \`$from\`:"
      rm -rf "$work/out"
      "$b" preview "$work/$from/manifest.json" -o "$work/out" --device "$device" --timings 2>&1 |
        grep -E 'timings:|note: shading| rendered' || true
    done
  done
fi
