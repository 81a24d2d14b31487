#pragma once
// One undoable change of the scene: keeps the scene before and after (scenes are small).

#include <QUndoCommand>

#include "model/scene/scene.h"

namespace fovea::widgets {

class SceneDocument;

class SceneEditCommand : public QUndoCommand {
 public:
  SceneEditCommand(SceneDocument* document, Scene before, Scene after, const QString& text, int mergeId = -1);
  void undo() override;
  void redo() override;
  // Commands with the same id >= 0 merge when pushed one after the other (the first keeps
  // its "before", takes the last one's "after" and text).
  int id() const override { return mergeId_; }
  bool mergeWith(const QUndoCommand* other) override;

 private:
  SceneDocument* document_;
  Scene before_, after_;
  int mergeId_ = -1;
};

}  // namespace fovea::widgets
