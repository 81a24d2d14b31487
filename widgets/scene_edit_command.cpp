#include "widgets/scene_edit_command.h"

#include "widgets/scene_document.h"

namespace fovea::widgets {

SceneEditCommand::SceneEditCommand(SceneDocument* document, Scene before, Scene after, const QString& text, int mergeId)
    : QUndoCommand(text),
      document_(document),
      before_(std::move(before)),
      after_(std::move(after)),
      mergeId_(mergeId) {}

bool SceneEditCommand::mergeWith(const QUndoCommand* other) {
  const auto* o = dynamic_cast<const SceneEditCommand*>(other);
  if (!o || o->mergeId_ != mergeId_ || mergeId_ < 0) return false;
  after_ = o->after_;
  setText(o->text());
  return true;
}

void SceneEditCommand::undo() {
  document_->setSceneState(before_);
}
void SceneEditCommand::redo() {
  document_->setSceneState(after_);
}

}  // namespace fovea::widgets
