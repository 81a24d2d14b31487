#include "viz/scene_view.h"

#include <QMouseEvent>

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include <vtkActor.h>
#include <vtkActor2DCollection.h>
#include <vtkAxesActor.h>
#include <vtkCamera.h>
#include <vtkCaptionActor2D.h>
#include <vtkCellPicker.h>
#include <vtkCubeSource.h>
#include <vtkDataSet.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkGenericRenderWindowInteractor.h>
#include <vtkMatrix4x4.h>
#include <vtkOrientationMarkerWidget.h>
#include <vtkPolyDataMapper.h>
#include <vtkProp.h>
#include <vtkProp3D.h>
#include <vtkProperty.h>
#include <vtkRenderStepsPass.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkTextProperty.h>

#include "model/scene/eye_scene.h"
#include "model/scene/scene_compare.h"
#include "model/scene/scene_geometry.h"
#include "model/units.h"
#include "viz/element_labels.h"
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

  // The margins: the colour bar's strip on the right, the scale bar's at the bottom.
  legend_ = vtkSmartPointer<vtkRenderer>::New();
  footer_ = vtkSmartPointer<vtkRenderer>::New();
  for (vtkRenderer* margin : {legend_.GetPointer(), footer_.GetPointer()}) {
    margin->InteractiveOff();
    margin->SetBackgroundAlpha(1.0);  // opaque in the blitted framebuffer
    renderWindow()->AddRenderer(margin);
  }
  applyMarginColors();
  scaleBar_ = std::make_unique<ScaleBar>(ren, footer_);
  labels_ = std::make_unique<ElementLabels>(ren);
  applyMarginColors();
  layer(QStringLiteral("seen")).setVisible(false);  // the eye's view only
  layoutViewports();

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
constexpr double kScreenMargin[3] = {0.13, 0.14, 0.17};
constexpr double kPrintMargin[3] = {1.0, 1.0, 1.0};
// Layers the eye's view hides: the light seen edge-on, fans converging on the camera, the
// eye's own marks around it, the handles, and the stages' travel bars and end stops (drawn
// mechanics: from the pupil the micro-OLED's stops were two big magenta balls at the top).
// (the left eye's train of a binocular scene too: the view is from the right eye's pupil)
const char* const kHiddenInEyeView[] = {"frustum", "rays",       "eye_marks", "handles",
                                        "stages",  "left-train", "left-rays", "left-eye_marks"};
}  // namespace

void SceneView::applyMarginColors() {
  const double* c = printLook_ ? kPrintMargin : kScreenMargin;
  legend_->SetBackground(c[0], c[1], c[2]);
  footer_->SetBackground(c[0], c[1], c[2]);
  const double* text = printLook_ ? kPrintText : kScreenText;
  if (labels_) labels_->setColor(text[0], text[1], text[2], printLook_ ? 1.0 : 0.08);
}

void SceneView::layoutViewports() {
  const double dpr = devicePixelRatioF();
  const double w = std::max(1.0, width() * dpr), h = std::max(1.0, height() * dpr);
  // Margins in device pixels, at most a third of the widget each way.
  const double fx = 1.0 - std::min(1.0 / 3.0, kLegendWidth_px * dpr / w);
  const double fy = std::min(1.0 / 3.0, kFooterHeight_px * dpr / h);
  renderer()->SetViewport(0.0, fy, fx, 1.0);
  legend_->SetViewport(fx, 0.0, 1.0, 1.0);
  footer_->SetViewport(0.0, 0.0, fx, fy);
  const double axes_px = 110.0 * dpr;
  const double ax1 = std::min(fx, axes_px / w), ay1 = std::min(1.0, fy + axes_px / h);
  axesWidget_->SetViewport(0.0, fy, ax1, ay1);
  // The labels keep off the triad (its whole viewport: the axes turn inside it).
  if (labels_) labels_->setAvoid({LabelRect{0.0, fy, ax1, ay1}});
}

