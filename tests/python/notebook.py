#!/usr/bin/env python3
"""docs/python.ipynb is docs/python.md as a Jupyter notebook that renders
without running: the prose as markdown cells, each ```python block as a
code cell with the output block shown after it as its stored output (the
outputs test python-docs checks against the module). `--write` makes the
notebook; without it, the committed notebook must equal what the page
makes now (test python-notebook), so the two never drift apart.

usage: notebook.py SOURCE_ROOT [--write]
"""
import json
import os
import re
import sys

PAIR = re.compile(r"```python\n(.*?)```\n(?:```\n(.*?)```\n)?", re.S)


def lines(text):
    """nbformat's list of source lines, each but the last ending in \\n."""
    out = text.splitlines(keepends=True)
    if out and out[-1].endswith("\n"):
        out[-1] = out[-1][:-1]
    return out


def markdown(text):
    text = text.strip("\n")
    return [{"cell_type": "markdown", "metadata": {}, "source": lines(text)}] if text.strip() else []


def notebook(md):
    cells, pos, count = [], 0, 0
    for m in PAIR.finditer(md):
        cells += markdown(md[pos:m.start()])
        count += 1
        code, out = m.group(1), m.group(2)
        cell = {"cell_type": "code", "execution_count": count, "metadata": {}, "outputs": [],
                "source": lines(code.rstrip("\n"))}
        if out is not None:
            cell["outputs"].append({"name": "stdout", "output_type": "stream", "text": lines(out.rstrip("\n") + "\n")})
        cells.append(cell)
        pos = m.end()
    cells += markdown(md[pos:])
    for k, c in enumerate(cells):
        c["id"] = "cell-%d" % k
    return {"cells": cells, "metadata": {"kernelspec": {"display_name": "Python 3", "language": "python",
                                                        "name": "python3"},
                                         "language_info": {"name": "python"}},
            "nbformat": 4, "nbformat_minor": 5}


def main(argv):
    root = argv[1]
    with open(os.path.join(root, "docs", "python.md"), encoding="utf-8") as f:
        nb = notebook(f.read())
    text = json.dumps(nb, indent=1, ensure_ascii=False, sort_keys=True) + "\n"
    path = os.path.join(root, "docs", "python.ipynb")
    if "--write" in argv:
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)
        return 0
    with open(path, encoding="utf-8") as f:
        same = f.read() == text
    print("1..1")
    print("%s 1 - docs/python.ipynb is docs/python.md as a notebook (%d cells)%s"
          % ("ok" if same else "not ok", len(nb["cells"]),
             "" if same else ": run tests/python/notebook.py . --write"))
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
