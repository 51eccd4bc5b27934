"""Opens MaterialX documents with MaterialX itself (PyPI materialx 1.39: the Academy Software
Foundation's Python bindings, installed by scripts/py-checkers.sh; run with that environment's
python), validates each with the standard data libraries, generates GLSL for every material with
MaterialX's own GLSL generator, and compiles each stage with glslang (glslangValidator, Debian's
glslang-tools). It shares no code with matforge's writer (lib/engine/mtlx.cpp).

    mtlx_open.py OUT_DIR FILE...

prints one JSON line per file:
  {"file", "ok", "error",            ok: read and valid with the standard libraries
   "materials": [{"name", "doc", "frag", "vert"}]}   doc: the material's doc string (MaterialX's
                                                     getDocString); frag, vert: glslang's messages ("" compiled)
The generated stages are kept in OUT_DIR (<file stem>.<material>.frag / .vert).
"""
import json
import os
import subprocess
import sys

import MaterialX as mx
from MaterialX import PyMaterialXGenGlsl as glsl
from MaterialX import PyMaterialXGenShader as gen


def compile_stage(source, path, stage):
    with open(path, "w", encoding="utf-8") as f:
        f.write(source)
    p = subprocess.run(["glslangValidator", "-S", stage, path], capture_output=True, text=True, check=False)
    return "" if p.returncode == 0 else (p.stdout + p.stderr).strip()


def open_one(path, out_dir, stdlib, search):
    rep = {"file": path, "ok": False, "error": "", "materials": []}
    doc = mx.createDocument()
    try:
        mx.readFromXmlFile(doc, path)
    except Exception as e:  # pylint: disable=broad-except  (MaterialX's parse errors have no common base)
        rep["error"] = str(e)
        return rep
    doc.importLibrary(stdlib)
    ok, message = doc.validate()
    rep["ok"], rep["error"] = bool(ok), message.strip()
    if not ok:
        return rep
    generator = glsl.GlslShaderGenerator.create()
    context = gen.GenContext(generator)
    context.registerSourceCodeSearchPath(search)
    stem = os.path.splitext(os.path.basename(path))[0]
    for node in doc.getMaterialNodes():
        m = {"name": node.getName(), "doc": node.getDocString(), "frag": "", "vert": ""}
        try:
            shader = generator.generate(node.getName(), node, context)
        except Exception as e:  # pylint: disable=broad-except
            m["frag"] = m["vert"] = "generation failed: " + str(e)
            rep["materials"].append(m)
            continue
        base = os.path.join(out_dir, stem + "." + node.getName())
        m["frag"] = compile_stage(shader.getSourceCode(gen.PIXEL_STAGE), base + ".frag", "frag")
        m["vert"] = compile_stage(shader.getSourceCode(gen.VERTEX_STAGE), base + ".vert", "vert")
        rep["materials"].append(m)
    return rep


def main():
    out_dir = sys.argv[1]
    os.makedirs(out_dir, exist_ok=True)
    search = mx.getDefaultDataSearchPath()
    stdlib = mx.createDocument()
    mx.loadLibraries(mx.getDefaultDataLibraryFolders(), search, stdlib)
    for path in sys.argv[2:]:
        print(json.dumps(open_one(path, out_dir, stdlib, search)), flush=True)


if __name__ == "__main__":
    main()
