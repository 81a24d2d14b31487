#pragma once
// A capture session's manifest (capture_session.h) as fit targets (model/analysis/fit_targets.h,
// docs/fitting.md). What a manifest really carries for a fit: for every capture of a geometric
// session on the peripheral display, its gaze and the HOE stage positions read back at the
// capture ("hoe.x", "hoe.y": the element coordinates, i.e. the HOE shift the session used at
// that gaze). Each becomes an x_p_mm target (yaw: hoe.x; pitch: hoe.y). The images themselves
// (the FOV seen) are not measured by the manifest and give no target. Colour and gaze sessions
// carry no observable of the fit.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/analysis/fit_targets.h"

namespace fovea::devices {

struct ManifestTargetOptions {
  double sigma_mm = 0.05;        // uncertainty of each x_p (stage repeatability and the operator's setting)
  std::string source = "bench";  // "source" of each target, followed by the capture's step id
};

struct ManifestTargets {
  std::vector<FitTarget> targets;
  std::vector<std::string> skipped;  // captures that gave no target, with the reason
};

// Throws std::invalid_argument when `manifest` is not a capture-session manifest (naming the key).
ManifestTargets fitTargetsFromManifest(const nlohmann::json& manifest, const ManifestTargetOptions& options = {});

}  // namespace fovea::devices
