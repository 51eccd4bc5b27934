#!/usr/bin/env bash
# run.sh: GPU block compression — time and error per format and effort for 1K/2K/4K maps,
# matforge's encoders (libsquish for BCn, ARM's astcenc library for ASTC: lib/texture) beside the
# command-line tools a studio would script, on the same inputs in one run: NVIDIA's `nvcompress`
# (NVIDIA Texture Tools 2.0.8, package libnvtt-bin; CPU, no CUDA here) and ARM's `astcenc` 4.2
# (package astcenc). Builds nothing.
#
#   bench/texture/run.sh [BUILD_DIR (build)] [--quick] [--work DIR] [--results DIR]
#
# Inputs: bench/throughput/make_library's smooth-noise maps (albedo, GL normal, roughness) at
# 1K, 2K and 4K (--quick: 1K), and `photo`: 1K photographs of the corpus (tests/data/corpus:
# Poly Haven's brown_planks_09 albedo, GL normal and the roughness of its ARM map, and
# broken_wall's ARM map whole as a BC1 `orm`, the vulkan-ktx2 preset's layout), where encoders
# meet far more distinct colours per block; all converted to 8-bit PNG once so every tool reads
# the same file. BC1 is also timed on one thread (`matforge 1t`), beside nvcompress's one.
# A last table: zstd's levels (the `zstd` CLI's benchmark, one thread) on matforge's BC files
# of the photographs, the size and time a KTX2 preset's `zstd_level` trades.
# Time per map: for the peers, the wall time of one process per file (/usr/bin/time: start-up,
# reading the PNG, encoding level 0, writing the file), what a script pays per file; for
# matforge, the time from reading the PNG to the file written inside one process (texture_bench
# prints it), what `ingest` pays per map (its start-up, ~0.3 s for OpenImageIO's plugins, comes
# once per run); matforge's process wall time is in the CSV too. Threads: matforge and astcenc
# use every core; nvcompress 2.0.8's CPU compressor uses one. Error: each output decoded back by
# a decoder other than the encoder where one exists (OpenImageIO's DDS reader for nvcompress's
# files, `astcenc -d` for astcenc's, texture_bench decode for matforge's) and compared with the
# PNG by one measure (texture_bench psnr): PSNR over the channels the format stores; for normals
# X, Y and the mean angle to the source's unit vector in degrees. nvcompress 2.0.8 encodes BC4
# from the alpha channel, so it is given the roughness map in R, G, B and A.
# Writes RESULTS/results.md and results.csv (default docs/texture/ for a full run; WORK/ for
# --quick).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=$(cd "$here/../.." && pwd)
invocation="bench/texture/run.sh${*:+ $*}"
build=build quick=0 work=/tmp/matforge-texture-bench results=""
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
tb=$build/bench-texture/texture_bench
make_library=$build/bench-throughput/make_library
for b in "$tb" "$make_library"; do [[ -x $b ]] || { echo "run.sh: $b not built" >&2; exit 1; }; done
for t in nvcompress nvdecompress astcenc oiiotool zstd; do
  command -v "$t" >/dev/null || { echo "run.sh: $t missing (Debian: apt-get install --no-install-recommends libnvtt-bin astcenc openimageio-tools)" >&2; exit 1; }
done
if ((quick)); then sizes=(1k photo); results=${results:-$work}; else sizes=(1k 2k 4k photo); results=${results:-$repo/docs/texture}; fi
rm -rf "$work" && mkdir -p "$work" "$results"
csv=$results/results.csv
echo "size,map,format,tool,effort,seconds,process_seconds,psnr_db,angle_deg,bytes" > "$csv"

# ---- inputs: one set per size, its albedo, normal and roughness as 8-bit PNG
corpus=$repo/tests/data/corpus/real
mkdir -p "$work/in/photo"
planks=$corpus/polyhaven_brown_planks_09_1k_jpg+webp/brown_planks_09
oiiotool "${planks}_diff_1k.jpg" --ch R,G,B -d uint8 -o "$work/in/photo/albedo.png"
oiiotool "${planks}_nor_gl_1k.jpg" --ch R,G,B -d uint8 -o "$work/in/photo/normal.png"
oiiotool "${planks}_arm_1k.jpg" --ch 1 -d uint8 -o "$work/in/photo/roughness.png"
oiiotool "$work/in/photo/roughness.png" --ch 0,0,0,0 -o "$work/in/photo/roughness-rgba.png"
oiiotool "$corpus/polyhaven_broken_wall_1k_jpg+webp/broken_wall_arm_1k.jpg" --ch R,G,B -d uint8 -o "$work/in/photo/orm.png"
for s in "${sizes[@]}"; do
  [[ $s == photo ]] && continue
  args=(--1k 0 --2k 0 --4k 0)
  case $s in 1k) args[1]=1 ;; 2k) args[3]=1 ;; 4k) args[5]=1 ;; esac
  "$make_library" "$work/lib-$s" "${args[@]}" >&2
  set_dir=$(find "$work/lib-$s/sets" -mindepth 1 -maxdepth 1 -type d | head -1)
  pick() { find "$set_dir" -maxdepth 1 -iname "*$1*" | grep -viE 'dx|preview' | sort | head -1; }
  mkdir -p "$work/in/$s"
  oiiotool "$(pick color)" --ch R,G,B -d uint8 -o "$work/in/$s/albedo.png"
  oiiotool "$(pick normalgl)" --ch R,G,B -d uint8 -o "$work/in/$s/normal.png"
  oiiotool "$(pick roughness)" --ch 0 -d uint8 -o "$work/in/$s/roughness.png"
  # NVTT 2.0.8 encodes BC4 from the alpha channel: nvcompress gets the map in R, G, B and A.
  oiiotool "$work/in/$s/roughness.png" --ch 0,0,0,0 -o "$work/in/$s/roughness-rgba.png"
