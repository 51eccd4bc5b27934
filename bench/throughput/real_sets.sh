#!/usr/bin/env bash
# real_sets.sh: matforge against the studio script on real vendor downloads (issue 28, item 3:
# glTF and Unity HDRP outputs together, as the script writes them in one pass a set).
#
#   bench/throughput/real_sets.sh [BUILD_DIR (build)] [--jobs N (2)] [--repeat N (3)]
#
# The library is the repository's corpus of real CC0 sets (tests/data/corpus/real: ambientCG,
# Poly Haven, 3dtextures.me and hand-named folders, JPEG maps with PNG heights). The script's
# set list (library.tsv, as make_library writes it) comes from tests/data/corpus/truth.json's
# roles, never from matforge: a JPEG map before a WebP copy, the GL normal map where a set has
# both, an ARM map where there is one. The script (oiiotool_peer.sh --unity-hdrp) writes the
# base colour, the GL normal map, glTF's ORM and HDRP's mask map, one oiiotool process per
# output; matforge runs `ingest --preset gltf,unity-hdrp --no-cache` (both presets' full output
# folders: also opacity, heights, material files, manifests, every check). Both at --jobs N
# (the script through xargs -P), alternating, median of --repeat rounds of wall time, each run
# after a sync. MATFORGE_BENCH_RAW=1 prints every round's two times (script, matforge) on stderr.
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
# shellcheck source=common.sh
source "$repo/bench/throughput/common.sh"
build=build jobs=2 repeat=3
while [[ $# -gt 0 ]]; do
  case $1 in
    --jobs) jobs=$2; shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    -*) echo "usage: real_sets.sh [BUILD_DIR] [--jobs N] [--repeat N]" >&2; exit 2 ;;
    *) build=$1; shift ;;
  esac
done
[[ $build = /* ]] || build=$repo/$build
matforge=$build/tools/matforge/matforge
[[ -x $matforge ]] || { echo "real_sets.sh: $matforge not built" >&2; exit 1; }
corpus=$repo/tests/data/corpus
work=$(mktemp -d /tmp/matforge-real-sets.XXXXXX)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/lib"
ln -s "$corpus/real" "$work/lib/sets"
python3 - "$corpus/truth.json" "$work/lib/library.tsv" <<'PY'
import json, sys
truth = json.load(open(sys.argv[1]))
rows = []
def pick(files, role, pred=lambda f, v: True):
    c = [f for f, v in files.items() if v.get("role") == role and pred(f, v)]
    c.sort(key=lambda f: (f.endswith(".webp"), f))  # the JPEG before its WebP copy
    return c[0] if c else "-"
for s in truth["sets"]:
    folder = s["folder"].split("/", 1)[1]
    groups = {}
    for f, v in s["files"].items():
        # One folder holds two sets: each file's set is its name before the role word.
        key = f.rsplit("_", 1)[0] if folder.startswith("flat_folder") else folder
        groups.setdefault(key, {})[f] = v
    for key, files in sorted(groups.items()):
        albedo = pick(files, "albedo")
        if albedo == "-":
            continue
        gl = pick(files, "normal", lambda f, v: v.get("normal_convention") == "gl")
        normal = gl if gl != "-" else pick(files, "normal")
        conv = files[normal].get("normal_convention", "gl") if normal != "-" else "gl"
        size = files[albedo]["pixels"].split("x")[0]
        name = key.replace("/", "_")
        rows.append([name, folder, size, albedo, normal, conv, pick(files, "ao"), pick(files, "roughness"),
                     pick(files, "metalness"), pick(files, "packed"), pick(files, "height")])
with open(sys.argv[2], "w") as o:
    o.write("name\tdir\tsize\talbedo\tnormal\tnormal_convention\tocclusion\troughness\tmetalness\tarm\theight\n")
    for r in rows:
        o.write("\t".join(r) + "\n")
PY
find "$corpus/real" -type f -exec cat {} + >/dev/null  # a warm page cache for both

for ((r = 0; r < repeat; r++)); do
  rm -rf "$work/peer" "$work/mf"
  # Each timed run starts with nothing of the other's left to write back: on two cores the
  # kernel's writeback of one run's files would otherwise be charged to the next.
  sync
  /usr/bin/time -f %e -o "$work/t" "$repo/bench/throughput/oiiotool_peer.sh" "$work/lib" "$work/peer" --jobs "$jobs" --unity-hdrp
  tail -n 1 "$work/t" >>"$work/peer.times"
  sync
  /usr/bin/time -f %e -o "$work/t" "$matforge" ingest "$corpus/real" -o "$work/mf" --preset gltf,unity-hdrp --no-cache \
    --jobs "$jobs" -q || (($? == 1))  # 1: the corpus's real errors are findings; outputs are written
  tail -n 1 "$work/t" >>"$work/mf.times"
done
[[ -z ${MATFORGE_BENCH_RAW:-} ]] || paste "$work/peer.times" "$work/mf.times" >&2
sets=$(($(wc -l <"$work/lib/library.tsv") - 1))
peer_files=$(find "$work/peer" -name '*.png' | wc -l)
mf_files=$(find "$work/mf" -type f | wc -l)
mf_sets=$(python3 -c 'import json, sys; print(len(json.load(open(sys.argv[1]))["materials"]))' "$work/mf/gltf/manifest.json")
p=$(median "$work/peer.times") m=$(median "$work/mf.times")
echo "| run (--jobs $jobs) | wall (median of $repeat) | files written |"
echo "|---|---:|---:|"
echo "| oiiotool script, glTF + HDRP mask map ($sets sets) | $p s | $peer_files |"
echo "| \`matforge ingest --preset gltf,unity-hdrp --no-cache\` ($mf_sets sets) | $m s | $mf_files |"
echo "| ratio | **$(awk -v a="$p" -v b="$m" 'BEGIN { printf "%.1f×", a / b }')** | |"
echo
echo "$(nproc) cores; tests/data/corpus/real; the script's sets from truth.json's roles."
