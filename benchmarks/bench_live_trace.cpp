// The studio's live trace while the hand moves (widgets/live_trace.h, TraceDetail::Coarse):
// the model calls a coarse job makes (diffractScene when the design moved, evaluateGaze,
// projectorGrid) at the coarse ray count, on ONE core (the target: a coarse trace well
// inside the 50 ms input-to-drawn budget at the default scene), next to the refined ones.
// The end-to-end latency including the GUI thread is measured separately under Xvfb
// (scripts/measure-drag-latency.sh, docs/benchmarks.md).
#include <benchmark/benchmark.h>

#include <tbb/global_control.h>

#include "app/embedded_scene.h"
#include "model/physics/projector_rays.h"
#include "model/physics/trace.h"
#include "model/scene/scene_io.h"

namespace {

// A gaze drag: the diffraction of the design is cached, each move re-evaluates the pupil.
void BM_LiveGazeMove(benchmark::State& state) {
  const tbb::global_control one_core(tbb::global_control::max_allowed_parallelism, 1);
  fovea::Scene s = fovea::embeddedDefaultScene();
  fovea::TraceOptions o;
  o.rays = static_cast<int>(state.range(0));
  o.keep_rays = true;
  const auto rays = fovea::diffractScene(s, o);
  double yaw = 0;
  for (auto _ : state) {
    s.eye.gaze_deg = {yaw, 0.0};
    yaw = yaw > 20 ? -20 : yaw + 0.5;
    benchmark::DoNotOptimize(fovea::evaluateGaze(s, rays, o).fov_deg.horizontal);
    benchmark::DoNotOptimize(fovea::projectorGrid(s.projector, o.rays));
  }
  state.counters["rays_per_wavelength"] = static_cast<double>(o.rays);
}
BENCHMARK(BM_LiveGazeMove)->Arg(500)->Arg(4000)->Unit(benchmark::kMillisecond);

// A handle drag of the projector: every move changes the geometry, so the whole trace runs.
void BM_LiveHandleMove(benchmark::State& state) {
  const tbb::global_control one_core(tbb::global_control::max_allowed_parallelism, 1);
  fovea::Scene s = fovea::embeddedDefaultScene();
  fovea::TraceOptions o;
  o.rays = static_cast<int>(state.range(0));
  o.keep_rays = true;
  const double x0 = s.projector.pose.position_mm[0];
  int step = 0;
  for (auto _ : state) {
    s.projector.pose.position_mm[0] = x0 + (step++ % 8) * 0.5;  // 0.5 mm per move
    const auto rays = fovea::diffractScene(s, o);
    benchmark::DoNotOptimize(fovea::evaluateGaze(s, rays, o).fov_deg.horizontal);
    benchmark::DoNotOptimize(fovea::projectorGrid(s.projector, o.rays));
  }
  state.counters["rays_per_wavelength"] = static_cast<double>(o.rays);
}
BENCHMARK(BM_LiveHandleMove)->Arg(500)->Arg(4000)->Unit(benchmark::kMillisecond);

}  // namespace
