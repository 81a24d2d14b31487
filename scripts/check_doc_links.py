#!/usr/bin/env python3
"""Every file README.md and docs/*.md point to exists (issue 27: two screenshots the docs showed
were never committed).

Checks Markdown links and images, [text](path) and ![alt](path), and repository paths in
backticks that name a file under docs/images/ or docs/img/ (`docs/images/x.png`, with "…-y.png"
shorthands left alone). External links (http:, https:, mailto:) and in-page anchors are skipped;
"path#anchor" is checked as "path".

Exit 0 when every target exists, 1 otherwise (each missing one printed as FILE:LINE: target).
"""
import glob
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
IMAGE_PATH = re.compile(r"`(docs/(?:images|img)/[A-Za-z0-9_./-]+\.(?:png|jpg|svg|gif))`")


def targets(line):
    for m in LINK.finditer(line):
        t = m.group(1)
        if re.match(r"^[a-z]+:", t) or t.startswith("#"):
            continue
        yield t.split("#", 1)[0], False
    for m in IMAGE_PATH.finditer(line):
        yield m.group(1), True


def main():
    docs = [os.path.join(ROOT, "README.md")] + sorted(glob.glob(os.path.join(ROOT, "docs", "*.md")))
    missing = 0
    checked = 0
    for doc in docs:
        base = os.path.dirname(doc)
        with open(doc, encoding="utf-8") as f:
            for n, line in enumerate(f, 1):
                for t, from_root in targets(line):
                    if not t:
                        continue
                    checked += 1
                    path = os.path.join(ROOT if from_root else base, t)
                    if not os.path.exists(path):
                        missing += 1
                        print(f"{os.path.relpath(doc, ROOT)}:{n}: {t} does not exist")
    print(f"{checked} links checked, {missing} missing")
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main())
