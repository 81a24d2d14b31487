#include "devices/bench/follow_gaze_table.h"

#include <algorithm>
#include <cstdio>

#include "model/analysis/trace_evaluator.h"

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
  return {interpolateClamped(gazes_deg, shift_x_mm, gaze_deg[0]) - interpolateClamped(gazes_deg, shift_x_mm, 0.0),
          interpolateClamped(gazes_deg, shift_y_mm, gaze_deg[1]) - interpolateClamped(gazes_deg, shift_y_mm, 0.0)};
}

StudyOutcome<FollowGazeTable> computeFollowGazeTable(const Scene& scene, const FollowGazeTableOptions& options,
                                                     const StudyControl& control) {
  StudyOutcome<FollowGazeTable> out;
  TraceEvaluatorOptions to;
  to.rays = options.rays;
  const FovEvaluator eval = traceEvaluator(to);
  const double lo = scene.eye.gaze_range_deg[0], hi = scene.eye.gaze_range_deg[1];
  const int n = std::max(2, options.samples);
  const double step = (hi - lo) / (n - 1);
  FollowGazeTable t;
  for (GazeAxis axis : {GazeAxis::Yaw, GazeAxis::Pitch}) {
    const auto sweep = sweepGaze(scene, eval, lo, hi, step, axis, ShiftMethod::Hoe, {}, control);
    if (!sweep.ok()) return out;
    std::vector<double>& shifts = axis == GazeAxis::Yaw ? t.shift_x_mm : t.shift_y_mm;
    std::vector<double> gazes;
    for (const auto& s : sweep.value->samples) {
      gazes.push_back(s.gaze_deg);
      shifts.push_back(s.shift_mm);
    }
    if (t.gazes_deg.empty()) t.gazes_deg = gazes;
  }
  if (t.shift_x_mm.size() != t.gazes_deg.size() || t.shift_y_mm.size() != t.gazes_deg.size()) return out;
  char src[160];
  std::snprintf(src, sizeof src, "gaze study: sweepGaze (traced HOE) over [%g, %g] deg, %zu gazes, %d rays", lo, hi,
                t.gazes_deg.size(), options.rays);
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
