#pragma once
// The default prototype bench (resources/scenes/prototype-bench.json, compiled in as the
// embedded default) as a Scene, for the suites: one loader instead of one per test file.
#include <QtGlobal>

#include "app/embedded_scene.h"
#include "model/scene/scene_io.h"

namespace fovea::testing {

inline Scene prototype() {
  SceneLoadResult r = parseScene(embeddedDefaultSceneJson(), "prototype-bench.json");
  if (!r.ok()) qFatal("the prototype scene does not load: %s", r.errors.front().c_str());
  return *r.scene;
}

}  // namespace fovea::testing
