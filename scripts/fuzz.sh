#!/usr/bin/env bash
# libFuzzer targets (tests/fuzz) for our parsers: preset, file-name discovery, the scene file, the
# manifest reader and the JPEG and plain-PNG readers (lib/image/direct.hpp).
#   scripts/fuzz.sh [SECONDS]          each target for SECONDS (default 30) on a scratch copy of
#                                      its committed corpus (CI: bounded, the corpus is unchanged)
#   FUZZ_GROW=1 scripts/fuzz.sh 3600   by hand: longer, new inputs merged into tests/fuzz/corpus
# A crash leaves crash-* in build-asan/artifacts/ and fails; commit it to the corpus once fixed.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
secs=${1:-30}
# shellcheck source=bootstrap.sh
source "$root/scripts/bootstrap.sh"
# The sanitizer build of scripts/test.sh (MATFORGE_SANITIZE=1) holds the fuzz targets: reused
# when it is there, configured the same way when not.
build=${FUZZ_BUILD:-$root/build-asan}
install_set dev
[[ -f $build/CMakeCache.txt ]] || configure_sanitizer "$build"
build_quietly "$build" fuzz
mkdir -p "$build/artifacts"
status=0
for exe in "$build"/tests/fuzz/fuzz_*; do
  name=${exe##*/fuzz_}
  seeds=$root/tests/fuzz/corpus/$name
  work=$build/corpus/$name
  rm -rf "$work" && mkdir -p "$work"
  echo "fuzz: $name for ${secs}s" >&2
  # -rss_limit_mb bounds a parser's memory; ASan's own leak check runs at exit. -max_len lets
  # inputs nest past the stack's limit: each JSON target's corpus holds a 100,000-level seed
  # (deep-nesting.json, 200 KB; a recursive reader overflows an 8 MB stack well before that).
  if ! ASAN_OPTIONS=detect_leaks=1 "$exe" "$work" "$seeds" -max_total_time="$secs" -rss_limit_mb=2048 -max_len=262144 \
       -timeout=10 -print_final_stats=1 -artifact_prefix="$build/artifacts/$name-" 2>"$build/$name.log"; then
    echo "fuzz: $name FAILED (log: $build/$name.log)" >&2
    tail -40 "$build/$name.log" >&2
    status=1
  else
    grep -E "stat::number_of_executed_units|stat::new_units_added" "$build/$name.log" | tr '\n' ' ' >&2; echo >&2
  fi
  if [[ ${FUZZ_GROW:-0} == 1 ]]; then
    "$exe" -merge=1 "$seeds" "$work" 2>/dev/null
  fi
done
exit $status
