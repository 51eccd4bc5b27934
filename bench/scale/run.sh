#!/usr/bin/env bash
# run.sh: how matforge's cost grows with the library (issue "past one machine", and "zip time is
# quadratic in entries"). Builds nothing; needs the release build (matforge, make_library,
# plot_csv) and oiiotool (openimageio-tools).
#
#   bench/scale/run.sh [BUILD_DIR (build)] [--quick] [--work DIR] [--results DIR]
#
# 1. Libraries of N tiny sets (three 64x64 maps each: color, roughness, GL normal; the files of
#    every set are hard links to one seed set, so making 10,000 of them takes seconds; the
#    names differ, so every set has its own action key and output folder), N = 100, 300, 1000,
#    3000, 10000 (--quick: 20, 100). For each, wall seconds and peak RSS (/usr/bin/time) of:
#      plan      discovery + the action key of every set (every file hashed)
#      cold      ingest --preset gltf with an empty cache (computes and stores every set)
#      warm      the same ingest again, nothing changed (every set restored)
#      one-edit  one map of one set rewritten (that set computed, the rest restored)
#      merge     `matforge merge` of the 4 shard manifests of `ingest --shard I/4` (the shards
#                restore from the shared cache)
#    Checked: the warm manifest is byte-identical to the cold one; the one-edit manifest to a
#    no-cache ingest of the edited library; the merged manifest to the one-edit manifest.
# 2. The throughput benchmark's library (bench/throughput/make_library: 40 x 1K + 8 x 2K +
#    2 x 4K, 50 sets; --quick: 4 x 1K): no-cache, cold, warm and one-edit, with the same checks,
#    against the targets warm <= 5 % of cold and one-edit <= cold / 50 + the warm run (start-up,
#    discovery and hashing, which every run pays).
# 3. Zip archives against folders: E map entries (E/2 sets of two 1x1 PNGs), E = 1,000, 10,000,
#    100,000 (--quick: 200, 2,000), `matforge validate` of the folder tree and of one .zip
#    holding the same files (stored).
# 4. Writes RESULTS/{results.md, scale.csv, zip.csv, time_vs_sets.png, rss_vs_sets.png,
#    zip_vs_folder.png} (default docs/scale/ for a full run; WORK/ for --quick).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=$(cd "$here/../.." && pwd)
invocation="bench/scale/run.sh${*:+ $*}"
build=build quick=0 work=/tmp/matforge-scale-bench results=""
while [[ $# -gt 0 ]]; do
  case $1 in
    --quick) quick=1; shift ;;
    --work) work=$2; shift 2 ;;
    --results) results=$2; shift 2 ;;
    -*) echo "usage: run.sh [BUILD_DIR] [--quick] [--work DIR] [--results DIR]" >&2; exit 2 ;;
    *) build=$1; shift ;;
  esac
