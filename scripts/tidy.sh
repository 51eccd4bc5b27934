#!/usr/bin/env bash
# clang-tidy-14 (checks and errors in .clang-tidy) over our C++ in lib/ and tools/.
#   scripts/tidy.sh [BUILD_DIR]        default: build-tidy/
# It analyses each file as the release build compiles it, from a tree of its own (configured
# one translation unit per file, the generated headers made, nothing compiled), so whatever the
# builds do (unity batches, sanitizers) the database names every file.
# Only the files that changed since they last passed are analysed: a file passes once for one
# key, the SHA-256 of clang-tidy's version, .clang-tidy, the file's compile flags and its
# preprocessed text (the file and every header it includes, paths taken relative to the clone).
# The keys of passed files are kept in $MATFORGE_TIDY_CACHE (default ~/.cache/matforge-tidy, beside
# matforge's result cache, never in it: ingest refuses a cache folder that holds other files;
# .ci/run keeps it outside the clone, between CI runs); MATFORGE_TIDY_CACHE=none analyses all.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-$root/build-tidy}
command -v clang-tidy-14 >/dev/null || { echo "tidy: clang-tidy-14 missing (apt-get install clang-tidy-14)" >&2; exit 2; }
# shellcheck source=bootstrap.sh
source "$root/scripts/bootstrap.sh"
configure "$build" -DCMAKE_UNITY_BUILD=OFF -DMATFORGE_TESTS=OFF -DMATFORGE_BENCHMARKS=OFF
cmake --build "$build" --target matforge_generated >"$build/generated.log" 2>&1 || { cat "$build/generated.log" >&2; exit 1; }
db=$build/compile_commands.json
cache=${MATFORGE_TIDY_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/matforge-tidy}

exec python3 - "$db" "$root" "$cache" "$(nproc)" <<'PY'
import concurrent.futures, hashlib, json, os, re, shlex, subprocess, sys, time

db, root, cache, jobs = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
t0 = time.time()
entries, seen = [], set()
for e in json.load(open(db)):
    f = os.path.relpath(os.path.join(e["directory"], e["file"]), root)
    if f.startswith(("lib/", "tools/")) and f.endswith(".cpp") and f not in seen:
        seen.add(f)
        entries.append((f, e))
if not entries:
    sys.exit(f"tidy: no sources of lib/ or tools/ in {db}")

version = subprocess.run(["clang-tidy-14", "--version"], capture_output=True, text=True).stdout
config = open(os.path.join(root, ".clang-tidy"), "rb").read()

def relative(text):
    return text.replace(root + "/", "").replace(root, ".")

def key(item):
    f, e = item
    args = e["arguments"] if "arguments" in e else shlex.split(e["command"])
    # The flags, less the compiler, the launcher and the output: the preprocessor's own command.
    flags = [a for a in args[1:] if a not in ("ccache", "/usr/bin/ccache")]
    if "-o" in flags:
        i = flags.index("-o")
        del flags[i:i + 2]
    flags = [a for a in flags if a != "-c" and not a.endswith(e["file"])]
    pp = subprocess.run(["clang++-14", *flags, "-Wno-unknown-warning-option", "-E", "-o", "-",
                         os.path.join(e["directory"], e["file"])], cwd=e["directory"], capture_output=True)
    # The prefix map (scripts/bootstrap.sh) renames paths in outputs only; it is not in the key.
    keyed = [a for a in flags if not a.startswith("-ffile-prefix-map=")]
    h = hashlib.sha256()
    for part in (version.encode(), config, relative(" ".join(keyed)).encode(), f.encode(),
                 relative(pp.stdout.decode("utf-8", "replace")).encode(), str(pp.returncode).encode()):
        h.update(hashlib.sha256(part).digest())
    return h.hexdigest()

use_cache = cache != "none"
with concurrent.futures.ThreadPoolExecutor(jobs) as pool:
    keys = list(pool.map(key, entries)) if use_cache else [None] * len(entries)
todo = [(f, k) for (f, _), k in zip(entries, keys) if not (use_cache and os.path.exists(os.path.join(cache, k)))]
print(f"tidy: {len(entries)} files, {len(entries) - len(todo)} unchanged since they passed, "
      f"{len(todo)} to analyse", file=sys.stderr)

noise = re.compile(r"^\d+ warnings? generated|^Suppressed|^Use -header-filter|non-user code")

def tidy(item):
    f, k = item
    # gcc-only warning flags in the database are not clang's business.
    p = subprocess.run(["clang-tidy-14", "-p", os.path.dirname(db), "--quiet",
                        "--extra-arg=-Wno-unknown-warning-option", f], cwd=root, capture_output=True, text=True)
    out = "".join(l for l in (p.stdout + p.stderr).splitlines(keepends=True) if not noise.search(l))
    if p.returncode == 0 and use_cache:
        os.makedirs(cache, exist_ok=True)
        open(os.path.join(cache, k), "w").write(f + "\n")
    return f, p.returncode, out

failed = []
with concurrent.futures.ThreadPoolExecutor(jobs) as pool:
    for f, rc, out in pool.map(tidy, todo):
        if out.strip():
            sys.stderr.write(out)
        if rc != 0:
            failed.append(f)
if failed:
    sys.exit(f"tidy: {len(failed)} files failed: {' '.join(failed)}")
print(f"tidy: clean in {time.time() - t0:.0f} s", file=sys.stderr)
PY
