#pragma once
// The HOE travel x_p(alpha) that follow-gaze and the capture wizard drive the HOE stages to:
// the gaze study's optimal HOE shift (sweepGaze, ShiftMethod::Hoe) tabulated over the
// scene's gaze range, yaw -> x, pitch -> y, interpolated linearly between samples and
// referred to the optimum at zero gaze (a zero gaze component keeps its stage at 0).
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
  std::vector<double> shift_x_mm;  // optimal HOE x for each yaw
  std::vector<double> shift_y_mm;  // optimal HOE y for each pitch
  std::string source;              // "gaze study: sweepGaze over [-20, 20] deg, 9 gazes, 800 rays"
  // x_p(alpha) for a (yaw, pitch) gaze, relative to the optimum at zero gaze.
  std::array<double, 2> hoeShift(std::array<double, 2> gaze_deg) const;
};

struct FollowGazeTableOptions {
  int samples = 9;  // gazes per axis over the scene's gaze range
  int rays = 800;   // traced rays per FOV evaluation
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
