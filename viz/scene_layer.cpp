#include "viz/scene_layer.h"

#include <vtkProp.h>
#include <vtkRenderer.h>

namespace fovea::viz {

SceneLayer::SceneLayer(vtkRenderer* renderer, QString name) : renderer_(renderer), name_(std::move(name)) {}

SceneLayer::~SceneLayer() {
  clear();
}

void SceneLayer::add(vtkProp* prop, const QString& elementId, bool pickable) {
  prop->SetVisibility(visible_);
  prop->SetPickable(pickable && !elementId.isEmpty());
  renderer_->AddViewProp(prop);
  entries_.push_back({prop, elementId});
}

void SceneLayer::clear() {
  for (auto& e : entries_) renderer_->RemoveViewProp(e.prop);
  entries_.clear();
}

void SceneLayer::removeElement(const QString& elementId) {
  std::erase_if(entries_, [&](const Entry& e) {
    if (e.element != elementId) return false;
    renderer_->RemoveViewProp(e.prop);
    return true;
  });
}

void SceneLayer::setVisible(bool visible) {
  visible_ = visible;
  for (auto& e : entries_) e.prop->SetVisibility(visible);
}

QString SceneLayer::elementOf(const vtkProp* prop) const {
  for (const auto& e : entries_)
    if (e.prop.GetPointer() == prop) return e.element;
  return {};
}

std::vector<vtkProp*> SceneLayer::propsOf(const QString& elementId) const {
  std::vector<vtkProp*> out;
  for (const auto& e : entries_)
    if (e.element == elementId) out.push_back(e.prop);
  return out;
}

}  // namespace fovea::viz
