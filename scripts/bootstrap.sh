#!/usr/bin/env bash
# Installs matforge's Debian packages when missing, then configures and builds.
# Usage: scripts/bootstrap.sh [BUILD_DIR] [extra cmake args...]
#        scripts/bootstrap.sh --packages-only   (install, do not build)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-$root/build}
shift || true

packages=(
  build-essential cmake ninja-build pkg-config
  libopenimageio-dev openimageio-tools libopencolorio-dev libopenexr-dev
  libcli11-dev libgtest-dev libgmock-dev libbenchmark-dev nlohmann-json3-dev libzip-dev libssl-dev libxml2-dev
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslc spirv-tools
  libglvnd0 libglx0 libgl1 libegl1 libopengl0
  clang-14 clang-tidy-14 clang-format-14 libclang-rt-14-dev  # CI: scripts/tidy.sh, scripts/format.sh --check, scripts/fuzz.sh (libFuzzer)
  python3 python3-jsonschema  # tests: scripts/check-schemas.py (manifest and report schemas)
  slurm-wlm munge  # tests: scripts/cluster-demo.sh (sharded ingest on a one-node Slurm cluster)
  libsquish-dev libastcenc-dev libzstd-dev  # lib/texture: BC1-BC5, ASTC, KTX2 zstd
  libnvtt-bin astcenc  # bench/texture: the peer tools (nvcompress, astcenc)
  chromium  # tests/report: headless browser check of matforge report
  strace  # tests/hostile: counts the archive opens of a 3,000-entry .zip
)
# tests/texture run the npm checkers (scripts/npm-checkers.sh); a Node.js that bundles npm
# (NodeSource's) conflicts with Debian's npm package.
command -v npm >/dev/null || packages+=(nodejs npm)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "bootstrap: installing ${missing[*]}" >&2
  sudo=""
  ((EUID == 0)) || sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  # --no-install-recommends keeps OpenCV, GDAL, ffmpeg and Qt out (OpenImageIO recommends them).
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

[[ $build == --packages-only ]] && exit 0

# The project's own builds treat every C++ and shader warning as an error (a plain `cmake`
# build does not); extra args after it may override.
# -g1 (line tables: file:line in backtraces and sanitizer reports) instead of -g: a third less
# compile time on the test files, the same code.
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMATFORGE_WERROR=ON \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" "$@" >/dev/null
cmake --build "$build" -j"$(nproc)"
