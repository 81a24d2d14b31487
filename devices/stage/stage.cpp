#include "devices/stage/stage.h"

#include <cmath>
#include <cstdio>
#include <limits>

namespace fovea::devices {

namespace {
std::string fmt(double v, const std::string& unit) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.4f %s", v, unit.c_str());
  return buf;
}
}  // namespace

std::string describeSetup(const ControllerParameters& p, const std::string& unit) {
  auto num = [](double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%g", v);
    return std::string(b);
  };
  auto mode = [](std::uint16_t m) -> std::string {
    switch (m & 0x7F) {
      case 1:
        return "ignored";
      case 2:
        return "makes";
      case 3:
        return "breaks";
      case 4:
        return "makes (home only)";
      case 5:
        return "breaks (home only)";
      default:
        return "mode " + std::to_string(m);
    }
  };
  std::string s = "velocity " + num(p.velocity.max_velocity) + " " + unit + "/s, " + num(p.velocity.acceleration) +
                  " " + unit + "/s^2";
  if (p.jog)
    s += "; jog " + std::string(p.jog->continuous ? "continuous" : "single-step ") +
         (p.jog->continuous ? "" : num(p.jog->step) + " " + unit) + " at " + num(p.jog->max_velocity) + " " + unit +
         "/s";
  s += p.home ? "; home " + std::string(p.home->direction == 1 ? "forward" : "reverse") + " at " +
                    num(p.home_velocity) + " " + unit + "/s"
              : "; home parameters not reported";
  s += p.limit_switches
           ? "; limit switches CW " + mode(p.limit_switches->cw_hard) + ", CCW " + mode(p.limit_switches->ccw_hard)
           : "; limit switches not reported";
  if (!p.written.empty()) {
    std::string w;
    for (const auto& x : p.written) w += (w.empty() ? "" : ", ") + x;
    s += " (written on connect: " + w + ")";
  }
  return s;
}

StageConfig defaultStageConfig(const apt::ControllerModel& controller, const apt::StageModel& stage) {
  StageConfig c;
  c.controller = controller;
  c.stage = stage;
  c.soft_min = stage.continuous ? -180.0 : stage.travel_min;
  c.soft_max = stage.continuous ? 180.0 : stage.travel_max;
  return c;
}

Stage::Stage(std::unique_ptr<Transport> transport, StageConfig config, std::shared_ptr<AptLogSink> trace)
    : transport_(std::move(transport)),
      config_(std::move(config)),
      trace_(std::move(trace)),
      units_(config_.controller, config_.stage) {}

Stage::~Stage() {
  try {
    disconnect();
  } catch (...) {
  }
}

std::string Stage::name() const {
  const DeviceInfo i = transport_->info();
  return (i.model.empty() ? config_.controller.name : i.model) + " " + i.serial;
}

void Stage::send(const apt::Message& m) {
  const auto bytes = apt::encode(m);
  try {
    transport_->write(bytes);
  } catch (const DeviceError& e) {
    if (e.kind() == DeviceError::Kind::Disconnected) {
      connected_ = false;
      state_.known = false;
    }
    throw;
  }
  if (trace_) trace_->message(true, bytes);
}

void Stage::absorb(const apt::Message& m) {
  namespace id = apt::id;
  if (m.id == id::kModGetChanEnableState) {
    state_.enabled = m.param2 == 0x01;
    return;
  }
  // State comes from status messages only (polls and the update stream). Completion
  // messages do not say the axis is at rest: a real K10CR1's MOVE_COMPLETED carries 0x80000030
  // (both "moving" bits set, "homed" clear), so the wait for a motion end polls instead.
  if (m.id != id::kMotGetStatusUpdate && m.id != id::kMotGetDcStatusUpdate) return;
  if (auto s = apt::parseChannelStatus(m)) {
    using namespace apt::status;
    state_.known = true;
    state_.position = units_.countsToPosition(s->position);
    state_.velocity = config_.controller.kind == apt::MotorKind::Stepper || config_.controller.sampling_interval_s <= 0
                          ? 0.0
                          : s->velocity_or_encoder / (units_.countsPerUnit() * config_.controller.sampling_interval_s);
    state_.bits = s->bits;
    state_.enabled = (s->bits & kChannelEnabled) != 0;
    state_.homed = (s->bits & kHomed) != 0;
    state_.homing = (s->bits & kHoming) != 0;
    state_.moving = (s->bits & kMovingMask) != 0;
    state_.forward_limit = (s->bits & kForwardHardLimit) != 0;
    state_.reverse_limit = (s->bits & kReverseHardLimit) != 0;
    state_.motion_error = (s->bits & kMotionError) != 0;
    if (on_state_) on_state_(state_);
  }
}

