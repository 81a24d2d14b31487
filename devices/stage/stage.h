#pragma once
// One motorised axis driven over the APT protocol through any Transport (USB or virtual).
//
// Safety rules:
//  - Soft limits (stage coordinates, mm or deg) are checked BEFORE any byte of a move is
//    sent: absolute targets directly, relative moves and jog steps against the last polled
//    position. A refused move throws DeviceError(SoftLimit) and the link sees nothing.
//  - Absolute moves and jogs need a homed axis (DeviceError(NotHomed)).
//  - Every wait has a timeout ending in DeviceError(Timeout) naming the device and message.
//  - A vanished link (unplug) throws DeviceError(Disconnected) and marks the axis position
//    unknown; reconnect() reopens the link and re-reads the state.
#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "devices/apt/apt_decoder.h"
#include "devices/apt/apt_message.h"
#include "devices/apt/stage_models.h"
#include "devices/stage/apt_log.h"
#include "devices/transport/device_error.h"
#include "devices/transport/transport.h"

namespace fovea::devices {

// Controller parameters the scene asks for, written on connect (unset: left as the
// controller has them). Units: mm or deg, per s, per s^2.
struct ControllerSetup {
  std::optional<double> max_velocity, acceleration;  // SET_VELPARAMS
  std::optional<double> jog_step;                    // SET_JOGPARAMS (single-step jogs)
  std::optional<double> home_velocity;               // SET_HOMEPARAMS
  // SET_LIMSWITCHPARAMS hard-limit mode for both switches: 1 ignore, 2 makes on contact,
  // 3 breaks on contact (protocol document).
  std::optional<std::uint16_t> limit_switch_mode;
  bool empty() const { return !max_velocity && !acceleration && !jog_step && !home_velocity && !limit_switch_mode; }
};

struct StageConfig {
  apt::ControllerModel controller;
  apt::StageModel stage;
  std::uint8_t channel = 1;
  std::uint8_t address = apt::addr::kGenericUsb;
  double soft_min = 0.0, soft_max = 0.0;          // stage coordinates (mm or deg)
  std::chrono::milliseconds reply_timeout{2000};  // requests (info, status, params)
  double move_timeout_margin_s = 3.0;             // added to 1.5x the profile time
  double settle_s = 0.05;                         // ringing after a motion completion (the camera stale-frame rule)
  ControllerSetup setup;                          // written on connect
};
// Soft limits default to the stage's travel (or +-180 deg for continuous rotation).
StageConfig defaultStageConfig(const apt::ControllerModel& controller, const apt::StageModel& stage);

struct AxisState {
  bool known = false;                     // false until polled, and after an unplug
  double position = 0.0, velocity = 0.0;  // mm (deg), mm/s (deg/s)
  bool enabled = false, homed = false, homing = false, moving = false;
  bool forward_limit = false, reverse_limit = false, motion_error = false;
  std::uint32_t bits = 0;
};

struct VelocitySettings {
  double max_velocity = 0, acceleration = 0;  // units/s, units/s^2
};
struct JogSettings {
  bool continuous = false;
  double step = 0, max_velocity = 0, acceleration = 0;
  bool immediate_stop = false;
};
// What the controller reported on connect (after the writes the scene asked for).
struct ControllerParameters {
  VelocitySettings velocity;
  std::optional<JogSettings> jog;
  std::optional<apt::HomeParams> home;  // raw; home_velocity converted below
  double home_velocity = 0;             // units/s
  double home_offset = 0;               // units
  std::optional<apt::LimitSwitchParams> limit_switches;
  std::vector<std::string> written;  // "velocity", "jog", "home", "limit switches"
};

// "velocity 2 mm/s, 1.5 mm/s^2; jog single-step 0.1 mm at 1 mm/s; home reverse at 1 mm/s;
// limit switches CW makes, CCW makes (written on connect: velocity)".
std::string describeSetup(const ControllerParameters& p, const std::string& unit);

// Checks of a target before any byte is sent (used by Stage and the CLI): finite, inside
// the soft limits, inside the stage's travel whatever the soft limits say, and encodable in
// the protocol's signed 32-bit counts. Throws DeviceError(SoftLimit / Usage).
void checkMoveTarget(const StageConfig& config, double target, const std::string& what, const std::string& device);
// The same for a relative distance's counts.
void checkEncodable(const StageConfig& config, double distance, const std::string& what);

class Stage {
 public:
  Stage(std::unique_ptr<Transport> transport, StageConfig config, std::shared_ptr<AptLogSink> trace = {});
  ~Stage();

