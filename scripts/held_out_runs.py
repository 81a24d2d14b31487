"""What the held-out sweeps share (scripts/auto-radius-sweep.py, scripts/refine-scale-sweep.py):
their command line and one `fovea-cli track --virtual N --domain wide` run on the wide domain's
held-out subsets per setting, on one core with one OpenCV thread, kept as JSON in a work folder
and reused when present (a run is written to PATH.part and renamed, so an interrupted one is not)."""
import argparse
import json
import os
import subprocess
import tempfile


def parse_args(doc, prefix, add=None):
    """The sweeps' options (--seed ..., --frames-per-subset, --work, --core, and `add`'s), the
    fovea-cli to run (FOVEA_CLI or the build tree's) and the work folder."""
    ap = argparse.ArgumentParser(description=doc.split("\n\n")[0])
    ap.add_argument("--seed", type=int, action="append", help="held-out seed (repeatable; default 5)")
    ap.add_argument("--frames-per-subset", type=int, default=1000)
    ap.add_argument("--work", help="keep the runs' JSON here (reused when present)")
    ap.add_argument("--core", type=int, default=0, help="the CPU core to run on (default 0)")
    if add:
        add(ap)
    a = ap.parse_args()
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    cli = os.environ.get("FOVEA_CLI", os.path.join(root, "build/default/app/fovea-cli"))
    work = a.work or tempfile.mkdtemp(prefix=prefix)
    os.makedirs(work, exist_ok=True)
    return a, cli, work


def track(cli, core, seed, frames_per_subset, extra, path):
    """The JSON of `fovea-cli track --virtual 8N --domain wide --seed S --json EXTRA...`."""
    if not os.path.exists(path):
        env = dict(os.environ, OPENCV_FOR_THREADS_NUM="1", OMP_NUM_THREADS="1")
        with open(path + ".part", "w") as out:
            subprocess.run(["taskset", "-c", str(core), cli, "track", "--virtual", str(frames_per_subset * 8),
                            "--domain", "wide", "--seed", str(seed), "--json", *extra], stdout=out, env=env, check=True)
        os.replace(path + ".part", path)
    return json.load(open(path))
