#pragma once
// --detector classical|learned|auto of the pupil-tracking commands (track, closed-loop,
// calibrate gaze): the chosen detector, or a usage error (exit 2) naming the choices; for
// learned and auto the network is loaded now, so a missing model is an input error (exit 1)
// naming its paths before any work.
#include <string>

#include "model/gaze/pupil_detector_choice.h"

namespace fovea::cli {

gaze::PupilDetectorKind detectorOrExit(const std::string& name);

}  // namespace fovea::cli