apt::Message Stage::waitFor(const std::function<bool(const apt::Message&)>& match, double timeout_s,
                            const std::string& what) {
  // Timeouts run on the link's clock: wall time for USB, simulated time for a virtual bench.
  const double deadline = transport_->now() + timeout_s;
  for (;;) {
    while (auto m = decoder_.next()) {
      if (trace_) trace_->message(false, decoder_.lastRaw());
      absorb(*m);
      if (auto r = apt::parseControllerResponse(*m)) {
        // The controller refused something: end the wait with its words, not a timeout.
        last_controller_error_ = name() + " reported " + apt::describe(*r);
        throw DeviceError(DeviceError::Kind::Controller, last_controller_error_ + " (while waiting for " + what + ")");
      }
      if (match(*m)) return *m;
    }
    const double remaining = deadline - transport_->now();
    if (remaining <= 0)
      throw DeviceError(DeviceError::Kind::Timeout,
                        name() + " did not answer " + what + " within " + fmt(timeout_s, "s"));
    if (estop_requested_.exchange(false) && connected_) {
      send(apt::moveStop(config_.address, chan(), apt::StopMode::Immediate));
      state_.moving = false;
    }
    const auto slice = std::min(remaining, 0.05);
    std::vector<std::uint8_t> bytes;
    try {
      bytes = transport_->read(std::chrono::milliseconds(static_cast<long>(std::ceil(slice * 1000))));
    } catch (const DeviceError& e) {
      if (e.kind() == DeviceError::Kind::Disconnected) {
        connected_ = false;
        state_.known = false;
        state_.moving = false;
        throw DeviceError(DeviceError::Kind::Disconnected, name() + " was disconnected while waiting for " + what +
                                                               "; position unknown until reconnect");
      }
      throw;
    }
    decoder_.feed(bytes);
  }
}

apt::Message Stage::request(const apt::Message& req, std::uint16_t reply_id) {
  send(req);
  return waitFor([reply_id](const apt::Message& m) { return m.id == reply_id; },
                 std::chrono::duration<double>(config_.reply_timeout).count(), apt::messageName(req.id));
}

void Stage::requireConnected() const {
  if (!connected_) throw DeviceError(DeviceError::Kind::Disconnected, name() + " is not connected");
}

void Stage::connect() {
  if (!transport_->isOpen()) transport_->open();
  decoder_.reset();
  connected_ = true;
  const auto info = request(apt::reqHwInfo(config_.address), apt::id::kHwGetInfo);
  if (auto i = apt::parseHwInfo(info))
    info_ = *i;
  else
    throw DeviceError(DeviceError::Kind::Protocol, name() + " sent a malformed HW_GET_INFO");
  request(apt::reqChanEnableState(config_.address, chan()), apt::id::kModGetChanEnableState);
  setUpController();
  poll();
}

std::uint8_t Stage::chan() const {
  return apt::channelIdent(config_.channel, config_.controller.channel_bit_mask);
}

