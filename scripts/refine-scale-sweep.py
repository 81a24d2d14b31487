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
import sys

import held_out_runs

SCALES = [0, 90 / 192, 105 / 192, 120 / 192, 135 / 192, 150 / 192]  # 0: a fixed 200 px canvas
SUBSETS = ["easy", "glints", "occlusion", "motion_blur", "off_axis", "partial", "hard"]


def subsets(cli, core, seed, frames, scale, path):
    """Per subset, the summary of a `--detector learned --refine-scale-above F` run."""
    run = held_out_runs.track(cli, core, seed, frames, ["--detector", "learned", "--refine-scale-above", f"{scale:.6g}"],
                              path)
    if abs(run.get("refine_scale_above", -1) - float(f"{scale:.6g}")) > 1e-9:
        sys.exit(f"refine-scale-sweep: {path} is not a run at --refine-scale-above {scale:.6g}")
    return {s["subset"]: s for s in run["summary"]["subsets"]}


def main():
    a, cli, work = held_out_runs.parse_args(__doc__, "refine-scale-", lambda ap: ap.add_argument(
        "--scale", type=float, action="append", help="F to run (repeatable; default 0 and T = 90-150 px)"))
    n = a.frames_per_subset
    for seed in a.seed or [5]:
        print(f"\nseed {seed}, {n} frames a subset: within 5 px / median centre error px")
        print("| F (T px) | " + " | ".join(SUBSETS) + " | closed FP |")
        print("| --- |" + " ---: |" * (len(SUBSETS) + 1))
        for f in a.scale or SCALES:
            subs = subsets(cli, a.core, seed, n, f, f"{work}/learned-s{seed}-n{n}-f{f:.6g}.json")
            cells = [f"{100 * subs[s]['detection_rate']:.1f} % / {subs[s]['centre_error_px_p50']:.2f}" for s in SUBSETS]
            name = "fixed canvas" if f == 0 else f"{f:.3f} ({192 * f:.0f})"
            print(f"| {name} | " + " | ".join(cells) + f" | {subs['closed']['false_positives']} |", flush=True)


if __name__ == "__main__":
    main()
