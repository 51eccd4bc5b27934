#!/usr/bin/env bash
# multi_preset.sh: what `ingest --preset a,b` saves over one run per preset (issue 28, item 1:
# at most 0.8x the time of the separate runs, on any library).
#
#   bench/throughput/multi_preset.sh [BUILD_DIR (build)] [--library DIR (tests/data/corpus/real)]
#                                    [--presets "gltf unity-hdrp"] [--jobs N (2)] [--repeat N (3)]
#                                    [--matforge BIN (BUILD_DIR's)] [--noise CORES (0.15)]
#                                    [--tail-library DIR]
#
# --library: any folder of sets. --tail-library: the tail-heavy library, made under DIR once
# (oiiotool, from the corpus): the corpus with five of its sets upscaled to 4K as a vendor's 4K
# download is (7 or 8 maps: 8-bit RGB JPEGs, the normal map a 16-bit RGB PNG, the height a 16-bit
# grey PNG). Each is larger than half the memory budget, so two never run at once; they begin
# first and end last (docs/performance.md, "Several presets in one run"). --matforge: another
# binary (a copy of an earlier build) timed the same way, for a before/after on one machine. --noise: on a machine others use
# too, each run waits (10 minutes at most) until the other processes take under CORES cores, and
# a run during which they took more is run again (3 tries); 0: neither.
#
# Times, with /usr/bin/time, every run computing (--no-cache) into a fresh folder: each preset
# alone, then all of them in one `--preset a,b` run; --repeat rounds, the runs alternating within
# a round (a drift in the machine's speed hits all alike); each keeps its median wall time and
# its median CPU time (user + system: the steadier figure when others share the machine). The
# 1-minute load average before each run and the CPU other processes took during it are noted,
# and their ranges printed: a noisy round shows.
# Checks that each preset's folder of the one run is byte-identical to its own run's (diff -r),
# and prints a Markdown table: each preset's run with its time over the first preset's (issue 28,
# item 4: `--presets "gltf vulkan-ktx2"`, at most 3x), the separate runs' sum, the one run, and
# their ratio, for the wall and the CPU time.
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
# shellcheck source=common.sh
source "$repo/bench/throughput/common.sh"
corpus=$repo/tests/data/corpus/real
build=build library=$corpus presets="gltf unity-hdrp" jobs=2 repeat=3 matforge= noise=0.15 tail_library=
usage='usage: multi_preset.sh [BUILD_DIR] [--library DIR | --tail-library DIR] [--presets "a b"] [--jobs N] [--repeat N] [--matforge BIN] [--noise CORES]'
while [[ $# -gt 0 ]]; do
  case $1 in
    --library) library=$2; shift 2 ;;
    --presets) presets=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    --matforge) matforge=$2; shift 2 ;;
    --noise) noise=$2; shift 2 ;;
    --tail-library) tail_library=$2; shift 2 ;;
    -*) echo "$usage" >&2; exit 2 ;;
    *) build=$1; shift ;;
  esac
