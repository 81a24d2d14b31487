#include "devices/calibration/manifest_targets.h"

#include <map>
#include <stdexcept>

#include "devices/calibration/capture_plan.h"
#include "model/io/json_fields.h"  // jsonTypeName

namespace fovea::devices {

ManifestTargets fitTargetsFromManifest(const nlohmann::json& m, const ManifestTargetOptions& options) {
  if (!m.is_object() || !m.contains("format") || !m["format"].is_string() ||
      m["format"].get<std::string>() != "fovea-capture-session")
    throw std::invalid_argument("not a capture session manifest (\"format\" must be \"fovea-capture-session\")");
  if (!(options.sigma_mm > 0)) throw std::invalid_argument("sigma must be > 0 mm");
  ManifestTargets out;
  if (m.contains("kind") && !m["kind"].is_string())
    throw std::invalid_argument("kind: must be a string, got " + jsonTypeName(m["kind"]));
  const std::string kind = m.value("kind", std::string());
  if (!m.contains("steps") || !m["steps"].is_array() || !m.contains("captures") || !m["captures"].is_array())
    throw std::invalid_argument("manifest: \"steps\" and \"captures\" must be lists");
  std::map<std::string, CaptureStep> steps;
  std::map<std::string, std::size_t> step_index;  // two steps of one id: a capture of it could be either
  for (std::size_t i = 0; i < m["steps"].size(); ++i) {
    const std::string at = "steps[" + std::to_string(i) + "]";
    CaptureStep s;
    try {
      s = captureStepFromJson(m["steps"][i], at);
    } catch (const std::exception& e) {
      throw std::invalid_argument(e.what());
    }
    if (const auto [it, fresh] = step_index.emplace(s.id, i); !fresh)
      throw std::invalid_argument(at + ".id: \"" + s.id + "\" is also the id of steps[" + std::to_string(it->second) +
                                  "] (each step of the plan needs its own id)");
    steps[s.id] = s;
  }
  if (kind != "geometric") {
    out.skipped.push_back("a " + kind + " session carries no observable of the fit (only geometric sessions do)");
    return out;
  }
  std::map<std::string, std::size_t> target_of_step;  // a step captured again: its last capture counts
  for (std::size_t ci = 0; ci < m["captures"].size(); ++ci) {
    const nlohmann::json& c = m["captures"][ci];
    const std::string at = "captures[" + std::to_string(ci) + "]";
    if (!c.is_object()) throw std::invalid_argument(at + ": must be an object, got " + jsonTypeName(c));
    if (!c.contains("step") || !c["step"].is_string()) throw std::invalid_argument(at + ".step: must be a string");
    if (c.contains("positions") && !c["positions"].is_object())
      throw std::invalid_argument(at + ".positions: must be an object, got " + jsonTypeName(c["positions"]));
    const std::string id = c["step"].get<std::string>();
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
    FitTarget target;
    try {
      target = parseFitTargets(nlohmann::json::array({t})).front();
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(at + ".positions." + key + ": " + e.what());
    }
    if (const auto seen = target_of_step.find(id); seen != target_of_step.end()) {
      out.targets[seen->second] = std::move(target);  // ids stay unique: `fit` reads its own output
      out.skipped.push_back(id + ": captured again; the last capture (" + at + ") is used");
    } else {
      target_of_step[id] = out.targets.size();
      out.targets.push_back(std::move(target));
    }
  }
  return out;
}

}  // namespace fovea::devices
