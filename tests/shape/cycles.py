#!/usr/bin/env python3
"""Cycles among modules, by includes and by calls.
  cycles.py SRCROOT BUILDDIR
A module is a source file's path without its extension (core/plan/hatch.c
and hatch.h are one). Include edges: X -> Y when X.c or X.h includes
"Y.h", found as the compiler finds it: beside X first, else by its stem in
core/, lua/, plugins/. Call edges: X -> Y when X.o needs a symbol (nm: U)
that Y.o defines (T, D, B, R): what the linker sees, so a call through a
header's static inline is not an edge.
Prints each strongly connected component of more than one module; exit 1
if there is any."""
import os
import re
import subprocess
import sys

root, build = sys.argv[1], sys.argv[2]
DIRS = ("core", "lua", "plugins")


def sccs(graph):
    index, low, stack, on, out, n = {}, {}, [], set(), [], [0]

    def visit(v):
        index[v] = low[v] = n[0]
        n[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def mod(path):
    rel = os.path.relpath(path, root)
    return os.path.splitext(rel)[0]


inc, names = {}, {}
for d in DIRS:
    for dp, _, fs in os.walk(os.path.join(root, d)):
        for f in fs:
            if f.endswith((".c", ".h")):
                names.setdefault(os.path.splitext(f)[0], mod(os.path.join(dp, f)))
for d in DIRS:
    for dp, _, fs in os.walk(os.path.join(root, d)):
        for f in fs:
            if not f.endswith((".c", ".h")):
                continue
            m = mod(os.path.join(dp, f))
            for line in open(os.path.join(dp, f), encoding="utf-8", errors="replace"):
                r = re.match(r'\s*#\s*include\s+"(?:.*/)?([A-Za-z_0-9]+)\.h"', line)
                if not r:
                    continue
                # as the compiler looks: the includer's directory first
                # (lua/lamina.c is not core/lamina.h), then the include path
                here = os.path.join(dp, r.group(1) + ".h")
                to = mod(here) if os.path.exists(here) else names.get(r.group(1))
                if to and to != m:
                    inc.setdefault(m, set()).add(to)
calls, defs, need = {}, {}, {}
for dp, _, fs in os.walk(build):
    for f in fs:
        stem = os.path.splitext(f)[0]
        src = os.path.join(root, os.path.relpath(os.path.join(dp, stem), build))
        if f.endswith(".o") and (os.path.exists(src + ".c") or stem in names):
            # build/lua/lamina.o is lua/lamina.c's, not core/lamina.h's
            m = mod(src) if os.path.exists(src + ".c") else names[stem]
            out = subprocess.run(["nm", os.path.join(dp, f)], capture_output=True, text=True).stdout
            for line in out.split("\n"):
                p = line.split()
                if len(p) == 2 and p[0] == "U":
                    need.setdefault(m, set()).add(p[1])
                elif len(p) == 3 and p[1] in "TDBR":
                    defs[p[2]] = m
for m, syms in need.items():
    for s in syms:
        if s in defs and defs[s] != m:
            calls.setdefault(m, set()).add(defs[s])
bad = 0
for what, g in (("include", inc), ("call", calls)):
    for c in sccs(g):
        bad += 1
        print("%s cycle: %s" % (what, " <-> ".join(c)))
sys.exit(1 if bad else 0)
