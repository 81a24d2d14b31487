// Pupil detector on 400x400 IR eye-camera frames (budget: <= 2 ms per frame on one core).
// Frames are rendered once, outside the timed loop, from each benchmark subset
// (model/gaze/pupil_benchmark.h); the detector is single-threaded (OpenCV's own threading
// is switched off so the time is one core's).
#include <benchmark/benchmark.h>

#include <opencv2/core.hpp>

#include "model/gaze/pupil_benchmark.h"
#include "model/gaze/pupil_detector.h"

namespace {

void BM_DetectPupil400(benchmark::State& state) {
  cv::setNumThreads(1);
  const auto subset = fovea::gaze::allSubsets()[static_cast<std::size_t>(state.range(0))];
  std::vector<cv::Mat> frames;
  for (int i = 0; i < 16; ++i) frames.push_back(fovea::gaze::renderBenchmarkFrame(subset, i, 42).image);
  std::size_t k = 0;
  int found = 0;
  for (auto _ : state) {
    const auto d = fovea::gaze::detectPupil(frames[k++ % frames.size()]);
    found += d.found ? 1 : 0;
    benchmark::DoNotOptimize(d.confidence);
  }
  state.SetLabel(fovea::gaze::subsetName(subset));
  state.counters["found_fraction"] = static_cast<double>(found) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_DetectPupil400)->DenseRange(0, 5)->Unit(benchmark::kMillisecond);

}  // namespace
