#include "devices/stage/stage_binding.h"

#include <algorithm>

namespace fovea::devices {

ControllerSetup controllerSetupFor(const StageControllerSetup& s) {
  ControllerSetup c;
  if (s.max_velocity > 0) c.max_velocity = s.max_velocity;
  if (s.acceleration > 0) c.acceleration = s.acceleration;
  if (s.jog_step > 0) c.jog_step = s.jog_step;
  if (s.home_velocity > 0) c.home_velocity = s.home_velocity;
  if (s.limit_switches == "ignore") c.limit_switch_mode = 1;
  if (s.limit_switches == "makes") c.limit_switch_mode = 2;
  if (s.limit_switches == "breaks") c.limit_switch_mode = 3;
  return c;
}

StageConfig stageConfigForBinding(const StageBinding& b) {
  const auto controller = apt::findController(b.controller);
  const auto stage = apt::findStage(b.stage_model);
  if (!controller)
    throw DeviceError(DeviceError::Kind::Usage,
                      "stage binding of " + b.element + "." + b.axis + ": unknown controller '" + b.controller + "'");
  if (!stage)
    throw DeviceError(DeviceError::Kind::Usage,
                      "stage binding of " + b.element + "." + b.axis + ": unknown stage model '" + b.stage_model + "'");
  StageConfig c = defaultStageConfig(*controller, *stage);
  if (b.counts_per_unit > 0) {  // calibrated against a gauge: replaces the model's figure
    c.stage.counts_per_unit = b.counts_per_unit;
    c.stage.source = "scene override (" + b.element + "." + b.axis + ")";
  }
  c.setup = controllerSetupFor(b.setup);
  c.channel = static_cast<std::uint8_t>(std::clamp(b.channel, 1, 255));
  const double lo = elementToStage(b, std::min(b.soft_limits[0], b.soft_limits[1]));
  const double hi = elementToStage(b, std::max(b.soft_limits[0], b.soft_limits[1]));
  c.soft_min = stage->continuous ? lo : std::max(lo, stage->travel_min);
  c.soft_max = stage->continuous ? hi : std::min(hi, stage->travel_max);
  if (c.soft_min > c.soft_max)
    throw DeviceError(DeviceError::Kind::Usage, "stage binding of " + b.element + "." + b.axis +
                                                    ": soft limits lie outside the " + stage->name + "'s travel");
  return c;
}

}  // namespace fovea::devices
