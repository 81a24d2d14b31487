#include "viz/element_handles.h"

#include <algorithm>
#include <cmath>

#include <vtkActor.h>
#include <vtkConeSource.h>
#include <vtkLineSource.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>

#include "model/scene/scene_geometry.h"
#include "viz/scene_elements.h"
#include "viz/scene_view.h"

namespace fovea::viz {

namespace {
constexpr std::array<std::array<double, 3>, 3> kAxisColor{{{0.95, 0.25, 0.25}, {0.30, 0.90, 0.30}, {0.30, 0.55, 1.00}}};
}

QString movableElement(const QString& id) {
  if (id == "projector" || id == "hoe" || id == "eye" || id == "beam_shaping_lens") return id;
  if (indexedElement(id, "hoe_layers") >= 0) return QStringLiteral("hoe");
  return {};
}

Eigen::Vector3d elementOrigin(const Scene& s, const QString& e) {
  if (e == "projector") return toVec(s.projector.pose.position_mm);
  if (e == "hoe") return toVec(s.hoe.pose.position_mm);
  if (e == "beam_shaping_lens") return toVec(s.lens.pose.position_mm);
  if (e == "eye") return placeEye(s).pupil_center;
  return Eigen::Vector3d::Zero();
}

void moveElement(Scene& s, const QString& e, const Eigen::Vector3d& d) {
  auto add = [&d](Vec3mm& p) {
    for (int i = 0; i < 3; ++i) p[static_cast<std::size_t>(i)] += d[i];
  };
  if (e == "projector") add(s.projector.pose.position_mm);
  if (e == "hoe") add(s.hoe.pose.position_mm);
  if (e == "beam_shaping_lens") add(s.lens.pose.position_mm);
  if (e == "eye") {
    s.eye.lateral_offset_mm[0] += d.x();
    s.eye.lateral_offset_mm[1] += d.y();
    s.eye.relief_mm -= d.z();
  }
}

ElementHandles::ElementHandles(SceneView* view) : view_(view) {}

void ElementHandles::show(const Scene& scene, const QString& element) {
  SceneLayer& layer = view_->layer("handles");
  layer.clear();
  element_ = movableElement(element);
  if (element_.isEmpty()) {
    view_->requestRender();
    return;
  }
  origin_ = elementOrigin(scene, element_);
  for (int a = 0; a < 3; ++a) {
    Eigen::Vector3d dir = Eigen::Vector3d::Zero();
    dir[a] = 1.0;
    const Eigen::Vector3d tip = origin_ + kLength_mm * dir, base = origin_ + (kLength_mm - 4.0) * dir;
    const bool hot = highlighted_ && *highlighted_ == a;
    const auto& c = kAxisColor[static_cast<std::size_t>(a)];
    vtkNew<vtkLineSource> line;
    line->SetPoint1(origin_.data());
    line->SetPoint2(base.data());
    auto lm = vtkSmartPointer<vtkPolyDataMapper>::New();
    lm->SetInputConnection(line->GetOutputPort());
    auto la = vtkSmartPointer<vtkActor>::New();
    la->SetMapper(lm);
    la->GetProperty()->SetColor(c[0], c[1], c[2]);
    la->GetProperty()->SetLineWidth(hot ? 6.0f : 3.5f);
    la->GetProperty()->LightingOff();
    layer.add(la, {}, false);
    vtkNew<vtkConeSource> cone;
    cone->SetResolution(24);
    cone->SetHeight(4.0);
    cone->SetRadius(hot ? 1.8 : 1.3);
    const Eigen::Vector3d mid = (tip + base) / 2;
    cone->SetCenter(mid.data());
    cone->SetDirection(dir.data());
    auto cm = vtkSmartPointer<vtkPolyDataMapper>::New();
    cm->SetInputConnection(cone->GetOutputPort());
    auto ca = vtkSmartPointer<vtkActor>::New();
    ca->SetMapper(cm);
    ca->GetProperty()->SetColor(hot ? 1.0 : c[0], hot ? 1.0 : c[1], hot ? 0.4 : c[2]);
    ca->GetProperty()->SetAmbient(0.5);
    layer.add(ca, {}, false);
  }
  view_->requestRender();
}

void ElementHandles::setHighlighted(std::optional<int> axis) {
  highlighted_ = axis;
}

std::optional<QPointF> ElementHandles::tipPosition(int axis) const {
  if (element_.isEmpty()) return std::nullopt;
  Eigen::Vector3d dir = Eigen::Vector3d::Zero();
  dir[axis] = 1.0;
  return view_->widgetPositionOf(origin_ + (kLength_mm - 2.0) * dir);
}

std::optional<int> ElementHandles::axisAt(const QPointF& pos, double tol) const {
  if (element_.isEmpty()) return std::nullopt;
  const auto o = view_->widgetPositionOf(origin_);
  if (!o) return std::nullopt;
  std::optional<int> best;
  double bestDist = tol;
  for (int a = 0; a < 3; ++a) {
    Eigen::Vector3d dir = Eigen::Vector3d::Zero();
    dir[a] = 1.0;
    const auto t = view_->widgetPositionOf(origin_ + kLength_mm * dir);
    if (!t) continue;
    // Distance from pos to the segment o..t, skipping the first 15 % (all arrows meet there).
    const QPointF ab = *t - *o;
    const double len2 = QPointF::dotProduct(ab, ab);
    if (len2 < 4.0) continue;
    const double s = std::clamp(QPointF::dotProduct(pos - *o, ab) / len2, 0.0, 1.0);
    if (s < 0.15) continue;
    const QPointF d = pos - (*o + s * ab);
    const double dist = std::hypot(d.x(), d.y());
    if (dist <= bestDist) {
      bestDist = dist;
      best = a;
    }
  }
  return best;
}

std::optional<double> ElementHandles::axisParameter(int axis, const Eigen::Vector3d& lineOrigin,
                                                    const QPointF& pos) const {
  Eigen::Vector3d u = Eigen::Vector3d::Zero();
  u[axis] = 1.0;
  const auto [p, v] = view_->viewRay(pos);
  // Closest points of the lines lineOrigin + t u and p + s v.
  const Eigen::Vector3d w = lineOrigin - p;
  const double b = u.dot(v), d = u.dot(w), e = v.dot(w);
  const double denom = 1.0 - b * b;
  if (denom < 1e-6) return std::nullopt;  // looking along the axis
  return (b * e - d) / denom;
}

}  // namespace fovea::viz
