#!/usr/bin/env python3
"""An example study with the `fovea` module (docs/python.md): the x_p sweep and eye box, a
Kogelnik-vs-RCWA map over probe angle and wavelength, and a short tolerance run; each number is
the one `fovea-cli` gives for the same options (tests/python/tst_example_study.py holds it).
Writes PNGs to the folder given (default .).
  PYTHONPATH=build/default/python /usr/bin/python3 docs/examples/python_study.py /tmp/study
The notebook docs/examples/python_study.ipynb is made from this file, one cell per numbered
section: python3 scripts/make_example_notebook.py (--check: is it current?)."""
import os
import sys

import matplotlib

if "ipykernel" not in sys.modules:  # a script writes PNGs; a notebook shows the figures inline
    matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import fovea  # noqa: E402

# The output folder: the script's argument (a notebook's kernel arguments start with "-").
out = sys.argv[1] if len(sys.argv) > 1 and not sys.argv[1].startswith("-") else "."
os.makedirs(out, exist_ok=True)
scene = fovea.Scene.embedded()

# 1. HOE travel x_p and FOV against gaze
#    (= fovea-cli sweep "" --gaze-from -30 --gaze-to 30 --gaze-step 5 --json).
sweep = fovea.run("sweep", scene, gaze_from=-30, gaze_to=30, gaze_step=5,
                  progress=lambda f: print(f"\rsweep {100 * f:5.1f} %", end="", file=sys.stderr))
print(file=sys.stderr)
gaze = [s["gaze_deg"] for s in sweep["samples"]]
fig, ax = plt.subplots(1, 2, figsize=(10, 4))
ax[0].plot(gaze, [s["hoe_shift_mm"] for s in sweep["samples"]], "o-")
ax[0].set(xlabel="gaze yaw (deg)", ylabel="HOE shift x_p (mm)", title=f"x_p rule {sweep['xp_rule']}")
ax[1].plot(gaze, [s["fov_deg"]["horizontal"] for s in sweep["samples"]], "o-", label="horizontal")
ax[1].plot(gaze, [s["fov_deg"]["vertical"] for s in sweep["samples"]], "s-", label="vertical")
ax[1].set(xlabel="gaze yaw (deg)", ylabel="FOV (deg)", title=f"eye box {sweep['eyebox_mm']:.2f} mm")
ax[1].legend()
fig.tight_layout()
fig.savefig(os.path.join(out, "sweep.png"), dpi=110)
print(f"eye box {sweep['eyebox_mm']:.3f} mm; x_p(20 deg) = "
      f"{next(s['hoe_shift_mm'] for s in sweep['samples'] if s['gaze_deg'] == 20):.3f} mm")

# 2. Kogelnik vs RCWA for a green reflection grating over probe angle and wavelength
#    (= fovea-cli grating --model rcwa, one grating at a time).
probe = np.linspace(-4, 4, 9)[:, None]
wl = np.linspace(520, 545, 6)[None, :]
grating = dict(n0=1.5, n1=0.02, thickness_um=8.0, period_nm=177.333, slant_deg=0.0)
k = fovea.kogelnik(**grating, probe_deg=probe, wavelength_nm=wl)["efficiency"]
r = fovea.rcwa(**grating, probe_deg=probe, wavelength_nm=wl)["efficiency"]
fig, ax = plt.subplots(figsize=(5, 4))
im = ax.imshow(k - r, origin="lower", aspect="auto", extent=[520, 545, -4, 4], cmap="RdBu")
ax.set(xlabel="wavelength (nm)", ylabel="probe angle (deg)", title="Kogelnik - RCWA efficiency")
fig.colorbar(im)
fig.savefig(os.path.join(out, "kogelnik_vs_rcwa.png"), dpi=110)
print(f"max |Kogelnik - RCWA| = {np.max(np.abs(k - r)):.4f} over {k.size} gratings")

# 3. A short tolerance run with the built-in prototype spec (= fovea-cli tolerance "" --spec
#    resources/tolerance/prototype-tolerance.json --trials 100 --seed 1 --json). 100 trials hold few independent samples (Saltelli
#    blocks; the run prints how many), so the interval is wide; docs/tolerancing.md runs 1000.
tol = fovea.run("tolerance", scene, trials=100, seed=1)
y = tol["yield"]
lo, hi = y["confidence_95"]
print(f"tolerance: yield {100 * y['value']:.1f} % of {tol['trials']} trials "
      f"(95 % interval {100 * lo:.1f}-{100 * hi:.1f} % over {y['independent_samples']:.0f} independent samples)")
