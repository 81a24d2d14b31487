#include "viz/element_labels.h"

#include <algorithm>
#include <cmath>

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

#include "model/scene/scene_geometry.h"
#include "viz/render_scale.h"

namespace fovea::viz {

namespace {
constexpr int kFontSize = 15;
}  // namespace

std::vector<ElementLabel> elementLabels(const Scene& scene) {
  std::vector<ElementLabel> out;
  const Frame pf = frameOf(scene.projector.pose);
  out.push_back({"projector", "projector", pf.toBench({0, 0, -18.5})});  // the body (scene_actors.cpp)
  const Frame hf = frameOf(scene.hoe.pose);
  out.push_back({"hoe", "HOE", hf.toBench({0.0, scene.hoe.size_mm[1] / 2, 0.0})});
  const EyePlacement e = placeEye(scene);
  out.push_back({"eye", "eye", e.rotation_center});
  out.push_back({"foveal_display", "micro-OLED", frameOf(scene.foveal_display.pose).origin});
  // The combiner sits on the zero-gaze axis, eye_distance_mm in front of the pupil.
  const EyePlacement e0 = placeEye(scene, 0.0, 0.0);
  out.push_back(
      {"foveal_display", "combiner", e0.pupil_center + scene.foveal_display.combiner.eye_distance_mm * e0.gaze});
  if (scene.lens.diameter_mm > 0.0)
    out.push_back({"beam_shaping_lens", scene.lens.enabled ? "lens" : "lens (off)",
                   frameOf(scene.lens.pose).origin + Eigen::Vector3d(0, scene.lens.diameter_mm / 2, 0)});
  return out;
}

ElementLabels::ElementLabels(vtkRenderer* renderer) : renderer_(renderer) {
  vtkNew<vtkPolyData> data;
  data->SetPoints(leaderPoints_);
  data->SetLines(vtkNew<vtkCellArray>());
  vtkNew<vtkPolyDataMapper2D> mapper;
  mapper->SetInputData(data);
  leaders_->SetMapper(mapper);
  leaders_->GetProperty()->SetLineWidth(1.0);
  leaders_->PickableOff();
  renderer_->AddViewProp(leaders_);
  callback_->SetClientData(this);
  callback_->SetCallback(&ElementLabels::onStart);
  renderer_->AddObserver(vtkCommand::StartEvent, callback_);
}

ElementLabels::~ElementLabels() {
  renderer_->RemoveObserver(callback_);
  renderer_->RemoveViewProp(leaders_);
  for (auto& t : texts_) renderer_->RemoveViewProp(t);
}

void ElementLabels::onStart(vtkObject*, unsigned long, void* clientData, void*) {
  static_cast<ElementLabels*>(clientData)->layout();
}

void ElementLabels::setScene(const Scene& scene) {
  labels_ = elementLabels(scene);
  while (texts_.size() < labels_.size()) {
    auto t = vtkSmartPointer<vtkTextActor>::New();
    vtkTextProperty* p = t->GetTextProperty();
    p->SetFontSize(kFontSize);
    p->SetVerticalJustificationToCentered();
    p->SetBackgroundOpacity(0.55);
    p->SetFrame(false);
    t->PickableOff();
    renderer_->AddViewProp(t);
    texts_.push_back(t);
  }
  setColor(rgb_[0], rgb_[1], rgb_[2], background_);
}

void ElementLabels::setVisible(bool on) {
  visible_ = on;
}

void ElementLabels::setColor(double r, double g, double b, double background) {
  rgb_[0] = r;
  rgb_[1] = g;
  rgb_[2] = b;
  background_ = background;
  for (auto& t : texts_) {
    t->GetTextProperty()->SetColor(r, g, b);
    t->GetTextProperty()->SetBackgroundColor(background, background, background);
  }
  leaders_->GetProperty()->SetColor(r, g, b);
  leaders_->GetProperty()->SetOpacity(0.7);
}

void ElementLabels::setAvoid(const std::vector<LabelRect>& normalizedRects) {
  avoid_ = normalizedRects;
}

void ElementLabels::layout() {
  shown_ = 0;
  boxes_.clear();
  vtkPolyData* data = vtkPolyData::SafeDownCast(leaders_->GetMapper()->GetInputDataObject(0, 0));
  vtkNew<vtkCellArray> lines;
  leaderPoints_->Reset();
  for (auto& t : texts_) t->VisibilityOff();
  const int* size = renderer_->GetSize();
  const int* origin = renderer_->GetOrigin();
  if (!visible_ || labels_.empty() || size[0] <= 0 || size[1] <= 0) {
    leaders_->VisibilityOff();
    data->SetLines(lines);
    return;
  }
  // Anchors on screen (display pixels), those behind the camera or outside the view dropped.
  vtkCamera* cam = renderer_->GetActiveCamera();
  double pos[3], fp[3];
  cam->GetPosition(pos);
  cam->GetFocalPoint(fp);
  const Eigen::Vector3d eye(pos[0], pos[1], pos[2]), ahead = (Eigen::Vector3d(fp[0], fp[1], fp[2]) - eye).normalized();
  struct Placed {
    std::size_t index;
    Eigen::Vector2d anchor;
  };
  std::vector<Placed> onScreen;
  for (std::size_t i = 0; i < labels_.size(); ++i) {
    const Eigen::Vector3d& a = labels_[i].anchor_mm;
    if ((a - eye).dot(ahead) <= 1.0) continue;  // behind (or at) the camera
    renderer_->SetWorldPoint(a.x(), a.y(), a.z(), 1.0);
    renderer_->WorldToDisplay();
    double d[3];
    renderer_->GetDisplayPoint(d);
    if (d[0] < origin[0] || d[0] > origin[0] + size[0] || d[1] < origin[1] || d[1] > origin[1] + size[1]) continue;
    onScreen.push_back({i, {d[0], d[1]}});
  }
  if (onScreen.empty()) {
    leaders_->VisibilityOff();
    data->SetLines(lines);
    return;
  }
  // Sizes in pixels of the frame being drawn (smaller while a drag draws at reduced resolution).
  const double px = pixelScale(renderer_);
  std::vector<LabelRequest> requests;
  for (const Placed& p : onScreen) {
    vtkTextActor* t = texts_[p.index];
    t->SetInput(labels_[p.index].text.toUtf8().constData());
    t->GetTextProperty()->SetJustificationToLeft();
    // The text's own extent (the font's metrics), with a little padding; the estimate from the
    // character count only when the text renderer gives none.
    double bb[4] = {0, 0, 0, 0};
    t->GetBoundingBox(renderer_, bb);
    double w = bb[1] - bb[0], h = bb[3] - bb[2];
    if (!(w > 1.0 && h > 1.0)) {
      w = 0.62 * kFontSize * px * static_cast<double>(labels_[p.index].text.size());
      h = kFontSize * px;
    }
    requests.push_back({p.anchor, w + 8.0 * px, h + 6.0 * px});
  }
  // The triad's viewport (and any other overlay the view reports) in display pixels.
  std::vector<LabelRect> obstacles;
  if (vtkRenderWindow* win = renderer_->GetRenderWindow()) {
    const int* ws = win->GetSize();
    for (const LabelRect& o : avoid_) obstacles.push_back({o.x0 * ws[0], o.y0 * ws[1], o.x1 * ws[0], o.y1 * ws[1]});
  }
  const LabelRect viewport{origin[0] + 2.0 * px, origin[1] + 2.0 * px, origin[0] + size[0] - 2.0 * px,
                           origin[1] + size[1] - 2.0 * px};
  const std::vector<PlacedLabel> placed = placeLabels(requests, viewport, obstacles, px);
  obstacles_ = obstacles;
  for (std::size_t k = 0; k < onScreen.size(); ++k) {
    const Placed& p = onScreen[k];
    const LabelRect& box = placed[k].box;
    boxes_.push_back(box);
    vtkTextActor* t = texts_[p.index];
    t->SetDisplayPosition(static_cast<int>(box.x0 + 4.0 * px), static_cast<int>((box.y0 + box.y1) / 2));
    t->VisibilityOn();
    const Eigen::Vector2d& end = placed[k].leaderEnd;
    // The 2-D mapper draws in viewport pixels: relative to the renderer's origin.
    const vtkIdType ids[2] = {leaderPoints_->InsertNextPoint(p.anchor.x() - origin[0], p.anchor.y() - origin[1], 0.0),
                              leaderPoints_->InsertNextPoint(end.x() - origin[0], end.y() - origin[1], 0.0)};
    lines->InsertNextCell(2, ids);
    ++shown_;
  }
  leaderPoints_->Modified();
  data->SetLines(lines);
  data->Modified();
  leaders_->VisibilityOn();
}

}  // namespace fovea::viz
