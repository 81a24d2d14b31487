#!/usr/bin/env python3
"""clang-tidy over the translation units below the given folders, skipping the ones already
found clean with exactly the same inputs.

A unit's cache key is a SHA-256 over: the clang-tidy version, the repository's .clang-tidy,
the unit's compile command (source root replaced by a placeholder, so clones elsewhere share
the cache), and every file the compiler read for it (the source and each header, from Ninja's
dependency log of the last build): project files by content, system headers by path, size and
modification time (a package upgrade changes those). Only clean results are stored, so a unit
that has findings, or one whose inputs were never checked (a fresh machine, a changed header,
an unbuilt object without a dependency log), is always run through clang-tidy.

Which units: with --all, every unit below the folders. Otherwise only what changed since a
base commit (see choose_base): each changed .cpp's own unit, and for each changed header one
unit that reads it (its sibling .cpp, else the first unit whose dependency log names it), so
every changed file is looked at once and a header's findings are reported through that unit
(HeaderFilterRegex). With --dependents, every unit that reads a changed file instead. A
change of .clang-tidy or an unknown base means all units. What the changed-files pass can miss
(an unchanged .cpp whose findings appear only with a changed header) is what
`scripts/lint.sh --all` or `--record` is for: before a release and weekly
(.ci/weekly). Measured on two cores with an empty cache: 9-53 s per unit, ~35 min for all of
model/ (docs/platform.md, "Timings").

Recording (--record FILE): a unit's clang-tidy result depends only on its inputs (above), so
"every unit clean at commit C" holds at HEAD when every unit whose inputs changed since C is
clean at HEAD. The record is written after a clean --all pass, or after a clean --dependents
pass whose base is the recorded commit itself (not after a changed-files pass: it looks at a
changed header through one unit only). lint.sh --record checks the tree is committed.

Usage: tidy_cached.py --build build/default [--jobs N] [--cache DIR] [--all | --base REV]
                      [--dependents] [--record FILE] FOLDER...
Exit status 1 when any unit has a finding (checks are errors), 0 otherwise.
"""
import argparse
import concurrent.futures
import hashlib
import json
import os
import shlex
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def ninja_deps(build, objects):
    """{object: [input files]} from `ninja -t deps` (objects never built are absent)."""
    out = subprocess.run(["ninja", "-C", build, "-t", "deps"] + objects, capture_output=True, text=True).stdout
    deps, current = {}, None
    for line in out.splitlines():
        if line and not line.startswith(" "):
            name = line.split(":", 1)[0]
            current = None if "(VALID)" not in line else name
            if current:
                deps[current] = []
        elif current and line.strip():
            deps[current].append(line.strip())
    return deps


_file_hashes = {}


def file_digest(path):
    if path not in _file_hashes:
        h = hashlib.sha256()
        try:
            if os.path.abspath(path).startswith(ROOT + os.sep):
                with open(path, "rb") as f:
                    h.update(f.read())
            else:
                st = os.stat(path)
                h.update(f"{st.st_size}:{st.st_mtime_ns}".encode())
        except OSError:
            h.update(b"missing")
        _file_hashes[path] = h.hexdigest()
    return _file_hashes[path]


def git(*args):
    r = subprocess.run(["git", "-C", ROOT] + list(args), capture_output=True, text=True)
    return r.stdout.strip() if r.returncode == 0 else None


def choose_base(explicit):
    """(commit, how) to diff against: --base REV / $FOVEA_TIDY_BASE; else the merge base with
    the branch's upstream when HEAD is not already on it; else the last commit at which a full
    clean pass was recorded (scripts/tidy-clean-commit, written by `lint.sh --all --record`)."""
    if explicit:
        commit = git("rev-parse", "--verify", "--quiet", explicit + "^{commit}")
        return commit, "given" if commit else f"given base {explicit} not found"
    upstream = git("rev-parse", "--verify", "--quiet", "@{upstream}")
    head = git("rev-parse", "HEAD")
    if upstream and head and upstream != head:
        mb = git("merge-base", "HEAD", upstream)
        if mb and mb != head:
            return mb, "merge base with the upstream branch"
    rec = recorded_clean_commit()
    return (rec, "last recorded clean pass (scripts/tidy-clean-commit)") if rec else \
        (None, "no recorded clean pass")


