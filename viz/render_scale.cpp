#include "viz/render_scale.h"

#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

namespace fovea::viz {

double pixelScale(vtkRenderer* renderer) {
  vtkRenderWindow* window = renderer ? renderer->GetRenderWindow() : nullptr;
  return window ? window->GetDPI() / 72.0 : 1.0;
}

}  // namespace fovea::viz
