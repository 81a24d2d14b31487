"""The example study (docs/examples/python_study.py and the notebook made from it) runs and prints
the numbers fovea-cli gives for the same options (issue 32, item 3). Run by CTest with
PYTHONPATH=<build>/python and FOVEA_CLI_PATH, FOVEA_SOURCE_DIR, FOVEA_TEST_TMP set."""
import contextlib
import io
import json
import os
import re
import subprocess
import sys
import tempfile
import unittest

import numpy as np

CLI = os.environ["FOVEA_CLI_PATH"]
SOURCE = os.environ["FOVEA_SOURCE_DIR"]
TMP = os.environ.get("FOVEA_TEST_TMP", tempfile.gettempdir())
SCRIPT = os.path.join(SOURCE, "docs", "examples", "python_study.py")
NOTEBOOK = os.path.join(SOURCE, "docs", "examples", "python_study.ipynb")


def cli_json(*args):
    env = dict(os.environ, FOVEA_CACHE_DIR=os.path.join(TMP, "example-study-cache"))
    p = subprocess.run([CLI, *args, "--json"], capture_output=True, text=True, env=env, timeout=600, check=True)
    return json.loads(p.stdout)


def numbers(text):
    """The study's printed numbers by line prefix."""
    out = {}
    m = re.search(r"eye box ([\d.]+) mm; x_p\(20 deg\) = (-?[\d.]+) mm", text)
    out["eyebox_mm"], out["xp20_mm"] = float(m.group(1)), float(m.group(2))
    m = re.search(r"max \|Kogelnik - RCWA\| = ([\d.]+) over (\d+) gratings", text)
    out["max_k_minus_r"], out["gratings"] = float(m.group(1)), int(m.group(2))
    m = re.search(r"tolerance: yield ([\d.]+) % of (\d+) trials \(95 % interval ([\d.]+)-([\d.]+) % over (\d+)", text)
    out["yield_pct"], out["trials"] = float(m.group(1)), int(m.group(2))
    out["interval_pct"] = (float(m.group(3)), float(m.group(4)))
    out["independent_samples"] = int(m.group(5))
    return out


class ExampleStudyTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.out = os.path.join(TMP, "example-study")
        os.makedirs(cls.out, exist_ok=True)
        p = subprocess.run([sys.executable, SCRIPT, cls.out], capture_output=True, text=True, timeout=600)
        if p.returncode != 0:
            raise AssertionError(f"{SCRIPT}: exit {p.returncode}\n{p.stderr}")
        cls.printed = numbers(p.stdout)

    def test_sweep_numbers_are_the_clis(self):
        doc = cli_json("sweep", "", "--gaze-from", "-30", "--gaze-to", "30", "--gaze-step", "5")
        self.assertEqual(self.printed["eyebox_mm"], round(doc["eyebox_mm"], 3))
        xp20 = next(s["hoe_shift_mm"] for s in doc["samples"] if s["gaze_deg"] == 20)
        self.assertEqual(self.printed["xp20_mm"], round(xp20, 3))
        self.assertTrue(os.path.getsize(os.path.join(self.out, "sweep.png")) > 10000)

    def test_kogelnik_rcwa_map_is_the_clis(self):
        # The map's largest difference, point by point through one `fovea-cli grating --batch`
        # (JSON lines in, one result line per grating out; "model" per line).
        batch = os.path.join(TMP, "example-study-gratings.jsonl")
        with open(batch, "w") as f:
            for probe in np.linspace(-4, 4, 9):
                for wl in np.linspace(520, 545, 6):
                    g = dict(n0=1.5, n1=0.02, thickness_um=8.0, period_nm=177.333, slant_deg=0.0,
                             probe_deg=float(probe), wavelength_nm=float(wl))
                    f.write(json.dumps(g) + "\n" + json.dumps(dict(g, model="rcwa")) + "\n")
        p = subprocess.run([CLI, "grating", "--batch", batch], capture_output=True, text=True, timeout=600, check=True)
        rows = [json.loads(line) for line in p.stdout.splitlines()]
        self.assertEqual(len(rows), 108)
        worst = max(abs(k["efficiency"] - r["efficiency"]) for k, r in zip(rows[0::2], rows[1::2]))
        self.assertTrue(all(r["model"] == "rcwa" for r in rows[1::2]))
        self.assertEqual(self.printed["gratings"], 54)
        self.assertEqual(self.printed["max_k_minus_r"], round(worst, 4))
        self.assertTrue(os.path.getsize(os.path.join(self.out, "kogelnik_vs_rcwa.png")) > 5000)

    def test_tolerance_numbers_are_the_clis(self):
        spec = os.path.join(SOURCE, "resources", "tolerance", "prototype-tolerance.json")
        doc = cli_json("tolerance", "", "--spec", spec, "--trials", "100", "--seed", "1")
        y = doc["yield"]
        self.assertEqual(self.printed["trials"], 100)
        self.assertEqual(self.printed["yield_pct"], round(100 * y["value"], 1))
        self.assertEqual(self.printed["interval_pct"],
                         (round(100 * y["confidence_95"][0], 1), round(100 * y["confidence_95"][1], 1)))
        self.assertEqual(self.printed["independent_samples"], round(y["independent_samples"]))

    def test_the_notebook_is_the_script_and_runs(self):
        made = subprocess.run([sys.executable, os.path.join(SOURCE, "scripts", "make_example_notebook.py"), "--check"],
                              capture_output=True, text=True)
        self.assertEqual(made.returncode, 0, made.stderr)
        with open(NOTEBOOK, encoding="utf-8") as f:
            nb = json.load(f)
        cells = [c for c in nb["cells"] if c["cell_type"] == "code"]
        self.assertEqual(len(cells), 4)  # set-up and the three sections
        # Run the code cells in order in one namespace, as a kernel would (the kernel's own
        # arguments start with "-", so the study writes to the working directory).
        folder = os.path.join(TMP, "example-notebook")
        os.makedirs(folder, exist_ok=True)
        here, argv = os.getcwd(), sys.argv
        printed = io.StringIO()
        try:
            os.chdir(folder)
            sys.argv = ["ipykernel_launcher.py", "-f", "kernel.json"]
            namespace = {"__name__": "__main__"}
            with contextlib.redirect_stdout(printed), contextlib.redirect_stderr(io.StringIO()):
                for c in cells:
                    exec(compile("".join(c["source"]), NOTEBOOK, "exec"), namespace)
        finally:
            os.chdir(here)
            sys.argv = argv
        self.assertEqual(numbers(printed.getvalue()), self.printed)
        self.assertTrue(os.path.exists(os.path.join(folder, "sweep.png")))


if __name__ == "__main__":
    unittest.main()
