#!/usr/bin/env bash
# Installs the Debian packages matforge needs when they are missing, then configures and builds.
#   scripts/bootstrap.sh --install build|python|test|dev   install one package set (each holds
#                                                   the one before it) and exit
#   scripts/bootstrap.sh BUILD_DIR [cmake args...]  install the test set, configure, build all
#   scripts/bootstrap.sh --packages-only            the same as --install dev (CI's first step)
# The sets: build = what building and running matforge needs (scripts/demo.sh); python = what
# its Python module adds (`pip install .`, scripts/package.sh); test = what the tests add
# (scripts/test.sh); dev = what CI adds (clang for the sanitizer and fuzzer build, clang-tidy,
# clang-format, ccache).
# The build prints one line per tenth of the work; the compiler's full output is in
# BUILD_DIR/build.log, and its end is printed when the build fails.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)

packages_build=(
  build-essential cmake ninja-build pkg-config
  libopenimageio-dev libopencolorio-dev libopenexr-dev libcli11-dev nlohmann-json3-dev
  openimageio-tools  # OpenImageIO's CMake package names its tools: configuring fails without them
  libzip-dev libssl-dev libstb-dev libsquish-dev libastcenc-dev libzstd-dev
  libdeflate-dev libjpeg-dev libwebp-dev  # lib/image/direct.hpp, png_writer.hpp
  libxml2-dev  # MaterialX sidecars (lib/material); the tests also parse JUnit with it
  libvulkan-dev glslc mesa-vulkan-drivers  # preview: shaders built by glslc, lavapipe without a GPU
  spirv-cross  # report --viewer: the renderer's shaders translated to ESSL 3.00 (WebGL2) at build time
)
packages_python=(
  python3-dev      # Python.h of Debian's python3, which the module is built for
  python3-venv     # `pip install .` into a virtual environment (Debian's python3 is externally managed)
  pybind11-dev     # the module's bindings in a CMake build (`pip install .` takes PyPI's, pinned in pyproject.toml)
  file             # scripts/package.sh: CPack's DEB generator runs file(1) before dpkg-shlibdeps, and fails without it
)
packages_test=(
  libgtest-dev libgmock-dev libbenchmark-dev
  libpng-dev       # tests/image: interlaced PNGs the direct reader must leave to OpenImageIO
  vulkan-validationlayers  # every GPU test fails on a validation message
  python3 python3-jsonschema  # scripts/check-schemas.py (manifest and report schemas)
  python3-venv     # scripts/py-checkers.sh: OpenUSD, MaterialX, Blender (bpy), texture2ddecoder from PyPI, pinned, under build/
  libgl1 libsm6 libice6 libx11-6 libxcb1 libxext6 libxfixes3 libxi6 libxrender1 libxkbcommon0  # what bpy links and does not bundle
  python3-yaml     # tests/texture/checkers/unity_check.py (Unity .mat and .meta YAML)
  glslang-tools    # tests/render: the d3d11 HLSL include compiled by glslang's HLSL front end
  slurm-wlm munge  # scripts/cluster-demo.sh (sharded ingest on a one-node Slurm cluster)
  chromium         # tests/report: headless browser check of matforge report
  strace           # tests/hostile: counts the archive opens of a 3,000-entry .zip
  util-linux       # unshare: tests/hostile's read-only and full output disks
)
# tests/texture run the npm checkers (scripts/npm-checkers.sh); a Node.js that bundles npm
# (NodeSource's) conflicts with Debian's npm package.
command -v npm >/dev/null || packages_test+=(nodejs npm)
# scripts/ktx-checker.sh builds libktx with Cargo (rustup's, where there is one, is as good) from
# crates it downloads with curl.
packages_test+=(curl)
command -v cargo >/dev/null || packages_test+=(cargo)
packages_dev=(
  clang-14 libclang-rt-14-dev  # the sanitizer + fuzzer build (scripts/test.sh, scripts/fuzz.sh)
  clang-tidy-14 clang-format-14  # scripts/tidy.sh, scripts/format.sh --check
  ccache  # .ci/run: a compiler cache kept outside the clone, between CI runs
)

install_set() {
  local set=$1 wanted=()
  case $set in
    build) wanted=("${packages_build[@]}") ;;
    python) wanted=("${packages_build[@]}" "${packages_python[@]}") ;;
    test) wanted=("${packages_build[@]}" "${packages_python[@]}" "${packages_test[@]}") ;;
    dev) wanted=("${packages_build[@]}" "${packages_python[@]}" "${packages_test[@]}" "${packages_dev[@]}") ;;
    *) echo "bootstrap: unknown package set '$set' (build, python, test or dev)" >&2; exit 2 ;;
  esac
  local missing=()
  for p in "${wanted[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  ((${#missing[@]})) || return 0
  echo "bootstrap: installing ${#missing[@]} Debian packages (${missing[*]}); 1-2 minutes on a fresh machine" >&2
  local sudo="" log t0=$SECONDS
  ((EUID == 0)) || sudo="sudo"
  log=$(mktemp /tmp/matforge-apt.XXXXXX)
  export DEBIAN_FRONTEND=noninteractive
  # --no-install-recommends keeps OpenCV, GDAL, ffmpeg and Qt out (OpenImageIO recommends them).
  if ! { $sudo apt-get update -q && $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"; } >"$log" 2>&1; then
    tail -n 30 "$log" >&2
    echo "bootstrap: apt-get failed (full log: $log)" >&2
    exit 1
  fi
  rm -f "$log"
  echo "bootstrap: packages installed in $((SECONDS - t0)) s" >&2
}

