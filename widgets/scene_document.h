#pragma once
// The open scene: the model's Scene, its file, and the undo stack through which every edit
// goes. Widgets read scene() and change it only with applyEdit(), which refuses a change
// that breaks the scene file's rules (model validateScene) and returns the messages.

#include <QObject>
#include <QString>
#include <QStringList>
#include <QUndoStack>

#include <functional>

#include "model/scene/scene.h"

namespace fovea::widgets {

class SceneDocument : public QObject {
  Q_OBJECT
 public:
  explicit SceneDocument(QObject* parent = nullptr);

  const Scene& scene() const { return scene_; }
  QUndoStack* undoStack() { return &undo_; }

  // The file the scene came from or was saved to; empty for the embedded default / new.
  const QString& filePath() const { return filePath_; }
  // "prototype-bench.json" or the name given to resetTo() for an unsaved scene.
  QString displayName() const;
  bool isModified() const { return !undo_.isClean(); }

  // Replaces the whole scene (New, Open): clears the undo history, marks it unmodified.
  void resetTo(const Scene& scene, const QString& filePath, const QString& displayName = {});
  // Records that the scene was saved as `filePath` (undo history kept, marked clean).
  void markSaved(const QString& filePath);

  // Applies `change` to a copy of the scene; if the result is valid, pushes an undoable
  // command named `text` and returns {}; otherwise changes nothing and returns every
  // problem ("eye.relief_mm: must be > 0, got -5"). Consecutive edits with the same
  // mergeId >= 0 merge into one undo step: one per gesture (a slider drag, a handle drag),
  // see newGestureId().
  QStringList applyEdit(const QString& text, const std::function<void(Scene&)>& change, int mergeId = -1);
  // A merge id not used before by this document.
  int newGestureId() { return ++gestures_; }

  // Used by the undo commands: sets the scene and notifies.
  void setSceneState(const Scene& scene);

 signals:
  void sceneChanged();   // any change of the scene's content
  void sceneReplaced();  // a different scene was loaded (New, Open)
  void modifiedChanged(bool modified);
  void filePathChanged(const QString& path);

 private:
  Scene scene_;
  QUndoStack undo_;
  QString filePath_;
  QString displayName_;
  int gestures_ = 0;
};

}  // namespace fovea::widgets
