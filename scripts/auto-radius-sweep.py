#!/usr/bin/python3
"""Chooses the auto pupil detector's acceptance radius (model/gaze/pupil_detector_choice.h).

Auto takes the classical fit near the learned centre when the fit's centre lies within a radius
of it. The radius is swept offline from two runs per seed on the wide domain's held-out subsets:
`fovea-cli track --detector learned` (the proposals) and `--detector auto --auto-radius-px 1e9`
(every classical fit the window around a proposal gives). For a rule r(d) auto's centre is the
fit when it moved <= r(d), d the proposal's major axis, else the proposal: the C++ rule, applied
to the same frames. Prints, per rule and subset, the share of centres within 5 px (PuRe's
measure, over frames with a visible pupil, a missed pupil counting as a miss) and the median
centre error of the frames found.

    scripts/auto-radius-sweep.py [--seed S ...] [--frames-per-subset N] [--work DIR] [--core C]

FOVEA_CLI overrides the fovea-cli (default build/default/app/fovea-cli), FOVEA_PUPIL_MODEL the
network. One core (taskset -c C, one OpenCV thread); about 4 minutes a seed at 1000 frames a subset.
"""
import math
import sys

import held_out_runs

# (px, diameters): radius max(px, diameters * d). The shipped rule is (2, 0); (2, 0.1) was the
# rule before 2026-12-06 (seventh session).
RULES = [(0, 0), (1, 0), (1.5, 0), (2, 0), (3, 0), (2, 0.02), (2, 0.05), (2, 0.1), (3, 0.15)]
SUBSETS = ["easy", "glints", "occlusion", "motion_blur", "off_axis", "partial", "hard"]


def sweep(learned, fits):
    """{(rule, subset): (within 5 px share, median error px)}."""
    if len(learned) != len(fits):
        sys.exit("auto-radius-sweep: the two runs have different frames")
    table = {}
    for px, frac in RULES:
        for sub in SUBSETS:
            n = ok = 0
            errs = []
            for lf, af in zip(learned, fits):
                if lf["subset"] != sub or not lf["truth"]["pupil_visible"]:
                    continue
                n += 1
                if not lf["found"]:
                    continue
                centre = lf["centre_px"]
                if af["found"]:
                    moved = math.dist(af["centre_px"], lf["centre_px"])
                    if moved <= max(px, frac * max(lf["ellipse"]["major_px"], 1.0)):
                        centre = af["centre_px"]
                e = math.dist(centre, lf["truth"]["centre_px"])
                errs.append(e)
                ok += e <= 5
            errs.sort()
            table[(px, frac), sub] = (ok / n if n else float("nan"), errs[len(errs) // 2] if errs else float("nan"))
    return table


def main():
    a, cli, work = held_out_runs.parse_args(__doc__, "auto-radius-")
    for seed in a.seed or [5]:
        n = a.frames_per_subset
        learned = held_out_runs.track(cli, a.core, seed, n, ["--detector", "learned"],
                                      f"{work}/learned-s{seed}-n{n}.json")["frames"]
        fits = held_out_runs.track(cli, a.core, seed, n, ["--detector", "auto", "--auto-radius-px", "1e9"],
                                   f"{work}/fits-s{seed}-n{n}.json")["frames"]
        table = sweep(learned, fits)
        print(f"\nseed {seed}, {n} frames a subset: within 5 px / median centre error px")
        print("| radius | " + " | ".join(SUBSETS) + " |")
        print("| --- |" + " ---: |" * len(SUBSETS))
        for rule in RULES:
            name = "learned alone" if rule == (0, 0) else (f"{rule[0]:g} px" if rule[1] == 0 else
                                                           f"max({rule[0]:g} px, {rule[1]:g} d)")
            cells = [f"{100 * table[rule, s][0]:.1f} % / {table[rule, s][1]:.2f}" for s in SUBSETS]
            print(f"| {name} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
