#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test (ctest).
#   scripts/test.sh              release build: all tests
#   MATFORGE_SANITIZE=1 scripts/test.sh   adds an ASan/UBSan/LSan build running the suite again
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$root/scripts/bootstrap.sh" "$root/build"
ctest --test-dir "$root/build" --output-on-failure -j"$(nproc)" --timeout 900
if [[ ${MATFORGE_SANITIZE:-0} == 1 ]]; then
  "$root/scripts/bootstrap.sh" "$root/build-asan" -DMATFORGE_SANITIZE=ON -DMATFORGE_BENCHMARKS=OFF
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --test-dir "$root/build-asan" --output-on-failure -j"$(nproc)" --timeout 1800
fi
