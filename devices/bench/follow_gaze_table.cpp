#include "devices/bench/follow_gaze_table.h"

#include <algorithm>
#include <cstdio>

#include "model/analysis/hoe_travel.h"

namespace fovea::devices {

double interpolateClamped(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
  if (xs.empty()) return 0.0;
  if (x <= xs.front()) return ys.front();
  if (x >= xs.back()) return ys.back();
  const auto it = std::upper_bound(xs.begin(), xs.end(), x);
  const std::size_t i = static_cast<std::size_t>(it - xs.begin());
  const double t = (x - xs[i - 1]) / (xs[i] - xs[i - 1]);
  return ys[i - 1] + t * (ys[i] - ys[i - 1]);
}

std::array<double, 2> FollowGazeTable::hoeShift(std::array<double, 2> gaze_deg) const {
  // Absolute x_p as hoeTravel gives it (no longer referred to the zero-gaze optimum: that made
  // the bench 0.17 mm off the sweep's x_p at 20 deg, issue 26).
  return {gaze_deg[0] != 0.0 ? interpolateClamped(gazes_deg, shift_x_mm, gaze_deg[0]) : 0.0,
          gaze_deg[1] != 0.0 ? interpolateClamped(gazes_deg, shift_y_mm, gaze_deg[1]) : 0.0};
}

StudyOutcome<FollowGazeTable> computeFollowGazeTable(const Scene& scene, const FollowGazeTableOptions& options,
                                                     const StudyControl& control) {
  StudyOutcome<FollowGazeTable> out;
  const XpRule rule = sceneXpRule(scene);
  const double lo = scene.eye.gaze_range_deg[0], hi = scene.eye.gaze_range_deg[1];
  const int n = std::max(2, options.samples);
  FollowGazeTable t;
  for (int i = 0; i < n; ++i) t.gazes_deg.push_back(lo + (hi - lo) * i / (n - 1));
  // One job per (axis, gaze): the x_p call of every other caller (hoe_travel.h).
  auto runs = runSamples<double>(
      2 * t.gazes_deg.size(),
      [&](std::size_t j) {
        const double g = t.gazes_deg[j % t.gazes_deg.size()];
        const bool yaw = j < t.gazes_deg.size();
        return hoeTravel(scene, yaw ? std::array{g, 0.0} : std::array{0.0, g}, rule).shift_mm[yaw ? 0 : 1];
      },
      control);
  if (!runs.ok()) return out;
  t.shift_x_mm.assign(runs.value->begin(), runs.value->begin() + static_cast<long>(t.gazes_deg.size()));
  t.shift_y_mm.assign(runs.value->begin() + static_cast<long>(t.gazes_deg.size()), runs.value->end());
  char src[160];
  std::snprintf(src, sizeof src, "gaze study: hoeTravel (%s, exact FOV) over [%g, %g] deg, %zu gazes", xpRuleName(rule),
                lo, hi, t.gazes_deg.size());
  t.source = src;
  out.status = StudyStatus::Completed;
  out.value = std::move(t);
  return out;
}

FollowGazeTableTask::FollowGazeTableTask(const Scene& scene, FollowGazeTableOptions options) {
  future_ = std::async(std::launch::async, [scene, options, cancel = cancel_] {
    StudyControl control;
    control.cancel = cancel.get();
    return computeFollowGazeTable(scene, options, control);
  });
}

FollowGazeTableTask::~FollowGazeTableTask() {
  cancel();
  if (future_.valid()) future_.wait();
}

void FollowGazeTableTask::cancel() {
  *cancel_ = true;
}

bool FollowGazeTableTask::ready() {
  return table().has_value();
}

std::optional<FollowGazeTable> FollowGazeTableTask::table() {
  if (!table_ && future_.valid() && future_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
    auto outcome = future_.get();
    if (outcome.ok()) table_ = std::move(*outcome.value);
  }
  return table_;
}

}  // namespace fovea::devices
