#include "devices/virtual/virtual_controller.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace fovea::devices {

namespace {
constexpr double kUpdatePeriod_s = 0.1;
constexpr int kMaxUnacknowledgedUpdates = 50;
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

VirtualAptController::VirtualAptController(VirtualControllerConfig config, std::shared_ptr<Clock> clock)
    : config_(std::move(config)),
      clock_(std::move(clock)),
      units_(config_.controller, config_.stage),
      now_(clock_->now()),
      homed_(config_.homed),
      enabled_(config_.enabled) {
  profile_ = MotionProfile::rest(now_, config_.position);
  const auto& s = config_.stage;
  vel_ = {1, 0, units_.accelerationToApt(s.default_acceleration), units_.velocityToApt(s.default_velocity)};
  jog_ = {1,
          apt::JogMode::SingleStep,
          units_.positionToCounts(s.rotation ? 1.0 : 0.1),
          0,
          units_.accelerationToApt(s.default_acceleration),
          units_.velocityToApt(s.default_velocity / 2),
          apt::StopMode::Profiled};
  home_ = {1, 2, 1, units_.velocityToApt(s.home_velocity), 0};
  limits_ = {1, 2, 2, 0, 0, 1};
}

double VirtualAptController::minTravel() const {
  return config_.stage.travel_min;
}
double VirtualAptController::maxTravel() const {
  return config_.stage.travel_max;
}
double VirtualAptController::positionLocked() const {
  return profile_.position(now_);
}
bool VirtualAptController::movingLocked() const {
  return motion_ != Motion::None && profile_.activeAt(now_);
}

using Lock = std::lock_guard<std::recursive_mutex>;
double VirtualAptController::position() const {
  Lock lock(mutex_);
  return positionLocked();
}
bool VirtualAptController::moving() const {
  Lock lock(mutex_);
  return movingLocked();
}
double VirtualAptController::positionAt(double t_s) const {
  Lock lock(mutex_);
  return profile_.position(t_s);
}
bool VirtualAptController::homed() const {
  Lock lock(mutex_);
  return homed_;
}
bool VirtualAptController::enabled() const {
  Lock lock(mutex_);
  return enabled_;
}
int VirtualAptController::identifyCount() const {
  Lock lock(mutex_);
  return identify_count_;
}
std::vector<apt::Message> VirtualAptController::received() const {
  Lock lock(mutex_);
  return received_;
}
apt::VelParams VirtualAptController::velParams() const {
  Lock lock(mutex_);
  return vel_;
}
apt::JogParams VirtualAptController::jogParams() const {
  Lock lock(mutex_);
  return jog_;
}
apt::HomeParams VirtualAptController::homeParams() const {
  Lock lock(mutex_);
  return home_;
}
apt::LimitSwitchParams VirtualAptController::limSwitchParams() const {
  Lock lock(mutex_);
  return limits_;
}
void VirtualAptController::setMute(bool mute) {
  Lock lock(mutex_);
  mute_ = mute;
}

apt::ChannelStatus VirtualAptController::status() const {
  apt::ChannelStatus s;
  s.channel = 1;
  const double x = positionLocked();
  s.position = units_.positionToCounts(x);
  const double v = profile_.velocity(now_);
  if (config_.controller.kind == apt::MotorKind::Stepper) {
    s.velocity_or_encoder = s.position;  // stepper layout: encoder count field
  } else {
    // Velocity word: counts per servo sample (the document leaves its scaling open).
    s.velocity_or_encoder =
        static_cast<std::int32_t>(std::lround(v * units_.countsPerUnit() * config_.controller.sampling_interval_s));
  }
  using namespace apt::status;
  std::uint32_t b = kMotorConnected;
  if (enabled_) b |= kChannelEnabled;
  if (homed_) b |= kHomed;
  if (motion_ == Motion::Home && movingLocked()) b |= kHoming;
  if (movingLocked()) {
    const bool jog = motion_ == Motion::JogStep || motion_ == Motion::JogContinuous;
    if (v > 0) b |= jog ? kJoggingForward : kMovingForward;
    if (v < 0) b |= jog ? kJoggingReverse : kMovingReverse;
  } else {
    b |= kSettled;
  }
  if (!config_.stage.continuous) {
    constexpr double eps = 1e-9;
    if (x >= maxTravel() - eps) b |= kForwardHardLimit;
    if (x <= minTravel() + eps) b |= kReverseHardLimit;
  }
  s.bits = b;
  return s;
}

apt::ChannelStatus VirtualAptController::completionStatus() const {
  apt::ChannelStatus s = status();
  // Completions use the DC layout; a stepper has no velocity word to report (zeros), where
  // its status update carries the encoder count.
  if (config_.controller.kind == apt::MotorKind::Stepper) s.velocity_or_encoder = 0;
  if (config_.completion_reports_moving)
    s.bits = apt::status::kChannelEnabled | apt::status::kMovingForward | apt::status::kMovingReverse;
  return s;
}

void VirtualAptController::send(const apt::Message& m) {
  if (mute_) return;
  auto bytes = apt::encode(m);
  out_.insert(out_.end(), bytes.begin(), bytes.end());
}

void VirtualAptController::receive(std::span<const std::uint8_t> bytes) {
  Lock lock(mutex_);
  advanceLocked(clock_->now());
  decoder_.feed(bytes);
  while (auto m = decoder_.next()) {
    received_.push_back(*m);
    if (m->dest != config_.address) continue;  // addressed to someone else
    handle(*m);
  }
}

std::vector<std::uint8_t> VirtualAptController::takeOutput() {
  Lock lock(mutex_);
  advanceLocked(clock_->now());
  std::vector<std::uint8_t> out;
  out.swap(out_);
  return out;
}

double VirtualAptController::nextEventTime() const {
  Lock lock(mutex_);
  if (!out_.empty()) return now_;
  double t = kInf;
  if (motion_ != Motion::None) t = std::min(t, std::max(now_, profile_.endTime()));
  if (updates_) t = std::min(t, next_update_);
  return t;
}

void VirtualAptController::advanceTo(double t_s) {
  Lock lock(mutex_);
  advanceLocked(t_s);
}

void VirtualAptController::advanceLocked(double t_s) {
  for (;;) {
    double t_motion = motion_ != Motion::None ? profile_.endTime() : kInf;
    double t_update = updates_ ? next_update_ : kInf;
    const double t_next = std::min(t_motion, t_update);
    if (t_next > t_s) break;
    now_ = std::max(now_, t_next);
    if (t_motion <= t_update) {
      finishMotion();
    } else {
      if (config_.controller.kind == apt::MotorKind::Stepper)
        send(apt::getStatusUpdate(config_.address, status()));
      else
        send(apt::getDcStatusUpdate(config_.address, status()));
      next_update_ += kUpdatePeriod_s;
      if (++unacknowledged_ >= kMaxUnacknowledgedUpdates) updates_ = false;  // host went quiet
    }
  }
  now_ = std::max(now_, t_s);
}

void VirtualAptController::finishMotion() {
  const Motion done = motion_;
  motion_ = Motion::None;
  jog_direction_ = 0;
  profile_ = MotionProfile::rest(now_, profile_.endPosition());
  switch (done) {
    case Motion::Home:
      homed_ = true;
      send(apt::moveHomed(config_.address, 1));
      break;
    case Motion::Move:
    case Motion::JogStep:
      if (limit_hit_)
        send(apt::moveStopped(config_.address, completionStatus()));
      else
        send(apt::moveCompleted(config_.address, completionStatus()));
      break;
    case Motion::JogContinuous:
    case Motion::Stopping:
      send(apt::moveStopped(config_.address, completionStatus()));
      break;
    case Motion::None:
      break;
  }
  limit_hit_ = false;
}

void VirtualAptController::startMove(double target, double v_max, double accel, Motion kind) {
  limit_hit_ = false;
  if (!config_.stage.continuous) {
    const double clamped = std::clamp(target, minTravel(), maxTravel());
    limit_hit_ = clamped != target;
    target = clamped;
  }
  const double from = positionLocked();
  profile_ = MotionProfile::trapezoid(now_, from, target, std::max(v_max, 1e-9), std::max(accel, 1e-9));
  motion_ = kind;
  if (profile_.endTime() <= now_) finishMotion();  // already there: reply at once
}

void VirtualAptController::stop(bool immediate) {
  if (!movingLocked()) {
    motion_ = Motion::Stopping;
    profile_ = MotionProfile::rest(now_, positionLocked());
    finishMotion();
    return;
  }
  const double x = positionLocked(), v = profile_.velocity(now_);
  const double a = std::max(units_.aptToAcceleration(vel_.acceleration), 1e-9);
  profile_ = immediate ? MotionProfile::rest(now_, x) : MotionProfile::decelerate(now_, x, v, a);
  if (!config_.stage.continuous && !immediate) {
    // A decelerating stop cannot run through the end of travel.
    const double end = std::clamp(profile_.endPosition(), minTravel(), maxTravel());
    if (end != profile_.endPosition()) profile_ = MotionProfile::trapezoid(now_, x, end, std::abs(v) + 1e-9, a);
  }
  motion_ = Motion::Stopping;
  if (profile_.endTime() <= now_) finishMotion();
}

void VirtualAptController::handle(const apt::Message& m) {
  namespace id = apt::id;
  const double vmax = units_.aptToVelocity(vel_.max_velocity);
  const double acc = units_.aptToAcceleration(vel_.acceleration);
  const bool motion = m.id == id::kMotMoveHome || m.id == id::kMotMoveAbsolute || m.id == id::kMotMoveRelative ||
                      m.id == id::kMotMoveJog;
  if (motion && config_.reject_motion) {
    apt::ControllerResponse r = *config_.reject_motion;
    r.message_id = m.id;
    r.rich = true;
    send(apt::hwRichResponse(config_.address, r));
    return;
  }
  switch (m.id) {
    case id::kModIdentify:
      ++identify_count_;
      break;
    case id::kHwReqInfo: {
      apt::HwInfo info;
      try {
        info.serial = static_cast<std::uint32_t>(std::stoul(config_.serial));
      } catch (const std::exception&) {
        info.serial = 0;  // non-numeric serial: the protocol field is a number
      }
      info.model = config_.controller.name;
      info.hw_type = config_.controller.kind == apt::MotorKind::Stepper ? 45 : 44;
      info.fw_major = 3;
      info.fw_interim = 1;
      info.notes = "virtual " + config_.stage.name;
      send(apt::getHwInfo(config_.address, info));
      break;
    }
    case id::kModSetChanEnableState:
      enabled_ = m.param2 == 0x01;
      if (!enabled_ && movingLocked()) {  // motor off: it stops where it is
        profile_ = MotionProfile::rest(now_, positionLocked());
        motion_ = Motion::None;
      }
      break;
    case id::kModReqChanEnableState:
      send(apt::getChanEnableState(config_.address, m.param1, enabled_));
      break;
    case id::kHwStartUpdateMsgs:
      updates_ = true;
      unacknowledged_ = 0;
      next_update_ = now_ + kUpdatePeriod_s;
      break;
    case id::kHwStopUpdateMsgs:
      updates_ = false;
      break;
    case id::kMotAckDcStatusUpdate:
      unacknowledged_ = 0;
      break;
    case id::kMotReqDcStatusUpdate:
      send(apt::getDcStatusUpdate(config_.address, status()));
      break;
    case id::kMotReqStatusUpdate:
      send(apt::getStatusUpdate(config_.address, status()));
      break;
    case id::kMotSetVelParams:
      if (auto p = apt::parseVelParams(m)) vel_ = *p;
      break;
    case id::kMotReqVelParams:
      send(apt::getVelParams(config_.address, vel_));
      break;
    case id::kMotSetJogParams:
      if (auto p = apt::parseJogParams(m)) jog_ = *p;
      break;
    case id::kMotReqJogParams:
      send(apt::getJogParams(config_.address, jog_));
      break;
    case id::kMotSetHomeParams:
      if (auto p = apt::parseHomeParams(m)) home_ = *p;
      break;
    case id::kMotReqHomeParams:
      send(apt::getHomeParams(config_.address, home_));
      break;
    case id::kMotSetLimSwitchParams:
      if (auto p = apt::parseLimSwitchParams(m)) limits_ = *p;
      break;
    case id::kMotReqLimSwitchParams:
      send(apt::getLimSwitchParams(config_.address, limits_));
      break;
    case id::kMotSetMoveAbsParams:
      if (auto p = apt::parseMoveParams(m)) stored_abs_ = p->value;
      break;
    case id::kMotSetMoveRelParams:
      if (auto p = apt::parseMoveParams(m)) stored_rel_ = p->value;
      break;
    case id::kMotMoveHome:
      if (enabled_) {
        homed_ = false;
        const double hv = units_.aptToVelocity(home_.velocity);
        startMove(0.0, hv > 0 ? hv : config_.stage.home_velocity, acc, Motion::Home);
      }
      break;
    case id::kMotMoveAbsolute: {
      std::optional<std::int32_t> counts;
      if (apt::isStoredMove(m))
        counts = stored_abs_;
      else if (auto p = apt::parseMoveAbsolute(m))
        counts = p->value;
      if (counts && enabled_) startMove(units_.countsToPosition(*counts), vmax, acc, Motion::Move);
      break;
    }
    case id::kMotMoveRelative: {
      std::optional<std::int32_t> counts;
      if (apt::isStoredMove(m))
        counts = stored_rel_;
      else if (auto p = apt::parseMoveRelative(m))
        counts = p->value;
      if (counts && enabled_) startMove(positionLocked() + units_.countsToPosition(*counts), vmax, acc, Motion::Move);
      break;
    }
    case id::kMotMoveJog:
      if (enabled_) {
        const double dir = m.param2 == static_cast<std::uint8_t>(apt::JogDirection::Forward) ? 1.0 : -1.0;
        const double jv = units_.aptToVelocity(jog_.max_velocity), ja = units_.aptToAcceleration(jog_.acceleration);
        if (jog_.mode == apt::JogMode::Continuous) {
          const double end =
              config_.stage.continuous ? positionLocked() + dir * 1e6 : (dir > 0 ? maxTravel() : minTravel());
          startMove(end, jv, ja, Motion::JogContinuous);
        } else {
          startMove(positionLocked() + dir * units_.countsToPosition(jog_.step_size), jv, ja, Motion::JogStep);
        }
      }
      break;
    case id::kMotMoveStop:
      stop(m.param2 == static_cast<std::uint8_t>(apt::StopMode::Immediate));
      break;
    default:
      break;  // not emulated: ignored like an unsupported message on the hardware
  }
}

}  // namespace fovea::devices
