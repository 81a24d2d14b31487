#pragma once
// Drag handles of a movable element in the 3D view: three arrows along the bench axes
// (x red, y green, z blue) from the element's origin, and the maths to drag them — the
// arrow under the mouse (screen-space distance to the projected arrow) and the parameter
// along an axis closest to a mouse ray. Drawn in the view's "handles" layer, not pickable.
// Element origins: projector / HOE / lens pose position; eye: the pupil centre.
//
// Rotation rings, one per angle of the element's rotation_deg (yaw, pitch, roll), each drawn
// about the axis that angle turns the element about in rotationFromDeg's R = Ry(yaw)
// Rx(-pitch) Rz(roll): yaw (green) about bench +y, pitch (red) about -(Ry(yaw) x) — the
// yawed x axis, signed so that +angle = +pitch — and roll (blue) about the element's own z
// axis R z. Turning a ring by an angle about its axis changes that one angle by the same
// amount exactly (the other two stay). The eye has yaw and pitch rings for its gaze, about
// its rotation centre.

#include <QPointF>
#include <QString>

#include <array>
#include <optional>

#include <Eigen/Core>

#include "model/scene/scene.h"

namespace fovea::viz {

class SceneView;

// Movable elements: "projector", "hoe", "eye", "beam_shaping_lens" (a HOE layer moves the HOE).
QString movableElement(const QString& id);
// The handle origin of a movable element (bench mm).
Eigen::Vector3d elementOrigin(const Scene& scene, const QString& element);
// Moves a movable element by `delta` (bench mm): pose position, or for the eye its lateral
// offset (x, y) and relief (z; moving towards -z increases the relief).
void moveElement(Scene& scene, const QString& element, const Eigen::Vector3d& delta);
// Rotation rings of an element: 3 (yaw, pitch, roll of its pose) or 2 for the eye (gaze).
int rotationRingCount(const QString& element);
// The angle (deg) ring `ring` turns: pose rotation_deg[ring], or for the eye gaze_deg[ring].
double elementAngle(const Scene& scene, const QString& element, int ring);
// Turns an element by `delta_deg` on ring `ring` (adds it to that angle).
void rotateElement(Scene& scene, const QString& element, int ring, double delta_deg);

class ElementHandles {
 public:
  static constexpr double kLength_mm = 22.0;
  explicit ElementHandles(SceneView* view);

  // Shows the handles of `element` (empty or not movable: none) at its origin in `scene`.
  void show(const Scene& scene, const QString& element);
  const QString& element() const { return element_; }
  const Eigen::Vector3d& origin() const { return origin_; }
  // The axis (0 x, 1 y, 2 z) whose arrow passes within `tolerance_px` of a widget position.
  std::optional<int> axisAt(const QPointF& widgetPos, double tolerance_px = 8.0) const;
  // Where an axis' arrow tip appears in the widget (for tests and tooltips).
  std::optional<QPointF> tipPosition(int axis) const;
  // Parameter t (mm) of the point of the line origin + t * axis closest to the mouse ray.
  std::optional<double> axisParameter(int axis, const Eigen::Vector3d& lineOrigin, const QPointF& widgetPos) const;
  void setHighlighted(std::optional<int> axis);

  // Rotation rings. Ring centre (eye: its rotation centre), radius and unit axis.
  static constexpr double kRingRadius_mm = 15.0;
  const Eigen::Vector3d& ringCenter() const { return ringCenter_; }
  double ringRadius() const { return ringRadius_; }
  Eigen::Vector3d ringAxis(int ring) const;
  int ringCount() const { return element_.isEmpty() ? 0 : rotationRingCount(element_); }
  // The bench point of a ring at `angle_deg` about its axis (0: along the ring's first in-plane axis).
  Eigen::Vector3d ringPoint(int ring, double angle_deg) const;
  // The ring whose drawn circle passes within `tolerance_px` of a widget position.
  std::optional<int> ringAt(const QPointF& widgetPos, double tolerance_px = 7.0) const;
  // The angle (deg, right-handed about the ring's axis) of the point where the mouse ray meets
  // the ring's plane; none when the ring is seen edge-on.
  std::optional<double> ringAngle(int ring, const QPointF& widgetPos) const;
  void setHighlightedRing(std::optional<int> ring);

 private:
  SceneView* view_;
  QString element_;
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  std::optional<int> highlighted_;
  Eigen::Vector3d ringCenter_ = Eigen::Vector3d::Zero();
  double ringRadius_ = kRingRadius_mm;
  std::array<Eigen::Vector3d, 3> ringAxes_{Eigen::Vector3d::UnitY(), -Eigen::Vector3d::UnitX(),
                                           Eigen::Vector3d::UnitZ()};
  std::optional<int> highlightedRing_;
};

}  // namespace fovea::viz
