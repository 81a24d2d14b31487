#pragma once
// The studio's 3D view of the bench: a VtkGlWidget with layers of actors. The "scene" layer
// holds the elements, "frustum" the projector's light and "stages" the translation stages'
// travel (viz/scene_actors.h); later features add their own layers (ray fans, handles) with
// layer(name). Clicking an element (press and release without dragging) emits
// elementPicked(id); setSelectedElement() draws a highlight box around it.
// Viewport layout: the scene renderer takes the window but for a right margin (the legend
// renderer: the colour bar) and a bottom margin (the scale bar), so neither ever covers the
// bench. Element labels (viz/element_labels.h) can be toggled. The camera frames the
// bench's elements tightly in the scene viewport at start and on Reset.

#include <QHash>
#include <QPointF>
#include <QString>

#include <map>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "model/scene/scene.h"
#include "viz/label_placement.h"
#include "viz/scene_layer.h"
#include "viz/vtk_gl_widget.h"

class vtkActor;
class vtkOrientationMarkerWidget;
class vtkCellPicker;
class vtkRenderer;
class vtkRenderStepsPass;

namespace fovea::viz {

class ScaleBar;
class ElementLabels;

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

  // Highlights an element (empty: none). Emits selectionChanged(), not elementPicked().
  void setSelectedElement(const QString& id);
  const QString& selectedElement() const { return selected_; }

  // The element under a widget position (logical pixels), or empty.
  QString elementAt(const QPointF& widgetPos);
  // Where a bench point (mm) appears in the widget (logical pixels), if in front of the camera.
  std::optional<QPointF> widgetPositionOf(const Eigen::Vector3d& bench_mm);

  // Draws the HOE plate (and its layers) displaced by `shift` (bench mm) from its pose: the
  // travel x_p applied by "HOE follows gaze". Kept across setScene().
  void setHoeDisplayShift(const Eigen::Vector3d& shift);
  const Eigen::Vector3d& hoeDisplayShift() const { return hoeShift_; }
  // A binocular scene's left train: its HOE displaced by its own eye's x_p (bench mm), or, with
  // none given, by the mirror image of the right one's (the same travel at mirrored gazes).
  void setLeftHoeDisplayShift(const std::optional<Eigen::Vector3d>& shift);
  Eigen::Vector3d leftHoeDisplayShift() const;

  // The camera ray through a widget position (logical pixels): origin and unit direction.
  std::pair<Eigen::Vector3d, Eigen::Vector3d> viewRay(const QPointF& widgetPos);

  // The standard views. The eye's view puts the camera in the pupil along the gaze, its view
  // angle fitted to the HOE, and hides what the eye cannot see as such (the projector's
  // frustum, the ray fans, the eye's own marks, handles, the stages' travel); the "seen" layer (the plate's area
  // whose light enters the pupil, trace_overlay.h) shows only there. Any other standard view
  // leaves it.
  void showStandardView(StandardView view);
  bool eyeViewMode() const { return eyeView_; }
  // Enters or leaves the eye's view's layer visibility without moving the camera (the report
  // restores a saved camera with it).
  void setEyeViewMode(bool on);
  // Frames the bench's elements (scene layer) in the scene viewport from the current
  // direction.
  void resetCamera();
  // Zooms the camera by `factor` (> 1 closer) about its focal point.
  void zoomCamera(double factor);
  double scaleBarLengthMm() const;
  // The renderer of the right margin, where the colour bar lives.
  vtkRenderer* legendRenderer() const;
  // Right and bottom margins in device pixels (the legend and scale-bar strips).
  static constexpr int kLegendWidth_px = 128;
  static constexpr int kFooterHeight_px = 40;
  // Element labels (projector, HOE, eye, micro-OLED, combiner, lens); on by default.
  void setLabelsVisible(bool on);
  bool labelsVisible() const;
  int labelsShown() const;
  // The last render's label boxes and the areas they keep off (the axes triad), in the render
  // window's pixels (y up), for tests.
  std::vector<LabelRect> labelBoxes() const;
  std::vector<LabelRect> labelObstacles() const;
  // The look of a printed figure: a light background, dark scale bar and colour-bar text,
  // no selection highlight and no interaction handles. Off restores the studio's look.
  void setPrintLook(bool on);
  bool printLook() const { return printLook_; }
  // While a hand drags (a slider or a handle): frames drawn for speed — translucency blended
  // in one pass in drawing order (VTK's render steps with its plain translucent pass; its
  // order-independent pass washed the HOE films out to white) instead of depth peeling,
  // which on a software renderer costs several full-viewport passes a frame. Off (the resting, refined frame):
  // exact depth-peeled blending. A mouse button held in the view (orbit, pan, zoom, a
  // handle) draws for speed too. Drag frames are also drawn at dragRenderScale() of the
  // view's resolution and magnified (VtkGlWidget::setRenderScale): llvmpipe's cost is per pixel.
  void setDragRendering(bool on);
  // The resolution of drag frames, 0.25 .. 1 of the view's in each direction (default 0.5;
  // Edit ▸ Preferences ▸ "3-D view resolution while dragging").
  void setDragRenderScale(double scale);
  double dragRenderScale() const { return dragRenderScale_; }
  // Draws one drag-rendered frame off screen (nothing on screen changes), so the GPU driver
  // compiles its shader variants now rather than on the first frame of the first drag (a
  // software renderer needs ~0.5 s for them). Call once the view shows what a drag will draw.
  void prepareDragRendering();
  bool dragRendering() const { return dragRendering_ || mouseHeld_; }

 signals:
  void elementPicked(const QString& id);
  // The highlighted element changed (setSelectedElement, by a click or programmatically).
  void selectionChanged(const QString& id);

 protected:
  void mousePressEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;
  void resizeGL(int w, int h) override;
  void wheelEvent(QWheelEvent* event) override;
  void paintGL() override;

 private:
  void updateHighlight();
  // The drawn props of an element: its scene-layer props and, for a stage, its travel bar.
  std::vector<vtkProp*> elementProps(const QString& id);
  void applyHoeShift();
  void layoutViewports();
  void applyMarginColors();
  void applyDragRendering();

  Scene scene_;
  bool hasScene_ = false;
  std::map<QString, std::unique_ptr<SceneLayer>> layers_;
  QString selected_;
  vtkSmartPointer<vtkActor> highlight_;
  vtkSmartPointer<vtkOrientationMarkerWidget> axesWidget_;
  vtkSmartPointer<vtkCellPicker> picker_;
  vtkSmartPointer<vtkRenderer> legend_;
  vtkSmartPointer<vtkRenderer> footer_;
  std::unique_ptr<ScaleBar> scaleBar_;
  std::unique_ptr<ElementLabels> labels_;
  bool eyeView_ = false;
  bool autoFramed_ = false;                // the camera is as the last framing left it (refit on resize)
  std::map<QString, bool> eyeViewHidden_;  // layers hidden by the eye's view: visibility before
  QPointF pressPos_;
  bool pressed_ = false;
  Eigen::Vector3d hoeShift_ = Eigen::Vector3d::Zero();
  std::optional<Eigen::Vector3d> leftHoeShift_;
  bool printLook_ = false;
  bool dragRendering_ = false;
  double dragRenderScale_ = 0.5;
  vtkSmartPointer<vtkRenderStepsPass> dragPass_;
  bool mouseHeld_ = false;
  bool handlesWereVisible_ = true;
};

}  // namespace fovea::viz
