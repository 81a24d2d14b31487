#include "devices/stage/stage_binding.h"

#include <algorithm>

namespace fovea::devices {

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
