#!/usr/bin/env bash
# Builds libktx itself (KTX-Software 4.0, the sources crates.io's libktx-rs-sys 0.3.3 carries,
# built with its own CMake) and the small program that loads every .ktx2 the tests write with it
# (tests/texture/checkers/ktx_open), into a folder of the build tree (never committed, never
# vendored). PyPI's pyktx has no Linux wheel (its source package builds against an installed
# libktx, which Debian 12 does not package); Cargo builds libktx from a registry package.
# Usage: scripts/ktx-checker.sh [DIR]   (default build/ktx; the tests run DIR/release/ktx_open)
# The crates Cargo.lock pins are downloaded from crates.io by name and version, checked against
# the lock's SHA-256 and unpacked into DIR/vendor; Cargo then builds offline from that folder.
# So Debian 12's own cargo (0.66, whose registry client knows only crates.io's git index, which
# is not reachable here) builds it as rustup's does; Cargo.lock's versions build with Rust 1.63.
# Needs cargo, cmake, a C++ compiler and curl. About 2.5 minutes on 2 cores. With
# MATFORGE_CHECKER_CACHE set (.ci/run sets it outside the clone) the build is kept there, keyed by
# the checker's sources, and a later clean clone copies the program from it.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
dir=${1:-$root/build/ktx}
src=$root/tests/texture/checkers/ktx_open
want=$(cat "$src/Cargo.lock" "$src/Cargo.toml" "$src/src/main.rs" | sha256sum | cut -c1-16)
[[ -f $dir/installed.txt && $(cat "$dir/installed.txt") == "$want" && -x $dir/release/ktx_open ]] && exit 0
for tool in cargo curl; do
  command -v $tool >/dev/null || { echo "ktx-checker: $tool is missing (Debian: apt-get install $tool)" >&2; exit 1; }
done
mkdir -p "$dir"
# Test processes run in parallel and each may call this: one builds, the others wait.
exec 9>"$dir/.lock"
flock 9
[[ -f $dir/installed.txt && $(cat "$dir/installed.txt") == "$want" && -x $dir/release/ktx_open ]] && exit 0

# name version sha256 of each registry package in the lock
mapfile -t crates < <(awk '
  /^\[\[package\]\]/ { if (src ~ /^"registry\+/) print name, version, sum; name = version = src = sum = "" }
  /^name = /     { name = $3 }    /^version = / { version = $3 }
  /^source = /   { src = $3 }     /^checksum = / { sum = $3 }
  END { if (src ~ /^"registry\+/) print name, version, sum }' "$src/Cargo.lock" | tr -d '"')
vendor=$dir/vendor
mkdir -p "$vendor" "$dir/crates"
for line in "${crates[@]}"; do
  read -r name version sum <<< "$line"
  crate=$dir/crates/$name-$version.crate
  if [[ ! -f $crate ]] || ! echo "$sum  $crate" | sha256sum --check --quiet 2>/dev/null; then
    curl -fsSL --retry 3 -o "$crate.part" "https://static.crates.io/crates/$name/$name-$version.crate"
    echo "$sum  $crate.part" | sha256sum --check --quiet || { echo "ktx-checker: $name $version: checksum differs from Cargo.lock" >&2; exit 1; }
    mv "$crate.part" "$crate"
  fi
  if [[ ! -f $vendor/$name-$version/.cargo-checksum.json ]]; then
    rm -rf "${vendor:?}/$name-$version"
    tar -xzf "$crate" -C "$vendor"
    # A directory source: the package's checksum (the lock's); no per-file list to verify.
    printf '{"files":{},"package":"%s"}' "$sum" > "$vendor/$name-$version/.cargo-checksum.json"
  fi
done
# A Cargo home of its own: the user's ~/.cargo is neither read nor written.
mkdir -p "$dir/cargo-home"
cat > "$dir/cargo-home/config.toml" <<TOML
[source.crates-io]
replace-with = "vendored"
[source.vendored]
directory = "$vendor"
TOML
target=$dir
[[ -n ${MATFORGE_CHECKER_CACHE:-} ]] && target=$MATFORGE_CHECKER_CACHE/ktx-$want
if [[ ! -x $target/release/ktx_open ]]; then
  CARGO_HOME="$dir/cargo-home" CARGO_TARGET_DIR="$target" \
    cargo build --quiet --release --locked --offline --manifest-path "$src/Cargo.toml" >&2
fi
if [[ $target != "$dir" ]]; then
  mkdir -p "$dir/release"
  cp "$target/release/ktx_open" "$dir/release/ktx_open.part"
  mv "$dir/release/ktx_open.part" "$dir/release/ktx_open"
fi
echo "$want" > "$dir/installed.txt"
