#!/usr/bin/env bash
# The pupil detectors' benchmark table of docs/gaze-tracking.md: each detector on the wide
# domain's held-out subsets (fovea-cli track --virtual N --domain wide --seed 2026), one core
# (OMP/OpenCV threads 1), printed as a Markdown table. Rates: within 5 px of the true centre
# over the frames with a visible pupil; centre-error percentiles count a missed pupil as
# infinite ("-" when more than that share is missed); FP: closed-eye frames with a pupil.
#   scripts/pupil-benchmark.sh [FRAMES_PER_SUBSET (default 50)] [DETECTORS (default "classical learned auto")]
set -euo pipefail
cd "$(dirname "$0")/.."
N=${1:-50}
DETECTORS=${2:-classical learned auto}
CLI=${FOVEA_CLI:-build/default/app/fovea-cli}
out=$(mktemp -d)
for d in $DETECTORS; do
  OPENCV_FOR_THREADS_NUM=1 OMP_NUM_THREADS=1 nice -n 10 taskset -c 0 "$CLI" track --virtual $((N * 8)) --domain wide --seed 2026 \
    --detector "$d" --json > "$out/$d.json"
done
/usr/bin/python3 - "$out" $DETECTORS <<'PY'
import json, sys
out, dets = sys.argv[1], sys.argv[2:]
f = lambda x, fmt="%.2f": "-" if x is None else fmt % x
print("| subset | detector | frames | within 5 px | p50 px | p90 px | p95 px | closed FP | ms/frame |")
print("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
runs = {d: json.load(open(f"{out}/{d}.json")) for d in dets}
order = ["easy", "glints", "occlusion", "motion_blur", "off_axis", "partial", "hard", "closed"]
for name in order:
    for d in dets:
        s = next(x for x in runs[d]["summary"]["subsets"] if x["subset"] == name)
        if name == "closed":
            print(f"| {name} | {d} | {s['frames']} | | | | | {s['false_positives']}/{s['frames']} | {s['mean_time_ms']:.2f} |")
        else:
            print(f"| {name} | {d} | {s['with_pupil']} | {100 * s['detection_rate']:.1f} % | {f(s['centre_error_px_p50'])} "
                  f"| {f(s['centre_error_px_p90'])} | {f(s['centre_error_px_p95'])} | | {s['mean_time_ms']:.2f} |")
PY
rm -rf "$out"
