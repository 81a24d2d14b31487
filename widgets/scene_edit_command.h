#pragma once
// One undoable change of the scene: keeps the scene before and after (scenes are small).

#include <QUndoCommand>

#include "model/scene/scene.h"

namespace fovea::widgets {

class SceneDocument;

class SceneEditCommand : public QUndoCommand {
 public:
  SceneEditCommand(SceneDocument* document, Scene before, Scene after, const QString& text);
  void undo() override;
  void redo() override;

 private:
  SceneDocument* document_;
  Scene before_, after_;
};

}  // namespace fovea::widgets
