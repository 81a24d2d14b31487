#pragma once
// A visible keyboard focus everywhere (issue 27 item 7): a widget that draws no focus of its
// own (the 3-D view, the scene tree, the message log, the plots, plain panels) shows a
// highlight-coloured ring around its edge while it holds a focus that came from Tab or
// Backtab. Fields that draw their own focus (line edits, spin boxes, combo boxes, buttons) get
// no ring. The ring is a child of the focused widget on top of its other children, passes the
// mouse through and follows the widget's size; a click (or any focus not from the keyboard)
// hides it. Tab never stops in a dock tabbed behind another (Qt's Tab chain visits its
// controls, unseen): it goes on to the next control shown, and a control of a scrolling form
// is scrolled into view. One application-wide event filter, also for widgets created later.

#include <QObject>
#include <QPointer>
#include <QWidget>

namespace fovea::widgets {

class FocusRing : public QWidget {
  Q_OBJECT
 public:
  explicit FocusRing(QWidget* target);

 protected:
  void paintEvent(QPaintEvent* event) override;
};

class FocusRingFilter : public QObject {
  Q_OBJECT
 public:
  using QObject::QObject;
  // Whether `w` draws its keyboard focus itself (then it gets no ring).
  static bool drawsOwnFocus(const QWidget* w);
  // Whether `w` sits in a dock tabbed behind another (in Qt's Tab chain, but not on screen).
  static bool behindATab(const QWidget* w);
  // The next (previous) widget of `from`'s Tab chain that Tab may focus and that is shown.
  static QWidget* nextShown(QWidget* from, bool forward);
  // The ring shown now, or null.
  FocusRing* ring() const { return ring_; }

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;

 private:
  void showAround(QWidget* w);
  void hide();
  QPointer<FocusRing> ring_;
};

// Installs one filter on the application (idempotent); it is owned by qApp.
void installFocusRing();
// The ring shown now (null when none): for tests.
FocusRing* currentFocusRing();

}  // namespace fovea::widgets