done
[[ $build = /* ]] || build=$repo/$build
[[ -n $matforge ]] || matforge=$build/tools/matforge/matforge
[[ -x $matforge ]] || { echo "multi_preset.sh: $matforge not built" >&2; exit 1; }

# make_tail_library DIR: DIR/sets, the tail-heavy library (above), unless made before.
make_tail_library() {
  local dir=$1 set big f name lower to
  [[ -d $corpus ]] || { echo "multi_preset.sh: $corpus: no such folder" >&2; exit 1; }
  [[ -f $dir/made ]] && return
  command -v oiiotool >/dev/null || { echo "multi_preset.sh: oiiotool not found (apt-get install openimageio-tools)" >&2; exit 1; }
  rm -rf "$dir/sets"
  mkdir -p "$dir/sets"
  cp -r "$corpus"/. "$dir/sets/"
  for set in 3dtextures_Fabric_polyester_003_SD 3dtextures_Ground_Wet_002 3dtextures_Metal_Damaged_001_SD \
    ambientcg_OfficeCeiling005_1K-JPG ambientcg_WoodFloor040_1K-JPG; do
    big=$dir/sets/$(sed -e 's/_SD$//' -e 's/1K-JPG$/4K-JPG/' -e '/4K-JPG$/!s/$/_4K/' <<<"$set")
    rm -rf "$dir/sets/$set"
    mkdir -p "$big"
    for f in "$corpus/$set"/*; do
      name=$(basename "$f")
      name=${name/1K-JPG/4K-JPG}
      lower=${name,,}
      to=$big/${name%.*}
      case $lower in
        *.mtlx | *.usdc) ;;  # MaterialX and USD files name the 1K maps
        *normaldx*) oiiotool "$f" --resize 400% --ch 0,1,2 -o "$to.jpg" ;;
        *normal* | *norm.*) oiiotool "$f" --resize 400% --ch 0,1,2 -d uint16 -o "$to.png" ;;
        *height* | *disp*) oiiotool "$f" --resize 400% --ch 0 -d uint16 -o "$to.png" ;;
        *.jpg)  # grey or colour, as RGB
          if (($(oiiotool "$f" --echo '{TOP.nchannels}') < 3)); then oiiotool "$f" --resize 400% --ch 0,0,0 -o "$to.jpg"
          else oiiotool "$f" --resize 400% --ch 0,1,2 -o "$to.jpg"; fi ;;
        *) oiiotool "$f" --resize 400% -o "$big/$name" ;;
      esac
    done
  done
  touch "$dir/made"
}
if [[ -n $tail_library ]]; then
  make_tail_library "$tail_library"
  library=$tail_library/sets
fi
[[ -d $library ]] || { echo "multi_preset.sh: $library: no such folder" >&2; exit 2; }
work=$(mktemp -d /tmp/matforge-multi.XXXXXX)
trap 'rm -rf "$work"' EXIT
read -ra list <<<"$presets"
joined=$(IFS=,; echo "${list[*]}")
find "$library" -type f -exec cat {} + >/dev/null  # a warm page cache for every contender
touch "$work/redone"

# The machine's busy CPU seconds so far (/proc/stat: user, nice, system, irq, softirq).
busy() { awk -v hz="$(getconf CLK_TCK)" '/^cpu / { print ($2 + $3 + $4 + $7 + $8) / hz }' /proc/stat; }
below() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a < b) }'; }
# Waits, 10 minutes at most, until the machine's busy CPU over 2 s is under $noise cores.
settle() {
  local a i
  for ((i = 0; i < 300; i++)); do
    a=$(busy)
    sleep 2
    if below "$(awk -v a="$a" -v b="$(busy)" 'BEGIN { print (b - a) / 2 }')" "$noise"; then return; fi
  done
  return 0  # never quiet: run anyway (the noise is reported)
}
# `timed NAME OUT ARGS...` appends NAME's wall seconds to $work/NAME.times, its CPU seconds (user
# + system) to $work/NAME.cpu, the load average before it to $work/load, and the CPU seconds the
# machine's other processes took meanwhile over its wall time (cores they took) to $work/others;
# runs it again (3 tries) while those were $noise cores or more.
timed() {
  local name=$1 out=$2 before load try wall cpu others
  shift 2
  for ((try = 1; try <= 3; try++)); do
    rm -rf "$out"
    if below 0 "$noise"; then settle; fi
    load=$(cut -d' ' -f1 /proc/loadavg)
    before=$(busy)
    /usr/bin/time -f '%e %U %S' -o "$work/t" "$matforge" ingest "$library" -o "$out" -q --no-cache --jobs "$jobs" "$@" || {
      local rc=$?
      ((rc == 1)) || { echo "multi_preset.sh: $name failed ($rc)" >&2; exit 1; }  # 1: findings, still written
    }
    # (time notes a non-zero exit on a line before)
    read -r wall cpu others < <(tail -n 1 "$work/t" | awk -v before="$before" -v after="$(busy)" \
      '{ print $1, $2 + $3, (after - before - $2 - $3) / $1 }')
    if ! below 0 "$noise" || below "$others" "$noise" || ((try == 3)); then break; fi
    echo "$name" >>"$work/redone"
  done
  echo "$wall" >>"$work/$name.times"
  echo "$cpu" >>"$work/$name.cpu"
  echo "$load" >>"$work/load"
  echo "$others" >>"$work/others"
}
for ((r = 0; r < repeat; r++)); do
  for p in "${list[@]}"; do timed "$p" "$work/alone/$p" --preset "$p"; done
  timed together "$work/together" --preset "$joined"
done
for p in "${list[@]}"; do
  diff -r "$work/alone/$p" "$work/together/$p" >/dev/null || { echo "multi_preset.sh: $p differs between the runs" >&2; exit 1; }
done
sets=$(python3 -c 'import json, sys; print(len(json.load(open(sys.argv[1]))["materials"]))' "$work/together/${list[0]}/manifest.json")
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", a / b }'; }
sum=0 cpu_sum=0
first=$(median "$work/${list[0]}.times")
echo "| run | wall (median of $repeat) | CPU (median) | wall × \`${list[0]}\` |"
echo "|---|---|---|---|"
for p in "${list[@]}"; do
  t=$(median "$work/$p.times") c=$(median "$work/$p.cpu")
  sum=$(awk -v a="$sum" -v b="$t" 'BEGIN { print a + b }')
  cpu_sum=$(awk -v a="$cpu_sum" -v b="$c" 'BEGIN { print a + b }')
  echo "| \`--preset $p\` | $t s | $c s | $(ratio "$t" "$first") |"
done
t=$(median "$work/together.times") c=$(median "$work/together.cpu")
echo "| separate runs, sum | $sum s | $cpu_sum s | |"
echo "| \`--preset $joined\` (one run) | $t s | $c s | |"
echo "| one run / separate runs | $(ratio "$t" "$sum") | $(ratio "$c" "$cpu_sum") | |"
echo
echo "$sets sets in $library; --jobs $jobs; $(nproc) cores; every run --no-cache into a fresh folder; each preset's folder of the one run byte-identical to its own run's."
range() { sort -g "$1" | awk 'NR == 1 { lo = $1 } { hi = $1 } END { printf "%.2f–%.2f", lo, hi }'; }
echo "One run's wall times: $(paste -sd' ' "$work/together.times") s. Noise: 1-minute load average before the runs $(range "$work/load") (this benchmark's own runs included); other processes took $(range "$work/others") cores during the runs; $(wc -l <"$work/redone") runs redone for noise (--noise $noise)."
