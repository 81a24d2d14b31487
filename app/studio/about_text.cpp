#include "app/studio/about_text.h"

#include <vtkVersion.h>
#include <opencv2/core/version.hpp>

#include <Eigen/Core>

#include "fovea/version.h"

namespace fovea::studio {

QString versionsHtml() {
  return QStringLiteral(
             "<h3>Foveated AR Studio %1</h3>"
             "<p>Design, simulate and bench-test a dynamically foveated AR display.</p>"
             "<table>"
             "<tr><td>Qt</td><td>%2 (built with %3)</td></tr>"
             "<tr><td>VTK</td><td>%4</td></tr>"
             "<tr><td>OpenCV</td><td>%5</td></tr>"
             "<tr><td>Eigen</td><td>%6.%7.%8</td></tr>"
             "</table>")
      .arg(FOVEA_VERSION_STRING, qVersion(), QT_VERSION_STR, vtkVersion::GetVTKVersion(), CV_VERSION)
      .arg(EIGEN_WORLD_VERSION)
      .arg(EIGEN_MAJOR_VERSION)
      .arg(EIGEN_MINOR_VERSION);
}

}  // namespace fovea::studio
