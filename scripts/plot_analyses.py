#!/usr/bin/python3
"""Plots the key design curves of docs/analyses.md from fovea-cli JSON.

Usage: scripts/plot_analyses.py [--cli build/default/app/fovea-cli] [--scene FILE] [--out docs/img]
       [--rays N]

Writes resolution_vs_eccentricity.png, fov_vs_gaze.png, travel_vs_gaze.png and the
gaze studies' raw JSON (gaze_studies.json). Needs python3-matplotlib (scripts/install-deps.sh);
uses the system interpreter because that is where Debian installs matplotlib.
"""
import argparse
import json
import os
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def run(cli, args):
    proc = subprocess.run([cli] + args + ["--json"], capture_output=True, text=True)
    if proc.returncode != 0:
        raise RuntimeError(f"fovea-cli {' '.join(args)} failed ({proc.returncode}): {proc.stderr.strip()}")
    return json.loads(proc.stdout)


def plot_resolution(cli, scene, out):
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5), sharey=True)
    for ax, gaze in zip(axes, (0, 15)):
        r = run(cli, ["resolution"] + scene + ["--gaze-deg", str(gaze)])
        ecc = [s["eccentricity_deg"] for s in r["samples"]]
        def col(key):
            return [s[key] if s[key] is not None else float("nan") for s in r["samples"]]
        ax.plot(ecc, col("peripheral_cpd"), label="peripheral display c_p")
        ax.plot(ecc, col("foveal_cpd"), label="foveal display c_f")
        ax.plot(ecc, col("optical_limit_cpd"), "--", label="combiner MTF30 (ray traced)")
        ax.plot(ecc, col("optical_limit_model_cpd"), ":", label="combiner MTF30 (scene model)")
        ax.plot(ecc, col("perceived_cpd"), "k", lw=2, label="perceived")
        ax.axhline(r["eye_limit_cpd"], color="grey", lw=0.8)
        ax.set_title(f"gaze {gaze} deg: {r['peripheral_pixel_integral']:.0f} of {r['pixels_horizontal']} projector columns on the HOE")
        ax.set_xlabel("eccentricity (deg)")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("angular resolution (cycles/deg)")
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "resolution_vs_eccentricity.png"), dpi=110)
    plt.close(fig)


def plot_sweeps(cli, scene, out, rays):
    extra = ["--rays", str(rays)] if rays else []
    data = {}
    for axis, lo, hi in (("yaw", -45, 45), ("pitch", -35, 35)):
        data[axis] = run(cli, ["sweep"] + scene + ["--gaze-from", str(lo), "--gaze-to", str(hi), "--gaze-step", "2.5",
                                                    "--axis", axis] + extra)
    methods = {m: run(cli, ["sweep"] + scene + ["--gaze-from", "-30", "--gaze-to", "30", "--gaze-step", "2.5",
                                                 "--method", m] + extra) for m in ("source",)}
    compare = run(cli, ["compare-shift"] + scene + extra)
    with open(os.path.join(out, "gaze_studies.json"), "w") as f:
        json.dump({"sweep": data, "source_sweep_yaw": methods["source"], "compare_shift": compare}, f, indent=1)

    fig, ax = plt.subplots(figsize=(8, 5))
    for axis, d in data.items():
        key = "horizontal" if axis == "yaw" else "vertical"
        g = [s["gaze_deg"] for s in d["samples"]]
        ax.plot(g, [s["fov_deg"][key] for s in d["samples"]], "o-", ms=3,
                label=f"{axis}, HOE shift: {key} FOV (eye box {d['eyebox_mm']:.1f} mm)")
        lo, hi = d["eyebox"]["gaze_range_deg"]
        ax.axvspan(lo, hi, alpha=0.06, color="C0" if axis == "yaw" else "C1")
    d = methods["source"]
    ax.plot([s["gaze_deg"] for s in d["samples"]], [s["fov_deg"]["horizontal"] for s in d["samples"]], "^:", ms=3,
            label=f"yaw, source shift: horizontal FOV (eye box {d['eyebox_mm']:.1f} mm)")
    ax.axhline(data["yaw"]["eyebox"]["reference_fov_deg"] - 3.0, color="grey", lw=0.8, ls="--")
    ax.set_xlabel("gaze angle (deg)")
    ax.set_ylabel("continuous FOV (deg)")
    ax.set_title("FOV vs gaze with the optimal shift (shaded: eye box; dashed: zero-gaze FOV - 3 deg)")
    ax.title.set_fontsize(9)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fov_vs_gaze.png"), dpi=110)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(8, 5))
    for axis, d in data.items():
        g = [s["gaze_deg"] for s in d["samples"]]
        ax.plot(g, [s["hoe_shift_mm"] for s in d["samples"]], "o-", ms=3, label=f"HOE shift x_p ({axis})")
        ax.fill_between(g, [s["shift_plateau_mm"][0] for s in d["samples"]],
                        [s["shift_plateau_mm"][1] for s in d["samples"]], alpha=0.12,
                        label=f"shifts within 5 deg of the best FOV ({axis})")
        ax.plot(g, [s["pupil_position_mm"] for s in d["samples"]], ":", label=f"pupil centre ({axis})")
    d = methods["source"]
    # No light in the pupil anywhere in the bracket: no travel to speak of.
    ax.plot([s["gaze_deg"] for s in d["samples"]],
            [s["source_shift_mm"] if s["best_fov_deg"] > 0 else float("nan") for s in d["samples"]], "^--", ms=3,
            label="point-source shift z_s (yaw)")
    ax.set_xlabel("gaze angle (deg)")
    ax.set_ylabel("mm")
    ax.set_title("Required travel vs gaze")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "travel_vs_gaze.png"), dpi=110)
    plt.close(fig)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    root = os.path.dirname(here)
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--cli", default=os.path.join(root, "build/default/app/fovea-cli"))
    p.add_argument("--scene", default="", help="scene file (default: the embedded prototype bench)")
    p.add_argument("--out", default=os.path.join(root, "docs/img"))
    p.add_argument("--rays", type=int, default=0, help="rays per wavelength (default: the CLI's, 12000)")
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    scene = [a.scene] if a.scene else []
    plot_resolution(a.cli, scene, a.out)
    print("wrote resolution_vs_eccentricity.png")
    try:
        plot_sweeps(a.cli, scene, a.out, a.rays)
        print("wrote fov_vs_gaze.png, travel_vs_gaze.png")
    except RuntimeError as e:
        print(f"skipped the gaze sweeps: {e}", file=sys.stderr)
        return 3
    return 0


if __name__ == "__main__":
    sys.exit(main())