void Stage::setUpController() {
  // Read every parameter set the moves depend on; write first where the scene asks (other
  // drivers report moves running the wrong way until the vendor software had set a
  // controller up once). Home and limit-switch parameters are optional replies: a
  // controller that does not answer them leaves them unreported.
  const ControllerSetup& want = config_.setup;
  params_ = ControllerParameters{};
  const std::string unit = config_.stage.unit();
  if (want.max_velocity || want.acceleration) {
    velocity();
    VelocitySettings v{want.max_velocity.value_or(units_.aptToVelocity(vel_.max_velocity)),
                       want.acceleration.value_or(units_.aptToAcceleration(vel_.acceleration))};
    setVelocity(v);
    params_.written.push_back("velocity");
  }
  params_.velocity = velocity();
  if (want.jog_step) {
    JogSettings j = jogSettings();
    j.step = *want.jog_step;
    j.continuous = false;
    if (!(j.max_velocity > 0)) j.max_velocity = params_.velocity.max_velocity / 2;
    if (!(j.acceleration > 0)) j.acceleration = params_.velocity.acceleration;
    setJogSettings(j);
    params_.written.push_back("jog");
  }
  params_.jog = jogSettings();
  auto optionalRequest = [&](const apt::Message& req, std::uint16_t reply) -> std::optional<apt::Message> {
    try {
      return request(req, reply);
    } catch (const DeviceError& e) {
      if (e.kind() == DeviceError::Kind::Timeout) return std::nullopt;
      throw;
    }
  };
  if (auto m = optionalRequest(apt::reqHomeParams(config_.address, chan()), apt::id::kMotGetHomeParams)) {
    auto h = apt::parseHomeParams(*m);
    if (h && want.home_velocity) {
      if (!(*want.home_velocity > 0) || *want.home_velocity > config_.stage.max_velocity * 1.0001)
        throw DeviceError(DeviceError::Kind::Usage, "home velocity " + fmt(*want.home_velocity, unit + "/s") +
                                                        " outside (0, " + fmt(config_.stage.max_velocity, "") +
                                                        "] of the " + config_.stage.name);
      h->velocity = units_.velocityToApt(*want.home_velocity);
      h->channel = chan();
      send(apt::setHomeParams(config_.address, *h));
      params_.written.push_back("home");
      m = request(apt::reqHomeParams(config_.address, chan()), apt::id::kMotGetHomeParams);
      h = apt::parseHomeParams(*m);
    }
    if (h) {
      params_.home = *h;
      params_.home_velocity = units_.aptToVelocity(h->velocity);
      params_.home_offset = units_.countsToPosition(h->offset);
    }
  }
  if (auto m = optionalRequest(apt::reqLimSwitchParams(config_.address, chan()), apt::id::kMotGetLimSwitchParams)) {
    auto l = apt::parseLimSwitchParams(*m);
    if (l && want.limit_switch_mode) {
      if (*want.limit_switch_mode < 1 || *want.limit_switch_mode > 3)
        throw DeviceError(DeviceError::Kind::Usage, "limit-switch mode must be 1 (ignore), 2 (makes) or 3 (breaks)");
      l->channel = chan();
      l->cw_hard = l->ccw_hard = *want.limit_switch_mode;
      send(apt::setLimSwitchParams(config_.address, *l));
      params_.written.push_back("limit switches");
      m = request(apt::reqLimSwitchParams(config_.address, chan()), apt::id::kMotGetLimSwitchParams);
      l = apt::parseLimSwitchParams(*m);
    }
    if (l) params_.limit_switches = *l;
  }
}

void Stage::disconnect() {
  if (transport_ && transport_->isOpen()) transport_->close();
  connected_ = false;
}

void Stage::reconnect() {
  transport_->close();
  connected_ = false;
  state_ = AxisState{};
  connect();
}

void Stage::identify() {
  requireConnected();
  send(apt::identify(config_.address));
}

void Stage::setEnabled(bool enabled) {
  requireConnected();
  send(apt::setChanEnableState(config_.address, chan(), enabled));
  request(apt::reqChanEnableState(config_.address, chan()), apt::id::kModGetChanEnableState);
  if (state_.enabled != enabled)
    throw DeviceError(DeviceError::Kind::Protocol, name() + " did not " + (enabled ? "enable" : "disable") +
                                                       " channel " + std::to_string(config_.channel));
}

