// The retinal image of both displays (issue 29, model/image/retina_image.h): a 1920x1080 chart
// on the default scene, wall time (target: <= 1 s on two cores, met; docs/physics.md section 6).
// BM_RetinaImage1080p: zero gaze twice (the first call fills the eye-PSF cache of
// retinal_psf.cpp, the second reuses it); BM_RetinaImage1080pNewGaze: a new gaze each call at
// one accommodation (the preview's gaze slider: only the gaze-dependent parts recomputed);
// BM_RetinaImage1080pNewAccommodation: a new accommodation each call (the accommodation
// slider: new eye PSFs every time).
#include <benchmark/benchmark.h>

#include <opencv2/core.hpp>

#include "app/embedded_scene.h"
#include "model/image/retina_image.h"
#include "model/scene/scene_io.h"

namespace {

cv::Mat retinaBenchChart() {
  cv::Mat chart(1080, 1920, CV_32FC3);
  for (int y = 0; y < chart.rows; ++y)  // 32-pixel checkerboard, linear 0.1 / 0.9
    for (int x = 0; x < chart.cols; ++x) {
      const float v = ((x / 32 + y / 32) % 2) ? 0.9F : 0.1F;
      chart.at<cv::Vec3f>(y, x) = {v, v, v};
    }
  return chart;
}

void BM_RetinaImage1080p(benchmark::State& state) {
  const fovea::Scene scene = fovea::embeddedDefaultScene();
  const cv::Mat chart = retinaBenchChart();
  fovea::image::RetinaImageOptions o;
  o.rays = static_cast<int>(state.range(0));
  for (auto _ : state) {
    const auto r = fovea::image::renderRetinaImage(scene, chart, o);
    benchmark::DoNotOptimize(r.power_on_retina);
  }
}
BENCHMARK(BM_RetinaImage1080p)->Arg(20000)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);

void BM_RetinaImage1080pNewGaze(benchmark::State& state) {
  const fovea::Scene scene = fovea::embeddedDefaultScene();
  const cv::Mat chart = retinaBenchChart();
  fovea::image::RetinaImageOptions o;
  o.rays = static_cast<int>(state.range(0));
  o.accommodation_d = 1.0;
  (void)fovea::image::renderRetinaImage(scene, chart, o);  // the eye PSFs of this accommodation
  double yaw = 0;
  for (auto _ : state) {
    yaw += 1.0;
    o.gaze_deg = {yaw, 0.0};
    const auto r = fovea::image::renderRetinaImage(scene, chart, o);
    benchmark::DoNotOptimize(r.power_on_retina);
  }
}
BENCHMARK(BM_RetinaImage1080pNewGaze)->Arg(20000)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(4);

void BM_RetinaImage1080pNewAccommodation(benchmark::State& state) {
  const fovea::Scene scene = fovea::embeddedDefaultScene();
  const cv::Mat chart = retinaBenchChart();
  fovea::image::RetinaImageOptions o;
  o.rays = static_cast<int>(state.range(0));
  (void)fovea::image::renderRetinaImage(scene, chart, o);  // the process warmed up
  double d = 0.4;
  for (auto _ : state) {
    d += 0.55;
    o.accommodation_d = d;
    const auto r = fovea::image::renderRetinaImage(scene, chart, o);
    benchmark::DoNotOptimize(r.power_on_retina);
  }
}
BENCHMARK(BM_RetinaImage1080pNewAccommodation)->Arg(20000)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(4);

}  // namespace
