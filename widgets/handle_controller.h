#pragma once
// Dragging elements in the 3D view by their handles (viz/element_handles.h): press on an
// arrow, drag along its axis, release. Every move goes through SceneDocument::applyEdit with
// one merge id per drag, so the property editor follows live and the whole drag is ONE undo
// step ("Move projector along x by 3 mm"). Moves snap to multiples of the snap step (Shift
// held: free); a double-click on an arrow asks for an exact distance. Events on the
// handles are consumed; everything else goes on to the view (orbit, pick).

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
  bool isDragging() const { return axis_.has_value(); }
  viz::ElementHandles* handles() const { return handles_; }

  // Moves the shown element along an axis by `delta_mm` as one undoable edit (numeric entry).
  bool moveBy(int axis, double delta_mm);

 signals:
  void dragFinished(const QString& element, int axis, double delta_mm);

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;

 private:
  void refresh();
  bool applyDelta(double delta_mm, int mergeId);

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
};

}  // namespace fovea::widgets
