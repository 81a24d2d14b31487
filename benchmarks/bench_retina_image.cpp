// The retinal image of both displays (issue 29, model/image/retina_image.h): a 1920x1080 chart
// at zero gaze on the default scene, wall time (target: <= 1 s on two cores; not met,
// docs/physics.md section 6).
#include <benchmark/benchmark.h>

#include <opencv2/core.hpp>

#include "app/embedded_scene.h"
#include "model/image/retina_image.h"
#include "model/scene/scene_io.h"

namespace {

void BM_RetinaImage1080p(benchmark::State& state) {
  const fovea::Scene scene = *fovea::parseScene(fovea::embeddedDefaultSceneJson(), "prototype").scene;
  cv::Mat chart(1080, 1920, CV_32FC3);
  for (int y = 0; y < chart.rows; ++y)  // 32-pixel checkerboard, linear 0.1 / 0.9
    for (int x = 0; x < chart.cols; ++x) {
      const float v = ((x / 32 + y / 32) % 2) ? 0.9F : 0.1F;
      chart.at<cv::Vec3f>(y, x) = {v, v, v};
    }
  fovea::image::RetinaImageOptions o;
  o.rays = static_cast<int>(state.range(0));
  for (auto _ : state) {
    const auto r = fovea::image::renderRetinaImage(scene, chart, o);
    benchmark::DoNotOptimize(r.power_on_retina);
  }
}
BENCHMARK(BM_RetinaImage1080p)->Arg(20000)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);

}  // namespace
