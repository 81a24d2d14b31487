#!/usr/bin/env python3
"""Makes docs/examples/python_study.ipynb from docs/examples/python_study.py, so the script and
the notebook are one study with one source (issue 32, "an example study as a plain script and a
notebook"): the docstring becomes the first markdown cell, the imports and set-up one code cell,
and each numbered section ("# 1. ...") a markdown cell with its comment and a code cell with its
code. No Jupyter needed: the notebook is nbformat 4.4 JSON, written without outputs.
  python3 scripts/make_example_notebook.py          write the notebook
  python3 scripts/make_example_notebook.py --check  exit 1 when the notebook is not current"""
import ast
import json
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCRIPT = os.path.join(ROOT, "docs", "examples", "python_study.py")
NOTEBOOK = os.path.join(ROOT, "docs", "examples", "python_study.ipynb")
SECTION = re.compile(r"^# (\d+)\. ")


def lines_of(text):
    """Notebook sources are lists of lines, each but the last ending in a newline."""
    rows = text.strip("\n").split("\n")
    return [r + "\n" for r in rows[:-1]] + rows[-1:]


def markdown(text):
    return {"cell_type": "markdown", "metadata": {}, "source": lines_of(text)}


def code(text):
    return {"cell_type": "code", "execution_count": None, "metadata": {}, "outputs": [], "source": lines_of(text)}


def notebook(script_text):
    module = ast.parse(script_text)
    doc = ast.get_docstring(module) or ""
    body = script_text.split("\n")
    # Skip the shebang and the docstring: the code starts after the docstring's last line.
    start = module.body[0].end_lineno if doc else 0
    rows = body[start:]
    cells = [markdown("# Example study: the `fovea` module\n\n" + doc)]
    chunk, comment = [], None

    def flush():
        if comment is not None:
            cells.append(markdown("\n".join(c[2:] if c.startswith("# ") else c[1:] for c in comment)))
        if any(r.strip() for r in chunk):
            cells.append(code("\n".join(chunk)))

    i = 0
    while i < len(rows):
        if SECTION.match(rows[i]):
            flush()
            comment, chunk = [], []
            while i < len(rows) and rows[i].startswith("#"):
                comment.append(rows[i])
                i += 1
            continue
        chunk.append(rows[i])
        i += 1
    flush()
    return {
        "cells": cells,
        "metadata": {
            "kernelspec": {"display_name": "Python 3", "language": "python", "name": "python3"},
            "language_info": {"name": "python"},
        },
        "nbformat": 4,
        "nbformat_minor": 4,
    }


def main():
    with open(SCRIPT, encoding="utf-8") as f:
        text = json.dumps(notebook(f.read()), indent=1, ensure_ascii=False) + "\n"
    if "--check" in sys.argv[1:]:
        current = open(NOTEBOOK, encoding="utf-8").read() if os.path.exists(NOTEBOOK) else ""
        if current != text:
            print(f"{NOTEBOOK} is not made from {SCRIPT}: run python3 scripts/make_example_notebook.py",
                  file=sys.stderr)
            return 1
        print("the notebook is current")
        return 0
    with open(NOTEBOOK, "w", encoding="utf-8") as f:
        f.write(text)
    print(f"wrote {NOTEBOOK}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
