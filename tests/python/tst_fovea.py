"""The `fovea` Python module (app/python) against fovea-cli: the same documents, the same
errors, the NumPy batch equal to the scalar answers. Run by CTest (label "python") with
PYTHONPATH=<build>/python and FOVEA_CLI_PATH, FOVEA_SOURCE_DIR, FOVEA_TEST_TMP set."""
import json
import math
import os
import subprocess
import tempfile
import threading
import unittest

import numpy as np

import fovea

CLI = os.environ["FOVEA_CLI_PATH"]
SOURCE = os.environ["FOVEA_SOURCE_DIR"]
TMP = os.environ.get("FOVEA_TEST_TMP", tempfile.gettempdir())


def cli(*args, code=0):
    """Runs fovea-cli; returns (stdout, stderr) after checking the exit code."""
    env = dict(os.environ, FOVEA_CACHE_DIR=os.path.join(TMP, "python-cache"))
    p = subprocess.run([CLI, *args], capture_output=True, text=True, env=env, timeout=600)
    if p.returncode != code:
        raise AssertionError(f"fovea-cli {' '.join(args)}: exit {p.returncode} (want {code})\n{p.stderr}")
    return p.stdout, p.stderr


def cli_json(*args):
    doc = json.loads(cli(*args, "--json")[0])
    doc.pop("cached", None)  # the CLI's study cache says whether it computed; not the result
    return doc


def canonical(doc):
    return json.dumps(doc, sort_keys=True)


class SceneTest(unittest.TestCase):
    def test_embedded_is_the_prototype(self):
        s = fovea.Scene.embedded()
        self.assertEqual(s["eye.relief_mm"], 22.0)
        self.assertEqual(s["projector.pixels[0]"], 1280)
        self.assertIsInstance(s["projector.pixels[0]"], int)
        self.assertEqual(s.validate(), [])
        self.assertIn("3 HOE layers", s.summary())

    def test_refused_value_has_the_validators_message_and_changes_nothing(self):
        s = fovea.Scene.embedded()
        before = s.to_json()
        with self.assertRaises(ValueError) as e:
            s["hoe_layers[0].n1"] = 1.6  # the file's first "n1" below
        self.assertEqual(s.to_json(), before)
        # The same words as `fovea-cli validate` on a file holding that value (minus "FILE: ").
        path = os.path.join(TMP, "python-bad-n1.json")
        with open(path, "w") as f:
            f.write(before.replace('"n1": 0.015', '"n1": 1.6', 1))
        out, _ = cli("validate", path, code=1)
        name = os.path.basename(path)  # the reader names a file by its name
        cli_lines = [line.split(": ", 1)[1] for line in out.splitlines() if line.startswith(name + ":")]
        self.assertEqual(len(cli_lines), 1)
        self.assertEqual(str(e.exception).splitlines(), cli_lines)
        with self.assertRaises(KeyError):
            s["eye.no_such_field"] = 1.0
        with self.assertRaises(ValueError):
            s["projector.pixels[0]"] = 12.5  # an integer field

    def test_save_load_round_trip(self):
        s = fovea.Scene.embedded()
        s["eye.relief_mm"] = 23.5
        path = os.path.join(TMP, "python-scene.json")
        s.save(path)
        again = fovea.Scene.load(path)
        self.assertEqual(again["eye.relief_mm"], 23.5)
        self.assertEqual(again.to_json(), s.to_json())
        with open(path) as f:
            self.assertEqual(f.read(), s.to_json())

    def test_unreadable_scene_is_a_value_error_naming_it(self):
        path = os.path.join(TMP, "python-malformed.json")
        with open(path, "w") as f:
            f.write("{ not json")
        with self.assertRaises(ValueError) as e:
            fovea.Scene.load(path)
        out, err = cli("validate", path, code=1)
        self.assertTrue(str(e.exception).startswith("python-malformed.json: malformed JSON at line 1"))
        self.assertIn(str(e.exception).splitlines()[0], out + err)


