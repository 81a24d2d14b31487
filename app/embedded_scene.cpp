#include "app/embedded_scene.h"

namespace fovea {
std::string_view embeddedDefaultSceneJson() {
  static constexpr std::string_view kJson =
#include "fovea/embedded_scene.inc"
      ;
  return kJson;
}
}  // namespace fovea