def changed_files(base):
    """Paths (relative to ROOT) changed since base, the working tree's edits and untracked files included."""
    out = git("diff", "--name-only", base) or ""
    untracked = git("ls-files", "--others", "--exclude-standard") or ""
    return {p for p in (out + "\n" + untracked).splitlines() if p}


def select_dependents(units, deps_of, changed):
    """Every unit that reads a changed file (its source or any header in its dependency log);
    a unit without a dependency log (never built) counts as reading everything."""
    changed_abs = {os.path.join(ROOT, rel) for rel in changed}

    def reads_changed(e):
        inputs = deps_of(e)
        return inputs is None or any(os.path.normpath(os.path.abspath(p)) in changed_abs
                                     for p in [e["file"], *inputs])
    return [e for e in units if reads_changed(e)]


def select_changed(units, deps_of, changed):
    """The units that look at every changed file once (see the module docstring)."""
    by_file = {os.path.relpath(os.path.abspath(e["file"]), ROOT): e for e in units}
    chosen = {}
    for rel in sorted(changed):
        if rel in by_file:
            chosen[rel] = by_file[rel]
        elif rel.endswith(".h"):
            sibling = rel[:-2] + ".cpp"
            if sibling in by_file:
                chosen.setdefault(sibling, by_file[sibling])
                continue
            for urel, e in sorted(by_file.items()):
                if any(os.path.normpath(p) == os.path.join(ROOT, rel) for p in deps_of(e)):
                    chosen.setdefault(urel, e)
                    break
    return list(chosen.values())


