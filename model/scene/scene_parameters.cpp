#include "model/scene/scene_parameters.h"

#include <climits>
#include <cmath>
#include <stdexcept>

#include "model/scene/scene_fields.h"
#include "model/scene/scene_io.h"

namespace fovea {

Scene withParameter(const Scene& scene, const std::string& path, double value) {
  if (!std::isfinite(value)) throw std::invalid_argument("parameter " + path + ": value must be finite");
  Scene out = scene;
  const auto target = numberAt(out, path);
  if (auto* d = std::get_if<double*>(&target)) {
    **d = value;
  } else {
    if (value != std::round(value) || std::fabs(value) > INT_MAX)
      throw std::invalid_argument("parameter " + path + ": must be an integer");
    *std::get<int*>(target) = static_cast<int>(value);
  }
  const std::vector<std::string> problems = validateScene(out);
  if (!problems.empty()) {
    std::string msg;
    for (const auto& p : problems) {
      if (!msg.empty()) msg += "; ";
      msg.append(path).append("=").append(formatNumber(value)).append(": ").append(p);
    }
    throw std::invalid_argument(msg);
  }
  return out;
}

double parameterValue(const Scene& scene, const std::string& path) {
  Scene copy = scene;
  const auto target = numberAt(copy, path);
  if (auto* d = std::get_if<double*>(&target)) return **d;
  return *std::get<int*>(target);
}

std::vector<std::string> parameterPaths(const Scene& scene) {
  std::vector<std::string> ids{"projector", "hoe"};
  for (std::size_t i = 0; i < scene.hoe_layers.size(); ++i) ids.push_back("hoe_layers[" + std::to_string(i) + "]");
  for (const char* id : {"eye", "foveal_display", "beam_shaping_lens", "foveation"}) ids.emplace_back(id);
  for (std::size_t i = 0; i < scene.stages.size(); ++i) ids.push_back("stages[" + std::to_string(i) + "]");
  Scene copy = scene;
  std::vector<std::string> out;
  for (const auto& id : ids) {
    for (const SceneField& f : elementFields(scene, id)) {
      const ValueRef ref = f.ref(copy);
      if (std::holds_alternative<double*>(ref) || std::holds_alternative<int*>(ref)) out.push_back(f.path);
      std::size_t n = 0;
      if (auto* a = std::get_if<std::span<double>>(&ref)) n = a->size();
      if (auto* a = std::get_if<std::span<int>>(&ref)) n = a->size();
      if (auto* v = std::get_if<std::vector<double>*>(&ref)) n = (*v)->size();
      for (std::size_t k = 0; k < n; ++k) out.push_back(f.path + "[" + std::to_string(k) + "]");
    }
  }
  return out;
}

}  // namespace fovea
