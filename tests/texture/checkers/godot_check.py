#!/usr/bin/env python3
"""Reads Godot 4 text resources (.tres) and texture import files (.import) as Godot does,
written here from Godot's documentation of the formats ("TSCN file format": [tag key=value ...]
headings, `key = value` properties, ExtResource("id"); ConfigFile's INI-like sections with
Variant values and ';' comments), not from matforge's writer:

    python3 godot_check.py FILE.tres...

prints one JSON line per .tres: {file, ok, error, heading: {tag, attributes}, ext: {id: {type,
path, resolved, exists, import: {section: {key: value}} or null}}, props: {key: value}}.
A property value ExtResource("id") becomes {"ext": id}; Color(...) etc. {"call": name, "args": [...]}.
Relative ext_resource paths resolve against the .tres's folder (Godot's loader localizes them so)."""
import json
import os
import re
import sys

TOKEN = re.compile(r'\s*(?:(?P<str>"(?:[^"\\]|\\.)*")|(?P<num>-?\d+(?:\.\d+)?(?:e[-+]?\d+)?)|'
                   r'(?P<word>[A-Za-z_][A-Za-z0-9_/]*)|(?P<punct>[(),=\[\]{}:]))')


def tokens(text):
    pos, out = 0, []
    while pos < len(text):
        if text[pos:].strip() == "":
            break
        m = TOKEN.match(text, pos)
        if not m:
            raise ValueError("unexpected text: " + text[pos:pos + 20])
        kind = m.lastgroup
        out.append((kind, m.group(kind)))
        pos = m.end()
    return out


def value(toks, i):
    """One Variant value from toks[i]; returns (value, next index)."""
    kind, t = toks[i]
    if kind == "str":
        return json.loads(t), i + 1
    if kind == "num":
        return (float(t) if any(c in t for c in ".e") else int(t)), i + 1
    if kind == "word":
        if t in ("true", "false"):
            return t == "true", i + 1
        if t == "null":
            return None, i + 1
        if i + 1 < len(toks) and toks[i + 1][1] == "(":
            args, i = [], i + 2
            while toks[i][1] != ")":
                v, i = value(toks, i)
                args.append(v)
                if toks[i][1] == ",":
                    i += 1
            if t == "ExtResource":
                return {"ext": args[0]}, i + 1
            return {"call": t, "args": args}, i + 1
        raise ValueError("bare word " + t)
    if t == "[":
        out, i = [], i + 1
        while toks[i][1] != "]":
            v, i = value(toks, i)
            out.append(v)
            if toks[i][1] == ",":
                i += 1
        return out, i + 1
    if t == "{":
        out, i = {}, i + 1
        while toks[i][1] != "}":
            k, i = value(toks, i)
            if toks[i][1] != ":":
                raise ValueError("expected ':' in a dictionary")
            v, i = value(toks, i + 1)
            out[str(k)] = v
            if toks[i][1] == ",":
                i += 1
        return out, i + 1
    raise ValueError("unexpected " + t)


def heading(line):
    toks = tokens(line.strip()[1:-1])
    if not toks or toks[0][0] != "word":
        raise ValueError("heading without a tag: " + line)
    attrs, i = {}, 1
    while i < len(toks):
        key = toks[i][1]
        if toks[i + 1][1] != "=":
            raise ValueError("heading attribute without '=': " + line)
        attrs[key], i = value(toks, i + 2)
    return toks[0][1], attrs


def sections(path):
    """[(tag, attributes, {key: value})] of a .tres or a ConfigFile (.import)."""
    out = []
    lines = open(path, encoding="utf-8").read().split("\n")
    i = 0
    while i < len(lines):
        line = lines[i].strip()
        i += 1
        if not line or line.startswith(";"):
            continue
        if line.startswith("["):
            tag, attrs = heading(line)
            out.append((tag, attrs, {}))
            continue
        key, sep, rest = line.partition("=")
        if not sep or not out:
            raise ValueError("a line that is neither a heading nor key = value: " + line)
        # A value may span lines (a dictionary or array): read until it parses.
        while True:
            try:
                toks = tokens(rest)
                v, end = value(toks, 0)
                if end != len(toks):
                    raise ValueError("text after the value: " + line)
                break
            except IndexError:
                if i >= len(lines):
                    raise
                rest += "\n" + lines[i]
                i += 1
        out[-1][2][key.strip()] = v
    return out


def check(path):
    out = {"file": path, "ok": False, "error": ""}
    try:
        secs = sections(path)
        tag, attrs, _ = secs[0]
        if tag != "gd_resource":
            raise ValueError("the first heading is " + tag + ", not gd_resource")
        out["heading"] = {"tag": tag, "attributes": attrs}
        out["ext"], out["props"] = {}, {}
        for tag, attrs, props in secs[1:]:
            if tag == "ext_resource":
                for k in ("type", "path", "id"):
                    if k not in attrs:
                        raise ValueError("ext_resource without " + k)
                p = attrs["path"]
                resolved = (p if p.startswith("res://") or os.path.isabs(p)
                            else os.path.normpath(os.path.join(os.path.dirname(path), p)))
                imp = resolved + ".import"
                out["ext"][str(attrs["id"])] = {
                    "type": attrs["type"], "path": p, "resolved": resolved, "exists": os.path.isfile(resolved),
                    "import": ({t: s for t, _, s in sections(imp)} if os.path.isfile(imp) else None)}
            elif tag == "resource":
                out["props"] = props
            else:
                raise ValueError("unexpected heading " + tag)
        for k, v in out["props"].items():
            if isinstance(v, dict) and "ext" in v and v["ext"] not in out["ext"]:
                raise ValueError(k + " names ExtResource(" + v["ext"] + "), which is not declared")
        out["ok"] = True
    except Exception as e:  # noqa: BLE001 - every failure is reported as the file's verdict
        out["error"] = type(e).__name__ + ": " + str(e)
    return out


if __name__ == "__main__":
    for f in sys.argv[1:]:
        print(json.dumps(check(f), sort_keys=True))
