// Gaze change at a 1920x1080 target: update of the foveal, peripheral and perceived images
// (budget: <= 16 ms on two cores, one 60 Hz frame). The target caches are built once, outside the loop.
//
// Besides wall time, `cpu_ms_per_update` is the process CPU time (all threads) per update:
// on two dedicated cores the wall time is at most that, and at least half of it, whatever
// else the machine is doing while the benchmark runs.
#include <benchmark/benchmark.h>

#include <ctime>

#include <opencv2/core.hpp>

#include "app/embedded_scene.h"
#include "model/image/foveation.h"
#include "model/scene/scene_io.h"

namespace {
double processCpuMs() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

void BM_CompositeGazeUpdate(benchmark::State& state) {
  const fovea::Scene scene = fovea::embeddedDefaultScene();
  cv::Mat target(1080, 1920, CV_32FC3);
  cv::randu(target, 0.0f, 1.0f);
  fovea::image::FoveatedCompositor comp(scene, state.range(0) != 0);
  comp.setTarget(target);
  comp.update({0.0, 0.0});
  int k = 0;
  double foveal = 0, peripheral = 0, perceived = 0;
  const double cpu0 = processCpuMs();
  for (auto _ : state) {
    // A saccade pattern over the +-15 deg x +-8 deg field.
    comp.update({-15.0 + (k * 7 % 31), -8.0 + (k * 3 % 17)});
    benchmark::DoNotOptimize(comp.perceivedImage().data);
    foveal += comp.timings().foveal_ms;
    peripheral += comp.timings().peripheral_ms;
    perceived += comp.timings().perceived_ms;
    ++k;
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["cpu_ms_per_update"] = (processCpuMs() - cpu0) / n;
  state.counters["foveal_ms"] = foveal / n;
  state.counters["peripheral_ms"] = peripheral / n;
  state.counters["perceived_ms"] = perceived / n;
  state.counters["threads"] = cv::getNumThreads();
}
BENCHMARK(BM_CompositeGazeUpdate)->Arg(1)->Arg(0)->ArgName("blend")->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_CompositeSetTarget(benchmark::State& state) {
  const fovea::Scene scene = fovea::embeddedDefaultScene();
  cv::Mat target(1080, 1920, CV_32FC3);
  cv::randu(target, 0.0f, 1.0f);
  fovea::image::FoveatedCompositor comp(scene, true);
  for (auto _ : state) comp.setTarget(target);
}
BENCHMARK(BM_CompositeSetTarget)->Unit(benchmark::kMillisecond)->UseRealTime();
}  // namespace
