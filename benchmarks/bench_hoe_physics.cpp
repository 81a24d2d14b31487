// Timings of the HOE physics core (targets: >= 20 M Kogelnik evaluations/s/core, a
// 20 000-ray gaze update in <= 16 ms, the 41-gaze sweep and its scaling over cores).
#include <benchmark/benchmark.h>

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include <tbb/global_control.h>

#include "app/embedded_scene.h"
#include "model/analysis/gaze_studies.h"
#include "model/analysis/trace_evaluator.h"
#include "model/physics/grating.h"
#include "model/physics/kogelnik_batch.h"
#include "model/physics/trace.h"
#include "model/physics/trace_pipeline.h"
#include "model/scene/scene_io.h"

namespace {

// n planar gratings uniform over the ranges of scripts/bench_python.py (xorshift64, fixed seed).
std::vector<fovea::PlanarGrating> randomGratings(std::size_t n) {
  std::vector<fovea::PlanarGrating> g(n);
  std::uint64_t x = 88172645463325252ULL;  // xorshift64: uniform in [0, 1)
  auto u = [&x] {
    x ^= x << 13, x ^= x >> 7, x ^= x << 17;
    return static_cast<double>(x >> 11) * 0x1.0p-53;
  };
  for (auto& p : g) {
    p.film = {1.45 + 0.15 * u(), 0.001 + 0.039 * u(), 2 + 38 * u(), 0.0};
    p.period_nm = 150 + 450 * u();
    p.slant_deg = -30 + 60 * u();
    p.probe_deg = -40 + 80 * u();
    p.wavelength_nm = 450 + 230 * u();
  }
  return g;
}

void BM_KogelnikLossless(benchmark::State& state) {
  std::vector<double> cs(1024), vt(1024);
  for (int i = 0; i < 1024; ++i) {
    cs[i] = (i % 2 ? -1.0 : 1.0) * (0.3 + 0.5 * i / 1024.0);
    vt[i] = 0.01 * (i - 512) / 512.0;
  }
  std::size_t i = 0;
  for (auto _ : state) {
    const auto r = fovea::kogelnik::lossless(0.8, cs[i & 1023], vt[i & 1023], 0.09, 16.0);
    benchmark::DoNotOptimize(r.efficiency);
    ++i;
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
}
BENCHMARK(BM_KogelnikLossless);

// The SIMD batch (kogelnik_batch.h) over 4096 prototype-like inputs, double and float.
template <class T>
void BM_KogelnikBatch(benchmark::State& state) {
  constexpr std::size_t n = 4096;
  std::vector<T> cr(n), cs(n), vt(n), kappa(n, T(0.118)), d(n, T(16)), eta(n);
  for (std::size_t i = 0; i < n; ++i) {
    cr[i] = T(0.6 + 0.4 * i / n);
    cs[i] = T((i % 4 ? -1.0 : 1.0) * (0.3 + 0.6 * i / n));
    vt[i] = T(0.02 * (double(i) - n / 2) / n);
  }
  for (auto _ : state) {
    fovea::kogelnik::losslessBatch(cr.data(), cs.data(), vt.data(), kappa.data(), d.data(), eta.data(), n);
    benchmark::DoNotOptimize(eta.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(n));
  state.SetLabel(fovea::kogelnik::batchInstructionSet());
}
BENCHMARK(BM_KogelnikBatch<double>);
BENCHMARK(BM_KogelnikBatch<float>);

void BM_Diffract3d(benchmark::State& state) {
  fovea::FilmGrating film{1.5, 0.015, 16.0, 0.0};
  const Eigen::Vector3d rho(5.0, 1.0, 16.7), k(4.0, 0.5, 33.0);
  for (auto _ : state) {
    const auto r = fovea::diffract3d(rho, k, film, 0.532, fovea::Polarization::S);
    benchmark::DoNotOptimize(r.kogelnik.efficiency);
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
}
BENCHMARK(BM_Diffract3d);

// 10^6 planar gratings as `fovea.kogelnik` answers them from NumPy (app/python/py_gratings.cpp:
// diffractPlanar per element, one core): the C++ side of its 1.2x target (docs/benchmarks.md).
void BM_DiffractPlanar1e6(benchmark::State& state) {
  constexpr std::size_t n = 1000000;
  const std::vector<fovea::PlanarGrating> g = randomGratings(n);
  std::vector<double> eta(n);
  for (auto _ : state) {
    for (std::size_t i = 0; i < n; ++i) eta[i] = fovea::diffractPlanar(g[i]).grating.kogelnik.efficiency;
    benchmark::DoNotOptimize(eta.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(n));
}
BENCHMARK(BM_DiffractPlanar1e6)->Unit(benchmark::kMillisecond)->UseRealTime();

// The same 10^6 gratings with everything `fovea.kogelnik` returns (efficiency, zero order, nu, xi,
// diffracted angle, reflection flag), written into freshly allocated arrays each time as the
// Python call must: the C++ batch that does the Python call's work (its first-touch page faults
// on ~41 MB of outputs included).
void BM_DiffractPlanar1e6AllOutputs(benchmark::State& state) {
  constexpr std::size_t n = 1000000;
  const std::vector<fovea::PlanarGrating> g = randomGratings(n);
  for (auto _ : state) {
    // new[] without value-initialisation, like NumPy's empty arrays behind py::array_t(shape).
    std::array<std::unique_ptr<double[]>, 5> out;
    for (auto& o : out) o.reset(new double[n]);
    std::unique_ptr<bool[]> refl(new bool[n]);
    for (std::size_t i = 0; i < n; ++i) {
      const fovea::PlanarDiffraction d = fovea::diffractPlanar(g[i]);
      out[0][i] = d.grating.kogelnik.efficiency;
      out[1][i] = d.grating.kogelnik.zero_order;
      out[2][i] = d.grating.kogelnik.nu;
      out[3][i] = d.grating.kogelnik.xi;
      out[4][i] = d.diffracted_deg ? *d.diffracted_deg : std::numeric_limits<double>::quiet_NaN();
      refl[i] = d.grating.reflection();
    }
    for (auto& o : out) benchmark::DoNotOptimize(o.get());
    benchmark::DoNotOptimize(refl.get());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(n));
}
BENCHMARK(BM_DiffractPlanar1e6AllOutputs)->Unit(benchmark::kMillisecond)->UseRealTime();

// Full trace (diffraction + gaze) of ~20 000 rays in total (3 wavelengths).
void BM_TraceScene20k(benchmark::State& state) {
  const fovea::Scene s = fovea::embeddedDefaultScene();
  fovea::TraceOptions o;
  o.rays = 6667;
  for (auto _ : state) benchmark::DoNotOptimize(fovea::traceScene(s, o).fov_deg.horizontal);
}
BENCHMARK(BM_TraceScene20k)->Unit(benchmark::kMillisecond);

// Gaze update only: the diffracted rays are reused (trace.h two-stage API).
void BM_GazeUpdate20k(benchmark::State& state) {
  const fovea::Scene s = fovea::embeddedDefaultScene();
  fovea::TraceOptions o;
  o.rays = 6667;
  const auto rays = fovea::diffractScene(s, o);
  double yaw = 0;
  for (auto _ : state) {
    o.gaze_deg = std::array<double, 2>{yaw, 0.0};
    yaw = yaw > 10 ? -10 : yaw + 0.5;
    benchmark::DoNotOptimize(fovea::evaluateGaze(s, rays, o).fov_deg.horizontal);
  }
}
BENCHMARK(BM_GazeUpdate20k)->Unit(benchmark::kMillisecond);

// Gaze update through the memoised pipeline (trace_pipeline.h): pupil, FOV and analyses only.
void BM_PipelineGazeUpdate20k(benchmark::State& state) {
  const fovea::Scene s = fovea::embeddedDefaultScene();
  fovea::TraceOptions o;
  o.rays = 6667;
  fovea::TracePipeline p;
  p.run(s, o);
  double yaw = 0;
  for (auto _ : state) {
    o.gaze_deg = std::array<double, 2>{yaw, 0.0};
    yaw = yaw > 10 ? -10 : yaw + 0.5;
    benchmark::DoNotOptimize(p.run(s, o).fov_deg.horizontal);
  }
}
BENCHMARK(BM_PipelineGazeUpdate20k)->Unit(benchmark::kMillisecond);

// Gaze and HOE shift together (x_p follows the gaze): everything after the projector grid
// reruns, with the pupil cull.
void BM_PipelineGazeAndShift20k(benchmark::State& state) {
  const fovea::Scene s = fovea::embeddedDefaultScene();
  fovea::TraceOptions o;
  o.rays = 6667;
  o.cull_to_pupil = true;
  fovea::TracePipeline p;
  double yaw = 0;
  for (auto _ : state) {
    o.gaze_deg = std::array<double, 2>{yaw, 0.0};
    o.hoe_shift_mm = {0.17 * yaw, 0.0};
    yaw = yaw > 10 ? -10 : yaw + 0.5;
    benchmark::DoNotOptimize(p.run(s, o).fov_deg.horizontal);
  }
}
BENCHMARK(BM_PipelineGazeAndShift20k)->Unit(benchmark::kMillisecond);

// The 41-gaze x_p sweep (-20..20 deg by 1 deg) of the gaze studies, default evaluator, on
// state.range(0) threads (1 vs 2: the scaling; process CPU time beside the wall time).
void BM_Sweep41Gazes(benchmark::State& state) {
  const fovea::Scene s = fovea::embeddedDefaultScene();
  const fovea::FovEvaluator eval = fovea::traceEvaluator({});
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(0)));
  for (auto _ : state)
    benchmark::DoNotOptimize(fovea::sweepGaze(s, eval, -20, 20, 1, fovea::GazeAxis::Yaw, fovea::ShiftMethod::Hoe).ok());
}
BENCHMARK(BM_Sweep41Gazes)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->UseRealTime()
    ->MeasureProcessCPUTime();

}  // namespace
