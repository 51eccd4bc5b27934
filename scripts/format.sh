#!/usr/bin/env bash
# clang-format-14 with the committed .clang-format over our C++ (*.cpp, *.hpp, *.h in lib/,
# tools/, tests/, bench/, python/; the GLSL shaders are not C++ and are left alone).
#   scripts/format.sh [FILE...]           rewrite the files in place (default: all of them)
#   scripts/format.sh --check [FILE...]   list the files that differ, with their changed-line
#                                         counts; exit 1 if any does, 0 if none
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
check=0
if [[ ${1:-} == --check ]]; then
  check=1
  shift
fi
command -v clang-format-14 >/dev/null || { echo "format: clang-format-14 missing (apt-get install clang-format-14)" >&2; exit 2; }

if (($#)); then
  files=("$@")
else
  # Tracked and new (not ignored) files, so build folders and scratch copies never count.
  mapfile -t files < <(git ls-files --cached --others --exclude-standard -- \
    'lib/*.cpp' 'lib/*.hpp' 'lib/*.h' 'tools/*.cpp' 'tools/*.hpp' 'tools/*.h' \
    'tests/*.cpp' 'tests/*.hpp' 'tests/*.h' 'bench/*.cpp' 'bench/*.hpp' 'bench/*.h' \
    'python/*.cpp' 'python/*.hpp' |
    grep -v '/shaders/' | sort -u | while read -r f; do [[ -f $f ]] && echo "$f"; done)
fi
((${#files[@]})) || { echo "format: no files" >&2; exit 2; }

if ((check == 0)); then
  printf '%s\0' "${files[@]}" | xargs -0 -P "$(nproc)" -n 8 clang-format-14 -i --style=file
  echo "format: ${#files[@]} files formatted" >&2
  exit 0
fi

# One line per differing file: "<lines to change> <file>" (lines of the file that would change).
differ() {
  local n
  n=$(clang-format-14 --style=file "$1" | diff --old-line-format='-
' --new-line-format='' --unchanged-line-format='' "$1" - | wc -l || true)
  if ((n)); then echo "$n $1"; fi
}
export -f differ
out=$(printf '%s\0' "${files[@]}" | xargs -0 -P "$(nproc)" -I{} bash -c 'differ "$1"' _ {} | sort -k2)
if [[ -z $out ]]; then
  echo "format: ${#files[@]} files clean" >&2
  exit 0
fi
echo "$out"
awk -v total="${#files[@]}" '{ n++; l += $1 } END { printf "format: %d of %d files differ (%d lines); run scripts/format.sh\n", n, total, l }' <<<"$out" >&2
exit 1
