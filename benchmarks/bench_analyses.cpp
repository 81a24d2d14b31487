// Timings of the design analyses (docs/analyses.md) on the prototype bench.
#include <benchmark/benchmark.h>

#include "app/embedded_scene.h"
#include "model/analysis/analysis_json.h"
#include "model/analysis/analysis_registry.h"
#include "model/analysis/angular_resolution.h"
#include "model/analysis/beam_shaping.h"
#include "model/analysis/foveal_optics.h"
#include "model/analysis/study_analyses.h"
#include "model/analysis/trace_fov.h"
#include "model/physics/trace.h"
#include "model/scene/scene_io.h"

namespace {
void BM_ResolutionProfile(benchmark::State& state) {
  const fovea::Scene s = fovea::embeddedDefaultScene();
  for (auto _ : state) benchmark::DoNotOptimize(fovea::analyzeResolution(s).peripheral_pixel_integral);
}
BENCHMARK(BM_ResolutionProfile)->Unit(benchmark::kMillisecond);

void BM_CombinerMtf30(benchmark::State& state) {
  const fovea::Scene s = fovea::embeddedDefaultScene();
  for (auto _ : state) benchmark::DoNotOptimize(fovea::tracedCombinerMtf30(s, 10.0, 5.0).mtf30_cpd);
}
BENCHMARK(BM_CombinerMtf30)->Unit(benchmark::kMicrosecond);

void BM_SpotEvaluationRealLens(benchmark::State& state) {
  const fovea::Scene s = fovea::embeddedDefaultScene();
  const fovea::PlacedLens lens{fovea::defaultLensCatalog()[6], {50.0, 2.0, 10.0}};
  for (auto _ : state) benchmark::DoNotOptimize(fovea::evaluateSpots(s, lens).rms_spot_um);
}
BENCHMARK(BM_SpotEvaluationRealLens)->Unit(benchmark::kMicrosecond);

void BM_LensOptimisation(benchmark::State& state) {
  const fovea::Scene s = fovea::embeddedDefaultScene();
  const auto catalog = fovea::defaultLensCatalog();
  for (auto _ : state) benchmark::DoNotOptimize(fovea::optimizeBeamShapingLens(s, catalog).value->rms_after_um);
}
BENCHMARK(BM_LensOptimisation)->Unit(benchmark::kMillisecond)->Iterations(1);
}  // namespace

// What `fovea.trace(scene, rays=4000)` computes (app/python/py_analyses.cpp), called from C++:
// the registry's trace defaults, traceScene with the rays kept, the FOV and the JSON document.
// The Python call's target is 1.1x this (docs/python.md); its conversion to Python objects and
// NumPy ray arrays is the difference.
void BM_TraceCallAsPython4000(benchmark::State& state) {
  const fovea::Scene s = fovea::embeddedDefaultScene();
  const auto& def = *fovea::analysis::findAnalysisDefinition("trace");
  nlohmann::json values = fovea::analysis::defaultValues(def);
  values["rays"] = 4000;
  if (!fovea::analysis::validateValues(def, values).empty()) state.SkipWithError("trace defaults refused");
  fovea::TraceOptions o = fovea::analysis::traceOptionsFrom(values);
  o.keep_rays = true;
  const auto method = fovea::analysis::traceFovMethodFrom(values);
  for (auto _ : state) {
    const fovea::TraceResult r = fovea::traceScene(s, o);
    benchmark::DoNotOptimize(fovea::traceResultJson(r, o, fovea::traceFov(s, r, o), method));
  }
}
BENCHMARK(BM_TraceCallAsPython4000)->Unit(benchmark::kMillisecond)->UseRealTime();
