#!/usr/bin/env bash
# oiiotool_peer.sh: the studio-script peer of `matforge ingest --preset gltf`.
#
#   oiiotool_peer.sh <library-dir> <out-dir> [--jobs N] [--png-like-matforge] [--unity-hdrp]
#
# For each set of <library-dir>/library.tsv (written by make_library) it writes the outputs
# matforge's gltf preset writes, with one oiiotool process per output map (decode, convert,
# pack, encode), as a studio's shell script would:
#   <name>/<name>_basecolor.png  sRGB 8-bit RGB: the albedo's codes copied (sRGB in, sRGB out)
#   <name>/<name>_normal.png     GL 8-bit RGB; DX inputs get G' = 1 - G. oiiotool has no
#                                renormalization: the 8-bit codes are copied, where matforge
#                                decodes, renormalizes and re-encodes (hence a 2-code tolerance)
#   <name>/<name>_orm.png        R = AO (1 when none), G = roughness, B = metalness (0 when
#                                none) 8-bit; a Poly Haven _arm_ map is already in that layout
# --unity-hdrp also writes Unity HDRP's mask map, as a script serving glTF and HDRP in one pass
# a set would (the base colour and the normal map are the same files for both):
#   <name>/<name>_mask.png       R = metalness (0 when none), G = AO (1 when none), B = 1,
#                                A = smoothness = 1 - roughness, 8-bit, alpha unassociated
# --jobs 1 (default) runs the commands one after another; --jobs N runs N at once (xargs -P).
# --png-like-matforge writes PNGs with matforge's encoder settings (Paeth filter, zlib RLE)
# instead of oiiotool's defaults: the script as it would be with matforge's encoder choice, so
# the report can separate what the encoder settings buy from what the rest of matforge does.
# The set list comes from library.tsv rather than from parsing vendor names in bash: the
# peer measures the conversions, not a naming parser.
set -euo pipefail

usage() { echo "usage: oiiotool_peer.sh <library-dir> <out-dir> [--jobs N] [--png-like-matforge] [--unity-hdrp]" >&2; exit 2; }
[[ $# -ge 2 ]] || usage
lib=$1 out=$2
shift 2
jobs=1
png=()
hdrp=0
while [[ $# -gt 0 ]]; do
  case $1 in
    --jobs) [[ $# -ge 2 && $2 =~ ^[1-9][0-9]*$ ]] || usage; jobs=$2; shift 2 ;;
    --unity-hdrp) hdrp=1; shift ;;
    --png-like-matforge) png=(--attrib png:compressionLevel 1 --attrib:type=int png:filter 128 --compression rle); shift ;;
    *) usage ;;
  esac
done
[[ -f $lib/library.tsv ]] || { echo "oiiotool_peer.sh: no $lib/library.tsv" >&2; exit 1; }
command -v oiiotool >/dev/null || { echo "oiiotool_peer.sh: oiiotool not found (apt-get install openimageio-tools)" >&2; exit 1; }

# Scalar maps are 1-channel files (channel "Y"): --ch 0 picks the first channel by index.
cmds=()
# The last argument of every command is the output file: the PNG settings go just before -o.
add() {
  local q args=("$@")
  local n=${#args[@]}
  args=("${args[@]:0:n-2}" ${png[@]+"${png[@]}"} "${args[@]:n-2}")
  printf -v q '%q ' "${args[@]}"
  cmds+=("$q")
}
while IFS=$'\t' read -r name dir size albedo normal conv ao rough metal arm height; do
  [[ $name == name ]] && continue  # header
  src=$lib/sets/$dir
  dst=$out/$name
  mkdir -p "$dst"
  add oiiotool "$src/$albedo" --ch R,G,B -d uint8 -o "$dst/${name}_basecolor.png"
  if [[ $conv == dx ]]; then
    add oiiotool "$src/$normal" --ch R,G,B --invert:chbegin=1:chend=2 -d uint8 -o "$dst/${name}_normal.png"
  else
    add oiiotool "$src/$normal" --ch R,G,B -d uint8 -o "$dst/${name}_normal.png"
  fi
  if [[ $arm != - ]]; then
    add oiiotool "$src/$arm" --ch R,G,B -d uint8 -o "$dst/${name}_orm.png"
  else
    if [[ $ao != - ]]; then a=("$src/$ao" --ch 0); else a=(--pattern constant:color=1 "${size}x${size}" 1); fi
    if [[ $metal != - ]]; then m=("$src/$metal" --ch 0); else m=(--pattern constant:color=0 "${size}x${size}" 1); fi
    add oiiotool "${a[@]}" "$src/$rough" --ch 0 --chappend "${m[@]}" --chappend --chnames R,G,B \
        -d uint8 -o "$dst/${name}_orm.png"
  fi
  if ((hdrp)); then
    if [[ $arm != - ]]; then
      add oiiotool "$src/$arm" --ch R=B,G=R,B=1.0,A=G --invert:chbegin=3:chend=4 \
          --attrib:type=int oiio:UnassociatedAlpha 1 -d uint8 -o "$dst/${name}_mask.png"
    else
      add oiiotool "${m[@]}" "${a[@]}" --chappend --pattern constant:color=1 "${size}x${size}" 1 --chappend \
          "$src/$rough" --ch 0 --invert --chappend --chnames R,G,B,A \
          --attrib:type=int oiio:UnassociatedAlpha 1 -d uint8 -o "$dst/${name}_mask.png"
    fi
  fi
  : "$height"  # displacement: not a gltf output
done < "$lib/library.tsv"

# Each command line is already shell-quoted; xargs hands one at a time to bash.
printf '%s\0' "${cmds[@]}" | xargs -0 -n1 -P "$jobs" bash -c 'eval "$1"' _