AxisState Stage::poll() {
  requireConnected();
  if (config_.controller.kind == apt::MotorKind::Stepper)
    request(apt::reqStatusUpdate(config_.address, chan()), apt::id::kMotGetStatusUpdate);
  else
    request(apt::reqDcStatusUpdate(config_.address, chan()), apt::id::kMotGetDcStatusUpdate);
  return state_;
}

double Stage::moveDuration(double distance) const {
  const double v = std::max(units_.aptToVelocity(vel_.max_velocity), 1e-9);
  const double a = std::max(units_.aptToAcceleration(vel_.acceleration), 1e-9);
  const double d = std::abs(distance);
  // Trapezoid: d >= v^2/a -> v/a + d/v; triangle otherwise -> 2 sqrt(d/a).
  return d >= v * v / a ? v / a + d / v : 2.0 * std::sqrt(d / a);
}

void checkEncodable(const StageConfig& config, double value, const std::string& what) {
  const double counts = std::round(value * config.stage.counts_per_unit);
  constexpr double lo = std::numeric_limits<std::int32_t>::min(), hi = std::numeric_limits<std::int32_t>::max();
  if (!(counts >= lo && counts <= hi)) {
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  " refused: %.6g %s is %.6g counts at %.6g counts/%s, beyond the protocol's signed "
                  "32-bit range; nothing was sent",
                  value, config.stage.unit().c_str(), counts, config.stage.counts_per_unit,
                  config.stage.unit().c_str());
    throw DeviceError(DeviceError::Kind::SoftLimit, what + buf);
  }
}

void checkMoveTarget(const StageConfig& config, double target, const std::string& what, const std::string& device) {
  const std::string unit = config.stage.unit();
  if (!std::isfinite(target)) throw DeviceError(DeviceError::Kind::Usage, what + ": target is not a finite number");
  if (target < config.soft_min - 1e-9 || target > config.soft_max + 1e-9)
    throw DeviceError(DeviceError::Kind::SoftLimit, what + " to " + fmt(target, unit) +
                                                        " refused: outside the soft limits [" +
                                                        fmt(config.soft_min, unit) + ", " + fmt(config.soft_max, unit) +
                                                        "] of " + device + "; nothing was sent");
  const apt::StageModel& s = config.stage;
  if (!s.continuous && (target < s.travel_min - 1e-9 || target > s.travel_max + 1e-9))
    throw DeviceError(DeviceError::Kind::SoftLimit,
                      what + " to " + fmt(target, unit) + " refused: outside the travel [" + fmt(s.travel_min, unit) +
                          ", " + fmt(s.travel_max, unit) + "] of the " + s.name + "; nothing was sent");
  checkEncodable(config, target, what + " to " + fmt(target, unit));
}

void Stage::checkTarget(double target, const std::string& what) const {
  checkMoveTarget(config_, target, what, name());
}

void Stage::requireReady() {
  if (!state_.known) poll();
  if (!state_.enabled)
    throw DeviceError(DeviceError::Kind::Disabled,
                      name() + ": channel " + std::to_string(config_.channel) + " is disabled: enable it first");
  if (!state_.homed)
    throw DeviceError(DeviceError::Kind::NotHomed,
                      name() + " is not homed: home it first (positions are meaningless before)");
}

void Stage::waitMotionEnd(double timeout_s, const std::string& what) {
  const auto m = waitFor(
      [](const apt::Message& r) {
        return r.id == apt::id::kMotMoveCompleted || r.id == apt::id::kMotMoveStopped || r.id == apt::id::kMotMoveHomed;
      },
      timeout_s, what);
  settled_at_ = transport_->now() + config_.settle_s;
  poll();  // the state after a motion comes from a status poll, never from the completion alone
  if (m.id == apt::id::kMotMoveStopped && what != "MOT_MOVE_STOP")
    throw DeviceError(DeviceError::Kind::Protocol,
                      name() + ": " + what + " ended early at " + fmt(state_.position, config_.stage.unit()) +
                          (state_.forward_limit || state_.reverse_limit ? " (limit switch)" : " (stopped)"));
}

