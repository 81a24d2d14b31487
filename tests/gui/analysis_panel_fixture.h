#pragma once
// Set-up shared by the studio's GUI tests of the analyses (Analyses panel, fit, tolerance, form
// defaults) and of recovery: the prototype scene the studio opens (app/embedded_scene.h's
// embeddedDefaultScene) and a scratch folder under $FOVEA_TEST_TMP as a Qt path
// (tests/test_files.h's testTmpDir).
#include <QString>

#include <string>

#include "app/embedded_scene.h"
#include "tests/test_files.h"

namespace fovea::testing {

// $FOVEA_TEST_TMP/<name>, created (emptied first when `fresh`), as a QString.
inline QString testTmpPath(const std::string& name, bool fresh = false) {
  return QString::fromStdString(testTmpDir(name, fresh).string());
}

}  // namespace fovea::testing