  void connect();  // open, read HW info, enable state, velocity parameters, status
  void disconnect();
  void reconnect();  // after an unplug: reopen and re-read everything
  bool connected() const { return connected_; }

  const StageConfig& config() const { return config_; }
  const apt::UnitConverter& units() const { return units_; }
  std::string name() const;  // "KDC101 27000001"
  apt::HwInfo hardwareInfo() const { return info_; }

  void identify();
  void setEnabled(bool enabled);
  void home();
  void moveAbsolute(double position);  // = startMoveAbsolute + waitForMotion
  void moveRelative(double distance);
  // Non-blocking variants for interactive use: checks, sends, returns the expected duration
  // (s); waitForMotion() then waits for MOVE_COMPLETED (MOVE_STOPPED ends it with an error).
  double startMoveAbsolute(double position);
  double startMoveRelative(double distance);
  void waitForMotion(double timeout_s);
  // waitForMotion with the blocking moves' timeout for a move of `duration_s` (as returned by
  // the start functions): 1.5 x the duration plus the configured margin.
  void finishMove(double duration_s);
  void jog(apt::JogDirection direction);  // one single-step jog, waits for completion
  void stop(bool immediate);              // waits for MOVE_STOPPED
  void sendStop(bool immediate);          // e-stop: the STOP message only, no wait
  // Thread-safe: the thread that owns this Stage sends an immediate stop within 50 ms,
  // even in the middle of a wait (the link itself is only touched by its owner thread).
  void requestEmergencyStop() { estop_requested_ = true; }
  AxisState poll();  // requests a status update
  AxisState state() const { return state_; }
  // Link-clock time from which the axis counts as settled: the arrival of its last motion
  // completion plus settle_s. Cameras discard frames exposed before it (captureSettled).
  double settledAt() const { return settled_at_; }
  VelocitySettings velocity();
  void setVelocity(const VelocitySettings& v);
  JogSettings jogSettings();
  void setJogSettings(const JogSettings& j);
  // Read on connect (and written first where config().setup asks).
  const ControllerParameters& controllerParameters() const { return params_; }
  // The last error the controller reported (HW_RESPONSE / HW_RICHRESPONSE), in words.
  const std::string& lastControllerError() const { return last_controller_error_; }

  // Unsolicited status messages (update stream) go here as well as into state().
  void setStateCallback(std::function<void(const AxisState&)> cb) { on_state_ = std::move(cb); }

  // Seconds a trapezoidal move of `distance` takes with the current velocity settings.
  double moveDuration(double distance) const;

 private:
  void send(const apt::Message& m);
  apt::Message waitFor(const std::function<bool(const apt::Message&)>& match, double timeout_s,
                       const std::string& what);
  apt::Message request(const apt::Message& req, std::uint16_t reply_id);
  void absorb(const apt::Message& m);
  void checkTarget(double target, const std::string& what) const;
  void requireConnected() const;
  void requireReady();  // enabled and homed
  void waitMotionEnd(double timeout_s, const std::string& what);
  void setUpController();
  std::uint8_t chan() const;  // channel ident on the wire

  std::unique_ptr<Transport> transport_;
  StageConfig config_;
  std::shared_ptr<AptLogSink> trace_;
  apt::UnitConverter units_;
  apt::StreamDecoder decoder_;
  apt::HwInfo info_;
  AxisState state_;
  apt::VelParams vel_;
  ControllerParameters params_;
  std::string last_controller_error_;
  bool connected_ = false;
  std::string pending_what_ = "move";
  double settled_at_ = 0.0;
  std::atomic<bool> estop_requested_{false};
  std::function<void(const AxisState&)> on_state_;
};

// Stops every axis at once (immediate stop sent to all first, then each confirmation
// awaited). Never throws: returns one message per axis that could not be stopped.
std::vector<std::string> emergencyStop(const std::vector<Stage*>& axes);

}  // namespace fovea::devices
