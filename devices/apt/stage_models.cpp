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
  // Encoder counts from the protocol document's stage table: Z8 motors 512 counts/rev x
  // 67:1 gearbox / 1 mm lead screw = 34 304 counts/mm; DDS linear encoder 0.5 um = 2 000
  // counts/mm; K10CR1 200 steps x 2048 microsteps x 120:1 worm / 360 deg = 409 600/3 per deg.
  // Travel and speed limits from the datasheets.
  static const std::vector<StageModel> models = {
      {"MTS25-Z8", false, 34304.0, 0.0, 25.0, false, 2.4, 4.0, 2.0, 1.5, 1.0},
      {"Z825B", false, 34304.0, 0.0, 25.0, false, 2.6, 4.0, 2.0, 1.5, 1.0},
      {"DDSM50", false, 2000.0, 0.0, 50.0, false, 500.0, 5000.0, 100.0, 1000.0, 10.0},
      {"K10CR1", true, 409600.0 / 3.0, -std::numeric_limits<double>::infinity(),
       std::numeric_limits<double>::infinity(), true, 10.0, 20.0, 10.0, 10.0, 5.0},
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
