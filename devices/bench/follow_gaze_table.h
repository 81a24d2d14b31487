#pragma once
// The HOE travel x_p(alpha) that follow-gaze and the capture wizard drive the HOE stages to:
// x_p from the one x_p source (model/analysis/hoe_travel.h hoeTravel, the scene's
// view.xp_rule: what `fovea-cli sweep` reports and the studio's live trace applies)
// tabulated over the scene's gaze range, yaw -> x, pitch -> y, interpolated linearly between
// samples (at a sample gaze it is hoeTravel's value exactly); a zero gaze component keeps its
// stage at 0, as hoeTravel does.
//
// Qt-free: the studio runs FollowGazeTableTask in the background and asks it for the table;
// until it is ready the callers use the geometric guess and say so.
#include <array>
#include <atomic>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "model/analysis/gaze_studies.h"
#include "model/scene/scene.h"

namespace fovea::devices {

struct FollowGazeTable {
  std::vector<double> gazes_deg;   // sample gazes (yaw for x, pitch for y), ascending
  std::vector<double> shift_x_mm;  // x_p along HOE x for each yaw (hoeTravel at (yaw, 0))
  std::vector<double> shift_y_mm;  // along HOE y for each pitch (hoeTravel at (0, pitch))
  std::string source;              // "gaze study: hoeTravel (plateau-middle) over [-20, 20] deg, 9 gazes"
  // x_p(alpha) for a (yaw, pitch) gaze: interpolated, a zero component 0.
  std::array<double, 2> hoeShift(std::array<double, 2> gaze_deg) const;
};

struct FollowGazeTableOptions {
  int samples = 9;  // gazes per axis over the scene's gaze range (the rule: the scene's view.xp_rule)
};

// Runs the two gaze sweeps (yaw, pitch). Cancelled: no value.
StudyOutcome<FollowGazeTable> computeFollowGazeTable(const Scene& scene, const FollowGazeTableOptions& options = {},
                                                     const StudyControl& control = {});

// Linear interpolation of ys(xs) at x, clamped to the ends (xs ascending, same size >= 1).
double interpolateClamped(const std::vector<double>& xs, const std::vector<double>& ys, double x);

// computeFollowGazeTable on a background task; cancel() or the destructor stops it (the
// running sample finishes, no new one starts).
class FollowGazeTableTask {
 public:
  FollowGazeTableTask(const Scene& scene, FollowGazeTableOptions options = {});
  ~FollowGazeTableTask();
  FollowGazeTableTask(const FollowGazeTableTask&) = delete;
  FollowGazeTableTask& operator=(const FollowGazeTableTask&) = delete;
  void cancel();
  // The table once computed (never blocks).
  std::optional<FollowGazeTable> table();
  bool ready();

 private:
  std::shared_ptr<std::atomic<bool>> cancel_ = std::make_shared<std::atomic<bool>>(false);
  std::future<StudyOutcome<FollowGazeTable>> future_;
  std::optional<FollowGazeTable> table_;
};

}  // namespace fovea::devices
