#pragma once
// The About box text: the studio's version and the versions of Qt, VTK and OpenCV it runs with.

#include <QString>

namespace fovea::studio {
QString versionsHtml();
}
