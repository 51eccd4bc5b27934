#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test (ctest).
#   scripts/test.sh                       release build (gcc) in build/: every test
#   MATFORGE_SANITIZE=1 scripts/test.sh   every test once: the release build runs those
#                                         labelled `slow` (each says why in its
#                                         tests/*/CMakeLists.txt), then the sanitizer build
#                                         (clang-14, build-asan/: ASan + UBSan + LSan; the
#                                         libFuzzer targets of scripts/fuzz.sh are built in the
#                                         same tree) runs all the others; any sanitizer report
#                                         fails its test
# Each stage prints its time. Tests read their paths from ctest (tests/common/test_env.hpp).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# shellcheck source=bootstrap.sh
source "$root/scripts/bootstrap.sh"

t0=$SECONDS
install_set test
configure "$root/build" -DMATFORGE_TESTS=ON -DMATFORGE_BENCHMARKS=ON -DMATFORGE_PYTHON=ON
build_quietly "$root/build"
"$root/scripts/npm-checkers.sh" "$root/build/npm"  # glTF-Validator, ktx-parse, MaterialX, three.js, Godot
"$root/scripts/py-checkers.sh" "$root/build/py"     # OpenUSD, MaterialX, Blender, texture2ddecoder for tests/texture
"$root/scripts/ktx-checker.sh" "$root/build/ktx"    # libktx for tests/texture (VulkanKtx2: slow, release only)
echo "test: release build $((SECONDS - t0)) s" >&2
t0=$SECONDS
# With the sanitizer stage to follow, the release build runs only what that stage leaves out.
release_only=()
[[ ${MATFORGE_SANITIZE:-0} == 1 ]] && release_only=(-L slow)
ctest --test-dir "$root/build" --output-on-failure -j"$(nproc)" --timeout 900 "${release_only[@]}"
echo "test: release tests $((SECONDS - t0)) s" >&2

if [[ ${MATFORGE_SANITIZE:-0} == 1 ]]; then
  t0=$SECONDS
  install_set dev
  configure_sanitizer "$root/build-asan"
  build_quietly "$root/build-asan"
  "$root/scripts/npm-checkers.sh" "$root/build-asan/npm"
  "$root/scripts/py-checkers.sh" "$root/build-asan/py"
  echo "test: sanitizer build $((SECONDS - t0)) s" >&2
  t0=$SECONDS
  # Child processes (the CLI and hostile tests run the binary) inherit these. Never
  # fast_unwind_on_malloc=0: it deadlocks lavapipe (checked on Mesa 22.3). A 32 MB
  # quarantine (default 256) keeps the memory-bound tests (8K set, bombs) meaningful.
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:detect_stack_use_after_return=1:strict_string_checks=1:quarantine_size_mb=32 \
  LSAN_OPTIONS=suppressions=$root/scripts/lsan.supp:print_suppressions=0 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --test-dir "$root/build-asan" --output-on-failure -j"$(nproc)" --timeout 1800 -LE slow
  echo "test: sanitizer tests $((SECONDS - t0)) s" >&2
fi
