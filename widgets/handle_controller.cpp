#include "widgets/handle_controller.h"

#include <QInputDialog>
#include <QMouseEvent>

#include <cmath>

#include "viz/element_handles.h"
#include "viz/scene_view.h"
#include "widgets/scene_document.h"

namespace fovea::widgets {

namespace {
const char* kAxisName[3] = {"x", "y", "z"};
const char* kRingName[3] = {"yaw", "pitch", "roll"};
}  // namespace

HandleController::HandleController(SceneDocument* document, viz::SceneView* view, QObject* parent)
    : QObject(parent), document_(document), view_(view), handles_(new viz::ElementHandles(view)) {
  view_->installEventFilter(this);
  connect(document_, &SceneDocument::sceneChanged, this, &HandleController::refresh);
}

HandleController::~HandleController() {
  view_->removeEventFilter(this);
  delete handles_;
}

void HandleController::setElement(const QString& id) {
  element_ = viz::movableElement(id);
  refresh();
}

void HandleController::setEnabled(bool on) {
  enabled_ = on;
  refresh();
}

void HandleController::refresh() {
  handles_->show(document_->scene(), enabled_ ? element_ : QString());
}

bool HandleController::applyDelta(double delta, int mergeId) {
  const int axis = *axis_;
  Eigen::Vector3d d = Eigen::Vector3d::Zero();
  d[axis] = delta - lastDelta_;  // the document already holds the previous step of this drag
  if (d.isZero()) return true;
  const QString el = element_;
  const QString text = tr("Move %1 along %2 by %3 mm").arg(el, kAxisName[axis]).arg(delta, 0, 'g', 6);
  const QStringList problems = document_->applyEdit(
      text, [el, d](Scene& s) { viz::moveElement(s, el, d); }, mergeId);
  if (!problems.isEmpty()) return false;  // refused (e.g. relief <= 0): stay at the last valid place
  lastDelta_ = delta;
  return true;
}

bool HandleController::moveBy(int axis, double delta) {
  if (element_.isEmpty() || axis < 0 || axis > 2) return false;
  axis_ = axis;
  lastDelta_ = 0.0;
  const bool ok = applyDelta(delta, -1);
  axis_.reset();
  if (ok) emit dragFinished(element_, axis, delta);
  return ok;
}

bool HandleController::applyTurn(double turn, int mergeId) {
  const int ring = *ring_;
  const double d = turn - lastTurn_;  // the document already holds the previous step of this drag
  if (d == 0.0) return true;
  const QString el = element_;
  const QString text = tr("Rotate %1: %2 by %3 deg").arg(el, kRingName[ring]).arg(turn, 0, 'g', 6);
  const QStringList problems = document_->applyEdit(
      text, [el, ring, d](Scene& s) { viz::rotateElement(s, el, ring, d); }, mergeId);
  if (!problems.isEmpty()) return false;
  lastTurn_ = turn;
  return true;
}

bool HandleController::rotateBy(int ring, double delta) {
  if (element_.isEmpty() || ring < 0 || ring >= viz::rotationRingCount(element_)) return false;
  ring_ = ring;
  lastTurn_ = 0.0;
  const bool ok = applyTurn(delta, -1);
  ring_.reset();
  if (ok) emit rotateFinished(element_, ring, delta);
  return ok;
}

bool HandleController::eventFilter(QObject* watched, QEvent* event) {
  if (watched != view_ || !enabled_ || element_.isEmpty()) return false;
  switch (event->type()) {
    case QEvent::MouseButtonPress: {
      auto* e = static_cast<QMouseEvent*>(event);
      if (e->button() != Qt::LeftButton) return false;
      const auto axis = handles_->axisAt(e->position());
      if (!axis) {
        const auto ring = handles_->ringAt(e->position());
        const auto angle = ring ? handles_->ringAngle(*ring, e->position()) : std::nullopt;
        if (!angle) return false;
        ring_ = ring;
        prevAngle_ = *angle;
        turned_ = lastTurn_ = 0.0;
        gesture_ = document_->newGestureId();
        handles_->setHighlightedRing(ring);
        refresh();
        return true;
      }
      const auto t = handles_->axisParameter(*axis, handles_->origin(), e->position());
      if (!t) return false;
      axis_ = axis;
      dragOrigin_ = handles_->origin();
      startParam_ = *t;
      lastDelta_ = 0.0;
      gesture_ = document_->newGestureId();
      handles_->setHighlighted(axis);
      refresh();
      return true;
    }
    case QEvent::MouseMove: {
      auto* e = static_cast<QMouseEvent*>(event);
      if (ring_) {
        const auto angle = handles_->ringAngle(*ring_, e->position());
        if (!angle) return true;
        turned_ += std::remainder(*angle - prevAngle_, 360.0);  // unwrap across +-180 deg
        prevAngle_ = *angle;
        const double step = (e->modifiers() & Qt::ShiftModifier) ? kFineAngleStep_deg : snap_deg_;
        applyTurn(step > 0.0 ? std::round(turned_ / step) * step : turned_, gesture_);
        return true;
      }
      if (!axis_) {
        const bool hover = handles_->axisAt(e->position()) || handles_->ringAt(e->position());
        view_->setCursor(hover ? Qt::SizeAllCursor : Qt::ArrowCursor);
        return false;
      }
      const auto t = handles_->axisParameter(*axis_, dragOrigin_, e->position());
      if (!t) return true;
      double delta = *t - startParam_;
      if (!(e->modifiers() & Qt::ShiftModifier) && snap_mm_ > 0.0) delta = std::round(delta / snap_mm_) * snap_mm_;
      applyDelta(delta, gesture_);
      return true;
    }
    case QEvent::MouseButtonRelease: {
      auto* e = static_cast<QMouseEvent*>(event);
      if (ring_ && e->button() == Qt::LeftButton) {
        const int ring = *ring_;
        const double turn = lastTurn_;
        ring_.reset();
        gesture_ = -1;
        handles_->setHighlightedRing(std::nullopt);
        refresh();
        emit rotateFinished(element_, ring, turn);
        return true;
      }
      if (!axis_ || e->button() != Qt::LeftButton) return false;
      const int axis = *axis_;
      const double delta = lastDelta_;
      axis_.reset();
      gesture_ = -1;
      handles_->setHighlighted(std::nullopt);
      refresh();
      emit dragFinished(element_, axis, delta);
      return true;
    }
    case QEvent::MouseButtonDblClick: {
      auto* e = static_cast<QMouseEvent*>(event);
      const auto axis = handles_->axisAt(e->position());
      if (!axis) {
        const auto ring = handles_->ringAt(e->position());
        if (!ring) return false;
        bool ok = false;
        const double d =
            QInputDialog::getDouble(view_, tr("Rotate %1").arg(element_), tr("Turn %1 by (deg):").arg(kRingName[*ring]),
                                    0.0, -360.0, 360.0, 3, &ok);
        if (ok && d != 0.0) rotateBy(*ring, d);
        return true;
      }
      bool ok = false;
      const double d =
          QInputDialog::getDouble(view_, tr("Move %1").arg(element_),
                                  tr("Distance along %1 (mm):").arg(kAxisName[*axis]), 0.0, -1000.0, 1000.0, 3, &ok);
      if (ok && d != 0.0) moveBy(*axis, d);
      return true;
    }
    default:
      return false;
  }
}

}  // namespace fovea::widgets