void SceneView::resizeGL(int w, int h) {
  VtkGlWidget::resizeGL(w, h);
  layoutViewports();
  // A camera the user has not moved since it was framed is framed again for the new size
  // (the first frame happens before the widget has one).
  if (autoFramed_ && hasScene_) {
    if (eyeView_)
      showStandardView(StandardView::EyeView);
    else
      resetCamera();
  }
}

void SceneView::wheelEvent(QWheelEvent* e) {
  autoFramed_ = false;
  VtkGlWidget::wheelEvent(e);
}

void SceneView::paintGL() {
  layoutViewports();
  VtkGlWidget::paintGL();
}

vtkRenderer* SceneView::legendRenderer() const {
  return legend_;
}

void SceneView::setLabelsVisible(bool on) {
  labels_->setVisible(on);
  requestRender();
}

bool SceneView::labelsVisible() const {
  return labels_->isVisible();
}

std::vector<LabelRect> SceneView::labelBoxes() const {
  return labels_->boxes();
}

std::vector<LabelRect> SceneView::labelObstacles() const {
  return labels_->obstacles();
}

int SceneView::labelsShown() const {
  return labels_->shownCount();
}

void SceneView::setEyeViewMode(bool on) {
  if (on == eyeView_) return;
  eyeView_ = on;
  if (on) {
    eyeViewHidden_.clear();
    for (const char* name : kHiddenInEyeView) {
      SceneLayer& l = layer(name);
      eyeViewHidden_[name] = l.isVisible();
      l.setVisible(false);
    }
  } else {
    for (const auto& [name, was] : eyeViewHidden_) layer(name).setVisible(was);
    eyeViewHidden_.clear();
  }
  layer(QStringLiteral("seen")).setVisible(on);
  scaleBar_->setVisible(!on);  // a length at the focal plane means nothing from the pupil
}

void SceneView::setDragRendering(bool on) {
  if (on == dragRendering_) return;
  dragRendering_ = on;
  applyDragRendering();
}

void SceneView::prepareDragRendering() {
  if (!isVisible() || dragRendering()) return;
  dragRendering_ = true;
  applyDragRendering();
  renderToImage();  // into an off-screen framebuffer
  dragRendering_ = false;
  applyDragRendering();
}

void SceneView::setDragRenderScale(double scale) {
  dragRenderScale_ = clampRenderScale(scale);
  applyDragRendering();
}

void SceneView::applyDragRendering() {
  const bool drag = dragRendering();
  setRenderScale(drag ? dragRenderScale_ : 1.0);  // repaints when it changes
  if (renderer()->GetUseDepthPeeling() == (drag ? 0 : 1)) return;
  renderer()->SetUseDepthPeeling(!drag);
  // Drag frames blend translucency in drawing order in one pass (VTK's standard steps with
  // its plain translucent pass); VTK 9.1's order-independent pass washes the stacked HOE
  // films and the eye out to white on llvmpipe.
  if (drag && !dragPass_) dragPass_ = vtkSmartPointer<vtkRenderStepsPass>::New();
  renderer()->SetPass(drag ? dragPass_.Get() : nullptr);
  requestRender();
}

