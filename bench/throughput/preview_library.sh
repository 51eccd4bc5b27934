#!/usr/bin/env bash
# preview_library.sh: `matforge preview` of a library of 1K materials on lavapipe (issue 28,
# item 5: 100 materials in under 10 s on a 2-core machine), from the PNGs of the default `gltf`
# ingest and from the BC blocks of a `vulkan-ktx2` ingest of the same sets (lavapipe samples
# them as written: nothing decoded, no mip made).
#
#   bench/throughput/preview_library.sh [BUILD_DIR (build)] [--materials N (100)] [--repeat N (3)]
#                                       [--device cpu|gpu|auto (cpu)]
#
# Makes the library (build/bench-throughput/make_library: N sets of 1K maps), ingests it once
# per preset (--no-cache), then times the two previews alternating, --repeat rounds, with
# /usr/bin/time (wall, user + sys); checks each run wrote one picture a material. Prints a
# Markdown table of every run, the medians and the load average.
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
# shellcheck source=common.sh
source "$repo/bench/throughput/common.sh"
build=build materials=100 repeat=3 device=cpu
while [[ $# -gt 0 ]]; do
  case $1 in
    --materials) materials=$2; shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    --device) device=$2; shift 2 ;;
    -*) echo "usage: preview_library.sh [BUILD_DIR] [--materials N] [--repeat N] [--device cpu|gpu|auto]" >&2; exit 2 ;;
    *) build=$1; shift ;;
  esac
done
[[ $build = /* ]] || build=$repo/$build
matforge=$build/tools/matforge/matforge make_library=$build/bench-throughput/make_library
for b in "$matforge" "$make_library"; do [[ -x $b ]] || { echo "preview_library.sh: $b not built" >&2; exit 1; }; done
work=$(mktemp -d /tmp/matforge-preview-library.XXXXXX)
trap 'rm -rf "$work"' EXIT

"$make_library" "$work/lib" --1k "$materials" --2k 0 --4k 0 >/dev/null
for p in gltf vulkan-ktx2; do
  "$matforge" ingest "$work/lib/sets" -o "$work/$p" --preset "$p" --no-cache -q || {
    rc=$?
    ((rc == 1)) || { echo "preview_library.sh: ingest --preset $p failed ($rc)" >&2; exit 1; }  # 1: findings, still written
  }
done

echo "| round | from | wall | CPU (user + sys) | load average (1 min) |"
echo "| ---: | --- | ---: | ---: | ---: |"
for ((r = 1; r <= repeat; r++)); do
  for p in gltf vulkan-ktx2; do
    rm -rf "$work/out"
    /usr/bin/time -f '%e %U %S' -o "$work/t" "$matforge" preview "$work/$p/manifest.json" -o "$work/out" \
      --device "$device" >"$work/log" 2>&1 || { cat "$work/log" >&2; exit 1; }
    n=$(find "$work/out" -maxdepth 1 -name '*.png' ! -name contact_sheet.png | wc -l)
    ((n == materials)) || { echo "preview_library.sh: $p: $n pictures for $materials materials" >&2; exit 1; }
    read -r wall user sys < <(tail -n 1 "$work/t")
    echo "$wall" >>"$work/$p.wall"
    echo "| $r | \`$p\` | $wall s | $(awk -v u="$user" -v s="$sys" 'BEGIN { printf "%.1f", u + s }') s | $(cut -d' ' -f1 /proc/loadavg) |"
  done
done
echo
echo "Medians: from \`gltf\` (PNG) $(median "$work/gltf.wall") s, from \`vulkan-ktx2\` (BC) $(median "$work/vulkan-ktx2.wall") s; $materials materials of 1K, --device $device, $(nproc) cores."
