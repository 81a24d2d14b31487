#pragma once
// The studio's 3D view of the bench: a VtkGlWidget with layers of actors. The "scene" layer
// holds the elements (viz/scene_actors.h); later features add their own layers (ray fans,
// handles) with layer(name). Clicking an element (press and release without dragging) emits
// elementPicked(id); setSelectedElement() draws a highlight box around it.

#include <QHash>
#include <QPointF>
#include <QString>

#include <map>
#include <memory>
#include <optional>

#include <Eigen/Core>

#include "model/scene/scene.h"
#include "viz/scene_layer.h"
#include "viz/vtk_gl_widget.h"

class vtkActor;
class vtkOrientationMarkerWidget;
class vtkCellPicker;

namespace fovea::viz {

class ScaleBar;

enum class StandardView { Isometric, Top, Side, EyeView };

class SceneView : public VtkGlWidget {
  Q_OBJECT
 public:
  explicit SceneView(QWidget* parent = nullptr);
  ~SceneView() override;

  // Rebuilds the scene layer from `scene`; keeps the camera unless `resetCamera`.
  void setScene(const Scene& scene, bool resetCamera = false);
  const Scene& scene() const { return scene_; }

  // A named layer, created (empty) on first use.
  SceneLayer& layer(const QString& name);
  SceneLayer& sceneLayer() { return layer(QStringLiteral("scene")); }

  // Highlights an element (empty: none). Emits nothing.
  void setSelectedElement(const QString& id);
  const QString& selectedElement() const { return selected_; }

  // The element under a widget position (logical pixels), or empty.
  QString elementAt(const QPointF& widgetPos);
  // Where a bench point (mm) appears in the widget (logical pixels), if in front of the camera.
  std::optional<QPointF> widgetPositionOf(const Eigen::Vector3d& bench_mm);

  void showStandardView(StandardView view);
  void resetCamera();
  double scaleBarLengthMm() const;

 signals:
  void elementPicked(const QString& id);

 protected:
  void mousePressEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;

 private:
  void updateHighlight();

  Scene scene_;
  bool hasScene_ = false;
  std::map<QString, std::unique_ptr<SceneLayer>> layers_;
  QString selected_;
  vtkSmartPointer<vtkActor> highlight_;
  vtkSmartPointer<vtkOrientationMarkerWidget> axesWidget_;
  vtkSmartPointer<vtkCellPicker> picker_;
  std::unique_ptr<ScaleBar> scaleBar_;
  QPointF pressPos_;
  bool pressed_ = false;
};

}  // namespace fovea::viz
