#include "widgets/scene_edit_command.h"

#include "widgets/scene_document.h"

namespace fovea::widgets {

SceneEditCommand::SceneEditCommand(SceneDocument* document, Scene before, Scene after, const QString& text)
    : QUndoCommand(text), document_(document), before_(std::move(before)), after_(std::move(after)) {}

void SceneEditCommand::undo() {
  document_->setSceneState(before_);
}
void SceneEditCommand::redo() {
  document_->setSceneState(after_);
}

}  // namespace fovea::widgets
