#include "widgets/focus_ring.h"

#include <QAbstractButton>
#include <QAbstractSpinBox>
#include <QApplication>
#include <QComboBox>
#include <QDockWidget>
#include <QEvent>
#include <QFocusEvent>
#include <QLineEdit>
#include <QPainter>
#include <QScrollArea>
#include <QTabBar>

namespace fovea::widgets {

FocusRing::FocusRing(QWidget* target) : QWidget(target) {
  setObjectName("focusRing");
  setAttribute(Qt::WA_TransparentForMouseEvents);
  setAttribute(Qt::WA_NoSystemBackground);
  setFocusPolicy(Qt::NoFocus);
  setGeometry(target->rect());
}

void FocusRing::paintEvent(QPaintEvent*) {
  QPainter p(this);
  QPen pen(palette().color(QPalette::Active, QPalette::Highlight), 2);
  pen.setJoinStyle(Qt::MiterJoin);
  p.setPen(pen);
  p.setBrush(Qt::NoBrush);
  p.drawRect(QRectF(rect()).adjusted(1, 1, -1, -1));
}

bool FocusRingFilter::drawsOwnFocus(const QWidget* w) {
  return qobject_cast<const QLineEdit*>(w) || qobject_cast<const QAbstractSpinBox*>(w) ||
         qobject_cast<const QComboBox*>(w) || qobject_cast<const QAbstractButton*>(w) ||
         qobject_cast<const QTabBar*>(w);
}

bool FocusRingFilter::behindATab(const QWidget* w) {
  // A dock tabbed behind another is "visible" to Qt (so in the Tab chain) but covered by the
  // front tab: nothing of it is on the screen.
  for (const QWidget* p = w; p && !p->isWindow(); p = p->parentWidget())
    if (qobject_cast<const QDockWidget*>(p) && p->visibleRegion().isEmpty()) return true;
  return false;
}

QWidget* FocusRingFilter::nextShown(QWidget* from, bool forward) {
  QWidget* window = from->window();
  for (QWidget* c = forward ? from->nextInFocusChain() : from->previousInFocusChain(); c && c != from;
       c = forward ? c->nextInFocusChain() : c->previousInFocusChain()) {
    if (c->window() != window || !c->isVisible() || !c->isEnabled() || !(c->focusPolicy() & Qt::TabFocus) ||
        c->focusProxy() || behindATab(c))
      continue;
    return c;
  }
  return nullptr;
}

void FocusRingFilter::showAround(QWidget* w) {
  if (ring_ && ring_->parentWidget() == w) {
    ring_->setGeometry(w->rect());
    ring_->raise();
    ring_->show();
    return;
  }
  hide();
  ring_ = new FocusRing(w);
  w->installEventFilter(this);  // follows its size
  ring_->raise();
  ring_->show();
}

void FocusRingFilter::hide() {
  if (!ring_) return;
  if (QWidget* target = ring_->parentWidget()) target->removeEventFilter(this);
  ring_->hide();
  ring_->deleteLater();
  ring_ = nullptr;
}

bool FocusRingFilter::eventFilter(QObject* watched, QEvent* event) {
  const QEvent::Type t = event->type();
  if (t == QEvent::Resize && ring_ && watched == ring_->parentWidget()) {
    ring_->setGeometry(ring_->parentWidget()->rect());
    return false;
  }
  if (t == QEvent::ChildAdded && ring_ && watched == ring_->parentWidget()) {
    ring_->raise();  // stays on top of children added later
    return false;
  }
  if (t != QEvent::FocusIn && t != QEvent::FocusOut) return false;
  auto* w = qobject_cast<QWidget*>(watched);
  if (!w || w == ring_) return false;
  const auto reason = static_cast<QFocusEvent*>(event)->reason();
  if (t == QEvent::FocusOut) {
    // A popup or another window taking the focus for a moment keeps the ring.
    if (ring_ && ring_->parentWidget() == w && reason != Qt::PopupFocusReason && reason != Qt::ActiveWindowFocusReason)
      hide();
    return false;
  }
  if (reason == Qt::TabFocusReason || reason == Qt::BacktabFocusReason) {
    // Tab landed on a control of a dock tabbed behind another: go on to the next one shown
    // (its FocusIn comes back here with the same reason).
    if (!w->isWindow() && behindATab(w)) {
      if (QWidget* next = nextShown(w, reason == Qt::TabFocusReason)) {
        next->setFocus(reason);
        return false;
      }
    }
    // Inside a scrolling form: scrolled into view, as Tab within the form does.
    for (QWidget* p = w->parentWidget(); p && !p->isWindow(); p = p->parentWidget())
      if (auto* scroll = qobject_cast<QScrollArea*>(p);
          scroll && scroll->widget() && scroll->widget()->isAncestorOf(w)) {
        scroll->ensureWidgetVisible(w);
        break;
      }
    if (drawsOwnFocus(w) || w->isWindow())
      hide();
    else
      showAround(w);
  } else if (reason != Qt::PopupFocusReason && reason != Qt::ActiveWindowFocusReason) {
    hide();
  }
  return false;
}

namespace {
FocusRingFilter* installedFilter() {
  return qApp ? qApp->findChild<FocusRingFilter*>(QString(), Qt::FindDirectChildrenOnly) : nullptr;
}
}  // namespace

void installFocusRing() {
  if (!qApp || installedFilter()) return;
  qApp->installEventFilter(new FocusRingFilter(qApp));
}

FocusRing* currentFocusRing() {
  FocusRingFilter* f = installedFilter();
  return f ? f->ring() : nullptr;
}

}  // namespace fovea::widgets
