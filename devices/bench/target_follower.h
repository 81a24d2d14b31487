#pragma once
// Follow a target that changes faster than the axis can move (the studio's "follow gaze":
// the HOE stages track x_p(alpha) as the gaze slider moves). Targets are coalesced: while a
// move runs only the latest target is kept, and the axis moves to it when the move ends.
// Targets within the deadband of the last commanded one are ignored. A target outside the
// soft limits is refused by the Stage (nothing sent) and reported on the axis.
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>

#include "devices/bench/axis_worker.h"

namespace fovea::devices {

class TargetFollower {
 public:
  TargetFollower(AxisWorker& axis, double deadband);
  void setTarget(double element_value);  // thread-safe, never blocks
  int movesCommanded() const;
  std::optional<double> lastCommanded() const;

 private:
  // Shared with the queued drain job, so a follower may go away while its axis still moves.
  struct State {
    std::mutex mutex;
    std::optional<double> pending, last_commanded;
    bool in_flight = false;
    int moves = 0;
  };
  static void drain(const std::shared_ptr<State>& st, const StageBinding& binding, double deadband, Stage& s);

  AxisWorker& axis_;
  double deadband_;
  std::shared_ptr<State> state_ = std::make_shared<State>();
};

// Several axes driven from one control value (the gaze angle): the map function returns
// the element targets, keyed by (element, axis), for a gaze (yaw, pitch) in degrees.
class GazeFollower {
 public:
  using Key = std::pair<std::string, std::string>;
  using Map = std::function<std::map<Key, double>(double yaw_deg, double pitch_deg)>;
  GazeFollower(std::vector<AxisWorker*> axes, Map map, double deadband);
  void setGaze(double yaw_deg, double pitch_deg);
  TargetFollower* follower(const std::string& element, const std::string& axis);

 private:
  Map map_;
  std::map<Key, std::unique_ptr<TargetFollower>> followers_;
};

}  // namespace fovea::devices
