#!/usr/bin/env python3
"""Check that the .c files of one folder stand in layers.

A file depends on another when it calls (or takes the address of) a
function that the other defines without `static`. Calls made in the
static inline functions of a header of the same folder count for every
.c file that includes that header; the header itself is no file of the
graph. Exits 1 printing a cycle if the graph has one, else 0 printing the
files bottom-up (layer number, file, the files it calls).

Given several folders, bottom-up (the rooms of common/, docs/architecture.md),
each folder's files must stand in layers, and a file may call only the
functions of its own folder and of the folders before it in the list: a
call up a floor is printed and exits 1, as a cycle does.

Names are matched, C is not parsed: a local variable or a field named like
another file's function counts as a call to it (rename one of them).
Standard library only, so that any checkout can run it.

usage: layers.py FOLDER [FOLDER...]
"""
import os
import re
import sys

IDENT = re.compile(r"[A-Za-z_]\w*")
INCLUDE = re.compile(r'^[ \t]*#[ \t]*include[ \t]*"([^"]+)"', re.M)


def strip(text):
    """The text with comments, string and character literals blanked
    (newlines kept), so that braces and names in them do not count."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(c + " " * (j - i - 2) + c if j - i >= 2 else " ")
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


PREPRO = re.compile(r"^[ \t]*#(?:[^\n\\]|\\.)*", re.M | re.S)


DEFINE = re.compile(r"^[ \t]*#[ \t]*define[ \t]+([A-Za-z_]\w*)(?!\()(.*)$", re.M)


def macros(code):
    """Object-like macros: name -> the words of its body."""
    return {m.group(1): IDENT.findall(m.group(2)) for m in DEFINE.finditer(code)}


def expand(words, macro, seen=()):
    """Words with the folder's object-like macros expanded (DEM_INLINE is
    `static inline ...`)."""
    out = []
    for w in words:
        if w in macro and w not in seen:
            out += expand(macro[w], macro, seen + (w,))
        else:
            out.append(w)
    return out


def scan(code, macro):
    """Top-level function definitions as (name, is_static), and the names
    used inside braces (bodies and initialisers) or in macro definitions."""
    defs, used = [], set()
    for m in PREPRO.finditer(code):
        used.update(IDENT.findall(m.group(0)))
    code = PREPRO.sub(lambda m: re.sub(r"[^\n]", " ", m.group(0)), code)
    depth, paren, start = 0, 0, 0
    for m in re.finditer(r"[A-Za-z_]\w*|[{}();]", code):
        t = m.group(0)
        if t == "{":
            if depth == 0 and paren == 0:
                head = code[start:m.start()]
                f = re.search(r"([A-Za-z_]\w*)\s*\([^;{}]*\)\s*$", head)
                if f and "=" not in head:
                    words = expand(IDENT.findall(head[:f.start(1)]), macro)
                    if words and words[-1] not in ("struct", "union", "enum"):
                        defs.append((f.group(1), "static" in words))
            depth += 1
        elif t == "}":
            depth -= 1
            if depth == 0:
                start = m.end()
        elif t == "(":
            paren += 1
        elif t == ")":
            paren -= 1
        elif t == ";":
            if depth == 0:
                start = m.end()
        elif depth > 0:
            used.add(t)
    return defs, used


def headers_of(folder, name, seen):
    """Headers of the folder that file `name` includes, transitively."""
    path = os.path.join(folder, name)
    with open(path, encoding="utf-8", errors="replace") as f:
        text = f.read()
    for h in INCLUDE.findall(text):
        if h not in seen and os.path.isfile(os.path.join(folder, h)):
            seen.add(h)
            headers_of(folder, h, seen)
    return seen


def folder_uses(folder):
    """The folder's .c files, the non-static functions each defines, and
    the names each uses (its own and those of the folder's headers it
    includes)."""
    sources = sorted(f for f in os.listdir(folder) if f.endswith(".c"))
    code = {}
    for f in os.listdir(folder):
        if f.endswith((".c", ".h")):
            with open(os.path.join(folder, f), encoding="utf-8", errors="replace") as fh:
                code[f] = strip(fh.read())
    macro = {}
    for f in sorted(code):
        macro.update(macros(code[f]))
    scanned = {f: scan(code[f], macro) for f in code}
    defines, uses = {}, {}
    for f in sources:
        defines[f] = {name for name, static in scanned[f][0] if not static}
        used = set(scanned[f][1])
        for h in headers_of(folder, f, set()):
            used |= scanned[h][1]
        uses[f] = used
    return sources, defines, uses


def graph(folder):
    sources, defines, uses = folder_uses(folder)
    owner = {}
    for f in sources:
        for name in defines[f]:
            owner[name] = f
    edges = {f: {} for f in sources}
    for f in sources:
        for name in uses[f]:
            g = owner.get(name)
            if g and g != f:
                edges[f].setdefault(g, set()).add(name)
    return sources, edges


def calls_up(folders):
    """Calls from a file of one folder to a function defined in a folder
    later in the list: (caller folder/file, callee folder/file, names)."""
    found = [folder_uses(d) for d in folders]
    owner = {}
    for k, (sources, defines, _) in enumerate(found):
        for f in sources:
            for name in defines[f]:
                owner[name] = (k, f)
    bad = []
    for k, (sources, _, uses) in enumerate(found):
        for f in sources:
            up = {}
            for name in uses[f]:
                if name in owner and owner[name][0] > k:
                    up.setdefault(owner[name], set()).add(name)
            for (j, g), names in sorted(up.items()):
                bad.append((os.path.join(folders[k], f), os.path.join(folders[j], g), names))
    return bad


def find_cycle(sources, edges):
    state, stack = {}, []

    def visit(f):
        state[f] = 1
        stack.append(f)
        for g in sorted(edges[f]):
            if state.get(g) == 1:
                return stack[stack.index(g):] + [g]
            if g not in state:
                c = visit(g)
                if c:
                    return c
        stack.pop()
        state[f] = 2
        return None

    for f in sources:
        if f not in state:
            c = visit(f)
            if c:
                return c
    return None


def bottom_up(sources, edges):
    """Files by layer: a file's layer is one above the highest it calls."""
    layer = {}

    def level(f):
        if f not in layer:
            layer[f] = 1 + max((level(g) for g in edges[f]), default=-1)
        return layer[f]

    for f in sources:
        level(f)
    return sorted(sources, key=lambda f: (layer[f], f)), layer


def layers(folder, title):
    """Print the folder's files bottom-up, or its cycle; 0 or 1."""
    sources, edges = graph(folder)
    if title:
        print(f"{folder}:")
    cycle = find_cycle(sources, edges)
    if cycle:
        print("cycle:")
        for a, b in zip(cycle, cycle[1:]):
            print(f"  {a} -> {b} ({', '.join(sorted(edges[a][b]))})")
        return 1
    order, layer = bottom_up(sources, edges)
    for f in order:
        calls = ", ".join(sorted(edges[f])) or "-"
        print(f"{layer[f]} {f}: {calls}")
    return 0


def main(argv):
    folders = argv[1:]
    if not folders or not all(os.path.isdir(d) for d in folders):
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 2
    status = 0
    for d in folders:
        status |= layers(d, len(folders) > 1)
    for f, g, names in calls_up(folders) if len(folders) > 1 else []:
        print(f"up a floor: {f} -> {g} ({', '.join(sorted(names))})")
        status = 1
    return status


if __name__ == "__main__":
    sys.exit(main(sys.argv))
