#!/usr/bin/python3
"""Chooses where the learned pupil detector's refining window starts to scale with the pupil
(model/gaze/learned_pupil_detector.h: kRefineScaleAboveMajor).

A first-stage major axis m above F of the refining window's span (192 px of a 400 px frame,
T = 192 F px) shrinks the window's canvas so that the pupil looks T px wide. The refining
stage was trained with T drawn from 90-150 px (scripts/train_pupil_net.py --scale-above), so F
is chosen within 0.47-0.78 on held-out frames: per F, one `fovea-cli track --detector learned
--refine-scale-above F` run per seed on the wide domain's held-out subsets. Prints, per F and
subset, the share of centres within 5 px (PuRe's measure; a missed pupil counts as a miss), the
median centre error, and the closed eyes' false positives, from the runs' own summaries.

    scripts/refine-scale-sweep.py [--seed S ...] [--scale F ...] [--frames-per-subset N] [--work DIR] [--core C]

FOVEA_CLI overrides the fovea-cli (default build/default/app/fovea-cli), FOVEA_PUPIL_MODEL the
network. One core (taskset -c C, one OpenCV thread); about 2 minutes a run at 1000 frames a subset.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

SCALES = [0, 90 / 192, 105 / 192, 120 / 192, 135 / 192, 150 / 192]  # 0: a fixed 200 px canvas
SUBSETS = ["easy", "glints", "occlusion", "motion_blur", "off_axis", "partial", "hard"]


def track(cli, core, seed, frames, scale, path):
    if not os.path.exists(path):
        env = dict(os.environ, OPENCV_FOR_THREADS_NUM="1", OMP_NUM_THREADS="1")
        with open(path + ".part", "w") as out:
            subprocess.run(["taskset", "-c", str(core), cli, "track", "--virtual", str(frames * 8), "--domain", "wide",
                            "--seed", str(seed), "--detector", "learned", "--refine-scale-above", f"{scale:.6g}",
                            "--json"], stdout=out, env=env, check=True)
        os.replace(path + ".part", path)
    run = json.load(open(path))
    if abs(run.get("refine_scale_above", -1) - float(f"{scale:.6g}")) > 1e-9:
        sys.exit(f"refine-scale-sweep: {path} is not a run at --refine-scale-above {scale:.6g}")
    return {s["subset"]: s for s in run["summary"]["subsets"]}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--seed", type=int, action="append", help="held-out seed (repeatable; default 5)")
    ap.add_argument("--scale", type=float, action="append", help="F to run (repeatable; default 0 and T = 90-150 px)")
    ap.add_argument("--frames-per-subset", type=int, default=1000)
    ap.add_argument("--work", help="keep the runs' JSON here (reused when present)")
    ap.add_argument("--core", type=int, default=0, help="the CPU core to run on (default 0)")
    a = ap.parse_args()
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    cli = os.environ.get("FOVEA_CLI", os.path.join(root, "build/default/app/fovea-cli"))
    work = a.work or tempfile.mkdtemp(prefix="refine-scale-")
    os.makedirs(work, exist_ok=True)
    n = a.frames_per_subset
    for seed in a.seed or [5]:
        print(f"\nseed {seed}, {n} frames a subset: within 5 px / median centre error px")
        print("| F (T px) | " + " | ".join(SUBSETS) + " | closed FP |")
        print("| --- |" + " ---: |" * (len(SUBSETS) + 1))
        for f in a.scale or SCALES:
            subs = track(cli, a.core, seed, n, f, f"{work}/learned-s{seed}-n{n}-f{f:.6g}.json")
            cells = [f"{100 * subs[s]['detection_rate']:.1f} % / {subs[s]['centre_error_px_p50']:.2f}" for s in SUBSETS]
            name = "fixed canvas" if f == 0 else f"{f:.3f} ({192 * f:.0f})"
            print(f"| {name} | " + " | ".join(cells) + f" | {subs['closed']['false_positives']} |", flush=True)


if __name__ == "__main__":
    main()