class AnalysesTest(unittest.TestCase):
    """Every registry analysis with fovea-cli options generated from the registry, with small
    settings, gives through Python the document `fovea-cli ... --json` prints."""

    CASES = {
        "trace": ({"gaze_yaw": 10.0, "gaze_pitch": 0.0, "rays": 1500},
                  ["--gaze-deg", "10,0", "--rays", "1500"]),
        "sweep": ({"gaze_from": -10.0, "gaze_to": 10.0, "gaze_step": 10.0, "rays": 1000},
                  ["--gaze-from", "-10", "--gaze-to", "10", "--gaze-step", "10", "--rays", "1000", "--no-cache"]),
        "compare-shift": ({"gaze_from": 0.0, "gaze_to": 10.0, "gaze_step": 10.0, "rays": 1000},
                          ["--gaze-from", "0", "--gaze-to", "10", "--gaze-step", "10", "--rays", "1000",
                           "--no-cache"]),
        "sensitivity": ({"parameter": "eye.relief_mm", "from": 20.0, "to": 24.0, "steps": 2, "rays": 1000},
                        ["--parameter", "eye.relief_mm", "--from", "20", "--to", "24", "--steps", "2", "--rays",
                         "1000", "--no-cache"]),
        "resolution": ({"samples": 61}, ["--samples", "61"]),
        "selectivity": ({"samples": 51}, ["--samples", "51"]),
        "optimize-lens": ({"starts": 1}, ["--starts", "1", "--no-cache"]),
    }

    # The analyses whose fovea-cli command is written by hand, each compared in its own test below.
    HAND_WRITTEN = {"tolerance": "test_tolerance_equals_the_cli", "grating": "test_grating_sweep_equals_the_cli",
                    "kogelnik-vs-rcwa": "test_kogelnik_vs_rcwa_equals_bench_quick",
                    "fit": "test_fit_equals_the_cli"}

    def test_every_generated_analysis_is_covered(self):
        generated = {k for k, v in fovea.analyses().items() if v["cli_generated"]}
        self.assertEqual(generated, set(self.CASES))

    def test_every_analysis_is_compared_with_the_cli(self):
        # A new analysis is either generated (CASES) or named here with the test that compares it.
        analyses = fovea.analyses()
        self.assertEqual(set(analyses), set(self.CASES) | set(self.HAND_WRITTEN))
        self.assertFalse(set(self.CASES) & set(self.HAND_WRITTEN))
        for analysis, test in self.HAND_WRITTEN.items():
            self.assertFalse(analyses[analysis]["cli_generated"], analysis)
            self.assertTrue(callable(getattr(self, test, None)), test)

    def test_python_equals_the_cli(self):
        scene = fovea.Scene.embedded()
        for analysis, (kwargs, flags) in self.CASES.items():
            with self.subTest(analysis=analysis):
                py = fovea.run(analysis, scene, **kwargs)
                py.pop("cached", None)
                doc = cli_json(analysis, "", *flags)
                if isinstance(doc, list):  # trace prints a list only for several gazes
                    doc = doc[0]
                self.assertEqual(canonical(py), canonical(doc))

    def test_trace_arrays_match_its_document(self):
        scene = fovea.Scene.embedded()
        r = fovea.trace(scene, gaze_deg=(10.0, 0.0), hoe_shift_mm=(1.5, 0.0), rays=1500)
        doc = cli_json("trace", "", "--gaze-deg", "10,0", "--hoe-shift-mm", "1.5,0", "--rays", "1500")
        a = r.pop("ray_arrays")
        self.assertEqual(canonical(r), canonical(doc))
        n = len(a["efficiency"])
        self.assertEqual(a["source_mm"].shape, (n, 3))
        self.assertEqual(a["field_deg"].shape, (n, 2))
        self.assertEqual(int(a["in_pupil"].sum()), doc["rays_in_pupil"])
        self.assertTrue(np.allclose(np.linalg.norm(a["out_direction"][a["hits_hoe"]], axis=1), 1.0, atol=1e-12)
                        or not a["hits_hoe"].any())
        # Zero-copy: every array is a strided view of the same ray records, kept alive by the views
        # themselves (the rest of the result dropped and collected).
        self.assertTrue(np.may_share_memory(a["source_mm"], a["in_pupil"]))
        self.assertIsNotNone(a["efficiency"].base)
        copy = a["efficiency"].copy()
        eff = a["efficiency"]
        del a, r
        import gc
        gc.collect()
        self.assertTrue(np.array_equal(eff, copy))
        self.assertTrue(np.all((eff >= 0) & (eff <= 1)))

    def test_tolerance_equals_the_cli(self):
        # tolerance has its own CLI options (--spec required); with the same spec, trials and seed
        # the Python run and `fovea-cli tolerance` give the same document.
        scene = fovea.Scene.embedded()
        spec = os.path.join(SOURCE, "resources", "tolerance", "prototype-tolerance.json")
        py = fovea.run("tolerance", scene, spec=spec, trials=12, seed=3)
        doc = cli_json("tolerance", "", "--spec", spec, "--trials", "12", "--seed", "3")
        self.assertEqual(doc["trials"], 12)
        self.assertEqual(canonical(py), canonical(doc))

    def test_grating_sweep_equals_the_cli(self):
        # The studio's probe-angle sweep of one grating: its "center" is the document of
        # `fovea-cli grating --json` for the same grating, each sample the answer of
        # `fovea-cli grating --model rcwa` (which carries Kogelnik's numbers too) at that probe angle.
        grating = {"n0": 1.52, "n1": 0.015, "thickness_um": 12.0, "period_nm": 350.0, "slant_deg": 30.0,
                   "probe_deg": 5.0, "wavelength_nm": 532.0, "polarization": "p", "absorption_per_mm": 0.1}
        span, samples = 4.0, 9
        py = fovea.run("grating", fovea.Scene.embedded(), span_deg=span, samples=samples, model="kogelnik+rcwa",
                       **grating)
        flags = []
        for k, v in grating.items():
            flags += ["--" + k.replace("_", "-"), str(v)]
        centre = grating["probe_deg"]
        probes = [centre - span + 2.0 * span * i / (samples - 1) for i in range(samples)]
        lines = "".join(json.dumps(dict(grating, probe_deg=p)) + "\n" for p in probes)
        path = os.path.join(TMP, "python-grating-sweep.jsonl")
        with open(path, "w") as f:
            f.write(lines)
        answers = [json.loads(line) for line in cli("grating", "--batch", path, "--model", "rcwa")[0].splitlines()]
        self.assertEqual(len(answers), samples)
        want = {"center": json.loads(cli("grating", *flags, "--json")[0]), "models": ["kogelnik", "rcwa"],
                "samples": [{"probe_deg": p, "detuning_deg": p - centre, "kogelnik_efficiency":
                             a["kogelnik_efficiency"], "xi": a["xi"], "nu": a["nu"], "rcwa_efficiency":
                             a["efficiency"], "rcwa_converged": a["rcwa"]["converged"]}
                            for p, a in zip(probes, answers)]}
        self.assertEqual(want["center"]["polarization"], "p")
        for s in want["samples"]:
            self.assertTrue(s["rcwa_converged"])
            self.assertTrue(0.0 < s["kogelnik_efficiency"] < 1.0)
            self.assertLess(abs(s["rcwa_efficiency"] - s["kogelnik_efficiency"]), 0.1)
        self.assertEqual(canonical(py), canonical(want))

    def test_kogelnik_vs_rcwa_equals_bench_quick(self):
        # The "quick" grid is the one of `fovea-cli bench --quick`, whose kogelnik_vs_rcwa section
        # summarises it by rho decade under other key names (docs/benchmarks.md). Every number but
        # the run times (mean Kogelnik ns, mean RCWA ms: measured anew by each run) is the same.
        py = fovea.run("kogelnik-vs-rcwa", fovea.Scene.embedded(), grid="quick")
        bench = json.loads(cli("bench", "--quick", "--json")[0])["kogelnik_vs_rcwa"]
        self.assertEqual(py["grid"], "quick")
        self.assertEqual(len(py["points"]), bench["points"])
        self.assertEqual(bench["points"], 24)
        names = {"rho_min": "rho_min", "rho_max": "rho_max", "points": "points", "max_error": "max_abs_error",
                 "median_error": "median_abs_error", "max_error_weak": "max_abs_error_nu_le_half_pi"}
        mine = [{names[k]: v for k, v in row.items() if k in names} for row in py["by_rho"]]
        theirs = [{k: v for k, v in row.items() if k in names.values()} for row in bench["by_rho"]]
        self.assertEqual(canonical(mine), canonical(theirs))
        for row in py["by_rho"]:  # timings: present and numbers; their values belong to benchmarks/
            self.assertIsInstance(row["mean_kogelnik_ns"], (int, float))
            self.assertIsInstance(row["mean_rcwa_ms"], (int, float))
        # The summary from the points themselves: the bench's numbers are those of these points.
        errors = sorted(p["abs_error"] for p in py["points"])
        self.assertEqual(max(r["max_abs_error"] for r in bench["by_rho"]), errors[-1])
        self.assertEqual(sum(r["points"] for r in bench["by_rho"]), len(errors))

    def test_fit_equals_the_cli(self):
        # One free parameter against two of the seed's simulated targets, two starts (the second
        # random, by the seed) and a small evaluation budget: the document of `fovea-cli fit --json`.
        scene = fovea.Scene.embedded()
        targets = os.path.join(SOURCE, "resources", "seed", "seed-targets.json")
        select = "sim-fov-h-0,sim-xp-0"
        py = fovea.run("fit", scene, targets=targets, free="eye.relief_mm", targets_select=select, starts=2, seed=4,
                       max_evals=12)
        doc = cli_json("fit", "", "--targets", targets, "--free", "eye.relief_mm", "--targets-select", select,
                       "--starts", "2", "--seed", "4", "--max-evals", "12")
        self.assertEqual([t["id"] for t in doc["targets"]], ["sim-fov-h-0", "sim-xp-0"])
        self.assertEqual(len(doc["start_results"]), 2)
        self.assertEqual(doc["evaluations"], sum(r["evaluations"] for r in doc["start_results"]))
        self.assertLess(doc["chi2"], doc["chi2_initial"])
        self.assertEqual(canonical(py), canonical(doc))

    def test_refused_parameter_has_the_cli_message(self):
        scene = fovea.Scene.embedded()
        with self.assertRaises(ValueError) as e:
            fovea.run("sweep", scene, gaze_step=0.0)
        _, err = cli("sweep", "", "--gaze-step", "0", "--json", code=2)
        self.assertIn(str(e.exception), err)
        with self.assertRaises(ValueError):
            fovea.run("no-such-analysis", scene)

    def test_progress_and_cancellation(self):
        scene = fovea.Scene.embedded()
        seen = []
        fovea.run("sweep", scene, gaze_from=0.0, gaze_to=10.0, gaze_step=5.0, rays=500, tolerance_deg=0.41,
                  progress=seen.append)
        self.assertEqual(seen[-1], 1.0)
        self.assertEqual(seen, sorted(seen))

        # An exception from the callback (as Ctrl-C raises KeyboardInterrupt in it) stops the
        # study: 161 gazes would take minutes; the first progress report ends it.
        def interrupt(_):
            raise KeyboardInterrupt

        with self.assertRaises(KeyboardInterrupt):
            fovea.run("sweep", scene, gaze_from=-40.0, gaze_to=40.0, gaze_step=0.5, rays=500, tolerance_deg=0.43,
                      progress=interrupt)

    def test_threads_run_studies_side_by_side(self):
        scene = fovea.Scene.embedded()
        results = [None, None]

        def work(i):
            results[i] = fovea.trace(scene, gaze_deg=(5.0 * i, 0.0), rays=800)["fov_deg"]

        threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        for i in range(2):
            self.assertEqual(results[i], fovea.trace(scene, gaze_deg=(5.0 * i, 0.0), rays=800)["fov_deg"])


