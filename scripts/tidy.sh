#!/usr/bin/env bash
# clang-tidy-14 (checks and errors in .clang-tidy) over our C++ in lib/ and tools/, using the
# compile_commands.json of a configured build.
#   scripts/tidy.sh [BUILD_DIR]        default: build/
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-$root/build}
db=$build/compile_commands.json
[[ -f $db ]] || { echo "tidy: no $db (configure first: scripts/bootstrap.sh $build)" >&2; exit 2; }
command -v clang-tidy-14 >/dev/null || { echo "tidy: clang-tidy-14 missing (apt-get install clang-tidy-14)" >&2; exit 2; }

mapfile -t files < <(python3 - "$db" "$root" <<'PY'
import json, sys, os
db, root = sys.argv[1], sys.argv[2]
keep = ("lib/", "tools/")
skip = ()
seen = set()
for e in json.load(open(db)):
    f = os.path.relpath(os.path.join(e["directory"], e["file"]), root)
    if f.startswith(keep) and not f.startswith(skip) and f.endswith(".cpp") and f not in seen:
        seen.add(f)
        print(f)
PY
)
((${#files[@]})) || { echo "tidy: no sources found in $db" >&2; exit 2; }
echo "tidy: ${#files[@]} files" >&2
cd "$root"
# gcc-only warning flags in the database are not clang's business.
printf '%s\n' "${files[@]}" | xargs -P "$(nproc)" -n 1 \
  clang-tidy-14 -p "$build" --quiet --extra-arg=-Wno-unknown-warning-option 2> >(grep -v -E '^[0-9]+ warnings? generated|^Suppressed|^Use -header-filter|non-user code' >&2)
echo "tidy: clean" >&2
