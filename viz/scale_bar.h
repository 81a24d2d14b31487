#pragma once
// A scale bar in millimetres for a renderer: a bar of a round length (1, 2 or 5 x 10^n mm)
// about 120 px long, valid at the camera's focal plane (perspective) or everywhere (parallel
// projection). Updated before each render of the measured renderer; drawn at the right end
// of a host renderer (the view's bottom margin, viz/scene_view.h), so it never covers the
// scene and the translucent passes never touch it.

#include <vtkNew.h>

class vtkActor2D;
class vtkCallbackCommand;
class vtkObject;
class vtkPoints;
class vtkRenderer;
class vtkTextActor;

namespace fovea::viz {

// Millimetres per pixel at the focal plane of the renderer's active camera.
double millimetresPerPixel(vtkRenderer* renderer);
// The largest 1, 2, 5 x 10^n not above `limit` (limit > 0).
double roundScaleLength(double limit);

class ScaleBar {
 public:
  ScaleBar(vtkRenderer* measured, vtkRenderer* host);
  ~ScaleBar();
  ScaleBar(const ScaleBar&) = delete;
  ScaleBar& operator=(const ScaleBar&) = delete;

  double lengthMm() const { return length_mm_; }
  void update();
  // Bar and label colour (white on the studio's dark background, dark in print).
  void setColor(double r, double g, double b);
  // Hidden where a length at the focal plane means nothing (the eye's view).
  void setVisible(bool on);

 private:
  static void onStart(vtkObject*, unsigned long, void* clientData, void*);
  vtkRenderer* renderer_;
  vtkRenderer* host_;
  vtkNew<vtkPoints> points_;
  vtkNew<vtkActor2D> bar_;
  vtkNew<vtkTextActor> label_;
  vtkNew<vtkCallbackCommand> callback_;
  double length_mm_ = 0.0;
};

}  // namespace fovea::viz
