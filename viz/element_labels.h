#pragma once
// Names on the bench in the 3-D view: "projector", "HOE", "eye", "micro-OLED", "combiner",
// "lens", each a 2-D text with a leader line to its element. Before every render the labels
// are placed at a fixed pixel distance from their anchor, pushed outwards from the middle of
// the bench on screen and along that direction until they overlap no other label, so they
// never sit on the elements' crowded middle. Anchors come from the model's geometry
// (model/scene/scene_geometry.h); the labels compute no physics.

#include <QString>

#include <vector>

#include <vtkNew.h>
#include <vtkSmartPointer.h>
#include <Eigen/Core>

#include "model/scene/scene.h"

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
};

}  // namespace fovea::viz
