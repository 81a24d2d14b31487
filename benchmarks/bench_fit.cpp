// The fit of issue 27: eye relief alone on the seed's simulated targets
// (resources/seed/seed-targets.json, group sim-; docs/fitting.md "Timing"). One evaluation of
// the 14 targets (what each of the fit's ~66 evaluations costs) on the prototype, two cores;
// counters carry the model's values so a speed-up that changes them shows here.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <tbb/global_control.h>
#include <nlohmann/json.hpp>

#include "app/embedded_scene.h"
#include "model/analysis/fit_targets.h"
#include "model/scene/scene_io.h"

namespace {

std::vector<fovea::FitTarget> seedSimulatedTargets() {
  // The source tree from the environment (as the tests, tests/test_paths.h), else the working directory.
  const char* root = std::getenv("FOVEA_SOURCE_DIR");
  std::ifstream in(std::string(root ? root : ".") + "/resources/seed/seed-targets.json");
  if (!in)
    throw std::runtime_error("resources/seed/seed-targets.json: run from the source tree or set FOVEA_SOURCE_DIR");
  return fovea::selectFitTargets(fovea::parseFitTargets(nlohmann::json::parse(in)), "sim-");
}

void BM_FitSeedSimulatedEvaluation(benchmark::State& state) {
  tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
  const fovea::Scene s = fovea::embeddedDefaultScene();
  const std::vector<fovea::FitTarget> targets = seedSimulatedTargets();
  std::vector<double> m;
  for (auto _ : state) benchmark::DoNotOptimize(m = fovea::evaluateTargets(s, targets, {}));
  for (std::size_t i = 0; i < targets.size(); ++i) state.counters[targets[i].id] = m[i];
}
BENCHMARK(BM_FitSeedSimulatedEvaluation)->Unit(benchmark::kMillisecond)->Iterations(2)->UseRealTime();

}  // namespace