def per_file_database(db):
    """The compile database clang-tidy needs: one entry per source file. A unity batch
    (cmake/FoveaBuildSpeed.cmake: a generated file of `#include "model/x.cpp"` lines) becomes one
    entry per source it includes, with the batch's flags and object (whose dependency log covers
    them all); the precompiled-header flags are dropped (GCC's .gch means nothing to clang, and a
    unit must include what it uses without the PCH)."""
    out = []
    for e in db:
        args = shlex.split(e["command"]) if "command" in e else list(e["arguments"])
        cleaned, skip = [], False
        for i, arg in enumerate(args):
            if skip:
                skip = False
                continue
            if arg == "-include" and i + 1 < len(args) and args[i + 1].endswith("cmake_pch.hxx"):
                skip = True
                continue
            if arg == "-Winvalid-pch":
                continue
            cleaned.append(arg)
        obj = cleaned[cleaned.index("-o") + 1] if "-o" in cleaned else None
        sources = [e["file"]]
        if "/unity/" in e["file"]:
            with open(e["file"]) as f:
                sources = [os.path.join(ROOT, line.split('"')[1]) for line in f if line.startswith("#include \"")]
        for src in sources:
            a = [src if x == e["file"] else x for x in cleaned]
            out.append({"directory": e["directory"], "file": src, "command": shlex.join(a), "object": obj})
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default="build/default")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    ap.add_argument("--cache", default=os.environ.get("FOVEA_TIDY_CACHE",
                                                      os.path.expanduser("~/.cache/fovea-clang-tidy")))
    ap.add_argument("--all", action="store_true", help="every unit, not only the changed files")
    ap.add_argument("--base", default=os.environ.get("FOVEA_TIDY_BASE"),
                    help="commit to diff against (default: see choose_base)")
    ap.add_argument("--dependents", action="store_true",
                    help="every unit that reads a changed file, not one per changed file")
    ap.add_argument("--record", metavar="FILE",
                    help="write HEAD to FILE when this pass proves every unit clean (see above)")
    ap.add_argument("folders", nargs="+")
    a = ap.parse_args()
    build = os.path.abspath(a.build)
    with open(os.path.join(build, "compile_commands.json")) as f:
        db = per_file_database(json.load(f))
    tidy_db = os.path.join(build, "tidy")
    os.makedirs(tidy_db, exist_ok=True)
    with open(os.path.join(tidy_db, "compile_commands.json"), "w") as f:
        json.dump([{k: e[k] for k in ("directory", "file", "command")} for e in db], f, indent=1)
    prefixes = tuple(os.path.join(ROOT, d.strip("/")) + os.sep for d in a.folders)
    units = [e for e in db if os.path.abspath(e["file"]).startswith(prefixes)]
    if not units:
        print("tidy: no translation units below " + " ".join(a.folders), file=sys.stderr)
        return 1
    tidy_version = subprocess.run(["clang-tidy", "--version"], capture_output=True, text=True).stdout
    with open(os.path.join(ROOT, ".clang-tidy"), "rb") as f:
        config = f.read()

    def objects_of(e):
        return e["object"]

    deps = ninja_deps(build, [o for o in map(objects_of, units) if o])

    def inputs_of(e):
        """The unit's inputs from the dependency log as absolute paths (None if never built);
        the log names build-tree files relative to the build folder."""
        inputs = deps.get(objects_of(e))
        return None if inputs is None else [p if os.path.isabs(p) else os.path.join(build, p) for p in inputs]
    # Whether a clean pass proves every unit clean at HEAD (the --record condition above).
    proves_all = a.all
    if not a.all:
        base, how = choose_base(a.base)
        changed = changed_files(base) if base else None
        always = {".clang-tidy"}  # what the checks are; the script only chooses units
        if changed is None or changed & always:
            why = how if changed is None else "the tidy configuration changed"
            print(f"tidy: all units ({why})")
            proves_all = True
        else:
            total = len(units)
            if a.dependents:
                units = select_dependents(units, inputs_of, changed)
                proves_all = base == recorded_clean_commit()
                look = "read them"
            else:
                units = select_changed(units, lambda e: inputs_of(e) or [], changed)
                look = "look at them"
            print(f"tidy: {len(changed)} files changed since {base[:10]} ({how}); {len(units)} of "
                  f"{total} units {look} (scripts/lint.sh --all checks every unit)")
            if not units:
                return record(a.record, proves_all)
    os.makedirs(a.cache, exist_ok=True)
    todo, cached = [], 0
    for e in units:
        inputs = inputs_of(e)
        key = None
        if inputs:
            h = hashlib.sha256()
            h.update(tidy_version.encode())
            h.update(config)
            h.update(e["command"].replace(ROOT, "<src>").encode())
            for full in sorted(set(inputs) | {e["file"]}):
                h.update(os.path.relpath(full, ROOT).encode() if full.startswith(ROOT) else full.encode())
                h.update(file_digest(os.path.normpath(full)).encode())
            key = h.hexdigest()
            if os.path.exists(os.path.join(a.cache, key)):
                cached += 1
                continue
        todo.append((e["file"], key))

    def run(item):
        path, key = item
        t0 = time.time()
        r = subprocess.run(["clang-tidy", "-p", tidy_db, "--quiet", "--warnings-as-errors=*",
                            "--extra-arg=-Wno-unknown-warning-option", path],
                           capture_output=True, text=True)
        clean = r.returncode == 0
        if clean and key:
            open(os.path.join(a.cache, key), "w").close()
        return path, clean, r.stdout, time.time() - t0

    start = time.time()
    failed = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, a.jobs)) as pool:
        for path, clean, out, secs in pool.map(run, todo):
            rel = os.path.relpath(path, ROOT)
            if not clean:
                failed.append(rel)
                sys.stdout.write(out)
            print(f"tidy: {rel}: {'clean' if clean else 'FINDINGS'} ({secs:.1f} s)", flush=True)
    print(f"tidy: {len(units)} units, {cached} unchanged since a clean check, {len(todo)} checked in "
          f"{time.time() - start:.0f} s with {a.jobs} jobs, {len(failed)} with findings")
    if failed:
        return 1
    return record(a.record, proves_all)


def recorded_clean_commit():
    """The commit in scripts/tidy-clean-commit, resolved (None when missing)."""
    try:
        with open(os.path.join(ROOT, "scripts", "tidy-clean-commit")) as f:
            return git("rev-parse", "--verify", "--quiet", f.read().split()[0] + "^{commit}")
    except (OSError, IndexError):
        return None


def record(path, proves_all):
    """After a clean pass: write HEAD to path when the pass proves every unit clean."""
    if not path:
        return 0
    if not proves_all:
        print("tidy: not recorded: this pass does not prove every unit clean (use --all, or "
              "--dependents from the recorded commit)")
        return 0
    head = git("rev-parse", "HEAD")
    with open(path, "w") as f:
        f.write(head + "\n")
    print(f"tidy: recorded {head[:10]} as a commit at which every unit is clean ({path})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
