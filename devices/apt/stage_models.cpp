#include "devices/apt/stage_models.h"

#include <cmath>
#include <limits>

namespace fovea::apt {

const std::vector<ControllerModel>& controllerModels() {
  static const std::vector<ControllerModel> models = {
      {"KDC101", MotorKind::DcServo, 2048.0 / 6e6, "27", "MTS25-Z8", "K-Cube brushed DC servo controller"},
      {"TDC001", MotorKind::DcServo, 2048.0 / 6e6, "83", "Z825B", "T-Cube brushed DC servo controller"},
      {"KBD101", MotorKind::Brushless, 102.4e-6, "28", "DDSM50", "K-Cube brushless DC controller"},
      {"K10CR1", MotorKind::Stepper, 0.0, "55", "K10CR1", "integrated stepper rotation mount"},
  };
  return models;
}

const std::vector<StageModel>& stageModels() {
  // Encoder counts per unit, each from the protocol document's conversion table ("Thorlabs
  // APT Controllers Host-Controller Communications Protocol", issue 25, section "Conversion
  // between position, velocity and acceleration values in encoder counts and real world
  // units"). Travel and speed limits from the stages' datasheets. A scene axis may override
  // counts_per_unit (calibrated against a gauge).
  constexpr double kInf = std::numeric_limits<double>::infinity();
  static const std::vector<StageModel> models = {
      // Z8 motor: 512 counts/rev x 67:1 gearbox / 1 mm lead screw = 34 304 counts/mm, the
      // document's figure for MTS25-Z8 / MTS50-Z8 / Z8xx on TDC001 and KDC101. (Kinesis ships
      // 34 554.96 counts/mm, a 67.49:1 gearbox; users who measure that override per axis.)
      {"MTS25-Z8", false, 34304.0, 0.0, 25.0, false, 2.4, 4.0, 2.0, 1.5, 1.0,
       "protocol document conversion table, MTS25-Z8 on KDC101/TDC001: 34 304 counts/mm (512 x 67 / 1 mm)"},
      // Z825B: the same Z8 motor and gearbox on a 1 mm lead screw -> the same figure.
      {"Z825B", false, 34304.0, 0.0, 25.0, false, 2.6, 4.0, 2.0, 1.5, 1.0,
       "protocol document conversion table, Z8xx actuators on KDC101/TDC001: 34 304 counts/mm"},
      // DDSM50: linear encoder of 0.5 um resolution -> 2 000 counts/mm (the document's DDS /
      // DDSM row for KBD101 / TBD001: 2 000 counts/mm, velocity x 13 421.77, accel. x 1.374).
      {"DDSM50", false, 2000.0, 0.0, 50.0, false, 500.0, 5000.0, 100.0, 1000.0, 10.0,
       "protocol document conversion table, DDSM/DDS stages on KBD101/TBD001: 2 000 counts/mm (0.5 um encoder)"},
      // K10CR1: 200 steps x 2048 microsteps x 120:1 worm per 360 deg = 136 533.33 counts/deg
      // (document: "K10CR1 ... 136 533 per degree", velocity x 7 329 109, accel. x 1 502).
      {"K10CR1", true, 409600.0 / 3.0, -kInf, kInf, true, 10.0, 20.0, 10.0, 10.0, 5.0,
       "protocol document conversion table, K10CR1: 136 533 counts/deg (200 x 2048 x 120 / 360)"},
  };
  return models;
}

std::optional<ControllerModel> findController(const std::string& name) {
  for (const auto& c : controllerModels())
    if (c.name == name) return c;
  return std::nullopt;
}

std::optional<StageModel> findStage(const std::string& name) {
  for (const auto& s : stageModels())
    if (s.name == name) return s;
  return std::nullopt;
}

std::optional<ControllerModel> controllerForSerial(const std::string& serial) {
  for (const auto& c : controllerModels())
    if (serial.size() == 8 && serial.rfind(c.serial_prefix, 0) == 0) return c;
  return std::nullopt;
}

UnitConverter::UnitConverter(const ControllerModel& controller, const StageModel& stage)
    : counts_per_unit_(stage.counts_per_unit) {
  if (controller.kind == MotorKind::Stepper) {
    velocity_scale_ = 53.68 * counts_per_unit_;
    acceleration_scale_ = 53.68 * 204.94e-6 * counts_per_unit_;
  } else {
    const double t = controller.sampling_interval_s;
    velocity_scale_ = counts_per_unit_ * t * 65536.0;
    acceleration_scale_ = counts_per_unit_ * t * t * 65536.0;
  }
}

namespace {
std::int32_t toInt32(double v) {
  const double r = std::round(v);  // clamp before converting: llround of a huge value is unspecified
  if (r > std::numeric_limits<std::int32_t>::max()) return std::numeric_limits<std::int32_t>::max();
  if (r < std::numeric_limits<std::int32_t>::min()) return std::numeric_limits<std::int32_t>::min();
  return static_cast<std::int32_t>(r);
}
}  // namespace

std::int32_t UnitConverter::positionToCounts(double units) const {
  return toInt32(units * counts_per_unit_);
}
double UnitConverter::countsToPosition(std::int32_t counts) const {
  return counts / counts_per_unit_;
}
std::int32_t UnitConverter::velocityToApt(double v) const {
  return toInt32(v * velocity_scale_);
}
double UnitConverter::aptToVelocity(std::int32_t apt) const {
  return apt / velocity_scale_;
}
std::int32_t UnitConverter::accelerationToApt(double a) const {
  return toInt32(a * acceleration_scale_);
}
double UnitConverter::aptToAcceleration(std::int32_t apt) const {
  return apt / acceleration_scale_;
}

}  // namespace fovea::apt
