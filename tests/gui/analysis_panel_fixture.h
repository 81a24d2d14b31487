#pragma once
// Set-up shared by the studio's GUI tests of the analyses (Analyses panel, fit, tolerance, form
// defaults) and of recovery: the prototype scene the studio opens, as a Scene, and a scratch
// folder under $FOVEA_TEST_TMP as a Qt path (tests/test_files.h's testTmpDir).
#include <QString>
#include <QtGlobal>

#include <string>

#include "app/embedded_scene.h"
#include "model/scene/scene_io.h"
#include "tests/test_files.h"

namespace fovea::testing {

// The embedded prototype scene; the test stops (qFatal) if it does not load, since every
// check after it would fail for that one reason.
inline Scene prototypeScene() {
  SceneLoadResult r = parseScene(embeddedDefaultSceneJson(), "prototype");
  if (!r.ok()) qFatal("embedded scene invalid");
  return *r.scene;
}

// $FOVEA_TEST_TMP/<name>, created (emptied first when `fresh`), as a QString.
inline QString testTmpPath(const std::string& name, bool fresh = false) {
  return QString::fromStdString(testTmpDir(name, fresh).string());
}

}  // namespace fovea::testing
