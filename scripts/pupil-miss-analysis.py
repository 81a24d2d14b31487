#!/usr/bin/python3
"""Where a pupil detector misses on the wide domain: reads `fovea-cli track ... --json` and prints,
per subset, the misses at 5 px (PuRe's measure, over frames with a visible pupil) split into
pupils not found and centres found but off, those off mostly vertically (|dy| > |dx|: the lid's
direction) or horizontally, and the share within 5 px by the true pupil's major axis.
docs/gaze-tracking.md quotes these for the hard, occlusion and partial subsets at seed 2026.

    scripts/pupil-miss-analysis.py TRACK.json [--subset NAME ...]

For example: build/default/app/fovea-cli track --virtual 8000 --domain wide --seed 2026
--detector learned --json > t.json; scripts/pupil-miss-analysis.py t.json --subset hard.
"""
import argparse
import json
import sys

MAJOR_BINS_PX = [(0, 60), (60, 100), (100, 140), (140, float("inf"))]


def analyse(frames, subset):
    visible = [f for f in frames if f["subset"] == subset and f["truth"]["pupil_visible"]]
    if not visible:
        return None
    not_found = [f for f in visible if not f["found"]]
    off = [f for f in visible if f["found"] and not f["error"]["within_5px"]]
    vertical = 0
    for f in off:
        dx = f["centre_px"][0] - f["truth"]["centre_px"][0]
        dy = f["centre_px"][1] - f["truth"]["centre_px"][1]
        vertical += abs(dy) > abs(dx)
    bins = []
    for lo, hi in MAJOR_BINS_PX:
        b = [f for f in visible if lo <= f["truth"]["ellipse"]["major_px"] < hi]
        if b:
            within = sum(1 for f in b if f["found"] and f["error"]["within_5px"])
            bins.append((lo, hi, len(b), within))
    return {"frames": len(visible), "not_found": len(not_found), "off": len(off), "vertical": vertical,
            "bins": bins}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("track_json")
    ap.add_argument("--subset", action="append", help="a subset (repeatable; default every one with a pupil)")
    args = ap.parse_args()
    try:
        with open(args.track_json) as fh:
            run = json.load(fh)
        frames = run["frames"]
    except (OSError, ValueError, KeyError, TypeError) as e:
        sys.exit(f"pupil-miss-analysis: {args.track_json}: not a fovea-cli track --json output ({e})")
    subsets = args.subset or sorted({f["subset"] for f in frames if f["truth"]["pupil_visible"]})
    summary = {x["subset"]: x for x in run.get("summary", {}).get("subsets", [])}
    print(f"{args.track_json}: detector {run.get('detector')}, seed {run.get('seed')}")
    for name in subsets:
        r = analyse(frames, name)
        if r is None:
            print(f"{name}: no frames with a visible pupil")
            continue
        misses = r["not_found"] + r["off"]
        # The same criterion as the CLI's summary (its detection_rate over the same frames): a
        # mismatch means this script and the C++ benchmark count misses differently.
        if name in summary and "detection_rate" in summary[name]:
            expected = round(summary[name]["detection_rate"] * r["frames"])
            if expected != r["frames"] - misses:
                sys.exit(f"pupil-miss-analysis: {name}: {r['frames'] - misses} within 5 px here, "
                         f"{expected} by the run's summary")
        print(f"{name}: {misses} misses at 5 px of {r['frames']}: {r['not_found']} not found, {r['off']} found "
              f"but off ({r['vertical']} vertically, {r['off'] - r['vertical']} horizontally)")
        for lo, hi, n, within in r["bins"]:
            upper = "up" if hi == float("inf") else f"{hi:.0f}"
            print(f"  major {lo:.0f}-{upper} px: {n} frames, {100.0 * within / n:.1f} % within 5 px")


if __name__ == "__main__":
    main()
