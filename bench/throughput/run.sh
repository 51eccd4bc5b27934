#!/usr/bin/env bash
# run.sh: matforge's throughput benchmark (the issue: "faster than the oiiotool pipeline, close
# to the I/O floor"). Builds nothing.
#
#   bench/throughput/run.sh [BUILD_DIR (build)] [--quick] [--work DIR] [--results DIR]
#                           [--jobs N (2)] [--peer-jobs "1 2"] [--repeat N (3; --quick: 1)]
#
# 1. make_library writes the library into WORK/lib (full: 40 x 1K, 8 x 2K, 2 x 4K; --quick:
#    4 x 1K, 1 x 2K) and a 4K-only one into WORK/lib4k (full: 4 sets; --quick: 2).
# 2. Times, one after another in this run, with /usr/bin/time (wall, user+sys CPU, max RSS):
#    the floor (OpenImageIO read + write, no processing) plain and --durable (fsync + rename, as
#    matforge writes), `matforge ingest --preset gltf --jobs N`, and oiiotool_peer.sh once per
#    --peer-jobs value (1 = serial as a plain script, 2 = xargs -P2). Then on the 4K library:
#    matforge and the floor, for peak RSS.
#    The floor and matforge run --repeat times, alternating (a drift in the machine's speed hits
#    both alike); each keeps its median-wall run.
# 3. Checks the peer's outputs against matforge's (compare_outputs; 1 code, normals 2).
# 4. Writes RESULTS/results.md and RESULTS/results.csv (default docs/throughput/ for a full
#    run; WORK/ for --quick so a smoke run never overwrites committed figures).
# Every input is read once before timing, so every contender starts from a warm page cache.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=$(cd "$here/../.." && pwd)
invocation="bench/throughput/run.sh${*:+ $*}"

