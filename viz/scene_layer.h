#pragma once
// A named group of VTK props in a renderer (the scene's elements, later ray fans, handles,
// ...). Each prop may belong to a scene element (viz/scene_elements.h) so picking it selects
// that element. Clearing or destroying the layer removes its props from the renderer.

#include <QString>

#include <vector>

#include <vtkSmartPointer.h>

class vtkProp;
class vtkRenderer;

namespace fovea::viz {

class SceneLayer {
 public:
  SceneLayer(vtkRenderer* renderer, QString name);
  ~SceneLayer();
  SceneLayer(const SceneLayer&) = delete;
  SceneLayer& operator=(const SceneLayer&) = delete;

  const QString& name() const { return name_; }
  void add(vtkProp* prop, const QString& elementId = {}, bool pickable = true);
  void clear();
  // Removes the props of one element (the rest stay).
  void removeElement(const QString& elementId);
  void setVisible(bool visible);
  bool isVisible() const { return visible_; }

  // The element a prop of this layer belongs to; empty when none or not ours.
  QString elementOf(const vtkProp* prop) const;
  std::vector<vtkProp*> propsOf(const QString& elementId) const;
  std::size_t size() const { return entries_.size(); }

 private:
  struct Entry {
    vtkSmartPointer<vtkProp> prop;
    QString element;
  };
  vtkRenderer* renderer_;
  QString name_;
  std::vector<Entry> entries_;
  bool visible_ = true;
};

}  // namespace fovea::viz