void SceneView::setPrintLook(bool on) {
  if (on == printLook_) return;
  printLook_ = on;
  vtkRenderer* ren = renderer();
  const auto& bg = on ? kPrintBackground : kScreenBackground;
  ren->SetBackground(bg[0][0], bg[0][1], bg[0][2]);
  ren->SetBackground2(bg[1][0], bg[1][1], bg[1][2]);
  const double* text = on ? kPrintText : kScreenText;
  scaleBar_->setColor(on ? text[0] : 1.0, on ? text[1] : 1.0, on ? text[2] : 1.0);
  applyMarginColors();
  vtkActor2DCollection* overlays = legend_->GetActors2D();
  overlays->InitTraversal();
  while (vtkActor2D* a = overlays->GetNextActor2D())
    if (auto* bar = vtkScalarBarActor::SafeDownCast(a)) {
      bar->GetTitleTextProperty()->SetColor(text[0], text[1], text[2]);
      bar->GetLabelTextProperty()->SetColor(text[0], text[1], text[2]);
      if (vtkTextProperty* note = bar->GetAnnotationTextProperty()) note->SetColor(text[0], text[1], text[2]);
    }
  // Handles: hidden in print; the eye's view hides them too and keeps their state to restore.
  SceneLayer& handles = layer(QStringLiteral("handles"));
  if (on) {
    handlesWereVisible_ = eyeView_ ? eyeViewHidden_[QStringLiteral("handles")] : handles.isVisible();
    if (eyeView_)
      eyeViewHidden_[QStringLiteral("handles")] = false;
    else
      handles.setVisible(false);
  } else if (eyeView_) {
    eyeViewHidden_[QStringLiteral("handles")] = handlesWereVisible_;
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
  // A gaze change (a drag of the gaze slider or the eye's rings) only turns the eye: redraw
  // its actors alone, the cheap path that keeps the GUI thread free while the hand moves.
  if (!first && !reset && scene_.eye.gaze_deg != scene.eye.gaze_deg && equalButGaze(scene_, scene)) {
    scene_ = scene;
    sceneLayer().removeElement(QStringLiteral("eye"));
    buildEyeActors(scene_, sceneLayer());
    if (scene_.binocular) {
      SceneLayer& left = layer(QStringLiteral("left-train"));
      left.removeElement(QStringLiteral("eye"));
      buildEyeActors(eyeScene(scene_, EyeSide::Left), left);
    }
    updateHighlight();
    requestRender();
    return;
  }
  scene_ = scene;
  hasScene_ = true;
  SceneLayer& l = sceneLayer();
  SceneLayer& light = layer(QStringLiteral("frustum"));
  SceneLayer& stages = layer(QStringLiteral("stages"));
  l.clear();
  light.clear();
  stages.clear();
  buildSceneActors(scene_, l, light, stages);
  // A binocular scene (model/scene/eye_scene.h): the left eye's mirrored train beside the
  // scene's own (right) one, in its own layer; its props carry the ids of the right train's
  // elements they mirror, so picking one selects the element both trains are built from.
  SceneLayer& left = layer(QStringLiteral("left-train"));
  left.clear();
  if (scene_.binocular) buildSceneActors(eyeScene(scene_, EyeSide::Left), left, light, stages);
  labels_->setScene(scene_);
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
    for (vtkProp* p : elementProps(selected_)) {
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

std::vector<vtkProp*> SceneView::elementProps(const QString& id) {
  std::vector<vtkProp*> props = sceneLayer().propsOf(id);
  for (vtkProp* p : layer(QStringLiteral("stages")).propsOf(id)) props.push_back(p);
  return props;
}

void SceneView::setHoeDisplayShift(const Eigen::Vector3d& shift) {
  if (shift == hoeShift_) return;
  hoeShift_ = shift;
  applyHoeShift();
  updateHighlight();
  requestRender();
}

void SceneView::setLeftHoeDisplayShift(const std::optional<Eigen::Vector3d>& shift) {
  if (shift == leftHoeShift_) return;
  leftHoeShift_ = shift;
  applyHoeShift();
  requestRender();
}

Eigen::Vector3d SceneView::leftHoeDisplayShift() const {
  return leftHoeShift_ ? *leftHoeShift_ : Eigen::Vector3d(-hoeShift_.x(), hoeShift_.y(), hoeShift_.z());
}

void SceneView::applyHoeShift() {
  QStringList ids{"hoe"};
  for (int i = 0; i < static_cast<int>(scene_.hoe_layers.size()); ++i) ids << hoeLayerId(i);
  const Eigen::Vector3d left = leftHoeDisplayShift();
  for (const QString& id : ids) {
    for (vtkProp* p : sceneLayer().propsOf(id))
      if (auto* p3 = vtkProp3D::SafeDownCast(p)) p3->SetPosition(hoeShift_.x(), hoeShift_.y(), hoeShift_.z());
    for (vtkProp* p : layer(QStringLiteral("left-train")).propsOf(id))
      if (auto* p3 = vtkProp3D::SafeDownCast(p)) p3->SetPosition(left.x(), left.y(), left.z());
  }
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
      setEyeViewMode(true);
      const EyePlacement e = placeEye(scene_);
      const Eigen::Vector3d at = e.pupil_center + 0.2 * e.gaze, focus = e.pupil_center + 100.0 * e.gaze;
      cam->SetPosition(at.x(), at.y(), at.z());
      cam->SetFocalPoint(focus.x(), focus.y(), focus.z());
      cam->SetViewUp(0, 1, 0);
      // The view angle takes in the whole plate as the eye sees it, with a 10 % margin: the
      // largest angle off the gaze of the plate's corners, horizontally or vertically scaled
      // by the viewport's aspect (VTK's view angle is the vertical one).
      const Frame hf = frameOf(scene_.hoe.pose);
      const Eigen::Vector3d right = e.gaze.cross(Eigen::Vector3d::UnitY()).normalized(), above = right.cross(e.gaze);
      const int* size = renderer()->GetSize();
      const double aspect = size[1] > 0 ? static_cast<double>(size[0]) / size[1] : 1.0;
      double half_tan = 0.0;
      for (double sx : {-0.5, 0.5})
        for (double sy : {-0.5, 0.5}) {
          const Eigen::Vector3d c =
              hf.toBench({sx * scene_.hoe.size_mm[0], sy * scene_.hoe.size_mm[1], 0.0}) + hoeShift_ - at;
          const double depth = c.dot(e.gaze);
          if (depth <= 1e-6) continue;
          half_tan = std::max({half_tan, std::abs(c.dot(above)) / depth, std::abs(c.dot(right)) / depth / aspect});
        }
      const double angle = half_tan > 0.0 ? 2.0 * std::atan(1.1 * half_tan) / kDeg : 100.0;
      cam->SetViewAngle(std::clamp(angle, 30.0, 150.0));
      autoFramed_ = true;
      renderer()->ResetCameraClippingRange();
      requestRender();
      return;
    }
  }
  setEyeViewMode(false);
  cam->SetFocalPoint(hoe.x(), hoe.y(), hoe.z());
  const Eigen::Vector3d from = hoe + 300.0 * dir;
  cam->SetPosition(from.x(), from.y(), from.z());
  cam->SetViewUp(up.x(), up.y(), up.z());
  resetCamera();
}

void SceneView::resetCamera() {
  vtkRenderer* ren = renderer();
  vtkCamera* cam = ren->GetActiveCamera();
  // The bench: the points of every element prop of the scene and stages layers (not the
  // light, the fans, the handles or the selection box) where they are drawn, at most ~400
  // per prop.
  std::vector<Eigen::Vector3d> corners;
  Eigen::AlignedBox3d box;
  for (const QString& id : elementIds(scene_))
    for (vtkProp* p : elementProps(id)) {
      auto* actor = vtkActor::SafeDownCast(p);
      vtkDataSet* data = actor && actor->GetMapper() ? actor->GetMapper()->GetInputAsDataSet() : nullptr;
      if (!data || data->GetNumberOfPoints() == 0) continue;
      vtkMatrix4x4* m = actor->GetMatrix();
      const vtkIdType n = data->GetNumberOfPoints(), stride = std::max<vtkIdType>(1, n / 400);
      for (vtkIdType i = 0; i < n; i += stride) {
        double q[4] = {0, 0, 0, 1}, w[4];
        data->GetPoint(i, q);
        q[3] = 1.0;
        m->MultiplyPoint(q, w);
        corners.emplace_back(w[0], w[1], w[2]);
        box.extend(corners.back());
      }
    }
  if (box.isEmpty()) {
    ren->ResetCamera();
    ren->ResetCameraClippingRange();
    requestRender();
    return;
  }
  // Fit the box's corners into the viewport with a margin, from the current direction: the
  // camera distance at which every corner's projection lies inside, then centre the
  // projected extent (a few rounds, as centring changes the distance a little).
  double pos[3], fp[3], vu[3];
  cam->GetPosition(pos);
  cam->GetFocalPoint(fp);
  cam->GetViewUp(vu);
  const Eigen::Vector3d back =
      (Eigen::Vector3d(pos[0], pos[1], pos[2]) - Eigen::Vector3d(fp[0], fp[1], fp[2])).normalized();
  const Eigen::Vector3d right = Eigen::Vector3d(vu[0], vu[1], vu[2]).cross(back).normalized(), up = back.cross(right);
  const int* size = ren->GetSize();
  const double aspect = size[1] > 0 ? static_cast<double>(size[0]) / size[1] : 1.0;
  const double tv = std::tan(cam->GetViewAngle() / 2.0 * kDeg) * 0.82, th = tv * aspect;  // 9 % margin each side
  Eigen::Vector3d centre = box.center();
  double distance = 1.0;
  for (int round = 0; round < 4; ++round) {
    distance = 1.0;
    for (const Eigen::Vector3d& corner : corners) {
      const Eigen::Vector3d c = corner - centre;
      const double toward = c.dot(back);
      distance = std::max({distance, toward + std::abs(c.dot(right)) / th, toward + std::abs(c.dot(up)) / tv});
    }
    double u0 = 1e9, u1 = -1e9, v0 = 1e9, v1 = -1e9;
    for (const Eigen::Vector3d& corner : corners) {
      const Eigen::Vector3d c = corner - centre;
      const double depth = distance - c.dot(back);
      u0 = std::min(u0, c.dot(right) / depth);
      u1 = std::max(u1, c.dot(right) / depth);
      v0 = std::min(v0, c.dot(up) / depth);
      v1 = std::max(v1, c.dot(up) / depth);
    }
    centre += distance * (0.5 * (u0 + u1) * right + 0.5 * (v0 + v1) * up);
  }
  const Eigen::Vector3d from = centre + distance * back;
  cam->SetFocalPoint(centre.x(), centre.y(), centre.z());
  cam->SetPosition(from.x(), from.y(), from.z());
  cam->SetViewUp(up.x(), up.y(), up.z());
  autoFramed_ = true;
  ren->ResetCameraClippingRange();
  requestRender();
}

void SceneView::zoomCamera(double factor) {
  autoFramed_ = false;
  renderer()->GetActiveCamera()->Zoom(factor);
  renderer()->ResetCameraClippingRange();
  requestRender();
}

double SceneView::scaleBarLengthMm() const {
  return scaleBar_->lengthMm();
}

void SceneView::mousePressEvent(QMouseEvent* e) {
  autoFramed_ = false;  // the user takes the camera
  if (e->button() == Qt::LeftButton) {
    pressPos_ = e->position();
    pressed_ = true;
  }
  mouseHeld_ = true;
  applyDragRendering();
  VtkGlWidget::mousePressEvent(e);
}

void SceneView::mouseReleaseEvent(QMouseEvent* e) {
  VtkGlWidget::mouseReleaseEvent(e);
  mouseHeld_ = e->buttons() != Qt::NoButton;
  applyDragRendering();
  if (e->button() != Qt::LeftButton || !pressed_) return;
  pressed_ = false;
  if ((e->position() - pressPos_).manhattanLength() > 4.0) return;  // a drag orbits, a click picks
  const QString id = elementAt(e->position());
  setSelectedElement(id);
  emit elementPicked(id);
}

}  // namespace fovea::viz
