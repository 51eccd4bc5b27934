#!/usr/bin/env bash
# run.sh: what the ingest cache (lib/store/cache.hpp) saves. Builds nothing.
#
#   bench/cache/run.sh [BUILD_DIR (build)] [--quick] [--work DIR] [--results DIR] [--tiny N]
#
# 1. make_library writes WORK/lib (full: 40 x 1K + 8 x 2K; --quick: 6 x 1K + 1 x 2K), and WORK/tiny
#    holds N sets of three 64x64 maps (full: 10,000; --quick: 500): the per-set overhead at scale.
# 2. Times `matforge ingest --preset gltf` (wall, /usr/bin/time) on each library:
#      no-cache   --no-cache, the baseline;
#      cold       an empty cache (the cost of storing: hard links, records, digests);
#      warm       the same output folder again, nothing changed (every set restored);
#      one-edit   one map of one set rewritten (that set computed, the rest restored);
#      new-out    a new output folder, the cache shared through $MATFORGE_CACHE (a CI job or a
#                 cluster node restoring another run's results).
#    and checks that every warm manifest is byte-identical to the no-cache one.
# 3. Writes RESULTS/results.md (default docs/cache/ for a full run; WORK/ for --quick).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=$(cd "$here/../.." && pwd)
invocation="bench/cache/run.sh${*:+ $*}"
build=build quick=0 work=/tmp/matforge-cache-bench results="" tiny=""
while [[ $# -gt 0 ]]; do
  case $1 in
    --quick) quick=1; shift ;;
    --work) work=$2; shift 2 ;;
    --results) results=$2; shift 2 ;;
    --tiny) tiny=$2; shift 2 ;;
    -*) echo "usage: run.sh [BUILD_DIR] [--quick] [--work DIR] [--results DIR] [--tiny N]" >&2; exit 2 ;;
    *) build=$1; shift ;;
  esac
done
[[ $build = /* ]] || build=$repo/$build
mf=$build/tools/matforge/matforge
make_library=$build/bench-throughput/make_library
for b in "$mf" "$make_library"; do [[ -x $b ]] || { echo "run.sh: $b not built" >&2; exit 1; }; done
command -v oiiotool >/dev/null || { echo "run.sh: oiiotool missing (openimageio-tools)" >&2; exit 1; }
if ((quick)); then n1=6 n2=1 tiny=${tiny:-500}; results=${results:-$work}; else n1=40 n2=8 tiny=${tiny:-10000}; results=${results:-$repo/docs/cache}; fi
rm -rf "$work" && mkdir -p "$work" "$results"

"$make_library" "$work/lib" --1k "$n1" --2k "$n2" --4k 0 >&2
# The tiny library: one 64x64 set made with oiiotool, copied N times under N names.
seed=$work/tiny-seed
mkdir -p "$seed"
oiiotool --pattern noise:type=uniform 64x64 3 -o "$seed/Tiny_Color.png"
oiiotool --pattern noise:type=uniform 64x64 1 -o "$seed/Tiny_Roughness.png"
oiiotool --pattern constant:color=0.5,0.5,1 64x64 3 -o "$seed/Tiny_NormalGL.png"
mkdir -p "$work/tiny"
for ((i = 0; i < tiny; i++)); do
  d=$work/tiny/Tiny$i
  mkdir "$d"
  for f in "$seed"/*; do b=$(basename "$f"); cp "$f" "$d/Tiny${i}_${b#Tiny_}"; done
done

# time_it LABEL CMD...: wall seconds of one run into $work/t.<label>
secs() { /usr/bin/time -f %e -o "$work/t" "$@" >/dev/null 2>"$work/log" || { cat "$work/log" >&2; exit 1; }; cat "$work/t"; }
declare -A T
for lib in lib tiny; do
  in=$work/$lib
  T[$lib.nocache]=$(secs "$mf" ingest "$in" -o "$work/$lib-nc" --no-cache -q)
  T[$lib.cold]=$(secs "$mf" ingest "$in" -o "$work/$lib-out" -q)
  T[$lib.warm]=$(secs "$mf" ingest "$in" -o "$work/$lib-out" -q)
  cmp "$work/$lib-out/manifest.json" "$work/$lib-nc/manifest.json" || { echo "run.sh: warm manifest differs ($lib)" >&2; exit 1; }
  # One map of one set rewritten: its set only is computed again.
  first=$(find "$in" -mindepth 2 -name '*olor*.png' | sort | sed -n 1p)
  oiiotool "$first" --addc 0.02 -o "$first"
  T[$lib.edit]=$(secs "$mf" ingest "$in" -o "$work/$lib-out" -q)
  T[$lib.newout]=$(MATFORGE_CACHE=$work/$lib-out/.matforge-cache secs "$mf" ingest "$in" -o "$work/$lib-out2" -q)
  # Sibling output folders: the manifests' relative source paths are the same, so are the bytes.
  cmp "$work/$lib-out/manifest.json" "$work/$lib-out2/manifest.json" || { echo "run.sh: restored manifest differs ($lib)" >&2; exit 1; }
  echo "run.sh: $lib: no-cache ${T[$lib.nocache]} s, cold ${T[$lib.cold]} s, warm ${T[$lib.warm]} s, one edit ${T[$lib.edit]} s, new out ${T[$lib.newout]} s" >&2
done

pct() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.1f %%", 100 * a / b }'; }
sets_lib=$(python3 -c 'import json, sys; print(len(json.load(open(sys.argv[1]))["materials"]))' "$work/lib-nc/manifest.json")
{
  echo "# Ingest cache: what it saves"
  echo
  echo "\`$invocation\` on $(nproc) cores, $(date -u +%Y-%m-%d); matforge $("$mf" --version 2>/dev/null | head -1)."
  echo "Wall seconds of \`matforge ingest --preset gltf\`; % of the no-cache run."
  echo
  echo "| library | sets | no cache | cold (storing) | warm (nothing changed) | one map edited | new output folder, shared cache |"
  echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: |"
  for lib in lib tiny; do
    n=$([[ $lib == lib ]] && echo "$sets_lib" || echo "$tiny")
    label=$([[ $lib == lib ]] && echo "${n1} x 1K + ${n2} x 2K" || echo "64x64 x $tiny")
    b=${T[$lib.nocache]}
    echo "| $label | $n | $b | ${T[$lib.cold]} ($(pct "${T[$lib.cold]}" "$b")) | ${T[$lib.warm]} ($(pct "${T[$lib.warm]}" "$b")) | ${T[$lib.edit]} ($(pct "${T[$lib.edit]}" "$b")) | ${T[$lib.newout]} ($(pct "${T[$lib.newout]}" "$b")) |"
  done
  echo
  echo "Checked: the warm manifest is byte-identical to the no-cache run's, and the new output folder's to the one-edit run's."
} > "$results/results.md"
cat "$results/results.md"