done
[[ $build = /* ]] || build=$repo/$build
mf=$build/tools/matforge/matforge
make_library=$build/bench-throughput/make_library
plot=$build/bench-scale/plot_csv
for b in "$mf" "$make_library" "$plot"; do [[ -x $b ]] || { echo "run.sh: $b not built" >&2; exit 1; }; done
command -v oiiotool >/dev/null || { echo "run.sh: oiiotool missing (openimageio-tools)" >&2; exit 1; }
if ((quick)); then
  counts=(20 100) entries=(200 2000) lib_args=(--1k 4 --2k 0 --4k 0) results=${results:-$work}
else
  counts=(100 300 1000 3000 10000) entries=(1000 10000 100000) lib_args=(--1k 40 --2k 8 --4k 2)
  results=${results:-$repo/docs/scale}
fi
rm -rf "$work" && mkdir -p "$work" "$results"
csv=$results/scale.csv zcsv=$results/zip.csv
echo "library,sets,step,seconds,peak_rss_mb" > "$csv"
echo "layout,entries,seconds,peak_rss_mb" > "$zcsv"

# measure FILE CMD...: "<seconds> <peak RSS MB>" of one run; the command's output to $work/log.
measure() {
  /usr/bin/time -f "%e %M" -o "$work/t" "$@" >"$work/log" 2>&1 || { cat "$work/log" >&2; exit 1; }
  awk '{ printf "%s %.1f\n", $1, $2 / 1024 }' "$work/t"
}
same() { cmp -s "$1" "$2" || { echo "run.sh: $1 and $2 differ ($3)" >&2; exit 1; }; }
# record LIBRARY SETS STEP CMD...
record() {
  local lib=$1 n=$2 step=$3
  shift 3
  read -r s m < <(measure "$@")
  echo "$lib,$n,$step,$s,$m" >> "$csv"
  echo "run.sh: $lib ($n sets) $step: $s s, $m MB" >&2
}
# Rewrites one map of one set with new bytes (a new file: hard links to the seed stay intact).
edit_one() {
  local f
  f=$(find "$1" -mindepth 2 -name '*olor*.png' | sort | sed -n 1p)
  oiiotool "$f" --addc 0.02 -o "$work/edited.png"
  rm "$f" && mv "$work/edited.png" "$f"
}

# ---- 1. tiny sets, N of them
seed=$work/seed
mkdir -p "$seed"
oiiotool --pattern noise:type=uniform:seed=1 64x64 3 -o "$seed/Color.png"
oiiotool --pattern noise:type=uniform:seed=2 64x64 1 -o "$seed/Roughness.png"
oiiotool --pattern constant:color=0.5,0.5,1 64x64 3 -o "$seed/NormalGL.png"
ingest_steps() {  # LIBRARY-LABEL SETS IN: the cold / warm / one-edit / merge rows of one library
  local label=$1 n=$2 in=$3 out=$work/out-$1 cache=$work/cache-$1
  record "$label" "$n" cold "$mf" ingest "$in" -o "$out" --cache "$cache" -q
  cp "$out/manifest.json" "$work/cold.json"
  record "$label" "$n" warm "$mf" ingest "$in" -o "$out" --cache "$cache" -q
  same "$out/manifest.json" "$work/cold.json" "$label: warm vs cold"
  edit_one "$in"
  record "$label" "$n" one-edit "$mf" ingest "$in" -o "$out" --cache "$cache" -q
  "$mf" ingest "$in" -o "$work/check-$label" --no-cache -q || true
  same "$out/manifest.json" "$work/check-$label/manifest.json" "$label: one-edit vs no-cache"
  for i in 0 1 2 3; do "$mf" ingest "$in" -o "$work/shards-$label" --cache "$cache" -q --shard "$i/4"; done
  record "$label" "$n" merge "$mf" merge "$work/shards-$label"/manifest.shard-{0,1,2,3}-of-4.json -o "$work/shards-$label/manifest.json"
  # The shards' folder is a sibling of $out: the manifests' relative sources are the same.
  same "$work/shards-$label/manifest.json" "$out/manifest.json" "$label: merged vs one run"
  rm -rf "$out" "$cache" "$work/check-$label" "$work/shards-$label"
}
for n in "${counts[@]}"; do
  in=$work/tiny$n
  # n folders of hard links to the seed maps (one process, not 3n): Tiny<i>/Tiny<i>_<map>.png
  python3 -c '
import os, sys
seed, out, n = sys.argv[1], sys.argv[2], int(sys.argv[3])
maps = sorted(f for f in os.listdir(seed) if f.endswith(".png"))
for i in range(n):
    d = os.path.join(out, f"Tiny{i}")
    os.makedirs(d)
    for m in maps:
        os.link(os.path.join(seed, m), os.path.join(d, f"Tiny{i}_{m}"))
' "$seed" "$in" "$n"
  record tiny "$n" plan "$mf" plan "$in" -o "$work/plan.json"
  ingest_steps tiny "$n" "$in"
  rm -rf "$in"
done

# ---- 2. the throughput library
"$make_library" "$work/lib" "${lib_args[@]}" >&2
in=$work/lib/sets
n=$(find "$in" -mindepth 1 -maxdepth 1 -type d | wc -l)
record throughput "$n" plan "$mf" plan "$in" -o "$work/plan.json"
record throughput "$n" no-cache "$mf" ingest "$in" -o "$work/nc" --no-cache -q
ingest_steps throughput "$n" "$in"

# ---- 3. zip against folders
for e in "${entries[@]}"; do
  z=$work/zip$e
  mkdir -p "$z/folders"
  oiiotool --pattern constant:color=0.4,0.5,0.6 1x1 3 -o "$z/c.png"
  oiiotool --pattern constant:color=0.5 1x1 1 -o "$z/r.png"
  python3 -c '
import os, sys
z, sets = sys.argv[1], int(sys.argv[2])
for s in range(sets):
    d = os.path.join(z, "folders", f"S{s}")
    os.makedirs(d)
    os.link(os.path.join(z, "c.png"), os.path.join(d, f"S{s}_Color.png"))
    os.link(os.path.join(z, "r.png"), os.path.join(d, f"S{s}_Roughness.png"))
' "$z" "$((e / 2))"
  (cd "$z/folders" && python3 -c '
import os, sys, zipfile
with zipfile.ZipFile(sys.argv[1], "w", zipfile.ZIP_STORED) as zf:
    for d in sorted(os.listdir(".")):
        for f in sorted(os.listdir(d)):
            zf.write(os.path.join(d, f))
' "$z/all.zip")
  for layout in folders zip; do
    target=$z/folders
    [[ $layout == zip ]] && target=$z/all.zip
    read -r s m < <(measure "$mf" validate "$target" --report json --report-file "$z/$layout.json" --fail-on never)
    echo "$layout,$e,$s,$m" >> "$zcsv"
    echo "run.sh: $layout, $e entries: $s s, $m MB" >&2
  done
  python3 - "$z/folders.json" "$z/zip.json" "$((e / 2))" <<'EOF'
import json, sys
a, b, n = json.load(open(sys.argv[1])), json.load(open(sys.argv[2])), int(sys.argv[3])
assert len(a["materials"]) == n == len(b["materials"]), (len(a["materials"]), len(b["materials"]), n)
EOF
  rm -rf "$z"
done

# ---- 4. the report
"$plot" "$csv" "$results/time_vs_sets.png" --x sets --y seconds --series step --where library=tiny \
  --title "MATFORGE: WALL TIME VS SETS (64X64 SETS)" --xlabel "SETS" --ylabel "SECONDS"
"$plot" "$csv" "$results/rss_vs_sets.png" --x sets --y peak_rss_mb --series step --where library=tiny \
  --title "MATFORGE: PEAK RSS VS SETS (64X64 SETS)" --xlabel "SETS" --ylabel "PEAK RSS, MB"
"$plot" "$zcsv" "$results/zip_vs_folder.png" --x entries --y seconds --series layout \
  --title "MATFORGE VALIDATE: ZIP VS FOLDERS" --xlabel "MAP ENTRIES" --ylabel "SECONDS"
python3 - "$csv" "$zcsv" "$results/results.md" "$invocation" "$(nproc)" "$("$mf" --version | head -1)" <<'EOF'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
zrows = list(csv.DictReader(open(sys.argv[2])))
out, invocation, cores, version = sys.argv[3], sys.argv[4], sys.argv[5], sys.argv[6]
steps = ["plan", "cold", "warm", "one-edit", "merge"]
def cell(lib, n, step):
    for r in rows:
        if r["library"] == lib and r["sets"] == n and r["step"] == step:
            return float(r["seconds"]), float(r["peak_rss_mb"])
    return None
L = ["# Scale: cost against the number of sets", "",
     f"`{invocation}` on {cores} cores; {version}. Wall seconds / peak RSS (MB) of each command, "
     "from /usr/bin/time; one run each.", "",
     "## Tiny sets (three 64x64 maps each)", "",
     "| sets | " + " | ".join(steps) + " | cold ms/set | warm ms/set |",
     "| ---: | " + " | ".join("---:" for _ in steps) + " | ---: | ---: |"]
counts = sorted({int(r["sets"]) for r in rows if r["library"] == "tiny"})
for n in counts:
    cells = [cell("tiny", str(n), s) for s in steps]
    txt = [f"{c[0]:.2f} s / {c[1]:.0f} MB" if c else "" for c in cells]
    cold, warm = cells[1], cells[2]
    L.append(f"| {n} | " + " | ".join(txt) + f" | {1000 * cold[0] / n:.1f} | {1000 * warm[0] / n:.2f} |")
if len(counts) >= 2:
    lo, hi = str(counts[0]), str(counts[-1])
    L += ["", f"From {lo} to {hi} sets ({int(hi) // int(lo)}x): " + ", ".join(
        f"{s} time x{cell('tiny', hi, s)[0] / max(cell('tiny', lo, s)[0], 1e-3):.1f}, "
        f"peak RSS x{cell('tiny', hi, s)[1] / cell('tiny', lo, s)[1]:.2f}" for s in steps) + "."]
L += ["", "![time](time_vs_sets.png)", "", "![rss](rss_vs_sets.png)", ""]
tn = next(r["sets"] for r in rows if r["library"] == "throughput")
c = {s: cell("throughput", tn, s) for s in ["plan", "no-cache", "cold", "warm", "one-edit", "merge"]}
L += ["## The throughput library", "",
      f"bench/throughput/make_library's library ({tn} sets of 1K/2K/4K PNG, JPEG and EXR maps).", "",
      "| step | seconds | peak RSS (MB) | % of the cold run |", "| --- | ---: | ---: | ---: |"]
for s, v in c.items():
    L.append(f"| {s} | {v[0]:.2f} | {v[1]:.0f} | {100 * v[0] / c['cold'][0]:.1f} % |")
warm_ok = c["warm"][0] <= 0.05 * c["cold"][0]
edit_bound = c["cold"][0] / int(tn) + c["warm"][0]
edit_ok = c["one-edit"][0] <= edit_bound
L += ["", f"- warm re-ingest: {c['warm'][0]:.2f} s = {100 * c['warm'][0] / c['cold'][0]:.1f} % of the cold "
      f"{c['cold'][0]:.2f} s (target <= 5 %: {'met' if warm_ok else 'NOT met'}).",
      f"- one set changed: {c['one-edit'][0]:.2f} s; target cold / {tn} + the warm run's fixed cost = "
      f"{edit_bound:.2f} s: {'met' if edit_ok else 'NOT met'}.",
      "- every result byte-identical: warm = cold manifest; one-edit = a no-cache run of the edited "
      "library; the merge of 4 shards = one run.", ""]
L += ["## Zip archives against folders (`matforge validate`)", "",
      "| map entries | folders | one .zip | zip / folders |", "| ---: | ---: | ---: | ---: |"]
for e in sorted({int(r["entries"]) for r in zrows}):
    f = next(r for r in zrows if r["layout"] == "folders" and int(r["entries"]) == e)
    z = next(r for r in zrows if r["layout"] == "zip" and int(r["entries"]) == e)
    L.append(f"| {e} | {float(f['seconds']):.2f} s / {float(f['peak_rss_mb']):.0f} MB | "
             f"{float(z['seconds']):.2f} s / {float(z['peak_rss_mb']):.0f} MB | {float(z['seconds']) / max(float(f['seconds']), 1e-3):.2f} |")
L += ["", "![zip](zip_vs_folder.png)", ""]
open(out, "w").write("\n".join(L))
EOF
cat "$results/results.md"
