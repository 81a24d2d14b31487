#pragma once
// Forms that do not change under the mouse wheel: a spin box, combo box or slider takes
// wheel events only while it has the keyboard focus; otherwise the wheel scrolls the form
// (the event goes on to the scroll area around the field). Such fields also stop taking the
// focus from the wheel (Qt::StrongFocus: click or Tab). One application-wide event filter
// covers every dock, dialog and form, also fields created later (rebuilt forms).

#include <QObject>

class QWidget;

namespace fovea::widgets {

class WheelGuard : public QObject {
  Q_OBJECT
 public:
  using QObject::QObject;
  // Whether `w` is a field the guard protects (spin box, combo box, slider).
  static bool isGuarded(const QWidget* w);

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;
};

// Installs one guard on the application (idempotent); the guard is owned by qApp.
void installWheelGuard();

}  // namespace fovea::widgets
