#!/usr/bin/env bash
# report_corpus.sh: what a new user waits for on the real corpus, step by step (issue: `report`
# was the slowest step, 20.5 s against 7.6 s for the ingest that wrote its manifest and 12.1 s
# for the previews; it should cost no more than the ingest).
#
#   bench/throughput/report_corpus.sh [BUILD_DIR (build)] [--repeat N (3)] [--device cpu|gpu|auto (cpu)]
#                                     [--matforge BIN (BUILD_DIR's)] [--corpus DIR (tests/data/corpus/real)]
#
# Each round, on the corpus: `ingest -o OUT --no-cache`, `preview OUT/manifest.json
# --device cpu`, `report OUT/manifest.json --previews PREV`, each timed with /usr/bin/time (wall,
# user + sys) into fresh folders; checks that the preview wrote one picture a material and the
# report its page. Prints a Markdown table of every run, the medians, the report over the ingest
# and the load average before each run (other work on the machine shows in it: compare the CPU
# column when it is high). --matforge times another build of matforge (a before/after pair).
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
# shellcheck source=common.sh
source "$repo/bench/throughput/common.sh"
build=build repeat=3 device=cpu matforge= corpus=$repo/tests/data/corpus/real
while [[ $# -gt 0 ]]; do
  case $1 in
    --repeat) repeat=$2; shift 2 ;;
    --device) device=$2; shift 2 ;;
    --matforge) matforge=$2; shift 2 ;;
    --corpus) corpus=$2; shift 2 ;;
    -*) echo "usage: report_corpus.sh [BUILD_DIR] [--repeat N] [--device cpu|gpu|auto] [--matforge BIN] [--corpus DIR]" >&2; exit 2 ;;
    *) build=$1; shift ;;
  esac
done
[[ $build = /* ]] || build=$repo/$build
[[ -n $matforge ]] || matforge=$build/tools/matforge/matforge
[[ -x $matforge ]] || { echo "report_corpus.sh: $matforge not built" >&2; exit 1; }
[[ -d $corpus ]] || { echo "report_corpus.sh: $corpus: no such folder" >&2; exit 1; }
work=$(mktemp -d /tmp/matforge-report-corpus.XXXXXX)
trap 'rm -rf "$work"' EXIT

# step NAME ROUND COMMAND...: runs COMMAND timed, appends its wall and CPU to NAME's files and
# prints the table row. Exit 1 is findings (the run still wrote everything); any other failure stops.
step() {
  local name=$1 round=$2 load rc=0
  shift 2
  load=$(cut -d' ' -f1 /proc/loadavg)
  /usr/bin/time -f '%e %U %S' -o "$work/t" "$@" >"$work/log" 2>&1 || rc=$?
  ((rc <= 1)) || { cat "$work/log" >&2; echo "report_corpus.sh: $name failed ($rc)" >&2; exit 1; }
  local wall user sys cpu
  read -r wall user sys < <(tail -n 1 "$work/t")
  cpu=$(awk -v u="$user" -v s="$sys" 'BEGIN { printf "%.2f", u + s }')
  echo "$wall" >>"$work/$name.wall"
  echo "$cpu" >>"$work/$name.cpu"
  echo "| $round | \`$name\` | $wall s | $cpu s | $load |"
}

echo "| round | step | wall | CPU (user + sys) | load average (1 min) |"
echo "| ---: | --- | ---: | ---: | ---: |"
for ((r = 1; r <= repeat; r++)); do
  rm -rf "$work/out" "$work/prev" "$work/rep"
  step ingest "$r" "$matforge" ingest "$corpus" -o "$work/out" --no-cache -q
  step preview "$r" "$matforge" preview "$work/out/manifest.json" -o "$work/prev" --device "$device"
  step report "$r" "$matforge" report "$work/out/manifest.json" -o "$work/rep" --previews "$work/prev" -q
  materials=$(python3 -c 'import json, sys; print(len(json.load(open(sys.argv[1]))["materials"]))' "$work/out/manifest.json")
  n=$(find "$work/prev" -maxdepth 1 -name '*.png' ! -name contact_sheet.png | wc -l)
  ((n == materials)) || { echo "report_corpus.sh: $n previews for $materials materials" >&2; exit 1; }
  [[ -s $work/rep/index.html ]] || { echo "report_corpus.sh: no index.html" >&2; exit 1; }
done
echo
ingest=$(median "$work/ingest.wall") report=$(median "$work/report.wall")
echo "Medians ($materials materials, $(nproc) cores, preview --device $device): ingest $ingest s wall," \
  "$(median "$work/ingest.cpu") s CPU; preview $(median "$work/preview.wall") s, $(median "$work/preview.cpu") s;" \
  "report $report s, $(median "$work/report.cpu") s. Report over ingest: $(awk -v a="$report" -v b="$ingest" \
  'BEGIN { printf "%.2f", a / b }')× wall, $(awk -v a="$(median "$work/report.cpu")" -v b="$(median "$work/ingest.cpu")" \
  'BEGIN { printf "%.2f", a / b }')× CPU."
