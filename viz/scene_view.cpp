#include "viz/scene_view.h"

#include <QMouseEvent>

#include <algorithm>
#include <cmath>
#include <limits>

#include <vtkActor.h>
#include <vtkActor2DCollection.h>
#include <vtkAxesActor.h>
#include <vtkCamera.h>
#include <vtkCaptionActor2D.h>
#include <vtkCellPicker.h>
#include <vtkCubeSource.h>
#include <vtkGenericRenderWindowInteractor.h>
#include <vtkOrientationMarkerWidget.h>
#include <vtkPolyDataMapper.h>
#include <vtkProp.h>
#include <vtkProp3D.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkTextProperty.h>

#include "model/scene/scene_geometry.h"
#include "viz/scale_bar.h"
#include "viz/scene_actors.h"
#include "viz/scene_elements.h"

namespace fovea::viz {

SceneView::SceneView(QWidget* parent) : VtkGlWidget(parent) {
  vtkRenderer* ren = renderer();
  ren->GradientBackgroundOn();
  ren->SetBackground(0.10, 0.11, 0.13);
  ren->SetBackground2(0.24, 0.27, 0.33);
  ren->SetUseDepthPeeling(true);  // correct blending of the translucent films and frustum
  ren->SetMaximumNumberOfPeels(8);

  auto axes = vtkSmartPointer<vtkAxesActor>::New();
  axes->SetShaftTypeToCylinder();
  axes->SetTotalLength(1.0, 1.0, 1.0);
  for (vtkCaptionActor2D* c :
       {axes->GetXAxisCaptionActor2D(), axes->GetYAxisCaptionActor2D(), axes->GetZAxisCaptionActor2D()})
    c->GetCaptionTextProperty()->SetFontSize(14);
  axesWidget_ = vtkSmartPointer<vtkOrientationMarkerWidget>::New();
  axesWidget_->SetOrientationMarker(axes);
  axesWidget_->SetInteractor(interactor());
  axesWidget_->SetViewport(0.0, 0.0, 0.16, 0.22);
  axesWidget_->SetEnabled(1);
  axesWidget_->InteractiveOff();

  scaleBar_ = std::make_unique<ScaleBar>(ren);

  picker_ = vtkSmartPointer<vtkCellPicker>::New();
  picker_->SetTolerance(0.004);

  highlight_ = vtkSmartPointer<vtkActor>::New();
  auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  highlight_->SetMapper(mapper);
  highlight_->GetProperty()->SetRepresentationToWireframe();
  highlight_->GetProperty()->SetColor(colors::kSelection[0], colors::kSelection[1], colors::kSelection[2]);
  highlight_->GetProperty()->SetLineWidth(2.5);
  highlight_->GetProperty()->LightingOff();
  highlight_->PickableOff();
  highlight_->VisibilityOff();
  ren->AddViewProp(highlight_);
}

namespace {
// The studio's dark gradient and the print look's light one (bottom, top).
constexpr double kScreenBackground[2][3] = {{0.10, 0.11, 0.13}, {0.24, 0.27, 0.33}};
constexpr double kPrintBackground[2][3] = {{1.0, 1.0, 1.0}, {0.90, 0.92, 0.95}};
constexpr double kScreenText[3] = {0.92, 0.92, 0.92};
constexpr double kPrintText[3] = {0.10, 0.10, 0.12};
}  // namespace

void SceneView::setPrintLook(bool on) {
  if (on == printLook_) return;
  printLook_ = on;
  vtkRenderer* ren = renderer();
  const auto& bg = on ? kPrintBackground : kScreenBackground;
  ren->SetBackground(bg[0][0], bg[0][1], bg[0][2]);
  ren->SetBackground2(bg[1][0], bg[1][1], bg[1][2]);
  const double* text = on ? kPrintText : kScreenText;
  scaleBar_->setColor(on ? text[0] : 1.0, on ? text[1] : 1.0, on ? text[2] : 1.0);
  vtkActor2DCollection* overlays = ren->GetActors2D();
  overlays->InitTraversal();
  while (vtkActor2D* a = overlays->GetNextActor2D())
    if (auto* bar = vtkScalarBarActor::SafeDownCast(a)) {
      bar->GetTitleTextProperty()->SetColor(text[0], text[1], text[2]);
      bar->GetLabelTextProperty()->SetColor(text[0], text[1], text[2]);
      if (vtkTextProperty* note = bar->GetAnnotationTextProperty()) note->SetColor(text[0], text[1], text[2]);
    }
  SceneLayer& handles = layer(QStringLiteral("handles"));
  if (on) {
    handlesWereVisible_ = handles.isVisible();
    handles.setVisible(false);
  } else {
    handles.setVisible(handlesWereVisible_);
  }
  updateHighlight();
  requestRender();
}

SceneView::~SceneView() {
  axesWidget_->SetEnabled(0);
  layers_.clear();
}

SceneLayer& SceneView::layer(const QString& name) {
  auto& slot = layers_[name];
  if (!slot) slot = std::make_unique<SceneLayer>(renderer(), name);
  return *slot;
}

void SceneView::setScene(const Scene& scene, bool reset) {
  const bool first = !hasScene_;
  scene_ = scene;
  hasScene_ = true;
  SceneLayer& l = sceneLayer();
  l.clear();
  buildSceneActors(scene_, l);
  applyHoeShift();
  updateHighlight();
  if (first || reset) showStandardView(StandardView::Isometric);
  requestRender();
}

void SceneView::setSelectedElement(const QString& id) {
  if (id == selected_) return;
  selected_ = id;
  updateHighlight();
  requestRender();
  emit selectionChanged(id);
}

void SceneView::updateHighlight() {
  double b[6] = {std::numeric_limits<double>::max(), -std::numeric_limits<double>::max(),
                 std::numeric_limits<double>::max(), -std::numeric_limits<double>::max(),
                 std::numeric_limits<double>::max(), -std::numeric_limits<double>::max()};
  bool any = false;
  if (!selected_.isEmpty()) {
    for (vtkProp* p : sceneLayer().propsOf(selected_)) {
      const double* pb = p->GetBounds();
      if (!pb) continue;
      for (int i = 0; i < 3; ++i) {
        b[2 * i] = std::min(b[2 * i], pb[2 * i]);
        b[2 * i + 1] = std::max(b[2 * i + 1], pb[2 * i + 1]);
      }
      any = true;
    }
  }
  if (!any || printLook_) {  // printed figures carry no selection box
    highlight_->VisibilityOff();
    return;
  }
  const double pad = 1.0;  // mm around the element
  vtkNew<vtkCubeSource> cube;
  cube->SetBounds(b[0] - pad, b[1] + pad, b[2] - pad, b[3] + pad, b[4] - pad, b[5] + pad);
  cube->Update();
  static_cast<vtkPolyDataMapper*>(highlight_->GetMapper())->SetInputData(cube->GetOutput());
  highlight_->VisibilityOn();
}

void SceneView::setHoeDisplayShift(const Eigen::Vector3d& shift) {
  if (shift == hoeShift_) return;
  hoeShift_ = shift;
  applyHoeShift();
  updateHighlight();
  requestRender();
}

void SceneView::applyHoeShift() {
  QStringList ids{"hoe"};
  for (int i = 0; i < static_cast<int>(scene_.hoe_layers.size()); ++i) ids << hoeLayerId(i);
  for (const QString& id : ids)
    for (vtkProp* p : sceneLayer().propsOf(id))
      if (auto* p3 = vtkProp3D::SafeDownCast(p)) p3->SetPosition(hoeShift_.x(), hoeShift_.y(), hoeShift_.z());
}

std::pair<Eigen::Vector3d, Eigen::Vector3d> SceneView::viewRay(const QPointF& pos) {
  vtkRenderer* ren = renderer();
  const double dpr = devicePixelRatioF();
  const double x = pos.x() * dpr, y = (height() - pos.y()) * dpr;
  double nearP[4], farP[4];
  ren->SetDisplayPoint(x, y, 0.0);
  ren->DisplayToWorld();
  ren->GetWorldPoint(nearP);
  ren->SetDisplayPoint(x, y, 1.0);
  ren->DisplayToWorld();
  ren->GetWorldPoint(farP);
  Eigen::Vector3d a(nearP[0] / nearP[3], nearP[1] / nearP[3], nearP[2] / nearP[3]);
  Eigen::Vector3d b(farP[0] / farP[3], farP[1] / farP[3], farP[2] / farP[3]);
  return {a, (b - a).normalized()};
}

QString SceneView::elementAt(const QPointF& pos) {
  const double dpr = devicePixelRatioF();
  const double x = pos.x() * dpr, y = (height() - pos.y()) * dpr;
  if (!picker_->Pick(x, y, 0.0, renderer())) return {};
  vtkProp* prop = picker_->GetViewProp();
  for (const auto& [name, l] : layers_) {
    QString id = l->elementOf(prop);
    if (!id.isEmpty()) return id;
  }
  return {};
}

std::optional<QPointF> SceneView::widgetPositionOf(const Eigen::Vector3d& p) {
  vtkRenderer* ren = renderer();
  ren->SetWorldPoint(p.x(), p.y(), p.z(), 1.0);
  ren->WorldToDisplay();
  double d[3];
  ren->GetDisplayPoint(d);
  if (d[2] < 0.0 || d[2] > 1.0) return std::nullopt;
  const double dpr = devicePixelRatioF();
  return QPointF(d[0] / dpr, height() - d[1] / dpr);
}

void SceneView::showStandardView(StandardView view) {
  vtkCamera* cam = renderer()->GetActiveCamera();
  cam->SetViewAngle(30.0);
  const Eigen::Vector3d hoe = toVec(scene_.hoe.pose.position_mm);
  Eigen::Vector3d dir = Eigen::Vector3d::UnitZ(), up(0, 1, 0);
  switch (view) {
    case StandardView::Top:  // from +y looking down, the world (+z) at the top of the screen
      dir = {0, 1, 0};
      up = {0, 0, 1};
      break;
    case StandardView::Side:  // from the projector's side (+x) looking at -x
      dir = {1, 0, 0};
      break;
    case StandardView::Isometric:  // from the world side, above and towards the projector
      dir = Eigen::Vector3d(0.8, 0.6, 1.0).normalized();
      break;
    case StandardView::EyeView: {
      const EyePlacement e = placeEye(scene_);
      const Eigen::Vector3d at = e.pupil_center + 0.2 * e.gaze, focus = e.pupil_center + 100.0 * e.gaze;
      cam->SetPosition(at.x(), at.y(), at.z());
      cam->SetFocalPoint(focus.x(), focus.y(), focus.z());
      cam->SetViewUp(0, 1, 0);
      cam->SetViewAngle(100.0);  // about the periphery the HOE serves
      renderer()->ResetCameraClippingRange();
      requestRender();
      return;
    }
  }
  cam->SetFocalPoint(hoe.x(), hoe.y(), hoe.z());
  const Eigen::Vector3d from = hoe + 300.0 * dir;
  cam->SetPosition(from.x(), from.y(), from.z());
  cam->SetViewUp(up.x(), up.y(), up.z());
  resetCamera();
}

void SceneView::resetCamera() {
  vtkRenderer* ren = renderer();
  // Frame the scene layer only (ignores the highlight and other overlays).
  double b[6];
  ren->ComputeVisiblePropBounds(b);
  if (b[0] <= b[1]) ren->ResetCamera(b);
  ren->GetActiveCamera()->Zoom(1.25);  // the bounding sphere frames loosely
  ren->ResetCameraClippingRange();
  requestRender();
}

void SceneView::zoomCamera(double factor) {
  renderer()->GetActiveCamera()->Zoom(factor);
  renderer()->ResetCameraClippingRange();
  requestRender();
}

double SceneView::scaleBarLengthMm() const {
  return scaleBar_->lengthMm();
}

void SceneView::mousePressEvent(QMouseEvent* e) {
  if (e->button() == Qt::LeftButton) {
    pressPos_ = e->position();
    pressed_ = true;
  }
  VtkGlWidget::mousePressEvent(e);
}

void SceneView::mouseReleaseEvent(QMouseEvent* e) {
  VtkGlWidget::mouseReleaseEvent(e);
  if (e->button() != Qt::LeftButton || !pressed_) return;
  pressed_ = false;
  if ((e->position() - pressPos_).manhattanLength() > 4.0) return;  // a drag orbits, a click picks
  const QString id = elementAt(e->position());
  setSelectedElement(id);
  emit elementPicked(id);
}

}  // namespace fovea::viz
