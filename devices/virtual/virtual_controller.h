#pragma once
// An APT motion controller in software: it decodes the real host bytes and answers with
// the real reply bytes, moving a simulated stage with trapezoidal velocity profiles in the
// time of an injectable clock.
//
// Behaviour (as documented for KDC101 / KBD101 / K10CR1, simplified where noted):
//  - MOD_IDENTIFY: no reply (the real cube flashes its display); counted.
//  - HW_REQ_INFO -> HW_GET_INFO (serial, model, "virtual <stage>" in the notes).
//  - MOD_SET/REQ_CHANENABLESTATE; disabling stops the motor where it is.
//  - MOT_MOVE_HOME: drives to the home switch (0) at the homing speed -> MOVE_HOMED.
//  - MOT_MOVE_ABSOLUTE / RELATIVE (6-byte form, or header-only form moving by the stored
//    SET_MOVEABSPARAMS / SET_MOVERELPARAMS): trapezoid with the VELPARAMS -> MOVE_COMPLETED, or
//    MOVE_STOPPED with a limit bit when the travel range cuts the move short. A new move
//    during a move replans from the current position at rest (simplification).
//  - MOT_MOVE_JOG: single step (step size) or continuous (to the travel end) with JOGPARAMS.
//  - MOT_MOVE_STOP: immediate (motor stops at once) or profiled (decelerates) -> MOVE_STOPPED.
//  - HW_START/STOP_UPDATEMSGS: status every 100 ms (DCSTATUSUPDATE; STATUSUPDATE for
//    steppers); the stream stops after 50 updates without MOT_ACK_DCSTATUSUPDATE.
//  - MOT_REQ_(DC)STATUSUPDATE, REQ_VELPARAMS, REQ_JOGPARAMS, REQ_HOMEPARAMS,
//    REQ_LIMSWITCHPARAMS answered; SET_ stored (homing runs at the HOMEPARAMS velocity).
//  - Steppers' MOVE_COMPLETED / MOVE_STOPPED use the DC status layout with a zero velocity
//    word (a real K10CR1's), not the stepper layout of GET_STATUSUPDATE.
//  - Motion commands on a disabled channel are ignored, as on the hardware.
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "devices/apt/apt_decoder.h"
#include "devices/apt/apt_message.h"
#include "devices/apt/stage_models.h"
#include "devices/virtual/motion_profile.h"
#include "devices/virtual/sim_clock.h"

namespace fovea::devices {

struct VirtualControllerConfig {
  apt::ControllerModel controller;
  apt::StageModel stage;
  std::string serial = "27000001";
  std::uint8_t address = apt::addr::kGenericUsb;
  // Power-on state. A real cube powers up unhomed at counter 0; the virtual bench defaults
  // to "homed at the home switch (0)", as a cube that was homed earlier in the session.
  bool homed = true;
  bool enabled = true;
  double position = 0.0;  // mm or deg
  // A real K10CR1's MOVE_COMPLETED carries status 0x80000030 (both moving bits set, homed
  // clear) although the move is over; true reproduces that.
  bool completion_reports_moving = false;
  // Fault injection: answer every motion command with HW_RICHRESPONSE (this code and text)
  // instead of moving.
  std::optional<apt::ControllerResponse> reject_motion;
};

class VirtualAptController {
 public:
  VirtualAptController(VirtualControllerConfig config, std::shared_ptr<Clock> clock);

  void receive(std::span<const std::uint8_t> bytes);  // bytes from the host
  std::vector<std::uint8_t> takeOutput();             // bytes for the host, up to clock time
  double nextEventTime() const;                       // when output will next appear (+inf: never)
  void advanceTo(double t_s);

  // Fault injection: a mute controller takes bytes and never answers.
  void setMute(bool mute);

  // Inspection (tests, the studio's virtual-bench view). Thread-safe: the emulator is
  // driven by its link's owner thread while views read it.
  const VirtualControllerConfig& config() const { return config_; }
  double position() const;
  double positionAt(double t_s) const;  // within the current motion
  bool homed() const;
  bool enabled() const;
  bool moving() const;
  int identifyCount() const;
  std::vector<apt::Message> received() const;
  apt::VelParams velParams() const;
  apt::JogParams jogParams() const;
  apt::HomeParams homeParams() const;
  apt::LimitSwitchParams limSwitchParams() const;

 private:
  enum class Motion { None, Move, Home, JogStep, JogContinuous, Stopping };
  double positionLocked() const;
  bool movingLocked() const;
  void advanceLocked(double t_s);
  void handle(const apt::Message& m);
  void send(const apt::Message& m);
  void startMove(double target, double v_max, double accel, Motion kind);
  void finishMotion();
  void stop(bool immediate);
  apt::ChannelStatus status() const;
  apt::ChannelStatus completionStatus() const;
  double minTravel() const;
  double maxTravel() const;

  mutable std::recursive_mutex mutex_;
  VirtualControllerConfig config_;
  std::shared_ptr<Clock> clock_;
  apt::UnitConverter units_;
  apt::StreamDecoder decoder_;
  std::vector<std::uint8_t> out_;
  std::vector<apt::Message> received_;
  double now_ = 0.0;
  bool homed_, enabled_, mute_ = false;
  MotionProfile profile_;
  Motion motion_ = Motion::None;
  bool limit_hit_ = false;
  int jog_direction_ = 0;
  apt::VelParams vel_;
  apt::JogParams jog_;
  apt::HomeParams home_;
  apt::LimitSwitchParams limits_;
  std::int32_t stored_abs_ = 0, stored_rel_ = 0;  // MOVEABSPARAMS, MOVERELPARAMS (counts)
  bool updates_ = false;
  double next_update_ = 0.0;
  int unacknowledged_ = 0;
  int identify_count_ = 0;
};

}  // namespace fovea::devices
