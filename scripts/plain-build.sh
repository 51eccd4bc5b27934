#!/usr/bin/env bash
# scripts/plain-build.sh [gcc|clang]: the plain `cmake -DCMAKE_BUILD_TYPE=Release` build users
# make (scripts/bootstrap.sh configure_plain), everything, with warnings as errors, in
# build-plain-<compiler>/. CI builds it with gcc (Debian's default compiler); clang is checked by
# hand before a release. Needs the test packages (scripts/bootstrap.sh --install test).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
source "$root/scripts/bootstrap.sh"
compiler=${1:-gcc}
[[ $compiler == gcc || $compiler == clang ]] || { echo "usage: $0 [gcc|clang]" >&2; exit 2; }
configure_plain "$root/build-plain-$compiler" "$compiler"
build_quietly "$root/build-plain-$compiler"