done

# time_of CMD...: wall seconds of one run (its output to $work/log)
time_of() {
  /usr/bin/time -f %e -o "$work/t" "$@" >"$work/log" 2>&1 || { cat "$work/log" >&2; return 1; }
  cat "$work/t"
}
# row SIZE MAP FORMAT TOOL EFFORT SECONDS PROCESS_SECONDS DECODED CHANNELS OUTFILE
row() {
  local q angle=""
  q=$("$tb" psnr "$work/in/$1/$2.png" "$8" "$9")
  [[ $9 == 2 ]] && angle=${q#* }
  echo "$1,$2,$3,$4,$5,$6,$7,${q%% *},$angle,$(stat -c %s "${10}")" >> "$csv"
  echo "run.sh: $1 $2 $3 $4 $5: $6 s (process $7 s), ${q} ($(stat -c %s "${10}") bytes)" >&2
}

o=$work/out
mkdir -p "$o"
for s in "${sizes[@]}"; do
  in=$work/in/$s
  # name map format channels matforge-flags nvcompress-flags astcenc-block astcenc-mode
  while read -r map format ch mflags nvflags block amode; do
    [[ -f $in/$map.png ]] || continue
    [[ $mflags == - ]] && mflags=""
    ext=dds
    [[ $format == astc* ]] && ext=ktx2
    for effort in fast normal thorough; do
      f=$o/$s-$map-$format-mf-$effort
      # shellcheck disable=SC2086
      t=$(time_of "$tb" encode "$in/$map.png" "$f.$ext" "$format" "$effort" $mflags --threads "$(nproc)")
      inside=$(cat "$work/log")
      "$tb" decode "$f.$ext" "$f.png"
      row "$s" "$map" "$format" matforge "$effort" "$inside" "$t" "$f.png" "$ch" "$f.$ext"
      [[ $format == bc1 ]] || continue
      # shellcheck disable=SC2086
      t=$(time_of "$tb" encode "$in/$map.png" "$f-1t.$ext" "$format" "$effort" $mflags --threads 1)
      inside=$(cat "$work/log")
      "$tb" decode "$f-1t.$ext" "$f-1t.png"
      row "$s" "$map" "$format" "matforge 1t" "$effort" "$inside" "$t" "$f-1t.png" "$ch" "$f-1t.$ext"
    done
    if [[ $nvflags != - ]]; then
      for effort in fast normal; do
        f=$o/$s-$map-$format-nv-$effort
        fast=""
        [[ $effort == fast ]] && fast=-fast
        nvin=$in/$map.png
        [[ $format == bc4 ]] && nvin=$in/$map-rgba.png
        # shellcheck disable=SC2086  # nvflags: several flags, split on purpose
        t=$(time_of nvcompress -nocuda -nomips -repeat $fast ${nvflags//,/ } "$nvin" "$f.dds")
        oiiotool "$f.dds" -d uint8 -o "$f.png"  # OpenImageIO's DDS reader (nvdecompress 2.0.8 misreads BC4)
        row "$s" "$map" "$format" nvcompress "$effort" "$t" "$t" "$f.png" "$ch" "$f.dds"
      done
    fi
    if [[ $block != - ]]; then
      for effort in fast medium thorough; do
        f=$o/$s-$map-$format-astc-$effort
        # As matforge's vulkan-ktx2-astc preset stores a normal: X, Y, Z in RGB (no -normal swizzle).
        t=$(time_of astcenc "-c$amode" "$in/$map.png" "$f.astc" "$block" "-$effort" -silent)
        astcenc "-d$amode" "$f.astc" "$f.png" -silent >/dev/null
        e=$effort
        [[ $e == medium ]] && e=normal
        row "$s" "$map" "$format" astcenc "$e" "$t" "$t" "$f.png" "$ch" "$f.astc"
      done
    fi
  done <<'EOF'
albedo bc1 3 --srgb -bc1 - -
orm bc1 3 - -bc1 - -
roughness bc4 1 - -bc4 - -
normal bc5 2 --normal -bc5,-normal - -
albedo astc-6x6 3 --srgb - 6x6 s
normal astc-4x4 2 --normal - 4x4 l
EOF
done

# zstd's levels on the photographs' BC files (matforge, normal effort), one stream.
zcsv=$results/zstd_levels.csv
echo "level,bytes_in,bytes_out,ratio,compress_mb_s" > "$zcsv"
cat "$o"/photo-*-bc[145]-mf-normal.dds > "$work/bc.bin"
for level in 1 3 6 9 12 15 17 19; do
  zstd -b"$level" -T1 -i2 "$work/bc.bin" 2>&1 | tr '\r' '\n' | grep 'MB/s' | tail -1 |
    sed -E 's/.*: *([0-9]+) -> *([0-9]+) \(x?([0-9.]+)\), *([0-9.]+) MB\/s.*/\1,\2,\3,\4/' |
    sed "s/^/$level,/" >> "$zcsv"
done

python3 - "$csv" "$results/results.md" "$invocation" "$(nproc)" "$zcsv" <<'EOF'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
out, invocation, cores = sys.argv[2], sys.argv[3], sys.argv[4]
L = ["# GPU block compression: matforge against nvcompress and astcenc", "",
     f"`{invocation}` on {cores} cores. Seconds per map: for nvcompress and astcenc the wall time "
     "of one process per file (start-up, read the 8-bit PNG, encode level 0, write the file), what "
     "a script running them per file pays; for matforge the time from reading the PNG to the file "
     "written inside its process, what `ingest` pays per map (its start-up, about 0.3 s, comes once "
     "per run; the process wall time is the CSV's process_seconds). Threads: matforge and astcenc "
     "use every core, nvcompress 2.0.8 (CPU, -nocuda) one. Error of the decoded level 0 against "
     "the PNG: PSNR over the channels the format stores (normals: X and Y, with the mean angle "
     "between unit vectors). NVTT 2.0.8 has no effort level between `-fast` and its default; "
     "astcenc's medium is listed as normal; matforge's is its `effort` preset field.", ""]
keyf = lambda r: (r["size"], r["map"], r["format"])
groups = []
for r in rows:
    if keyf(r) not in groups: groups.append(keyf(r))
L += ["| size | map | format | tool | effort | s per map | process s | PSNR dB | mean angle ° | bytes |",
      "| --- | --- | --- | --- | --- | ---: | ---: | ---: | ---: | ---: |"]
for g in groups:
    for r in rows:
        if keyf(r) == g:
            L.append(f"| {r['size']} | {r['map']} | {r['format']} | {r['tool']} | {r['effort']} | {float(r['seconds']):.3f} | {float(r['process_seconds']):.2f} | "
                     f"{float(r['psnr_db']):.2f} | {r['angle_deg'] or ''} | {r['bytes']} |")
L += ["", "## matforge against the peer at the same effort", "",
      "| size | map | format | effort | peer | matforge s / peer s | matforge dB − peer dB |",
      "| --- | --- | --- | --- | --- | ---: | ---: |"]
for g in groups:
    mf = {r["effort"]: r for r in rows if keyf(r) == g and r["tool"] == "matforge"}
    for r in rows:
        if keyf(r) == g and not r["tool"].startswith("matforge") and r["effort"] in mf:
            m = mf[r["effort"]]
            L.append(f"| {g[0]} | {g[1]} | {g[2]} | {r['effort']} | {r['tool']} | "
                     f"{float(m['seconds']) / max(float(r['seconds']), 1e-3):.2f} | {float(m['psnr_db']) - float(r['psnr_db']):+.2f} |")
z = list(csv.DictReader(open(sys.argv[5])))
L += ["", "## zstd level", "",
      "The KTX2 presets' `zstd_level` on the photographs' BC1, BC4 and BC5 files above (`zstd -bN -T1`, "
      "one stream; matforge compresses each mip level apart).", "",
      "| level | bytes in | bytes out | ratio | MB/s compressing | bytes against level 19 |",
      "| ---: | ---: | ---: | ---: | ---: | ---: |"]
last = float(z[-1]["bytes_out"]) if z else 1.0
for r in z:
    L.append(f"| {r['level']} | {r['bytes_in']} | {r['bytes_out']} | {r['ratio']} | {r['compress_mb_s']} | "
             f"{(float(r['bytes_out']) / last - 1) * 100:+.1f} % |")
open(out, "w").write("\n".join(L) + "\n")
EOF
cat "$results/results.md"
