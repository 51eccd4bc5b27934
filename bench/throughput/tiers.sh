#!/usr/bin/env bash
# tiers.sh: what `ingest --tiers 512,1024` saves over one run per tier (issue 48, item 4:
# resolution tiers from one decode).
#
#   bench/throughput/tiers.sh [BUILD_DIR (build)] [--library DIR (tests/data/corpus/real)]
#                             [--preset NAME (gltf)] [--tiers "512 1024"] [--jobs N (2)] [--repeat N (3)]
#
# Times, with /usr/bin/time, every run computing (--no-cache) into a fresh folder: the preset
# alone with each tier's max_size (a preset file: `matforge presets show NAME`, its max_size
# set), then every tier in one `--tiers` run; --repeat rounds, the runs alternating within a
# round (a drift in the machine's speed hits all alike); each keeps its median wall and CPU
# (user + system) time. Checks that each tier's folder of the one run is byte-identical to its
# own run's (diff -r), and prints a Markdown table: each tier alone, the separate runs' sum, the
# one run, and their ratio.
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
# shellcheck source=common.sh
source "$repo/bench/throughput/common.sh"
build=build library=$repo/tests/data/corpus/real preset=gltf tiers="512 1024" jobs=2 repeat=3
while [[ $# -gt 0 ]]; do
  case $1 in
    --library) library=$2; shift 2 ;;
    --preset) preset=$2; shift 2 ;;
    --tiers) tiers=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    -*) echo "usage: tiers.sh [BUILD_DIR] [--library DIR] [--preset NAME] [--tiers \"512 1024\"] [--jobs N] [--repeat N]" >&2; exit 2 ;;
    *) build=$1; shift ;;
  esac
done
[[ $build = /* ]] || build=$repo/$build
matforge=$build/tools/matforge/matforge
[[ -x $matforge ]] || { echo "tiers.sh: $matforge not built" >&2; exit 1; }
work=$(mktemp -d /tmp/matforge-tiers.XXXXXX)
trap 'rm -rf "$work"' EXIT
read -ra list <<<"$tiers"
joined=$(IFS=,; echo "${list[*]}")
for t in "${list[@]}"; do  # the preset at each tier's size, as a user writes it
  "$matforge" presets show "$preset" | python3 -c 'import json, sys; j = json.load(sys.stdin); j["max_size"] = int(sys.argv[1]); json.dump(j, open(sys.argv[2], "w"), indent=2)' "$t" "$work/$preset-$t.json"
done
find "$library" -type f -exec cat {} + >/dev/null  # a warm page cache for every contender

# `timed NAME OUT ARGS...` appends NAME's wall seconds to $work/NAME.times, its CPU seconds
# (user + system) to $work/NAME.cpu.
timed() {
  local name=$1 out=$2
  shift 2
  rm -rf "$out"
  /usr/bin/time -f '%e %U %S' -o "$work/t" "$matforge" ingest "$library" -o "$out" -q --no-cache --jobs "$jobs" "$@" || {
    local rc=$?
    ((rc == 1)) || { echo "tiers.sh: $name failed ($rc)" >&2; exit 1; }  # 1: findings, still written
  }
  tail -n 1 "$work/t" | awk '{ print $1 }' >>"$work/$name.times"  # (time notes a non-zero exit on a line before)
  tail -n 1 "$work/t" | awk '{ print $2 + $3 }' >>"$work/$name.cpu"
}
for ((r = 0; r < repeat; r++)); do
  for t in "${list[@]}"; do timed "$t" "$work/alone/$t" --preset "$work/$preset-$t.json"; done
  timed together "$work/together" --preset "$preset" --tiers "$joined"
done
for t in "${list[@]}"; do
  diff -r "$work/alone/$t" "$work/together/$t" >/dev/null || { echo "tiers.sh: tier $t differs between the runs" >&2; exit 1; }
done
sets=$(python3 -c 'import json, sys; print(len(json.load(open(sys.argv[1]))["materials"]))' "$work/together/${list[0]}/manifest.json")
sum=0 cpu_sum=0
echo "| run | wall (median of $repeat) | CPU, user + system (median) |"
echo "|---|---:|---:|"
for t in "${list[@]}"; do
  w=$(median "$work/$t.times") c=$(median "$work/$t.cpu")
  sum=$(awk -v a="$sum" -v b="$w" 'BEGIN { print a + b }')
  cpu_sum=$(awk -v a="$cpu_sum" -v b="$c" 'BEGIN { print a + b }')
  echo "| \`--preset $preset\`, max_size $t | $w s | $c s |"
done
w=$(median "$work/together.times") c=$(median "$work/together.cpu")
echo "| separate runs, sum | $sum s | $cpu_sum s |"
echo "| \`--preset $preset --tiers $joined\` (one run) | $w s | $c s |"
echo "| one run / separate runs | $(awk -v a="$w" -v b="$sum" 'BEGIN { printf "%.2f", a / b }') | $(awk -v a="$c" -v b="$cpu_sum" 'BEGIN { printf "%.2f", a / b }') |"
echo
echo "$sets sets in $library; --jobs $jobs; $(nproc) cores; load before: $(cut -d' ' -f1-3 /proc/loadavg); every run --no-cache into a fresh folder; each tier's folder of the one run byte-identical to its own run's."
