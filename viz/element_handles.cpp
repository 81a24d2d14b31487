#include "viz/element_handles.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <vtkActor.h>
#include <vtkCellArray.h>
#include <vtkConeSource.h>
#include <vtkLineSource.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>

#include "model/scene/scene_geometry.h"
#include "model/units.h"
#include "viz/polyline.h"
#include "viz/scene_elements.h"
#include "viz/scene_view.h"

namespace fovea::viz {

namespace {
constexpr std::array<std::array<double, 3>, 3> kAxisColor{{{0.95, 0.25, 0.25}, {0.30, 0.90, 0.30}, {0.30, 0.55, 1.00}}};
constexpr int kRingSegments = 96;
// Ring colours: yaw turns about y (green), pitch about the yawed x (red), roll about z (blue).
constexpr std::array<int, 3> kRingColorAxis{1, 0, 2};

// In-plane unit vectors (u, v = axis x u) of a ring: angles are right-handed about the axis.
std::pair<Eigen::Vector3d, Eigen::Vector3d> ringBasis(const Eigen::Vector3d& axis) {
  const Eigen::Vector3d u = axis.unitOrthogonal();
  return {u, axis.cross(u)};
}

}  // namespace

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

int rotationRingCount(const QString& e) {
  if (e == "eye") return 2;
  if (e == "projector" || e == "hoe" || e == "beam_shaping_lens") return 3;
  return 0;
}

namespace {
std::array<double, 3>* poseAngles(Scene& s, const QString& e) {
  if (e == "projector") return &s.projector.pose.rotation_deg;
  if (e == "hoe") return &s.hoe.pose.rotation_deg;
  if (e == "beam_shaping_lens") return &s.lens.pose.rotation_deg;
  return nullptr;
}
}  // namespace

double elementAngle(const Scene& scene, const QString& e, int ring) {
  if (ring < 0 || ring >= rotationRingCount(e)) return 0.0;
  const auto k = static_cast<std::size_t>(ring);
  if (e == "eye") return scene.eye.gaze_deg[k];
  if (e == "projector") return scene.projector.pose.rotation_deg[k];
  if (e == "hoe") return scene.hoe.pose.rotation_deg[k];
  return scene.lens.pose.rotation_deg[k];
}

void rotateElement(Scene& s, const QString& e, int ring, double delta_deg) {
  if (ring < 0 || ring >= rotationRingCount(e)) return;
  if (e == "eye")
    s.eye.gaze_deg[static_cast<std::size_t>(ring)] += delta_deg;
  else
    (*poseAngles(s, e))[static_cast<std::size_t>(ring)] += delta_deg;
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
  // Ring axes from the current angles (see the header): yaw about y, pitch about -(yawed x),
  // roll about the element's z.
  const bool eye = element_ == "eye";
  const double yaw = elementAngle(scene, element_, 0), pitch = elementAngle(scene, element_, 1);
  const double roll = eye ? 0.0 : elementAngle(scene, element_, 2);
  const Eigen::Matrix3d r = rotationFromDeg({yaw, pitch, roll});
  ringAxes_ = {Eigen::Vector3d::UnitY(), -rotationFromDeg({yaw, 0.0, 0.0}).col(0), r.col(2)};
  if (eye) {
    const EyePlacement p = placeEye(scene);
    ringCenter_ = p.rotation_center;
    ringRadius_ = p.eyeball_radius_mm + 3.0;
  } else {
    ringCenter_ = origin_;
    ringRadius_ = kRingRadius_mm;
  }
  for (int k = 0; k < ringCount(); ++k) {
    std::vector<Eigen::Vector3d> pts;
    for (int i = 0; i < kRingSegments; ++i) pts.push_back(ringPoint(k, 360.0 * i / kRingSegments));
    const bool hot = highlightedRing_ && *highlightedRing_ == k;
    const auto& c = kAxisColor[static_cast<std::size_t>(kRingColorAxis[static_cast<std::size_t>(k)])];
    layer.add(hot ? flatLineActor(pts, {1.0, 1.0, 0.4}, 5.0, true) : flatLineActor(pts, c, 2.5, true), {}, false);
  }
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

void ElementHandles::setHighlightedRing(std::optional<int> ring) {
  highlightedRing_ = ring;
}

Eigen::Vector3d ElementHandles::ringAxis(int ring) const {
  return ringAxes_[static_cast<std::size_t>(std::clamp(ring, 0, 2))];
}

Eigen::Vector3d ElementHandles::ringPoint(int ring, double angle_deg) const {
  const auto [u, v] = ringBasis(ringAxis(ring));
  const double t = angle_deg * kDeg;
  return ringCenter_ + ringRadius_ * (std::cos(t) * u + std::sin(t) * v);
}

std::optional<int> ElementHandles::ringAt(const QPointF& pos, double tol) const {
  std::optional<int> best;
  double bestDist = tol;
  for (int k = 0; k < ringCount(); ++k) {
    std::optional<QPointF> prev = view_->widgetPositionOf(ringPoint(k, 0.0));
    for (int i = 1; i <= kRingSegments; ++i) {
      const std::optional<QPointF> next = view_->widgetPositionOf(ringPoint(k, 360.0 * i / kRingSegments));
      if (prev && next) {
        const QPointF ab = *next - *prev;
        const double len2 = QPointF::dotProduct(ab, ab);
        const double s = len2 > 0.0 ? std::clamp(QPointF::dotProduct(pos - *prev, ab) / len2, 0.0, 1.0) : 0.0;
        const QPointF d = pos - (*prev + s * ab);
        const double dist = std::hypot(d.x(), d.y());
        if (dist <= bestDist) {
          bestDist = dist;
          best = k;
        }
      }
      prev = next;
    }
  }
  return best;
}

std::optional<double> ElementHandles::ringAngle(int ring, const QPointF& pos) const {
  if (ring < 0 || ring >= ringCount()) return std::nullopt;
  const Eigen::Vector3d a = ringAxis(ring);
  const auto [p, d] = view_->viewRay(pos);
  const double along = d.dot(a);
  if (std::abs(along) < 0.05) return std::nullopt;  // the ring is seen (nearly) edge-on
  const Eigen::Vector3d q = p + ((ringCenter_ - p).dot(a) / along) * d - ringCenter_;
  const auto [u, v] = ringBasis(a);
  return std::atan2(q.dot(v), q.dot(u)) / kDeg;
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
