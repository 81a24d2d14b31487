// The benchmarks' scene: the embedded prototype bench, as the studio opens it.
#pragma once

#include "app/embedded_scene.h"
#include "model/scene/scene_io.h"

namespace fovea::bench {

inline Scene prototypeScene() {
  return *parseScene(embeddedDefaultSceneJson(), "prototype").scene;
}

}  // namespace fovea::bench
