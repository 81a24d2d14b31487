#include "widgets/wheel_guard.h"

#include <QAbstractSlider>
#include <QAbstractSpinBox>
#include <QApplication>
#include <QComboBox>
#include <QEvent>
#include <QWheelEvent>

namespace fovea::widgets {

bool WheelGuard::isGuarded(const QWidget* w) {
  return qobject_cast<const QAbstractSpinBox*>(w) || qobject_cast<const QComboBox*>(w) ||
         qobject_cast<const QAbstractSlider*>(w);
}

bool WheelGuard::eventFilter(QObject* watched, QEvent* event) {
  const QEvent::Type t = event->type();
  if (t != QEvent::Wheel && t != QEvent::Polish) return false;
  auto* w = qobject_cast<QWidget*>(watched);
  if (!w || !isGuarded(w)) return false;
  // A scroll bar is a slider too, but the wheel is what it is for.
  if (w->inherits("QScrollBar")) return false;
  // Click or Tab focuses the field; the wheel does not (nor does a tab-only policy keep a
  // click from focusing a slider, which would leave the wheel no way in).
  if (w->focusPolicy() != Qt::NoFocus && w->focusPolicy() != Qt::StrongFocus) w->setFocusPolicy(Qt::StrongFocus);
  if (t == QEvent::Polish) return false;
  if (w->hasFocus()) return false;
  // Filtered but not accepted: QApplication::notify passes the wheel on to the parents, so
  // the scroll area around the form scrolls and the field keeps its value.
  event->ignore();
  return true;
}

void installWheelGuard() {
  if (!qApp || qApp->findChild<WheelGuard*>(QString(), Qt::FindDirectChildrenOnly)) return;
  qApp->installEventFilter(new WheelGuard(qApp));
}

}  // namespace fovea::widgets