build=build quick=0 work=/tmp/matforge-throughput results="" jobs=2 peer_jobs="1 2" repeat=""
usage() {
  echo "usage: run.sh [BUILD_DIR] [--quick] [--work DIR] [--results DIR] [--jobs N] [--peer-jobs \"1 2\"] [--repeat N]" >&2
  exit 2
}
build_set=0
while [[ $# -gt 0 ]]; do
  case $1 in
    --quick) quick=1; shift ;;
    --work) [[ $# -ge 2 ]] || usage; work=$2; shift 2 ;;
    --results) [[ $# -ge 2 ]] || usage; results=$2; shift 2 ;;
    --jobs) [[ $# -ge 2 && $2 =~ ^[1-9][0-9]*$ ]] || usage; jobs=$2; shift 2 ;;
    --peer-jobs) [[ $# -ge 2 && $2 =~ ^[0-9\ ]*$ ]] || usage; peer_jobs=$2; shift 2 ;;
    --repeat) [[ $# -ge 2 && $2 =~ ^[1-9][0-9]*$ ]] || usage; repeat=$2; shift 2 ;;
    -h|--help) usage ;;
    -*) usage ;;
    *) [[ $build_set == 0 ]] || usage; build=$1; build_set=1; shift ;;
  esac
done
[[ $build = /* ]] || build=$repo/$build
if [[ $quick == 1 ]]; then
  n1=4 n2=1 n4=0 n4rss=2 mode=quick
  : "${results:=$work}" "${repeat:=1}"
else
  n1=40 n2=8 n4=2 n4rss=4 mode=full
  : "${results:=$repo/docs/throughput}" "${repeat:=3}"
fi

matforge=$build/tools/matforge/matforge
tp=$build/bench-throughput
for b in "$matforge" "$tp/make_library" "$tp/floor" "$tp/compare_outputs"; do
  [[ -x $b ]] || { echo "run.sh: $b not built (ninja -C $build matforge make_library floor compare_outputs)" >&2; exit 1; }
done
for t in oiiotool /usr/bin/time; do
  command -v "$t" >/dev/null || { echo "run.sh: $t not found" >&2; exit 1; }
done

log() { echo "run.sh: $*" >&2; }
# The work dir is wiped: only when it is new, empty, or one of ours (marker), never any folder.
if [[ -e $work && ! -e $work/.matforge-throughput && -n $(ls -A "$work" 2>/dev/null) ]]; then
  echo "run.sh: $work exists and is not a work dir of run.sh; choose another --work" >&2; exit 1
fi
rm -rf "$work"
mkdir -p "$work" "$results"
touch "$work/.matforge-throughput"
load_before=$(uptime)
# Load sampled every 5 s while the benchmark runs: the report says how shared the machine was.
( while :; do cut -d' ' -f1 /proc/loadavg; sleep 5; done ) > "$work/load.samples" 2>/dev/null &
sampler=$!
trap 'kill "$sampler" 2>/dev/null || true' EXIT

log "generating the library ($n1 x 1K, $n2 x 2K, $n4 x 4K) and the 4K library ($n4rss x 4K) in $work"
"$tp/make_library" "$work/lib" --1k "$n1" --2k "$n2" --4k "$n4" --jobs "$jobs" >&2
"$tp/make_library" "$work/lib4k" --1k 0 --2k 0 --4k "$n4rss" --jobs "$jobs" >&2
sets=$(($(wc -l < "$work/lib/library.tsv") - 1))
sets4k=$(($(wc -l < "$work/lib4k/library.tsv") - 1))
find "$work/lib" "$work/lib4k" -type f -exec cat {} + > /dev/null  # warm page cache for all

# timed LABEL SETS CMD...: one timed run; appends "label sets wall user sys rss_kb" to $work/times.
: > "$work/times"
timed() {
  local label=$1 n=$2; shift 2
  local rc=0
  log "timing $label: $*"
  /usr/bin/time -f '%e %U %S %M' -o "$work/time.$label" "$@" > "$work/log.$label" 2>&1 || rc=$?
  # matforge exits 1 for findings at error level; the outputs are still written and checked.
  if [[ $rc != 0 && ! ( $label == matforge* && $rc == 1 ) ]]; then
    log "$label failed (exit $rc):"; tail -20 "$work/log.$label" >&2; exit 1
  fi
  [[ $rc == 0 ]] || log "$label exited $rc (findings at error level): see $work/log.$label"
  echo "$label $n $(tail -1 "$work/time.$label")" >> "$work/times"
}

# keep_median LABEL: of the runs labelled LABEL, keep the one with the median wall time.
: > "$work/repeats"
keep_median() {
  local label=$1 n
  awk -v l="$label" '$1 == l' "$work/times" | sort -k3,3n > "$work/runs.$label"
  awk -v l="$label" '$1 != l' "$work/times" > "$work/times.rest"
  mv "$work/times.rest" "$work/times"
  n=$(wc -l < "$work/runs.$label")
  sed -n "$(((n + 1) / 2))p" "$work/runs.$label" >> "$work/times"
  echo "$label: $(cut -d' ' -f3 "$work/runs.$label" | paste -sd' ' -) s" >> "$work/repeats"
}
# floor_and_matforge SUFFIX LIB SETS: the floor and matforge, alternating, --repeat times each.
floor_and_matforge() {
  local sfx=$1 lib=$2 n=$3 r
  for ((r = 1; r <= repeat; r++)); do
    rm -rf "$work/out-floor$sfx" "$work/out-matforge$sfx"
    timed "floor$sfx" "$n" "$tp/floor" "$lib" -o "$work/out-floor$sfx" --jobs "$jobs"
    timed "matforge$sfx" "$n" "$matforge" ingest "$lib/sets" -o "$work/out-matforge$sfx" --preset gltf --jobs "$jobs"
  done
  keep_median "floor$sfx"
  keep_median "matforge$sfx"
}

floor_and_matforge "" "$work/lib" "$sets"
timed floor-durable "$sets" "$tp/floor" "$work/lib" -o "$work/out-floor-durable" --jobs "$jobs" --durable
timed floor-pngdefault "$sets" "$tp/floor" "$work/lib" -o "$work/out-floor-pngdefault" --jobs "$jobs" --png-default
peers=()
for p in $peer_jobs; do
  timed "oiiotool-P$p" "$sets" "$here/oiiotool_peer.sh" "$work/lib" "$work/out-oiiotool-P$p" --jobs "$p"
  peers+=("oiiotool-P$p")
done
# The script with matforge's PNG encoder settings, as many jobs as matforge: what is left of
# the speedup once the encoder choice is taken out of it.
timed "oiiotool-P$jobs-fastpng" "$sets" "$here/oiiotool_peer.sh" "$work/lib" "$work/out-oiiotool-P$jobs-fastpng" \
  --jobs "$jobs" --png-like-matforge
peers+=("oiiotool-P$jobs-fastpng")
floor_and_matforge -4k "$work/lib4k" "$sets4k"
load_after=$(uptime)
kill "$sampler" 2>/dev/null || true
load_stats=$(awk -v cpus="$(nproc)" '
  { s += $1; n++; if (n == 1 || $1 < lo) lo = $1; if ($1 > hi) hi = $1 }
  END { if (!n) { print "no samples"; exit }
        printf "1-min load average over %d samples (every 5 s): min %.2f, mean %.2f, max %.2f on %d CPUs", n, lo, s / n, hi, cpus
        # The benchmark itself keeps about --jobs CPUs busy; more means other work competed.
        if (s / n > cpus + 1) printf "\n- **The machine was shared while measuring**: wall times (and the wall ratios) are inflated and noisy; CPU times are steadier. Re-run on a quiet machine." }' \
  "$work/load.samples")

# Correctness: the peer must have written what matforge wrote.
check_ok=1
: > "$work/compare.txt"
for p in "${peers[@]}"; do
  echo "== matforge vs $p" >> "$work/compare.txt"
  "$tp/compare_outputs" "$work/out-matforge" "$work/out-$p" >> "$work/compare.txt" 2>&1 || check_ok=0
done
cat "$work/compare.txt" >&2

# ---------------------------------------------------------------- report
inputs_desc=$(find "$work/lib/sets" -type f | sed -E 's/.*\.//' | sort | uniq -c | awk '{printf "%s%s %s", sep, $1, $2; sep=", "}')
lib_mb=$(du -sm "$work/lib/sets" | cut -f1)
out_mb=$(du -sm "$work/out-matforge" | cut -f1)
peer_mb=n/a  # --peer-jobs "": the floor and matforge alone
[[ -z ${peer_jobs// /} ]] || peer_mb=$(du -sm "$work/out-oiiotool-P${peer_jobs%% *}" | cut -f1)
cpu_model=$(lscpu | sed -n 's/^Model name:[[:space:]]*//p' | head -1)
mem_gb=$(awk '/MemTotal/ {printf "%.0f", $2 / 1048576}' /proc/meminfo)
oiio_version=$(oiiotool --version 2>/dev/null | head -1)
rev=$(git -C "$repo" rev-parse --short HEAD 2>/dev/null || echo unknown)
[[ -z $(git -C "$repo" status --porcelain 2>/dev/null | head -1) ]] || rev="$rev (with uncommitted changes)"

# CSV, one row per timed run; ratios against the plain floor and the oiiotool script(s).
awk '
  { label[NR] = $1; n[NR] = $2; wall[NR] = $3; user[NR] = $4; sys[NR] = $5; rss[NR] = $6
    w[$1] = $3; c[$1] = $4 + $5 }
  function ratio(a, b) { return b > 0 ? sprintf("%.2f", a / b) : "" }
  END {
    printf "label,sets,wall_s,cpu_s,user_s,sys_s,max_rss_mb,sets_per_s,ratio_vs_floor,ratio_vs_floor_cpu,"
    printf "speedup_vs_oiiotool_serial,speedup_vs_oiiotool_p2,cpu_speedup_vs_oiiotool_serial\n"
    for (i = 1; i <= NR; i++) {
      is4k = label[i] ~ /-4k$/
      fl = is4k ? "floor-4k" : "floor"
      cpu = user[i] + sys[i]
      s1 = is4k ? "" : ratio(w["oiiotool-P1"], wall[i])
      s2 = is4k ? "" : ratio(w["oiiotool-P2"], wall[i])
      sc = is4k ? "" : ratio(c["oiiotool-P1"], cpu)
      printf "%s,%d,%.2f,%.2f,%.2f,%.2f,%.0f,%.2f,%s,%s,%s,%s,%s\n", label[i], n[i], wall[i], cpu, user[i], sys[i],
             rss[i] / 1024, (wall[i] > 0 ? n[i] / wall[i] : 0), ratio(wall[i], w[fl]), ratio(cpu, c[fl]), s1, s2, sc
    }
  }' "$work/times" > "$results/results.csv"

col() { awk -F, -v l="$1" -v c="$2" 'NR == 1 { for (i = 1; i <= NF; i++) h[$i] = i } $1 == l { print $h[c] }' "$results/results.csv"; }
goal() { awk -v v="$1" -v t="$2" -v op="$3" 'BEGIN { ok = (op == ">=") ? v + 0 >= t : v + 0 <= t; print (v == "" ? "n/a" : ok ? "met" : "NOT met") }'; }
speed1=$(col matforge speedup_vs_oiiotool_serial) speed2=$(col matforge speedup_vs_oiiotool_p2)
ratio=$(col matforge ratio_vs_floor) rss4k=$(col matforge-4k max_rss_mb)
floor_speed=$(col floor-pngdefault speedup_vs_oiiotool_serial)
fast_speed=$(col matforge "speedup_vs_oiiotool_p2")
fastpng_wall=$(awk -v l="oiiotool-P$jobs-fastpng" '$1 == l { print $3 }' "$work/times")
mf_wall=$(awk '$1 == "matforge" { print $3 }' "$work/times")
speed_fastpng=$(awk -v a="$fastpng_wall" -v b="$mf_wall" 'BEGIN { if (b > 0) printf "%.2f", a / b }')
ratio_cpu=$(col matforge ratio_vs_floor_cpu) speed_cpu=$(col matforge cpu_speedup_vs_oiiotool_serial)

{
  echo "# Throughput benchmark ($mode run)"
  echo
  echo "Reproduce (from the repository root, after building):"
  echo
  echo '```sh'
  echo "cmake -S . -B build -G Ninja && ninja -C build matforge make_library floor compare_outputs"
  echo "$invocation"
  echo '```'
  echo
  echo "Library: $sets sets ($n1 x 1K, $n2 x 2K, $n4 x 4K), $lib_mb MB of inputs ($inputs_desc);"
  echo "matforge wrote $out_mb MB (the oiiotool script, with oiiotool's default PNG settings, $peer_mb MB)."
  echo "4K library for peak RSS: $sets4k x 4K sets. Generated by"
  echo "\`make_library\` (deterministic); every input read once before timing (warm page cache)."
  echo
  echo "| run | wall s | CPU s | peak RSS MB | sets/s | × floor (wall) | × floor (CPU) | speedup vs oiiotool serial | speedup vs oiiotool -P2 | CPU speedup vs oiiotool |"
  echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
  tail -n +2 "$results/results.csv" | while IFS=, read -r l n wall cpu u s rss sps r rc s1 s2 sc; do
    case $l in
      floor) d="floor: OpenImageIO read + write, no processing (--jobs $jobs)" ;;
      floor-durable) d="floor --durable (write aside + fsync + rename, as matforge)" ;;
      floor-pngdefault) d="floor --png-default (libpng's default PNG settings, as oiiotool: the script's floor)" ;;
      oiiotool-P*-fastpng) d="oiiotool_peer.sh --jobs ${jobs} --png-like-matforge (matforge's PNG settings)" ;;
      matforge) d="\`matforge ingest --preset gltf --jobs $jobs\`" ;;
      oiiotool-P1) d="oiiotool_peer.sh, serial (one oiiotool per map)" ;;
      oiiotool-P*) d="oiiotool_peer.sh --jobs ${l#oiiotool-P} (xargs -P${l#oiiotool-P})" ;;
      matforge-4k) d="4K only: \`matforge ingest --jobs $jobs\`" ;;
      floor-4k) d="4K only: floor --jobs $jobs" ;;
      *) d=$l ;;
    esac
    echo "| $d | $wall | $cpu | $rss | $sps | ${r:-–} | ${rc:-–} | ${s1:-–} | ${s2:-–} | ${sc:-–} |"
  done
  echo
  echo "Goals (2-core machine): ≥ 5× faster than the oiiotool script — serial: ${speed1:-n/a}× ($(goal "$speed1" 5 '>=')),"
  echo "-P2: ${speed2:-n/a}× ($(goal "$speed2" 5 '>=')); ≤ 1.3× the floor: ${ratio}× ($(goal "$ratio" 1.3 '<='));"
  echo "in CPU time (steadier than wall on a loaded machine): ${speed_cpu:-n/a}× less than the serial script, ${ratio_cpu}× the floor's;"
  echo "peak RSS ≤ 1.5 GB (1536 MB) with --jobs $jobs on 4K sets: ${rss4k} MB ($(goal "$rss4k" 1536 '<='))."
  echo
  echo "Where the speedup comes from. Deflate is most of the work: with libpng's default settings"
  echo "(adaptive row filters, zlib level 6, what oiiotool writes) the floor itself is only"
  echo "${floor_speed:-n/a}× faster than the serial script. matforge writes its PNGs with the Paeth filter"
  echo "and zlib's RLE strategy (docs/throughput/png_tradeoff.md: several times faster to encode, files"
  echo "about as small), and its floor rows above use the same settings. Given those same settings,"
  echo "the script at -P$jobs is ${speed_fastpng:-n/a}× slower than matforge: the rest of the speedup is one"
  echo "process instead of one per map, one decode per file and the parallel scheduling."
  echo
  echo "Output check (oiiotool peer vs matforge; tolerance 1 code, normals 2):"
  [[ $check_ok == 1 ]] && echo "**all outputs match**." || echo "**MISMATCH** — see below."
  echo
  echo '```'
  cat "$work/compare.txt"
  echo '```'
  echo
  echo "## Measurement"
  echo
  echo "- Machine: $(nproc) CPUs ($cpu_model), $mem_gb GB RAM; $(uname -sr); $oiio_version; matforge $rev."
  echo "- Load: before \`$load_before\`; after \`$load_after\`."
  echo "- $load_stats"
  echo "- \`/usr/bin/time -f '%e %U %S %M'\`: wall, user + sys CPU (children included), max RSS. For"
  echo "  the oiiotool script, max RSS is that of its largest single process, not the sum of the"
  echo "  processes running at once."
  echo "- The floor and matforge (both libraries) ran $repeat times each, alternating; the table keeps"
  echo "  each one's median-wall run. All walls: $(paste -sd';' "$work/repeats" | sed 's/;/; /g')."
  echo "- × floor is wall (or CPU) time over the plain floor's (4K rows: over the 4K floor). The floor decodes"
  echo "  to native 8/16-bit/half pixels and encodes the same three 8-bit PNGs per set with matforge's"
  echo "  PNG settings (--png-default: libpng's);"
  echo "  matforge also validates every pixel, decodes, converts and renormalizes normals, hashes and"
  echo "  fsyncs (its 8-bit maps stay 8-bit codes otherwise; EXR inputs are read as float)."
  echo "- The peer copies the 8-bit normal codes (oiiotool has no renormalization); matforge"
  echo "  renormalizes, hence the 2-code tolerance for normals."
} > "$results/results.md"

cat "$results/results.md"
log "results in $results/results.md and $results/results.csv"
[[ $check_ok == 1 ]] || { log "output check FAILED"; exit 1; }