void Stage::home() {
  requireConnected();
  if (!state_.known) poll();
  if (!state_.enabled)  // the controller would ignore the command and the wait would time out
    throw DeviceError(DeviceError::Kind::Disabled, name() + ": channel " + std::to_string(config_.channel) +
                                                       " is disabled: enable it before homing");
  const double span = config_.stage.continuous ? 360.0 : config_.stage.travel_max - config_.stage.travel_min;
  const double timeout = 1.5 * span / std::max(config_.stage.home_velocity, 1e-6) + config_.move_timeout_margin_s;
  send(apt::moveHome(config_.address, chan()));
  state_.homing = true;
  waitFor([](const apt::Message& m) { return m.id == apt::id::kMotMoveHomed; }, timeout, "MOT_MOVE_HOME");
  settled_at_ = transport_->now() + config_.settle_s;
  poll();
}

double Stage::startMoveAbsolute(double position) {
  requireConnected();
  checkTarget(position, "move");
  requireReady();
  const double duration = moveDuration(position - state_.position);
  send(apt::moveAbsolute(config_.address, chan(), units_.positionToCounts(position)));
  pending_what_ = "MOT_MOVE_ABSOLUTE";
  state_.moving = true;
  return duration;
}

double Stage::startMoveRelative(double distance) {
  requireConnected();
  if (!std::isfinite(distance))
    throw DeviceError(DeviceError::Kind::Usage, "relative move: distance is not a finite number");
  requireReady();
  poll();
  const std::string what = "relative move by " + fmt(distance, config_.stage.unit());
  checkEncodable(config_, distance, what);
  checkTarget(state_.position + distance, what);
  const double duration = moveDuration(distance);
  send(apt::moveRelative(config_.address, chan(), units_.positionToCounts(distance)));
  pending_what_ = "MOT_MOVE_RELATIVE";
  state_.moving = true;
  return duration;
}

void Stage::waitForMotion(double timeout_s) {
  waitMotionEnd(timeout_s, pending_what_);
}

void Stage::finishMove(double duration_s) {
  waitForMotion(1.5 * duration_s + config_.move_timeout_margin_s);
}

void Stage::moveAbsolute(double position) {
  finishMove(startMoveAbsolute(position));
}

void Stage::moveRelative(double distance) {
  finishMove(startMoveRelative(distance));
}

void Stage::jog(apt::JogDirection direction) {
  requireConnected();
  const JogSettings j = jogSettings();
  if (j.continuous)
    throw DeviceError(DeviceError::Kind::SoftLimit,
                      name() + " is in continuous jog mode, which cannot honour soft limits; set single-step jogs");
  requireReady();
  poll();
  const double sign = direction == apt::JogDirection::Forward ? 1.0 : -1.0;
  checkTarget(state_.position + sign * j.step, std::string("jog ") + (sign > 0 ? "forward" : "reverse"));
  const double v = std::max(j.max_velocity, 1e-9), a = std::max(j.acceleration, 1e-9);
  const double t = j.step >= v * v / a ? v / a + j.step / v : 2.0 * std::sqrt(j.step / a);
  send(apt::moveJog(config_.address, chan(), direction));
  waitMotionEnd(1.5 * t + config_.move_timeout_margin_s, "MOT_MOVE_JOG");
}

void Stage::sendStop(bool immediate) {
  requireConnected();
  send(apt::moveStop(config_.address, chan(), immediate ? apt::StopMode::Immediate : apt::StopMode::Profiled));
}

