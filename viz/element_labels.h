#pragma once
// Names on the bench in the 3-D view: "projector", "HOE", "eye", "micro-OLED", "combiner",
// "lens", each a 2-D text with a leader line to its element. Before every render (so also
// after a dock resizes the view) the labels are placed on screen by viz/label_placement.h:
// none overlaps another or the axes triad, leaders avoid crossing labels and each other. Anchors come from the model's
// geometry (model/scene/scene_geometry.h); the labels compute no physics.

#include <QString>

#include <vector>

#include <vtkNew.h>
#include <vtkSmartPointer.h>
#include <Eigen/Core>

#include "model/scene/scene.h"
#include "viz/label_placement.h"

class vtkActor2D;
class vtkCallbackCommand;
class vtkObject;
class vtkPoints;
class vtkRenderer;
class vtkTextActor;

namespace fovea::viz {

struct ElementLabel {
  QString element;  // element id (viz/scene_elements.h)
  QString text;
  Eigen::Vector3d anchor_mm = Eigen::Vector3d::Zero();  // bench point the leader line ends at
};

// The labels of a scene's elements and where they point (the lens only when it exists).
std::vector<ElementLabel> elementLabels(const Scene& scene);

class ElementLabels {
 public:
  explicit ElementLabels(vtkRenderer* renderer);
  ~ElementLabels();
  ElementLabels(const ElementLabels&) = delete;
  ElementLabels& operator=(const ElementLabels&) = delete;

  void setScene(const Scene& scene);
  void setVisible(bool on);
  bool isVisible() const { return visible_; }
  void setColor(double r, double g, double b, double background);  // text; background grey level
  // Labels drawn in the last layout (anchors in front of the camera and inside the view).
  int shownCount() const { return shown_; }
  // Places the labels for the renderer's current camera (called before each render).
  void layout();
  // Screen areas to keep free, in the render window's normalised coordinates (0..1, y up):
  // the axes triad's viewport.
  void setAvoid(const std::vector<LabelRect>& normalizedRects);
  // The last layout's label boxes and the areas avoided, in display pixels (y up).
  const std::vector<LabelRect>& boxes() const { return boxes_; }
  const std::vector<LabelRect>& obstacles() const { return obstacles_; }

 private:
  static void onStart(vtkObject*, unsigned long, void* clientData, void*);
  vtkRenderer* renderer_;
  std::vector<ElementLabel> labels_;
  std::vector<vtkSmartPointer<vtkTextActor>> texts_;
  vtkNew<vtkPoints> leaderPoints_;
  vtkNew<vtkActor2D> leaders_;
  vtkNew<vtkCallbackCommand> callback_;
  double rgb_[3] = {0.95, 0.95, 0.95};
  double background_ = 0.08;
  bool visible_ = true;
  int shown_ = 0;
  std::vector<LabelRect> avoid_;
  std::vector<LabelRect> boxes_;
  std::vector<LabelRect> obstacles_;
};

}  // namespace fovea::viz
