#include "model/analysis/eyebox_walk.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "model/analysis/study_runner.h"

namespace fovea {

EyeBox walkEyeBox(const std::vector<double>& gazes, GazeAxis axis, const GazeStudyOptions& options,
                  const GazeSampleSource& sample) {
  const GazeSample reference = sample(0.0);
  const double threshold = eyeBoxThresholdDeg(axisFov(reference.fov, axis), options);
  auto good = [&](const GazeSample& s) { return axisFov(s.fov, axis) >= threshold; };
  // finishSweep's border(): the side's gazes by |gaze|, the last inside and the first outside,
  // then border_bisections halvings between them.
  auto border = [&](int direction) -> std::pair<GazeSample, bool> {
    std::vector<double> side;
    for (const double g : gazes)
      if (direction > 0 ? g > 0 : g < 0) side.push_back(g);
    std::sort(side.begin(), side.end(), [](double a, double b) { return std::abs(a) < std::abs(b); });
    GazeSample inside = reference;
    bool found_outside = false;
    double g_out = 0;
    for (const double g : side) {
      GazeSample s = sample(g);
      if (!good(s)) {
        found_outside = true;
        g_out = g;
        break;
      }
      inside = s;  // GazeSample is trivially copyable (clang-tidy performance-move-const-arg)
    }
    if (!found_outside) return {inside, false};
    double g_in = inside.gaze_deg;
    for (int k = 0; k < options.border_bisections; ++k) {
      const double mid = 0.5 * (g_in + g_out);
      GazeSample s = sample(mid);
      if (good(s)) {
        inside = s;  // GazeSample is trivially copyable (clang-tidy performance-move-const-arg)
        g_in = mid;
      } else {
        g_out = mid;
      }
    }
    return {inside, true};
  };
  const auto sides = runSamples<std::pair<GazeSample, bool>>(
      2, [&](std::size_t i) { return border(i == 0 ? -1 : +1); }, StudyControl{});
  const auto& [low, low_bounded] = (*sides.value)[0];
  const auto& [high, high_bounded] = (*sides.value)[1];
  EyeBox eb;
  eb.reference_fov_deg = axisFov(reference.fov, axis);
  setEyeBoxBorders(eb, low, low_bounded, high, high_bounded);
  return eb;
}

}  // namespace fovea
