#pragma once
// `fovea-cli sweep` (the registry's run function, defaults otherwise) at one yaw gaze under an
// x_p rule: the x_p the one-x_p tests (issue 26) compare every other source with.
#include <QtGlobal>

#include <nlohmann/json.hpp>

#include "model/analysis/analysis_registry.h"
#include "model/analysis/hoe_travel.h"

namespace fovea::testing {

// The sweep's document; qFatal when the registry refuses the call (a test set-up fault).
inline nlohmann::json sweepAtYaw(const Scene& scene, double yaw_deg, XpRule rule) {
  const auto* def = analysis::findAnalysisDefinition("sweep");
  if (!def) qFatal("no sweep analysis in the registry");
  nlohmann::json v = analysis::defaultValues(*def);
  v["gaze-from"] = yaw_deg;
  v["gaze-to"] = yaw_deg;
  v["gaze-step"] = 5.0;
  v["xp-rule"] = xpRuleName(rule);
  auto doc = def->run(scene, v, {});
  if (!doc) qFatal("sweep refused the gaze %g", yaw_deg);
  return *doc;
}

}  // namespace fovea::testing
