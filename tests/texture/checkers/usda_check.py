#!/usr/bin/env python3
"""An independent reader of USD text layers (.usda), written from the USD grammar (the crate
format's text twin: a `#usda 1.0` header, layer metadata in parentheses, nested `def` prims
with optional metadata, attributes `[uniform] TYPE NAME[.connect] [= VALUE]`, values that are
strings, @asset paths@, </prim/paths.props>, tuples, arrays, numbers and tokens). It shares no
code with matforge's writer (lib/engine/usd.cpp).

    usda_check.py FILE...

prints one JSON line per file: {"file", "ok", "error", "metadata": {...}, "prims": {"/Path":
{"type", "attributes": {"name": {"type", "uniform", "value"?, "connect"?}}}}}; every
connection is resolved: "unresolved" lists the targets whose prim or property is not declared.
"""
import json
import os
import re
import sys

TOKEN = re.compile(r'''
    (?P<ws>[ \t\r\n]+) | (?P<comment>\#[^\n]*) |
    (?P<string>"(?:[^"\\\n]|\\.)*") | (?P<asset>@[^@\n]*@) | (?P<path><[^>\n]*>) |
    (?P<punct>[(){}\[\],=]) |
    (?P<word>[A-Za-z_][A-Za-z0-9_:.]*|[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)
''', re.X)


def tokens(text):
    pos, out = 0, []
    while pos < len(text):
        m = TOKEN.match(text, pos)
        if not m:
            raise ValueError(f"unexpected character {text[pos]!r} at offset {pos}")
        pos = m.end()
        kind = m.lastgroup
        if kind in ("ws", "comment"):
            continue
        out.append((kind, m.group()))
    return out


class Parser:
    def __init__(self, toks):
        self.t, self.i = toks, 0

    def peek(self, k=0):
        return self.t[self.i + k] if self.i + k < len(self.t) else (None, None)

    def take(self, want=None):
        tok = self.peek()
        if tok[0] is None or (want is not None and tok[1] != want):
            raise ValueError(f"expected {want!r}, got {tok[1]!r} (token {self.i})")
        self.i += 1
        return tok

    def value(self):
        kind, text = self.take()
        if kind == "string":
            return json.loads(text)
        if kind == "asset":
            return {"asset": text[1:-1]}
        if kind == "path":
            return {"path": text[1:-1]}
        if text in ("(", "["):
            close = ")" if text == "(" else "]"
            items = []
            while self.peek()[1] != close:
                items.append(self.value())
                if self.peek()[1] == ",":
                    self.take(",")
            self.take(close)
            return items
        if kind == "word":
            try:
                return float(text) if re.match(r"[-+.\d]", text) else text
            except ValueError:
                return text
        raise ValueError(f"unexpected {text!r}")

    def metadata(self):
        meta = {}
        self.take("(")
        while self.peek()[1] != ")":
            kind, text = self.take()
            if kind == "string":  # a doc string alone
                meta["doc"] = json.loads(text)
                continue
            if text in ("prepend", "append", "add", "delete", "reorder"):  # a list edit
                text = self.take()[1]
            self.take("=")
            meta[text] = self.value()
        self.take(")")
        return meta

    def prim(self, parent, prims):
        self.take("def")
        kind, ptype = self.peek()
        if kind == "word":
            self.take()
        else:
            ptype = ""
        name = json.loads(self.take()[1])
        path = parent + "/" + name
        meta = self.metadata() if self.peek()[1] == "(" else {}
        entry = prims.setdefault(path, {"type": ptype, "attributes": {}})
        refs = meta.get("references", [])
        refs = refs if isinstance(refs, list) else [refs]
        if refs:
            entry["references"] = [r["asset"] for r in refs if isinstance(r, dict) and "asset" in r]
        self.take("{")
        while self.peek()[1] != "}":
            if self.peek()[1] == "def":
                self.prim(path, prims)
                continue
            uniform = False
            if self.peek()[1] == "uniform":
                self.take()
                uniform = True
            atype = self.take()[1]
            aname = self.take()[1]
            connect = aname.endswith(".connect")
            aname = aname[: -len(".connect")] if connect else aname
            attr = entry["attributes"].setdefault(aname, {"type": atype, "uniform": uniform})
            if self.peek()[1] == "=":
                self.take("=")
                v = self.value()
                attr["connect" if connect else "value"] = v
            if self.peek()[1] == "(":
                self.metadata()
        self.take("}")


def read(file):
    text = open(file, encoding="utf-8").read()
    if not text.startswith("#usda 1.0"):
        raise ValueError("no '#usda 1.0' header")
    p = Parser(tokens(text.split("\n", 1)[1]))
    meta = p.metadata() if p.peek()[1] == "(" else {}
    prims = {}
    while p.peek()[0] is not None:
        p.prim("", prims)
    unresolved = []
    folder = os.path.dirname(os.path.abspath(file))
    for path, prim in prims.items():
        for ref in prim.get("references", []):
            if not os.path.isfile(os.path.join(folder, ref)):
                unresolved.append(f"{path} references {ref}: no such file")
        for name, attr in prim["attributes"].items():
            target = attr.get("connect")
            if target is None:
                continue
            tpath, _, prop = target["path"].partition(".")
            if tpath not in prims or prop not in prims[tpath]["attributes"]:
                unresolved.append(f"{path}.{name} -> {target['path']}")
    return {"metadata": meta, "prims": prims, "unresolved": unresolved}


for f in sys.argv[1:]:
    out = {"file": f}
    try:
        out.update(read(f))
        out["ok"] = True
    except (ValueError, OSError, UnicodeDecodeError, json.JSONDecodeError) as e:
        out["ok"] = False
        out["error"] = str(e)
    print(json.dumps(out))
