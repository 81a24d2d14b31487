#pragma once
// Drag handles of a movable element in the 3D view: three arrows along the bench axes
// (x red, y green, z blue) from the element's origin, and the maths to drag them — the
// arrow under the mouse (screen-space distance to the projected arrow) and the parameter
// along an axis closest to a mouse ray. Drawn in the view's "handles" layer, not pickable.
// Element origins: projector / HOE / lens pose position; eye: the pupil centre.

#include <QPointF>
#include <QString>

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

 private:
  SceneView* view_;
  QString element_;
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  std::optional<int> highlighted_;
};

}  // namespace fovea::viz
