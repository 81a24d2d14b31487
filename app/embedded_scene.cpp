#include "app/embedded_scene.h"

#include <stdexcept>
#include <string>

#include "model/scene/scene_io.h"

namespace fovea {
std::string_view embeddedDefaultSceneJson() {
  static constexpr std::string_view kJson =
#include "fovea/embedded_scene.inc"
      ;
  return kJson;
}

Scene embeddedDefaultScene() {
  SceneLoadResult r = parseScene(embeddedDefaultSceneJson(), std::string(kEmbeddedSceneName));
  if (!r.ok())
    throw std::runtime_error(std::string(kEmbeddedSceneName) +
                             " does not load: " + (r.errors.empty() ? "no scene" : r.errors.front()));
  return std::move(*r.scene);
}
}  // namespace fovea
