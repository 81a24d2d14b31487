#include "devices/bench/target_follower.h"

#include <cmath>

#include "devices/stage/stage_binding.h"

namespace fovea::devices {

TargetFollower::TargetFollower(AxisWorker& axis, double deadband) : axis_(axis), deadband_(deadband) {}

void TargetFollower::setTarget(double element_value) {
  std::lock_guard lock(state_->mutex);
  state_->pending = element_value;
  if (state_->in_flight) return;  // the running drain picks it up
  state_->in_flight = true;
  axis_.submit(
      [st = state_, binding = axis_.binding(), deadband = deadband_](Stage& s) { drain(st, binding, deadband, s); });
}

void TargetFollower::drain(const std::shared_ptr<State>& st, const StageBinding& binding, double deadband, Stage& s) {
  for (;;) {
    double target = 0.0;
    {
      std::lock_guard lock(st->mutex);
      if (!st->pending) {
        st->in_flight = false;
        return;
      }
      target = *st->pending;
      st->pending.reset();
      if (st->last_commanded && std::abs(target - *st->last_commanded) <= deadband) continue;
      st->last_commanded = target;
      ++st->moves;
    }
    try {
      s.moveAbsolute(elementToStage(binding, target));
    } catch (...) {
      std::lock_guard lock(st->mutex);
      st->in_flight = false;
      st->last_commanded.reset();  // unknown where it ended: do not deadband the next target
      throw;                       // reported on the axis (snapshot last_error)
    }
  }
}

int TargetFollower::movesCommanded() const {
  std::lock_guard lock(state_->mutex);
  return state_->moves;
}

std::optional<double> TargetFollower::lastCommanded() const {
  std::lock_guard lock(state_->mutex);
  return state_->last_commanded;
}

GazeFollower::GazeFollower(std::vector<AxisWorker*> axes, Map map, double deadband) : map_(std::move(map)) {
  for (AxisWorker* a : axes)
    followers_[{a->binding().element, a->binding().axis}] = std::make_unique<TargetFollower>(*a, deadband);
}

void GazeFollower::setGaze(double yaw_deg, double pitch_deg) {
  for (const auto& [key, value] : map_(yaw_deg, pitch_deg)) {
    auto it = followers_.find(key);
    if (it != followers_.end()) it->second->setTarget(value);
  }
}

TargetFollower* GazeFollower::follower(const std::string& element, const std::string& axis) {
  auto it = followers_.find({element, axis});
  return it == followers_.end() ? nullptr : it->second.get();
}

}  // namespace fovea::devices
