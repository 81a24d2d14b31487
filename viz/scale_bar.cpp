#include "viz/scale_bar.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <QString>

#include <vtkActor2D.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCommand.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper2D.h>
#include <vtkProperty2D.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>

#include "viz/render_scale.h"

namespace fovea::viz {

double millimetresPerPixel(vtkRenderer* renderer) {
  const int* size = renderer->GetSize();
  if (size[1] <= 0) return 0.0;
  vtkCamera* cam = renderer->GetActiveCamera();
  // Visible height at the focal plane: 2 d tan(view angle / 2), or 2 x parallel scale.
  const double height_mm = cam->GetParallelProjection()
                               ? 2.0 * cam->GetParallelScale()
                               : 2.0 * cam->GetDistance() * std::tan(cam->GetViewAngle() * std::numbers::pi / 360.0);
  return height_mm / size[1];
}

double roundScaleLength(double limit) {
  const double decade = std::pow(10.0, std::floor(std::log10(limit)));
  for (double m : {5.0, 2.0, 1.0})
    if (m * decade <= limit) return m * decade;
  return decade;
}

ScaleBar::ScaleBar(vtkRenderer* measured, vtkRenderer* host) : renderer_(measured), host_(host) {
  vtkNew<vtkPolyData> data;
  for (int i = 0; i < 6; ++i) points_->InsertNextPoint(0, 0, 0);
  vtkNew<vtkCellArray> lines;
  const vtkIdType bar[2] = {0, 1}, tick_a[2] = {2, 3}, tick_b[2] = {4, 5};
  lines->InsertNextCell(2, bar);
  lines->InsertNextCell(2, tick_a);
  lines->InsertNextCell(2, tick_b);
  data->SetPoints(points_);
  data->SetLines(lines);
  vtkNew<vtkPolyDataMapper2D> mapper;
  mapper->SetInputData(data);
  bar_->SetMapper(mapper);
  bar_->GetProperty()->SetColor(1, 1, 1);
  bar_->GetProperty()->SetLineWidth(2.0);
  bar_->PickableOff();
  label_->GetTextProperty()->SetFontSize(14);
  label_->GetTextProperty()->SetColor(1, 1, 1);
  label_->GetTextProperty()->SetJustificationToCentered();
  label_->PickableOff();
  host_->AddViewProp(bar_);
  host_->AddViewProp(label_);
  callback_->SetClientData(this);
  callback_->SetCallback(&ScaleBar::onStart);
  renderer_->AddObserver(vtkCommand::StartEvent, callback_);
}

void ScaleBar::setColor(double r, double g, double b) {
  bar_->GetProperty()->SetColor(r, g, b);
  label_->GetTextProperty()->SetColor(r, g, b);
}

void ScaleBar::setVisible(bool on) {
  bar_->SetVisibility(on);
  label_->SetVisibility(on);
}

ScaleBar::~ScaleBar() {
  renderer_->RemoveObserver(callback_);
  host_->RemoveViewProp(bar_);
  host_->RemoveViewProp(label_);
}

void ScaleBar::onStart(vtkObject*, unsigned long, void* clientData, void*) {
  static_cast<ScaleBar*>(clientData)->update();
}

void ScaleBar::update() {
  const double mmpp = millimetresPerPixel(renderer_);
  const int* size = host_->GetSize();
  const int* origin = host_->GetOrigin();
  if (!(mmpp > 0.0) || size[0] <= 0) return;
  // Pixel sizes of the frame being drawn (smaller while a drag draws at reduced resolution):
  // the bar's length in millimetres does not change with the resolution.
  const double s = pixelScale(renderer_);
  length_mm_ = roundScaleLength(120.0 * s * mmpp);
  const double px = length_mm_ / mmpp;
  // Bar and label in the host's viewport pixels (the 2-D mapper's default coordinates).
  const double x1 = size[0] - 24.0 * s, x0 = x1 - px, y = std::max(8.0 * s, size[1] * 0.30), tick = 5.0 * s;
  points_->SetPoint(0, x0, y, 0);
  points_->SetPoint(1, x1, y, 0);
  points_->SetPoint(2, x0, y - tick, 0);
  points_->SetPoint(3, x0, y + tick, 0);
  points_->SetPoint(4, x1, y - tick, 0);
  points_->SetPoint(5, x1, y + tick, 0);
  points_->Modified();
  const QString text = QString::number(length_mm_, 'g', 3) + " mm";
  label_->SetInput(text.toUtf8().constData());
  label_->SetDisplayPosition(origin[0] + static_cast<int>((x0 + x1) / 2), origin[1] + static_cast<int>(y + 8 * s));
}

}  // namespace fovea::viz
