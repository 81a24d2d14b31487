#!/usr/bin/env python3
"""Holds the measured numbers of README.md and docs/ to the commands that produce them (issue 26).

scripts/doc-numbers.json lists, per command, the sentences of a document that print its
results, with placeholders for the numbers: {PATH:FORMAT} or {PATH*SCALE:FORMAT}, where PATH
walks the command's JSON output (a.b[2].c) and FORMAT is a Python format spec (".2f"; "s" for
a string such as a lens part, which --static matches as one word); {PATH-(PATH2):FORMAT} is the
difference of two outputs (a span the document prints, computed before rounding);
"unicode_minus": true prints negative numbers with U+2212 as the document does.
A check names either a fovea-cli "command" ("{tmp}" in an argument is a fresh temporary folder:
an output file the command must write) or a "file", the JSON a regenerating script wrote and
the repository keeps (the pupil network's figures, written by scripts/train_pupil_net.py).

  check_doc_numbers.py --static      every sentence, numbers as wildcards, is in its document
                                     (cheap: CTest runs it, so a doc edit cannot orphan an entry)
  check_doc_numbers.py --run [-k RE] runs the commands (fovea-cli from FOVEA_CLI or
                                     build/default/app/fovea-cli) and checks every number at the
                                     printed precision; prints what the document should say when
                                     it does not (before a release, and after a change that moves
                                     the numbers: the full run is that release step, docs/platform.md)

CTest runs --static as docs.numbers_manifest and `--run -k RE` on a fast subset (trace, exact
sweeps, selectivity, blend-profile, resolution at zero gaze, optimize-lens, one compare-shift;
10-20 s) as docs.numbers_run_fast (tests/CMakeLists.txt holds the regex). The slow commands
(tolerance, closed loop, calibrate, pupil benchmarks, fits, dense sweeps, the other eye-box
runs) run only in the full --run.

Exit code 0 when everything holds, 1 when something does not (each failure printed), 2 for a
malformed manifest.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PLACEHOLDER = re.compile(r"\{([A-Za-z0-9_.\[\]-]+?)(?:-\(([A-Za-z0-9_.\[\]-]+)\))?(?:\*([-0-9.e]+))?:([^{}]*)\}")
NUMBER = r"[-+−]?[0-9][0-9,]*(?:\.[0-9]+)?(?:e[-+]?[0-9]+)?"
WORD = r"[A-Za-z0-9_.-]+"


def walk(doc, path):
    """doc at PATH (a.b[2].c); KeyError/IndexError name the missing step."""
    value = doc
    for part in re.findall(r"[^.\[\]]+|\[\d+\]", path):
        if part.startswith("["):
            value = value[int(part[1:-1])]
        else:
            value = value[part]
    return value


def render(text, doc, unicode_minus=False):
    def one(m):
        value = walk(doc, m.group(1))
        if value is None:
            raise ValueError(f"{m.group(1)} is null")
        if m.group(2):
            value = value - walk(doc, m.group(2))
        if m.group(3):
            value = value * float(m.group(3))
        out = format(value, m.group(4))
        return out.replace("-", "−") if unicode_minus else out

    return PLACEHOLDER.sub(one, text)


def pattern(text):
    parts = PLACEHOLDER.split(text)
    # split() yields literal, path, subtracted path, scale, format, literal, ...; a string
    # placeholder (format "s": a lens part, a detector name) matches one word, a number any number
    out = re.escape(parts[0])
    for i in range(1, len(parts), 5):
        out += (WORD if parts[i + 3].endswith("s") else NUMBER) + re.escape(parts[i + 4])
    return re.compile(out)


def load_manifest():
    with open(os.path.join(ROOT, "scripts", "doc-numbers.json"), encoding="utf-8") as f:
        manifest = json.load(f)
    for i, check in enumerate(manifest["checks"]):
        for key in ("doc", "expect"):
            if key not in check:
                raise SystemExit(f"doc-numbers.json: check {i} has no \"{key}\"")
        if ("command" in check) == ("file" in check):
            raise SystemExit(f"doc-numbers.json: check {i} needs one of \"command\" and \"file\"")
        if "file" in check and not os.path.isfile(os.path.join(ROOT, check["file"])):
            raise SystemExit(f"doc-numbers.json: check {i}: no file {check['file']}")
    return manifest


def source_name(check):
    return " ".join(check["command"]) if "command" in check else check["file"]


def read_doc(rel):
    with open(os.path.join(ROOT, rel), encoding="utf-8") as f:
        return " ".join(f.read().split())  # sentences wrap across lines: compare with single spaces


def static_check(manifest):
    failures = 0
    for check in manifest["checks"]:
        text = read_doc(check["doc"])
        for sentence in check["expect"]:
            if not pattern(sentence).search(text):
                print(f"{check['doc']}: no sentence of the shape {sentence!r}")
                failures += 1
    return failures


def cli_path():
    cli = os.environ.get("FOVEA_CLI", os.path.join(ROOT, "build", "default", "app", "fovea-cli"))
    if not os.access(cli, os.X_OK):
        raise SystemExit(f"no fovea-cli at {cli} (build it, or set FOVEA_CLI)")
    return cli


def run_command(cli, command):
    with tempfile.TemporaryDirectory(prefix="doc-numbers-") as tmp:
        args = [a.replace("{tmp}", tmp) for a in command]
        return subprocess.run([cli] + args, cwd=ROOT, capture_output=True, text=True)


def run_check(manifest, only):
    cli = None
    failures = 0
    outputs = {}  # a command that holds sentences of several documents runs once
    for check in manifest["checks"]:
        name = source_name(check)
        if only and not re.search(only, name):
            continue
        start = time.time()
        if "file" in check:
            with open(os.path.join(ROOT, check["file"]), encoding="utf-8") as f:
                doc = json.load(f)
        else:
            cli = cli or cli_path()
            key = tuple(check["command"])
            if key not in outputs:
                outputs[key] = run_command(cli, check["command"])
            proc = outputs[key]
            if proc.returncode != 0:
                print(f"FAIL fovea-cli {name}: exit {proc.returncode}\n{proc.stderr.strip()}")
                failures += 1
                continue
            doc = json.loads(proc.stdout)
        text = read_doc(check["doc"])
        for sentence in check["expect"]:
            try:
                want = render(sentence, doc, check.get("unicode_minus", False))
            except (KeyError, IndexError, TypeError, ValueError) as e:
                print(f"FAIL {check['doc']}: {sentence!r}: the output has no {e}")
                failures += 1
                continue
            if " ".join(want.split()) not in text:
                found = pattern(sentence).search(text)
                print(f"FAIL {check['doc']}: should say {want!r}" + (f", says {found.group(0)!r}" if found else ""))
                failures += 1
        print(f"checked {'fovea-cli ' if 'command' in check else ''}{name} ({time.time() - start:.0f} s)")
    return failures


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    mode = ap.add_mutually_exclusive_group(required=True)
    mode.add_argument("--static", action="store_true", help="check the sentences exist, numbers as wildcards")
    mode.add_argument("--run", action="store_true", help="run the commands and check every number")
    ap.add_argument("-k", metavar="RE", help="with --run: only the commands matching RE")
    args = ap.parse_args()
    manifest = load_manifest()
    failures = static_check(manifest) if args.static else run_check(manifest, args.k)
    n = sum(len(c["expect"]) for c in manifest["checks"]
            if args.static or not args.k or re.search(args.k, source_name(c)))
    print(f"{n - failures if failures <= n else 0} of {n} sentences hold" if failures else f"all {n} sentences hold")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
