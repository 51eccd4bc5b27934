#!/usr/bin/env bash
# Builds the Debian package matforge_<version>_<arch>.deb (CPack, cmake/MatforgePackage.cmake:
# the runtime dependencies found by dpkg-shlibdeps, plus the Vulkan loader and Mesa's drivers,
# which matforge loads at run time). It ships the Python module for Debian's /usr/bin/python3
# in /usr/lib/python3/dist-packages/matforge (python/CMakeLists.txt).
#   scripts/package.sh OUTDIR            build it into OUTDIR (from a Release build in
#                                        build-package/: the binary and the module, no tests)
#   scripts/package.sh OUTDIR --check    then install it with apt, run ingest, validate,
#                                        preview (lavapipe) and report on sample_materials/
#                                        through /usr/bin/matforge, validate again through
#                                        /usr/bin/python3's `import matforge`, and remove it again
#                                        (root or sudo; refused when a matforge package is
#                                        already installed, which is not ours to remove)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
out=${1:?usage: scripts/package.sh OUTDIR [--check]}
check=${2:-}
# shellcheck source=bootstrap.sh
source "$root/scripts/bootstrap.sh"
install_set python
build=$root/build-package
# The configuration scripts/demo.sh builds (so CI compiles that one too), with the module.
configure_release "$build" -DMATFORGE_PYTHON=ON
build_quietly "$build" matforge matforge_python
mkdir -p "$out"
out=$(cd "$out" && pwd)
(cd "$build" && cpack -G DEB -B "$out" >"$build/cpack.log" 2>&1) || { cat "$build/cpack.log" >&2; exit 1; }
rm -rf "$out/_CPack_Packages"
deb=$(ls -t "$out"/matforge_*.deb | head -n 1)
echo "package: $deb" >&2
dpkg-deb --field "$deb" Package Version Architecture Depends | sed 's/^/package:   /' >&2
[[ $check == --check ]] || exit 0

sudo=""
((EUID == 0)) || sudo="sudo"
if dpkg-query -W -f='${Status}' matforge 2>/dev/null | grep -q "install ok installed"; then
  echo "package: a matforge package is installed already; not replacing it (remove it first)" >&2
  exit 2
fi
work=$(mktemp -d /tmp/matforge-package.XXXXXX)
remove() {
  local rc=$?
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get remove -y -q matforge >"$work/remove.log" 2>&1 || true
  rm -rf "$work"
  exit "$rc"
}
trap remove EXIT
$sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "$deb" >"$work/install.log" 2>&1 ||
  { cat "$work/install.log" >&2; exit 1; }
mf=/usr/bin/matforge
[[ -x $mf ]] || { echo "package: no $mf after installing $deb" >&2; exit 1; }
"$mf" --version | sed 's/^/package:   /' >&2
# The image module comes from the package (lib/matforge beside bin/), not from a build tree.
loaded=$(LD_DEBUG=files "$mf" --version 2>&1)
grep -q 'file=/usr/bin/../lib/matforge/matforge_oiio.so ' <<<"$loaded" ||
  { echo "package: /usr/bin/matforge did not load the packaged matforge_oiio.so" >&2; exit 1; }
# The installed binary, not the build tree's: the samples through every command. A cache of its
# own, so nothing is restored from the tests' runs.
export MATFORGE_CACHE=$work/cache
"$mf" ingest "$root/sample_materials" -o "$work/out" -q
"$mf" validate "$root/sample_materials" --report json --report-file "$work/validate.json" --fail-on never
"$mf" preview "$work/out/manifest.json" -o "$work/preview" --device cpu --contact-sheet "$work/contact_sheet.png"
"$mf" report "$work/out/manifest.json" -o "$work/report" --previews "$work/preview"
n=$(python3 -c 'import json, sys; print(len(json.load(open(sys.argv[1]))["materials"]))' "$work/out/manifest.json")
previews=$(find "$work/preview" -name '*.png' | wc -l)
for f in "$work/validate.json" "$work/contact_sheet.png" "$work/report/index.html"; do
  [[ -s $f ]] || { echo "package: the installed matforge wrote no $f" >&2; exit 1; }
done
((n >= 4 && previews == n)) || { echo "package: $n materials, $previews previews" >&2; exit 1; }
# The packaged module, from Debian's python3 outside the clone: its findings are the CLI's, and
# it loads the packaged image module.
# shellcheck disable=SC2016
(cd "$work" && LD_DEBUG=files /usr/bin/python3 -c '
import json, sys, matforge
assert matforge.__file__.startswith("/usr/lib/python3/dist-packages/matforge/"), matforge.__file__
assert matforge.libraries()[0].startswith("OpenImageIO 2."), matforge.libraries()
v = matforge.validate(sys.argv[1])
cli = json.load(open(sys.argv[2]))
assert {m.name: [f.code for f in m.findings] for m in v.materials} == {m["name"]: [f["code"] for f in m["findings"]] for m in cli["materials"]}
print(len(v.materials))
' "$root/sample_materials" "$work/validate.json" >"$work/python.out" 2>"$work/python.log") ||
  { tail -n 20 "$work/python.log" >&2; echo "package: /usr/bin/python3 could not use the packaged module" >&2; exit 1; }
grep -q 'file=/usr/bin/../lib/matforge/matforge_oiio.so ' "$work/python.log" ||
  { echo "package: the packaged Python module did not load the packaged matforge_oiio.so" >&2; exit 1; }
[[ $(cat "$work/python.out") == "$n" ]] || { echo "package: the module validated $(cat "$work/python.out") materials, not $n" >&2; exit 1; }
trap - EXIT
$sudo env DEBIAN_FRONTEND=noninteractive apt-get remove -y -q matforge >"$work/remove.log" 2>&1 ||
  { cat "$work/remove.log" >&2; exit 1; }
[[ ! -e $mf ]] || { echo "package: $mf is still there after apt-get remove" >&2; exit 1; }
[[ ! -e /usr/lib/python3/dist-packages/matforge ]] ||
  { echo "package: /usr/lib/python3/dist-packages/matforge is still there after apt-get remove" >&2; exit 1; }
rm -rf "$work"
echo "package: installed, ran ingest, validate, preview and report on $n materials through $mf and validate through" \
  "/usr/bin/python3's import matforge, removed" >&2
