#!/usr/bin/python3
"""Checks that the modules of lib/ include only what they link.

Usage: check-layers.py LAYERS_TXT LIB_DIR

LAYERS_TXT is the module graph lib/CMakeLists.txt declares, written by CMake at configure time
(build/layers.txt, one line per module: "name: public deps | private deps"). A file of lib/M/
may include "X/..." only where X is M, a module M links (PUBLIC or PRIVATE), or a module one of
those reaches through PUBLIC links: what the compiler sees of a static library's headers. A
folder of lib/ that the graph does not declare is an error too. Prints every include that breaks
this (file:line, the module it reaches, M's allowed set) and exits 1; 0 with a one-line summary.
Standard library only: Debian's /usr/bin/python3 or any CPython 3.
"""
import pathlib
import re
import sys


def read_graph(path):
    public, private = {}, {}
    for line in pathlib.Path(path).read_text().splitlines():
        if not line.strip():
            continue
        name, _, deps = line.partition(":")
        pub, _, priv = deps.partition("|")
        public[name.strip()] = pub.split()
        private[name.strip()] = priv.split()
    return public, private


def main():
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    public, private = read_graph(sys.argv[1])
    lib = pathlib.Path(sys.argv[2])

    def visible(module, seen=None):
        """The module and everything its PUBLIC links reach."""
        seen = set() if seen is None else seen
        if module not in seen:
            seen.add(module)
            for d in public.get(module, []):
                visible(d, seen)
        return seen

    include = re.compile(r'^\s*#\s*include\s+"([A-Za-z0-9_]+)/')
    problems, checked = [], 0
    for folder in sorted(p for p in lib.iterdir() if p.is_dir()):
        module = folder.name
        if module not in public:
            problems.append(f"lib/{module}/: a folder no matforge_module() declares")
            continue
        allowed = {module}
        for d in public[module] + private[module]:
            allowed |= visible(d)
        for f in sorted(folder.rglob("*")):
            if f.suffix not in (".hpp", ".cpp", ".h", ".inc", ".hlsli"):
                continue
            for n, line in enumerate(f.read_text(errors="replace").splitlines(), 1):
                m = include.match(line)
                if not m:
                    continue
                target = m.group(1)
                if target not in public:  # not a module: a generated file ("shaders/x.inc")
                    continue
                checked += 1
                if target not in allowed:
                    problems.append(f"{f.relative_to(lib.parent)}:{n}: includes {target}/, which "
                                    f"matforge_{module} does not link (it reaches: {', '.join(sorted(allowed))})")
    for p in problems:
        print(p)
    if problems:
        print(f"check-layers: {len(problems)} include(s) outside the declared links", file=sys.stderr)
        return 1
    print(f"check-layers: {checked} includes of {len(public)} modules follow the declared links")
    return 0


if __name__ == "__main__":
    sys.exit(main())
