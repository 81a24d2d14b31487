#pragma once
// Controllers and stages the bench uses, with the conversions between real units (mm or
// degrees) and the APT protocol's integer units.
//
// Protocol document, "Conversion between position, velocity and acceleration values in
// encoder counts and real world units":
//   position      P_apt = EncCnt * P
//   DC servo / brushless controllers, sampling interval T:
//     velocity    V_apt = EncCnt * T * 65536 * V        (counts per sample, 16.16 fixed point)
//     accel.      A_apt = EncCnt * T^2 * 65536 * A      (counts per sample^2, 16.16 fixed point)
//     T = 2048 / 6e6 s for KDC101 / TDC001, T = 102.4 us for KBD101 / TBD001.
//   Trinamic stepper controllers (K10CR1, KST101, TST101): V_apt = 53.68 * EncCnt * V,
//     A_apt = 53.68 * 204.94e-6 * EncCnt * A  (= EncCnt * A / 90.9).
// Check (document's table): Z8 actuators on a KDC101, EncCnt 34 304/mm -> 767 367 per mm/s
// and 261.93 per mm/s^2; K10CR1 136 533/deg -> 7 329 109 per deg/s and 1 502 per deg/s^2.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace fovea::apt {

enum class MotorKind { DcServo, Brushless, Stepper };

struct ControllerModel {
  std::string name;  // "KDC101"
  MotorKind kind = MotorKind::DcServo;
  double sampling_interval_s = 2048.0 / 6e6;  // T (servo/brushless only)
  std::string serial_prefix;                  // Thorlabs serial numbers start with a model code ("27")
  std::string default_stage;                  // "MTS25-Z8"
  std::string description;
  bool channel_bit_mask = false;  // channel idents 3/4 sent as 0x04/0x08 (multi-channel benchtop units)
};

struct StageModel {
  std::string name;                            // "MTS25-Z8"
  bool rotation = false;                       // units: degrees (true) or mm (false)
  double counts_per_unit = 1.0;                // EncCnt per mm or per degree
  double travel_min = 0.0, travel_max = 25.0;  // mm or deg; rotation stages may be continuous
  bool continuous = false;                     // unlimited rotation
  double max_velocity = 1.0;                   // units/s (datasheet)
  double max_acceleration = 1.0;               // units/s^2
  double default_velocity = 1.0, default_acceleration = 1.0;
  double home_velocity = 1.0;
  std::string unit() const { return rotation ? "deg" : "mm"; }
  std::string source;  // where counts_per_unit comes from
};

const std::vector<ControllerModel>& controllerModels();
const std::vector<StageModel>& stageModels();
std::optional<ControllerModel> findController(const std::string& name);
std::optional<StageModel> findStage(const std::string& name);
// Controller model from a Thorlabs serial number's prefix ("27xxxxxx" -> KDC101).
std::optional<ControllerModel> controllerForSerial(const std::string& serial);

// Real units <-> APT integer units for one controller driving one stage.
class UnitConverter {
 public:
  UnitConverter(const ControllerModel& controller, const StageModel& stage);
  std::int32_t positionToCounts(double units) const;
  double countsToPosition(std::int32_t counts) const;
  std::int32_t velocityToApt(double units_per_s) const;
  double aptToVelocity(std::int32_t apt) const;
  std::int32_t accelerationToApt(double units_per_s2) const;
  double aptToAcceleration(std::int32_t apt) const;
  double velocityScale() const { return velocity_scale_; }          // APT units per (unit/s)
  double accelerationScale() const { return acceleration_scale_; }  // APT units per (unit/s^2)
  double countsPerUnit() const { return counts_per_unit_; }

 private:
  double counts_per_unit_, velocity_scale_, acceleration_scale_;
};

}  // namespace fovea::apt
