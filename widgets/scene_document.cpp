#include "widgets/scene_document.h"

#include <QFileInfo>

#include "model/scene/scene_io.h"
#include "widgets/scene_edit_command.h"

namespace fovea::widgets {

SceneDocument::SceneDocument(QObject* parent) : QObject(parent) {
  connect(&undo_, &QUndoStack::cleanChanged, this, [this](bool clean) { emit modifiedChanged(!clean); });
}

QString SceneDocument::displayName() const {
  if (!filePath_.isEmpty()) return QFileInfo(filePath_).fileName();
  return displayName_.isEmpty() ? QStringLiteral("untitled.json") : displayName_;
}

void SceneDocument::resetTo(const Scene& scene, const QString& filePath, const QString& displayName) {
  const bool wasModified = isModified();
  undo_.clear();
  undo_.setClean();
  scene_ = scene;
  displayName_ = displayName;
  if (filePath != filePath_) {
    filePath_ = filePath;
  }
  emit filePathChanged(filePath_);
  emit sceneReplaced();
  emit sceneChanged();
  if (wasModified) emit modifiedChanged(false);
}

void SceneDocument::markSaved(const QString& filePath) {
  filePath_ = filePath;
  undo_.setClean();
  emit filePathChanged(filePath_);
}

QStringList SceneDocument::applyEdit(const QString& text, const std::function<void(Scene&)>& change, int mergeId) {
  Scene after = scene_;
  change(after);
  QStringList problems;
  for (const auto& p : validateScene(after)) problems << QString::fromStdString(p);
  if (!problems.isEmpty()) return problems;
  if (after == scene_) return {};
  undo_.push(new SceneEditCommand(this, scene_, after, text, mergeId));
  return {};
}

void SceneDocument::setSceneState(const Scene& scene) {
  scene_ = scene;
  emit sceneChanged();
}

}  // namespace fovea::widgets
