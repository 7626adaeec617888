#!/usr/bin/env python3
"""Files of one folder must stand in layers (issue 12): no two .c files may
call each other, directly or around a loop.

usage: layers.py FOLDER [-v]

For each .c file of FOLDER, the functions (and objects) it defines without
`static`; then, in every other .c file of the folder, the uses of those
names, calls or not (a function handed over as a pointer is still leaned
on). A use inside a static inline function of a header of the folder
counts for the .c files that use that inline function: the header is no
file of its own, but what it calls is. Comments, strings and character
constants are blanked first. The file graph is printed bottom-up (each
file after those it uses); exit 1 with a cycle if there is one, else 0.
Standard library only.
"""
import os
import re
import sys

IDENT = re.compile(r"[A-Za-z_]\w*")
KEYWORDS = {
    "if", "for", "while", "switch", "return", "sizeof", "_Alignof", "_Generic",
    "_Static_assert", "do", "else", "case", "default", "goto", "break", "continue",
}
QUALIFIERS = {"static", "const", "volatile", "extern", "struct", "union", "enum", "_Thread_local"}


def strip(text):
    """Blank comments, strings, character constants and preprocessor lines,
    keeping line structure."""
    out, i, n = [], 0, len(text)
    at_line_start = True
    while i < n:
        c = text[i]
        if at_line_start and c == "#":
            # a directive, with its continuation lines
            j = i
            while j < n and text[j] != "\n":
                j += 2 if text[j] == "\\" and j + 1 < n else 1
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
            continue
        if c in " \t":
            out.append(c)
            i += 1
            continue
        at_line_start = c == "\n"
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
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(" " * (j + 1 - i))
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def top_level(code):
    """Split code into top-level declarations: (head, body) where head is
    the text before a top-level `{` or `;` and body the braced text (or
    '')."""
    items, depth, start, i, n = [], 0, 0, 0, len(code)
    head = None
    while i < n:
        c = code[i]
        if c == "{":
            if depth == 0:
                head = code[start:i]
                body_start = i
            depth += 1
        elif c == "}":
            depth -= 1
            if depth == 0:
                # a function body ends the declaration; an initialiser or a
                # struct body goes on to its `;`
                if re.search(r"\)\s*$", head):
                    items.append((head, code[body_start:i + 1]))
                    start = i + 1
                    head = None
        elif c == ";" and depth == 0:
            items.append((code[start:i] if head is None else head, code[start:i]))
            start = i + 1
            head = None
        i += 1
    return items


def definitions(code):
    """Names defined in code: {name: (static, inline, body)} for functions
    with a body and objects defined at top level."""
    out = {}
    for head, body in top_level(code):
        words = IDENT.findall(head)
        if not words or words[0] in ("typedef", "extern"):
            continue
        static = "static" in words
        inline = "inline" in words
        m = re.search(r"(\w+)\s*\([^()]*(\([^()]*\)[^()]*)*\)\s*$", head)
        if m and body.startswith("{"):
            out[m.group(1)] = (static, inline, body)
            continue
        if head is not body and "(" not in head.split("=")[0]:
            # an object: the declarator before `=` (or the last name)
            # (a type and a name: not a bare struct, union or enum)
            decl = head.split("=")[0]
            names = [w for w in IDENT.findall(decl) if w not in QUALIFIERS]
            if len(names) >= 2:
                out[names[-1]] = (static, inline, body)
    return out


def uses(code):
    return set(w for w in IDENT.findall(code) if w not in KEYWORDS)


def file_graph(folder):
    srcs = sorted(f for f in os.listdir(folder) if f.endswith(".c"))
    hdrs = sorted(f for f in os.listdir(folder) if f.endswith(".h"))
    code = {}
    for f in srcs + hdrs:
        with open(os.path.join(folder, f), encoding="utf-8") as fh:
            code[f] = strip(fh.read())
    owner = {}
    for f in srcs:
        for name, (static, _, _) in definitions(code[f]).items():
            # main is the program's entry: nothing calls it, and a field
            # of that name elsewhere is no use of it
            if not static and name != "main":
                owner.setdefault(name, f)
    # what each header inline function uses, through other inlines too
    inl = {}
    for h in hdrs:
        for name, (static, inline, body) in definitions(code[h]).items():
            if static and inline:
                inl[name] = uses(body)
    changed = True
    while changed:
        changed = False
        for name, u in inl.items():
            more = set().union(*(inl[v] for v in u if v in inl and v != name)) - u
            if more:
                u |= more
                changed = True
    graph = {f: {} for f in srcs}
    for f in srcs:
        mine = definitions(code[f])
        used = uses(code[f])
        for v in list(used):
            if v in inl and v not in mine:
                used |= inl[v]
        for v in used:
            g = owner.get(v)
            if g and g != f and not (v in mine and mine[v][0]):
                graph[f].setdefault(g, set()).add(v)
    return graph


def find_cycle(graph):
    colour, stack = {}, []

    def visit(f):
        colour[f] = 1
        stack.append(f)
        for g in sorted(graph[f]):
            if colour.get(g) == 1:
                return stack[stack.index(g):] + [g]
            if g not in colour:
                c = visit(g)
                if c:
                    return c
        stack.pop()
        colour[f] = 2
        return None

    for f in sorted(graph):
        if f not in colour:
            c = visit(f)
            if c:
                return c
    return None


def layers(graph):
    """Bottom-up: level 0 uses no other file, level k uses files below k."""
    level = {}

    def lev(f):
        if f not in level:
            level[f] = 0
            level[f] = 1 + max((lev(g) for g in graph[f]), default=-1)
        return level[f]

    for f in graph:
        lev(f)
    return level


def main(argv):
    if len(argv) < 2 or not os.path.isdir(argv[1]):
        print(__doc__.strip(), file=sys.stderr)
        return 2
    verbose = "-v" in argv[2:]
    graph = file_graph(argv[1])
    cycle = find_cycle(graph)
    if cycle:
        print("cycle: " + " -> ".join(cycle))
        for a, b in zip(cycle, cycle[1:]):
            print("  %s -> %s: %s" % (a, b, ", ".join(sorted(graph[a][b]))))
        return 1
    level = layers(graph)
    for f in sorted(graph, key=lambda f: (level[f], f)):
        deps = sorted(graph[f])
        if verbose:
            deps = ["%s (%s)" % (g, ", ".join(sorted(graph[f][g]))) for g in deps]
        print("%d %s -> %s" % (level[f], f, ", ".join(deps) if deps else "-"))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
