#pragma once
// Dragging elements in the 3D view by their handles (viz/element_handles.h): press on an
// arrow, drag along its axis, release. Every move goes through SceneDocument::applyEdit with
// one merge id per drag, so the property editor follows live and the whole drag is ONE undo
// step ("Move projector along x by 3 mm"). Moves snap to multiples of the snap step (Shift
// held: free); a double-click on an arrow asks for an exact distance. Events on the
// handles are consumed; everything else goes on to the view (orbit, pick).
// Rotation rings work the same way: press on a ring, drag around it, release — ONE undo step
// ("Rotate projector: yaw by 5 deg"); the turn snaps to the angle step (1 deg; Shift held:
// 0.1 deg), a double-click on a ring asks for an exact angle.

#include <QObject>
#include <QPointF>

#include <optional>

#include <Eigen/Core>

namespace fovea::viz {
class SceneView;
class ElementHandles;
}  // namespace fovea::viz

namespace fovea::widgets {

class SceneDocument;

class HandleController : public QObject {
  Q_OBJECT
 public:
  HandleController(SceneDocument* document, viz::SceneView* view, QObject* parent = nullptr);
  ~HandleController() override;

  void setElement(const QString& id);
  void setEnabled(bool on);
  bool isEnabled() const { return enabled_; }
  void setSnapStep(double mm) { snap_mm_ = mm; }
  double snapStep() const { return snap_mm_; }
  void setAngleSnapStep(double deg) { snap_deg_ = deg; }
  double angleSnapStep() const { return snap_deg_; }
  static constexpr double kFineAngleStep_deg = 0.1;  // Shift held during a ring drag
  bool isDragging() const { return axis_.has_value() || ring_.has_value(); }
  bool isRotating() const { return ring_.has_value(); }
  viz::ElementHandles* handles() const { return handles_; }

  // Moves the shown element along an axis by `delta_mm` as one undoable edit (numeric entry).
  bool moveBy(int axis, double delta_mm);
  // Turns the shown element on ring `ring` (0 yaw, 1 pitch, 2 roll; the eye: its gaze yaw,
  // pitch) by `delta_deg` as one undoable edit (numeric entry).
  bool rotateBy(int ring, double delta_deg);

 signals:
  void dragFinished(const QString& element, int axis, double delta_mm);
  void rotateFinished(const QString& element, int ring, double delta_deg);

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;

 private:
  void refresh();
  bool applyDelta(double delta_mm, int mergeId);
  bool applyTurn(double turn_deg, int mergeId);

  SceneDocument* document_;
  viz::SceneView* view_;
  viz::ElementHandles* handles_;
  QString element_;
  bool enabled_ = true;
  double snap_mm_ = 1.0;
  // Drag state.
  std::optional<int> axis_;
  Eigen::Vector3d dragOrigin_ = Eigen::Vector3d::Zero();
  double startParam_ = 0.0, lastDelta_ = 0.0;
  int gesture_ = -1;
  // Ring drag state: the mouse angle unwrapped across +-180 deg since the press.
  double snap_deg_ = 1.0;
  std::optional<int> ring_;
  double prevAngle_ = 0.0, turned_ = 0.0, lastTurn_ = 0.0;
};

}  // namespace fovea::widgets