void Stage::stop(bool immediate) {
  const bool was_moving = state_.moving || !state_.known;
  sendStop(immediate);  // first, whatever the state: stopping must never wait on a query
  if (!was_moving) {
    // Idle axis: not every firmware answers a stop with MOVE_STOPPED; the status says enough.
    settled_at_ = transport_->now() + config_.settle_s;
    poll();
    return;
  }
  const double v = std::max(std::abs(state_.velocity), units_.aptToVelocity(vel_.max_velocity));
  const double a = std::max(units_.aptToAcceleration(vel_.acceleration), 1e-9);
  waitFor([](const apt::Message& m) { return m.id == apt::id::kMotMoveStopped; }, v / a + config_.move_timeout_margin_s,
          "MOT_MOVE_STOP");
  settled_at_ = transport_->now() + config_.settle_s;
  poll();
}

VelocitySettings Stage::velocity() {
  requireConnected();
  const auto m = request(apt::reqVelParams(config_.address, chan()), apt::id::kMotGetVelParams);
  if (auto p = apt::parseVelParams(m)) vel_ = *p;
  return {units_.aptToVelocity(vel_.max_velocity), units_.aptToAcceleration(vel_.acceleration)};
}

void Stage::setVelocity(const VelocitySettings& v) {
  requireConnected();
  if (!(v.max_velocity > 0) || !(v.acceleration > 0) || v.max_velocity > config_.stage.max_velocity * 1.0001 ||
      v.acceleration > config_.stage.max_acceleration * 1.0001)
    throw DeviceError(DeviceError::Kind::Usage,
                      "velocity " + fmt(v.max_velocity, config_.stage.unit() + "/s") + ", acceleration " +
                          fmt(v.acceleration, config_.stage.unit() + "/s^2") + " outside (0, " +
                          fmt(config_.stage.max_velocity, "") + "] / (0, " + fmt(config_.stage.max_acceleration, "") +
                          "] of the " + config_.stage.name);
  apt::VelParams p{chan(), 0, units_.accelerationToApt(v.acceleration), units_.velocityToApt(v.max_velocity)};
  send(apt::setVelParams(config_.address, p));
  velocity();  // read back what the controller accepted
}

JogSettings Stage::jogSettings() {
  requireConnected();
  const auto m = request(apt::reqJogParams(config_.address, chan()), apt::id::kMotGetJogParams);
  const auto p = apt::parseJogParams(m);
  if (!p) throw DeviceError(DeviceError::Kind::Protocol, name() + " sent malformed jog parameters");
  return {p->mode == apt::JogMode::Continuous, units_.countsToPosition(p->step_size),
          units_.aptToVelocity(p->max_velocity), units_.aptToAcceleration(p->acceleration),
          p->stop_mode == apt::StopMode::Immediate};
}

void Stage::setJogSettings(const JogSettings& j) {
  requireConnected();
  if (!(j.step > 0) || !(j.max_velocity > 0) || !(j.acceleration > 0) ||
      j.max_velocity > config_.stage.max_velocity * 1.0001)
    throw DeviceError(
        DeviceError::Kind::Usage,
        "jog settings need a positive step, velocity and acceleration within the " + config_.stage.name + "'s limits");
  apt::JogParams p{chan(),
                   j.continuous ? apt::JogMode::Continuous : apt::JogMode::SingleStep,
                   units_.positionToCounts(j.step),
                   0,
                   units_.accelerationToApt(j.acceleration),
                   units_.velocityToApt(j.max_velocity),
                   j.immediate_stop ? apt::StopMode::Immediate : apt::StopMode::Profiled};
  send(apt::setJogParams(config_.address, p));
}

std::vector<std::string> emergencyStop(const std::vector<Stage*>& axes) {
  std::vector<std::string> problems;
  std::vector<Stage*> sent;
  for (Stage* s : axes) {  // first every STOP, as fast as possible
    try {
      s->sendStop(true);
      sent.push_back(s);
    } catch (const std::exception& e) {
      problems.push_back(e.what());
    }
  }
  for (Stage* s : sent) {  // then confirm each
    try {
      s->poll();
    } catch (const std::exception& e) {
      problems.push_back(e.what());
    }
  }
  return problems;
}

}  // namespace fovea::devices
