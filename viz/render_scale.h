#pragma once
// Render-window pixels per logical view pixel, for overlays that size things in pixels
// (leader lengths, label boxes, the scale bar's length): the window's DPI over VTK's 72. It is
// the render scale of VtkGlWidget::setRenderScale — 1 at full resolution, 0.5 while a drag
// draws at half resolution — so such overlays keep their size on screen after magnification.

class vtkRenderer;

namespace fovea::viz {

double pixelScale(vtkRenderer* renderer);

}  // namespace fovea::viz