class GratingTest(unittest.TestCase):
    def random_gratings(self, n, seed=7):
        rng = np.random.default_rng(seed)
        return dict(n0=rng.uniform(1.45, 1.6, n), n1=rng.uniform(0.001, 0.04, n),
                    thickness_um=rng.uniform(2, 40, n), period_nm=rng.uniform(150, 600, n),
                    slant_deg=rng.uniform(-30, 30, n), probe_deg=rng.uniform(-40, 40, n),
                    wavelength_nm=rng.uniform(450, 680, n))

    def test_batch_equals_the_scalar_calls(self):
        g = self.random_gratings(100_000)
        batch = fovea.kogelnik(**g)
        self.assertEqual(batch["efficiency"].shape, (100_000,))
        for i in range(0, 100_000, 97):  # 1 031 scalar calls spread over the batch
            one = fovea.kogelnik(**{k: v[i] for k, v in g.items()})
            for key in ("efficiency", "zero_order", "nu", "xi"):
                self.assertEqual(float(one[key][()]), float(batch[key][i]), key)
        eff = batch["efficiency"]
        self.assertTrue(np.all((eff >= 0) & (eff <= 1)))
        # Lossless: what is not diffracted stays in the zero order (energy).
        self.assertLess(np.max(np.abs(eff + batch["zero_order"] - 1)), 1e-12)

    def test_batch_equals_the_cli(self):
        g = self.random_gratings(5, seed=3)
        batch = fovea.kogelnik(**g)
        for i in range(5):
            flags = []
            for k, v in g.items():
                flags += ["--" + k.replace("_", "-"), repr(float(v[i]))]
            doc = json.loads(cli("grating", *flags, "--json")[0])
            self.assertLess(abs(doc["efficiency"] - batch["efficiency"][i]), 1e-12)
            self.assertLess(abs(doc["xi"] - batch["xi"][i]), 1e-9 * max(1.0, abs(doc["xi"])))
            if doc["diffracted_deg"] is None:
                self.assertTrue(math.isnan(batch["diffracted_deg"][i]))
            else:
                self.assertLess(abs(doc["diffracted_deg"] - batch["diffracted_deg"][i]), 1e-9)

    def test_broadcasting_and_refusals(self):
        angles = np.linspace(-5, 5, 11)
        r = fovea.kogelnik(1.5, 0.02, 16.0, 177.333, 0.0, angles[:, None], np.array([520.0, 532.0, 545.0]))
        self.assertEqual(r["efficiency"].shape, (11, 3))
        # Every element as its scalar call: constant columns (zero-stride broadcasts, read without a
        # copy) and strided views (copied to contiguous) give the same numbers as plain arrays.
        for i in (0, 4, 10):
            for j in range(3):
                one = fovea.kogelnik(1.5, 0.02, 16.0, 177.333, 0.0, float(angles[i]), [520.0, 532.0, 545.0][j])
                self.assertEqual(float(one["efficiency"][()]), float(r["efficiency"][i, j]))
        n1 = np.broadcast_to(np.float64(0.02), (11, 3))  # all strides zero
        probe = np.repeat(angles, 2)[::2][:, None]  # a strided view
        r2 = fovea.kogelnik(1.5, n1, 16.0, 177.333, 0.0, probe, np.array([520.0, 532.0, 545.0]))
        self.assertTrue(np.array_equal(r2["efficiency"], r["efficiency"]))
        self.assertTrue(np.array_equal(r2["reflection"], r["reflection"]))
        with self.assertRaises(ValueError) as e:
            fovea.kogelnik(1.5, [0.02, 1.6], 16.0, 177.333, 0.0, 0.0, 532.0)
        self.assertIn("grating 1: n1", str(e.exception))
        with self.assertRaises(ValueError):
            fovea.kogelnik(1.5, 0.02, 16.0, 177.333, 0.0, 0.0, 532.0, polarization="q")

    def test_rcwa_equals_the_cli(self):
        flags = ["--n0", "1.5", "--n1", "0.02", "--thickness-um", "8", "--period-nm", "177.333",
                 "--slant-deg", "0", "--probe-deg", "0", "--wavelength-nm", "532", "--model", "rcwa"]
        doc = json.loads(cli("grating", *flags, "--json")[0])
        r = fovea.rcwa(1.5, 0.02, 8.0, 177.333, 0.0, 0.0, 532.0)
        self.assertLess(abs(float(r["efficiency"][()]) - doc["efficiency"]), 1e-12)


if __name__ == "__main__":
    unittest.main()
