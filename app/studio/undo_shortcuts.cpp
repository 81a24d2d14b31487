#include "app/studio/undo_shortcuts.h"

#include <QAbstractSpinBox>
#include <QKeyEvent>
#include <QLineEdit>
#include <QTimer>

namespace fovea::studio {

namespace {

enum class UndoKey { None, Undo, Redo };

UndoKey undoKeyOf(const QKeyEvent* e) {
  if (e->matches(QKeySequence::Undo)) return UndoKey::Undo;
  if (e->matches(QKeySequence::Redo)) return UndoKey::Redo;
  if (e->key() == Qt::Key_Y && (e->modifiers() & ~Qt::KeypadModifier) == Qt::ControlModifier) return UndoKey::Redo;
  return UndoKey::None;
}

// The line edit a key event aimed at `watched` would edit, if any.
QLineEdit* lineEditOf(QObject* watched) {
  if (auto* le = qobject_cast<QLineEdit*>(watched)) return le;
  if (auto* spin = qobject_cast<QAbstractSpinBox*>(watched)) return spin->findChild<QLineEdit*>();
  return nullptr;
}

}  // namespace

DocumentUndoShortcuts::DocumentUndoShortcuts(QObject* parent) : QObject(parent) {}

bool DocumentUndoShortcuts::eventFilter(QObject* watched, QEvent* event) {
  if (event->type() != QEvent::ShortcutOverride && event->type() != QEvent::KeyPress) return false;
  auto* key = static_cast<QKeyEvent*>(event);
  QLineEdit* field = lineEditOf(watched);
  if (!field || field->isReadOnly()) return false;
  if (event->type() == QEvent::KeyPress) {
    // Enter commits the field: from then on its text is not "typed" any more.
    if (key->key() == Qt::Key_Return || key->key() == Qt::Key_Enter)
      QTimer::singleShot(0, field, [field] { field->setModified(false); });
    return false;
  }
  const UndoKey which = undoKeyOf(key);
  if (which == UndoKey::None) return false;
  // Typed, uncommitted text: the field's own undo. Otherwise the document's.
  if (field->isModified() && (which == UndoKey::Undo ? field->isUndoAvailable() : field->isRedoAvailable()))
    return false;
  // Not accepted and not delivered to the field: the window's Undo/Redo action takes the key.
  key->ignore();
  return true;
}

}  // namespace fovea::studio
