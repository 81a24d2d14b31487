// The learned pupil detector (model/gaze/learned_pupil_detector.h) on 400x400 IR eye-camera
// frames of the wide domain's held-out subsets (target: <= 3 ms per frame on one core, the
// 120 Hz eye camera's budget shared with the rest of the loop), and the auto detector (the
// learned proposal refined by the classical fit). One thread: cv::setNumThreads(1). Frames
// are rendered once, outside the timed loop; the model is the source tree's
// resources/pupil/pupil-net.onnx unless $FOVEA_PUPIL_MODEL names another.
#include <benchmark/benchmark.h>

#include <opencv2/core.hpp>

#include "model/gaze/learned_pupil_detector.h"
#include "model/gaze/pupil_detector_choice.h"
#include "model/gaze/wide_eye_domain.h"

namespace {

std::vector<cv::Mat> wideFrames(int subset_index) {
  const auto subset = fovea::gaze::heldOutWideSubsets()[static_cast<std::size_t>(subset_index)];
  std::vector<cv::Mat> frames;
  for (int i = 0; i < 16; ++i) frames.push_back(fovea::gaze::renderWideFrame(subset, i, 42).image);
  return frames;
}

void run(benchmark::State& state, fovea::gaze::PupilDetectorKind kind) {
  cv::setNumThreads(1);
  const auto frames = wideFrames(static_cast<int>(state.range(0)));
  try {
    fovea::gaze::requireLearnedModel();
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  std::size_t k = 0;
  int found = 0;
  for (auto _ : state) {
    const auto d = fovea::gaze::detectPupilWith(kind, frames[k++ % frames.size()]);
    found += d.found ? 1 : 0;
    benchmark::DoNotOptimize(d.confidence);
  }
  state.SetLabel(
      fovea::gaze::wideSubsetName(fovea::gaze::heldOutWideSubsets()[static_cast<std::size_t>(state.range(0))]));
  state.counters["found_fraction"] = static_cast<double>(found) / static_cast<double>(state.iterations());
}

void BM_LearnedPupil400(benchmark::State& state) {
  run(state, fovea::gaze::PupilDetectorKind::Learned);
}
void BM_AutoPupil400(benchmark::State& state) {
  run(state, fovea::gaze::PupilDetectorKind::Auto);
}
BENCHMARK(BM_LearnedPupil400)->DenseRange(0, 7)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AutoPupil400)->DenseRange(0, 7)->Unit(benchmark::kMillisecond);

}  // namespace
