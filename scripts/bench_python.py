#!/usr/bin/env python3
"""Wall-clock benchmark of the `fovea` Python module beside `fovea-cli` through a subprocess
(docs/benchmarks.md, "Python module"). Not a test: timings vary with the machine.
  PYTHONPATH=build/default/python /usr/bin/python3 scripts/bench_python.py [build/default]"""
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

import fovea

build = sys.argv[1] if len(sys.argv) > 1 else "build/default"
cli = os.path.join(build, "app", "fovea-cli")


def best(f, repeat=3, clock=time.perf_counter):
    times = []
    for _ in range(repeat):
        t = clock()
        f()
        times.append(clock() - t)
    return min(times)


def cpp(name):
    """(wall, CPU) seconds per iteration of a Google Benchmark of fovea-benchmarks, fastest of 5."""
    exe = os.path.join(build, "benchmarks", "fovea-benchmarks")
    p = subprocess.run([exe, f"--benchmark_filter=^{name}$", "--benchmark_repetitions=5",
                        "--benchmark_report_aggregates_only=false", "--benchmark_format=json"],
                       check=True, capture_output=True, text=True)
    runs = [b for b in json.loads(p.stdout)["benchmarks"] if b.get("run_type") == "iteration"]
    scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[runs[0]["time_unit"]]
    return min(b["real_time"] for b in runs) * scale, min(b["cpu_time"] for b in runs) * scale


rng = np.random.default_rng(1)


def gratings(n):
    return dict(n0=rng.uniform(1.45, 1.6, n), n1=rng.uniform(0.001, 0.04, n), thickness_um=rng.uniform(2, 40, n),
                period_nm=rng.uniform(150, 600, n), slant_deg=rng.uniform(-30, 30, n),
                probe_deg=rng.uniform(-40, 40, n), wavelength_nm=rng.uniform(450, 680, n))


out = {}
g = gratings(1_000_000)
out["kogelnik_1e6_python_s"] = best(lambda: fovea.kogelnik(**g), repeat=5)
out["kogelnik_1e6_python_cpu_s"] = best(lambda: fovea.kogelnik(**g), repeat=5, clock=time.process_time)
# The C++ loops: diffractPlanar over 10^6 gratings into one reused array, and with all six of
# fovea.kogelnik's outputs into fresh arrays (the Python call's work).
out["kogelnik_1e6_cpp_s"], out["kogelnik_1e6_cpp_cpu_s"] = cpp("BM_DiffractPlanar1e6/real_time")
out["kogelnik_1e6_cpp_all_outputs_s"], out["kogelnik_1e6_cpp_all_outputs_cpu_s"] = cpp(
    "BM_DiffractPlanar1e6AllOutputs/real_time")
# The same question through fovea-cli grating --batch (JSON lines), 1e5 gratings, scaled to 1e6.
g5 = {k: v[:100_000] for k, v in g.items()}
with tempfile.NamedTemporaryFile("w", suffix=".jsonl", delete=False) as f:
    for i in range(100_000):
        f.write(json.dumps({k: float(v[i]) for k, v in g5.items()}) + "\n")
    lines = f.name
out["kogelnik_1e6_cli_batch_s"] = 10 * best(
    lambda: subprocess.run([cli, "grating", "--batch", lines], check=True, capture_output=True), repeat=1)
os.unlink(lines)

scene = fovea.Scene.embedded()
fovea.trace(scene, rays=4000)  # first call: the scene's memo
out["trace_4000_python_s"] = best(lambda: fovea.trace(scene, rays=4000), repeat=20)
out["trace_4000_python_cpu_s"] = best(lambda: fovea.trace(scene, rays=4000), repeat=20, clock=time.process_time)
out["trace_4000_cpp_s"], out["trace_4000_cpp_cpu_s"] = cpp("BM_TraceCallAsPython4000/real_time")
out["trace_4000_cli_subprocess_s"] = best(
    lambda: subprocess.run([cli, "trace", "", "--rays", "4000", "--json"], check=True, capture_output=True))
out["sweep_default_python_s"] = best(lambda: fovea.run("sweep", scene), repeat=1)
out["sweep_default_cli_subprocess_s"] = best(
    lambda: subprocess.run([cli, "sweep", "", "--no-cache", "--json"], check=True, capture_output=True), repeat=1)
out["kogelnik_ratio_wall_all_outputs"] = out["kogelnik_1e6_python_s"] / out["kogelnik_1e6_cpp_all_outputs_s"]
out["kogelnik_ratio_wall_one_output"] = out["kogelnik_1e6_python_s"] / out["kogelnik_1e6_cpp_s"]
out["trace_ratio_wall"] = out["trace_4000_python_s"] / out["trace_4000_cpp_s"]
out["load_average"] = os.getloadavg()
print(json.dumps(out, indent=2))
