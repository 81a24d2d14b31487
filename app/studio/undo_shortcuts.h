#pragma once
// Undo and redo from any focus. A text field (QLineEdit, a spin box's editor) claims
// Ctrl+Z for its own text history, so after Enter in a property field the document's undo
// never fired. This application-wide filter leaves the key to the field only while it
// holds typed, uncommitted text; otherwise Ctrl+Z, Ctrl+Shift+Z and Ctrl+Y go to the
// window's Undo/Redo actions (the document's undo stack). Enter (or leaving the field) commits the text.

#include <QObject>

namespace fovea::studio {

class DocumentUndoShortcuts : public QObject {
  Q_OBJECT
 public:
  explicit DocumentUndoShortcuts(QObject* parent);

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;
};

}  // namespace fovea::studio
