#pragma once
// Scene <-> stage: a fovea::StageBinding (model/scene/scene.h) says which controller and
// stage drive which element coordinate. Element coordinate = stage reading + home_offset,
// so the binding's soft limits (element coordinates) become stage soft limits by
// subtracting home_offset, intersected with the stage's travel.
#include <optional>
#include <string>

#include "devices/stage/stage.h"
#include "model/scene/scene.h"

namespace fovea::devices {

// The scene's controller set-up request in the Stage's terms.
ControllerSetup controllerSetupFor(const StageControllerSetup& setup);
// Throws DeviceError(Usage) naming the unknown model or the empty limit interval. Applies
// the binding's counts-per-unit override and controller set-up.
StageConfig stageConfigForBinding(const StageBinding& binding);
inline double elementToStage(const StageBinding& b, double element) {
  return element - b.home_offset;
}
inline double stageToElement(const StageBinding& b, double stage) {
  return stage + b.home_offset;
}

}  // namespace fovea::devices
