// Timings of the design analyses (docs/analyses.md) on the prototype bench.
#include <benchmark/benchmark.h>

#include "app/embedded_scene.h"
#include "model/analysis/angular_resolution.h"
#include "model/analysis/beam_shaping.h"
#include "model/analysis/foveal_optics.h"
#include "model/scene/scene_io.h"

namespace {
fovea::Scene prototype() {
  return *fovea::parseScene(fovea::embeddedDefaultSceneJson(), "prototype").scene;
}

void BM_ResolutionProfile(benchmark::State& state) {
  const fovea::Scene s = prototype();
  for (auto _ : state) benchmark::DoNotOptimize(fovea::analyzeResolution(s).peripheral_pixel_integral);
}
BENCHMARK(BM_ResolutionProfile)->Unit(benchmark::kMillisecond);

void BM_CombinerMtf30(benchmark::State& state) {
  const fovea::Scene s = prototype();
  for (auto _ : state) benchmark::DoNotOptimize(fovea::tracedCombinerMtf30(s, 10.0, 5.0).mtf30_cpd);
}
BENCHMARK(BM_CombinerMtf30)->Unit(benchmark::kMicrosecond);

void BM_SpotEvaluationRealLens(benchmark::State& state) {
  const fovea::Scene s = prototype();
  const fovea::PlacedLens lens{fovea::defaultLensCatalog()[6], {50.0, 2.0, 10.0}};
  for (auto _ : state) benchmark::DoNotOptimize(fovea::evaluateSpots(s, lens).rms_spot_um);
}
BENCHMARK(BM_SpotEvaluationRealLens)->Unit(benchmark::kMicrosecond);

void BM_LensOptimisation(benchmark::State& state) {
  const fovea::Scene s = prototype();
  const auto catalog = fovea::defaultLensCatalog();
  for (auto _ : state) benchmark::DoNotOptimize(fovea::optimizeBeamShapingLens(s, catalog).value->rms_after_um);
}
BENCHMARK(BM_LensOptimisation)->Unit(benchmark::kMillisecond)->Iterations(1);
}  // namespace
