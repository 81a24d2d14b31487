#include "model/analysis/eyebox_walk.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "model/analysis/study_runner.h"

namespace fovea {

std::optional<std::pair<GazeSample, bool>> eyeBoxBorder(const std::vector<double>& gazes, int direction,
                                                        const GazeSample& reference,
                                                        const std::function<bool(const GazeSample&)>& inside_box,
                                                        const GazeSampleSource& at_gaze, const GazeSampleSource& search,
                                                        int bisections, const StudyControl& control) {
  std::vector<double> side;
  for (const double g : gazes)
    if (direction > 0 ? g > 0 : g < 0) side.push_back(g);
  std::sort(side.begin(), side.end(), [](double a, double b) { return std::abs(a) < std::abs(b); });
  GazeSample inside = reference;
  std::optional<double> g_out;
  for (const double g : side) {
    GazeSample s = at_gaze(g);
    if (!inside_box(s)) {
      g_out = g;
      break;
    }
    inside = s;  // GazeSample is trivially copyable (clang-tidy performance-move-const-arg)
  }
  if (!g_out) return std::make_pair(inside, false);
  double g_in = inside.gaze_deg;
  for (int k = 0; k < bisections; ++k) {
    if (control.cancelled()) return std::nullopt;
    const double mid = 0.5 * (g_in + *g_out);
    GazeSample s = search(mid);
    if (inside_box(s)) {
      inside = s;  // GazeSample is trivially copyable (clang-tidy performance-move-const-arg)
      g_in = mid;
    } else {
      g_out = mid;
    }
  }
  return std::make_pair(inside, true);
}

EyeBox walkEyeBox(const std::vector<double>& gazes, GazeAxis axis, const GazeStudyOptions& options,
                  const GazeSampleSource& sample) {
  const GazeSample reference = sample(0.0);
  const double threshold = eyeBoxThresholdDeg(axisFov(reference.fov, axis), options);
  auto good = [&](const GazeSample& s) { return axisFov(s.fov, axis) >= threshold; };
  // finishSweep's borders, with every gaze searched only when the walk reaches it.
  const StudyControl never;
  const auto sides = runSamples<std::pair<GazeSample, bool>>(
      2,
      [&](std::size_t i) {
        return *eyeBoxBorder(gazes, i == 0 ? -1 : +1, reference, good, sample, sample, options.border_bisections,
                             never);
      },
      StudyControl{});
  const auto& [low, low_bounded] = (*sides.value)[0];
  const auto& [high, high_bounded] = (*sides.value)[1];
  EyeBox eb;
  eb.reference_fov_deg = axisFov(reference.fov, axis);
  setEyeBoxBorders(eb, low, low_bounded, high, high_bounded);
  return eb;
}

}  // namespace fovea
