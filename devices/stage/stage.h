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

struct StageConfig {
  apt::ControllerModel controller;
  apt::StageModel stage;
  std::uint8_t channel = 1;
  std::uint8_t address = apt::addr::kGenericUsb;
  double soft_min = 0.0, soft_max = 0.0;          // stage coordinates (mm or deg)
  std::chrono::milliseconds reply_timeout{2000};  // requests (info, status, params)
  double move_timeout_margin_s = 3.0;             // added to 1.5x the profile time
  double settle_s = 0.05;                         // ringing after a motion completion (the camera stale-frame rule)
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

  std::unique_ptr<Transport> transport_;
  StageConfig config_;
  std::shared_ptr<AptLogSink> trace_;
  apt::UnitConverter units_;
  apt::StreamDecoder decoder_;
  apt::HwInfo info_;
  AxisState state_;
  apt::VelParams vel_;
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
