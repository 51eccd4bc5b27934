#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test (ctest).
#   scripts/test.sh              release build: all tests
#   MATFORGE_SANITIZE=1 scripts/test.sh   adds an ASan/UBSan/LSan build running the suite again
#                                         (benchmarks off; any report fails the test: the
#                                         sanitizers abort, LSan exits non-zero), but for the
#                                         slow tests tests/sanitizer_skip.txt lists and says why
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
t0=$SECONDS
"$root/scripts/bootstrap.sh" "$root/build"
"$root/scripts/npm-checkers.sh" "$root/build/npm"  # glTF-Validator and ktx-parse for tests/texture
echo "test: release build $((SECONDS - t0)) s" >&2
t0=$SECONDS
ctest --test-dir "$root/build" --output-on-failure -j"$(nproc)" --timeout 900
echo "test: release tests $((SECONDS - t0)) s" >&2
if [[ ${MATFORGE_SANITIZE:-0} == 1 ]]; then
  t0=$SECONDS
  # -O1 -g1: a third less compile time than -O2 -g; line tables keep file:line in reports.
  "$root/scripts/bootstrap.sh" "$root/build-asan" -DMATFORGE_SANITIZE=ON -DMATFORGE_BENCHMARKS=OFF \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG"
  echo "test: sanitizer build $((SECONDS - t0)) s" >&2
  t0=$SECONDS
  # tests/sanitizer_skip.txt: the slow tests whose time goes to uninstrumented third-party code
  # or to real data a smaller test already covers here; they run in the release stage above.
  skip="^($(sed -e 's/#.*//' -e 's/[[:space:]]*$//' -e '/^$/d' "$root/tests/sanitizer_skip.txt" | paste -sd'|'))\$"
  # Child processes (the CLI and hostile tests run the binary) inherit these. Never
  # fast_unwind_on_malloc=0: it deadlocks lavapipe (checked on Mesa 22.3). A 32 MB
  # quarantine (default 256) keeps the memory-bound tests (8K set, bombs) meaningful.
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:detect_stack_use_after_return=1:strict_string_checks=1:quarantine_size_mb=32 \
  LSAN_OPTIONS=suppressions=$root/scripts/lsan.supp:print_suppressions=0 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --test-dir "$root/build-asan" --output-on-failure -j"$(nproc)" --timeout 1800 -E "$skip"
  echo "test: sanitizer tests $((SECONDS - t0)) s" >&2
fi
