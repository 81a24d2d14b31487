#include "devices/calibration/manifest_targets.h"

#include <map>
#include <stdexcept>

#include "devices/calibration/capture_plan.h"

namespace fovea::devices {

ManifestTargets fitTargetsFromManifest(const nlohmann::json& m, const ManifestTargetOptions& options) {
  if (!m.is_object() || m.value("format", std::string()) != "fovea-capture-session")
    throw std::invalid_argument("not a capture session manifest (\"format\" must be \"fovea-capture-session\")");
  if (!(options.sigma_mm > 0)) throw std::invalid_argument("sigma must be > 0 mm");
  ManifestTargets out;
  const std::string kind = m.value("kind", std::string());
  if (!m.contains("steps") || !m["steps"].is_array() || !m.contains("captures") || !m["captures"].is_array())
    throw std::invalid_argument("manifest: \"steps\" and \"captures\" must be lists");
  std::map<std::string, CaptureStep> steps;
  for (std::size_t i = 0; i < m["steps"].size(); ++i) {
    try {
      const CaptureStep s = captureStepFromJson(m["steps"][i]);
      steps[s.id] = s;
    } catch (const std::exception& e) {
      throw std::invalid_argument("manifest: steps[" + std::to_string(i) + "]: " + e.what());
    }
  }
  if (kind != "geometric") {
    out.skipped.push_back("a " + kind + " session carries no observable of the fit (only geometric sessions do)");
    return out;
  }
  std::vector<FitTarget> raw;
  for (const auto& c : m["captures"]) {
    const std::string id = c.value("step", std::string());
    const auto it = steps.find(id);
    if (it == steps.end()) {
      out.skipped.push_back(id + ": no such step in the plan");
      continue;
    }
    const CaptureStep& s = it->second;
    if (s.display != BenchDisplay::Peripheral) continue;  // the foveal capture at the same pose adds nothing
    const double yaw = s.gaze_deg[0], pitch = s.gaze_deg[1];
    if (yaw != 0 && pitch != 0) {
      out.skipped.push_back(id + ": gaze on both axes (the x_p observable follows one axis)");
      continue;
    }
    const bool is_pitch = pitch != 0;
    const std::string key = is_pitch ? "hoe.y" : "hoe.x";
    const auto positions = c.value("positions", nlohmann::json::object());
    if (!positions.contains(key) || !positions[key].is_number()) {
      out.skipped.push_back(id + ": no " + key + " position recorded (the HOE axis is not motorised)");
      continue;
    }
    nlohmann::json t{{"id", "x_p " + id},
                     {"observable", "x_p_mm"},
                     {"gaze_deg", is_pitch ? pitch : yaw},
                     {"axis", is_pitch ? "pitch" : "yaw"},
                     {"value", positions[key].get<double>()},
                     {"sigma", options.sigma_mm},
                     {"unit", "mm"},
                     {"source", options.source + " (" + id + ")"}};
    out.targets.push_back(parseFitTargets(nlohmann::json::array({t})).front());
  }
  return out;
}

}  // namespace fovea::devices