# build_quietly BUILD_DIR [TARGET...]: one line per tenth of the build, the full log in
# BUILD_DIR/build.log, its errors on the terminal when it fails.
build_quietly() {
  local build=$1 t0=$SECONDS
  shift
  local targets=()
  for t in "$@"; do targets+=(--target "$t"); done
  echo "bootstrap: building ${*:-everything} in ${build#"$root"/} ($(nproc) cores)" >&2
  set +e
  NINJA_STATUS="[%f/%t] " cmake --build "$build" -j"$(nproc)" "${targets[@]}" 2>&1 | tee "$build/build.log" |
    awk '/^\[[0-9]+\/[0-9]+\] / { split(substr($1, 2), a, "/"); p = int(10 * a[1] / a[2]);
           if (p > last) { last = p; printf "bootstrap:   %3d%% (%d of %d steps)\n", 10 * p, a[1], a[2] > "/dev/stderr"; fflush() } }'
  local rc=${PIPESTATUS[0]}
  set -e
  if ((rc != 0)); then
    grep -E -A12 'error|FAILED' "$build/build.log" | head -n 80 >&2
    echo "bootstrap: the build failed (full log: $build/build.log)" >&2
    exit "$rc"
  fi
  echo "bootstrap: built in $((SECONDS - t0)) s" >&2
}

# configure BUILD_DIR [cmake args...]: the project's own configuration. Warnings are errors (a
# plain `cmake` build only warns); -g1 keeps file:line in backtraces and sanitizer reports at a
# third less compile time than -g; a unity build (the files of a target compiled as one
# translation unit, up to 16 at a time: headers parsed and templates instantiated once a batch,
# half the compile time of one unit per file; scripts/tidy.sh keeps one unit per file). ccache,
# when installed, with paths taken relative to the clone, so two clones share the cache (CI:
# .ci/run points CCACHE_DIR outside the clone). A unity source includes each file by its
# absolute path, which lands in __FILE__ (every GoogleTest assertion) and the debug information:
# -ffile-prefix-map writes those relative to the clone, so a clone elsewhere still hits the cache.
configure() {
  local build=$1
  shift
  mkdir -p "$build"
  local launcher=()
  if command -v ccache >/dev/null; then
    launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache
      "-DCMAKE_CXX_FLAGS=-ffile-prefix-map=$root/=" "-DCMAKE_C_FLAGS=-ffile-prefix-map=$root/=")
  fi
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMATFORGE_WERROR=ON \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" -DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=16 \
    "${launcher[@]}" "$@" >"$build/configure.log" 2>&1 ||
    { cat "$build/configure.log" >&2; exit 1; }
}
export CCACHE_BASEDIR=$root CCACHE_NOHASHDIR=1

# configure_release BUILD_DIR [cmake args...]: the binary alone, built fast (scripts/demo.sh,
# scripts/package.sh, which adds the Python module): no tests or benchmarks (so no test
# packages), -O2 as every tested build, no debug information. Measured in a bare Debian 12
# chroot on 2 cores: 90 s against 163 s for the per-file RelWithDebInfo build.
configure_release() {
  local build=$1
  shift
  configure "$build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O2 -DNDEBUG" -DMATFORGE_TESTS=OFF \
    -DMATFORGE_BENCHMARKS=OFF "$@"
}

# configure_sanitizer BUILD_DIR: clang-14 with ASan + UBSan + LSan on every target of ours
# (MATFORGE_SANITIZE) and the libFuzzer targets (MATFORGE_FUZZ) in the same tree: one compile
# serves the sanitizer suite (scripts/test.sh) and the fuzzers (scripts/fuzz.sh). -O1: a third
# less compile time than -O2, and the sanitizers' own guidance for usable stacks.
configure_sanitizer() {
  configure "$1" -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 -DMATFORGE_SANITIZE=ON \
    -DMATFORGE_FUZZ=ON -DMATFORGE_TESTS=ON -DMATFORGE_BENCHMARKS=OFF \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG"
}

# configure_plain BUILD_DIR gcc|clang: the build a user makes by hand (README: `cmake
# -DCMAKE_BUILD_TYPE=Release`): CMake's own Release flags (-O3), one unit per file, tests and
# benchmarks included, no flags of ours but warnings as errors (and ccache's path mapping), so a
# warning only that build shows (GCC 12's -O3 diagnostics, clang's unused constants) fails CI
# (scripts/plain-build.sh, .ci/run's `plain` stage).
configure_plain() {
  local compilers=(-DCMAKE_C_COMPILER=gcc -DCMAKE_CXX_COMPILER=g++)
  [[ $2 == clang ]] && compilers=(-DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14)
  mkdir -p "$1"
  local launcher=()
  if command -v ccache >/dev/null; then
    launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache
      "-DCMAKE_CXX_FLAGS=-ffile-prefix-map=$root/=" "-DCMAKE_C_FLAGS=-ffile-prefix-map=$root/=")
  fi
  cmake -S "$root" -B "$1" -G Ninja -DCMAKE_BUILD_TYPE=Release -DMATFORGE_WERROR=ON "${compilers[@]}" \
    "${launcher[@]}" >"$1/configure.log" 2>&1 || { cat "$1/configure.log" >&2; exit 1; }
}

# Sourced (scripts/demo.sh, scripts/test.sh): the functions only.
[[ ${BASH_SOURCE[0]} != "$0" ]] && return 0

case ${1:-} in
  --install) install_set "${2:?--install build, python, test or dev}"; exit 0 ;;
  --packages-only) install_set dev; exit 0 ;;
esac
build=${1:-$root/build}
shift || true
install_set test
# The test build: the Python module too (its tests import it: python/CMakeLists.txt).
configure "$build" -DMATFORGE_PYTHON=ON "$@"
build_quietly "$build"
