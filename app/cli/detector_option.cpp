#include "app/cli/detector_option.h"

#include <exception>

#include "app/cli/cli_common.h"

namespace fovea::cli {

gaze::PupilDetectorKind detectorOrExit(const std::string& name) {
  const auto kind = gaze::parseDetectorKind(name);
  if (!kind) usageError("--detector: '" + name + "' is not one of " + gaze::kDetectorChoices);
  if (*kind != gaze::PupilDetectorKind::Classical) {
    try {
      gaze::requireLearnedModel();
    } catch (const std::exception& e) {
      inputError("--detector " + name + ": " + e.what());
    }
  }
  return *kind;
}

}  // namespace fovea::cli
