// Design exploration at scale: the exact (edge) FOV estimator, the gaze sweep on it, and one
// tolerance trial. Counters carry the values, so accuracy and time read off one table:
//   fov_h_deg / dense_h_deg: the edge estimate and the dense one at 512 000 rays/λ (converged
//   to its ray spacing, docs/benchmarks.md "Ray count vs FOV error").
#include <benchmark/benchmark.h>

#include <map>
#include <optional>
#include <string>

#include <tbb/global_control.h>

#include "app/embedded_scene.h"
#include "model/analysis/fov_edges.h"
#include "model/analysis/gaze_studies.h"
#include "model/analysis/tolerance_analysis.h"
#include "model/analysis/tolerance_run.h"
#include "model/analysis/tolerance_spec.h"
#include "model/analysis/tolerance_trial.h"
#include "model/analysis/trace_evaluator.h"
#include "model/physics/trace_pipeline.h"
#include "model/scene/scene_io.h"

namespace {

double denseConverged(const fovea::Scene& s, std::optional<double> lambda) {
  static std::map<int, double> memo;
  const int key = lambda ? static_cast<int>(*lambda) : 0;
  if (memo.count(key)) return memo[key];
  fovea::TraceOptions t;
  t.rays = 512000;
  t.wavelength_nm = lambda;
  t.keep_field_rays = true;
  t.cull_to_pupil = true;
  fovea::TracePipeline p;
  return memo[key] = fovea::continuousFov(p.run(s, t).field_rays, 0.1).horizontal_deg;
}

// One FOV evaluation, one core: range(0) = tolerance in mdeg, range(1) = 1 for 532 nm only.
void BM_EdgeFov(benchmark::State& state) {
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  const fovea::Scene s = fovea::embeddedDefaultScene();
  fovea::TraceEvaluatorOptions o;
  o.fov_method = fovea::FovMethod::Edges;
  o.edge_tolerance_deg = state.range(0) * 1e-3;
  if (state.range(1)) o.wavelength_nm = 532.0;
  const fovea::FovEvaluator eval = fovea::traceEvaluator(o);
  fovea::FovSample f;
  for (auto _ : state) benchmark::DoNotOptimize(f = eval(s, fovea::FovQuery{}));
  state.counters["fov_h_deg"] = f.horizontal_deg;
  state.counters["fov_v_deg"] = f.vertical_deg;
  state.counters["dense_h_deg"] = denseConverged(s, o.wavelength_nm);
}
BENCHMARK(BM_EdgeFov)->Args({5, 1})->Args({50, 1})->Args({5, 0})->Args({50, 0})->Unit(benchmark::kMillisecond);

// The 41-gaze x_p sweep (-20..20 deg by 1 deg) on the edge estimator, two cores, 3 λ.
void BM_Sweep41GazesEdges(benchmark::State& state) {
  tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
  const fovea::Scene s = fovea::embeddedDefaultScene();
  fovea::TraceEvaluatorOptions o;
  o.fov_method = fovea::FovMethod::Edges;
  o.edge_tolerance_deg = 0.05;
  const fovea::FovEvaluator eval = fovea::traceEvaluator(o);
  double eyebox = 0;
  for (auto _ : state) {
    const auto r = fovea::sweepGaze(s, eval, -20, 20, 1, fovea::GazeAxis::Yaw, fovea::ShiftMethod::Hoe);
    eyebox = r.value->eyebox.width_mm;
  }
  state.counters["eyebox_mm"] = eyebox;
}
BENCHMARK(BM_Sweep41GazesEdges)->Unit(benchmark::kMillisecond)->Iterations(1);

// One tolerance trial of the default spec (resources/tolerance/prototype-tolerance.json, compiled
// in), one core:
// range(0) = 0 refind (x_p re-found per gaze), 1 fixed.
void BM_ToleranceTrial(benchmark::State& state) {
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  const fovea::Scene s = fovea::embeddedDefaultScene();
  nlohmann::json j = nlohmann::json::parse(fovea::analysis::defaultToleranceSpecText());
  j["compensator"] = state.range(0) ? "fixed" : "refind";
  const fovea::ToleranceSpec spec = fovea::parseToleranceSpec(j);
  const fovea::FovEvaluator eval = fovea::toleranceEvaluator(spec);
  const fovea::CompensationTable table = fovea::nominalCompensation(s, spec, eval);
  std::uint64_t i = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(fovea::runToleranceTrial(s, spec, eval, fovea::trialInputs(spec, 1, i++), table));
}
BENCHMARK(BM_ToleranceTrial)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
