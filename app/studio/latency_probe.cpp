#include "app/studio/latency_probe.h"

#include <QCoreApplication>
#include <QMouseEvent>
#include <QTimer>

#include <cstdio>

namespace fovea::studio {

LatencyProbe* LatencyProbe::createIfRequested(QObject* parent) {
  if (qEnvironmentVariableIsEmpty("FOVEA_LATENCY_LOG")) return nullptr;
  return new LatencyProbe(parent);
}

LatencyProbe::LatencyProbe(QObject* parent) : QObject(parent) {
  clock_.start();
  QCoreApplication::instance()->installEventFilter(this);
}

bool LatencyProbe::eventFilter(QObject* watched, QEvent* event) {
  if (event->type() == QEvent::MouseMove && static_cast<QMouseEvent*>(event)->buttons() != Qt::NoButton &&
      watched->isWidgetType()) {
    const qint64 t = clock_.elapsed();
    if (t != lastInput_) {
      lastInput_ = t;
      // Runs once the move (and everything it triggered synchronously) is handled.
      QTimer::singleShot(0, this, [this, t] { std::fprintf(stderr, "gui: %lld\n", clock_.elapsed() - t); });
    }
  }
  return false;
}

void LatencyProbe::noteRequest(quint64 generation) {
  if (lastInput_ >= 0) inputOf_[generation] = lastInput_;
}

void LatencyProbe::noteDelivered(quint64 generation) {
  deliveredAt_[generation] = clock_.elapsed();
}

void LatencyProbe::noteDrawn(quint64 generation, const char* detail, double compute_ms, double paint_ms) {
  const auto it = inputOf_.find(generation);
  if (it == inputOf_.end()) return;
  const auto d = deliveredAt_.find(generation);
  const qint64 delivered = d == deliveredAt_.end() ? -1 : d->second - it->second;
  std::fprintf(stderr, "latency: %s %lld compute %.1f paint %.1f delivered %lld\n", detail,
               clock_.elapsed() - it->second, compute_ms, paint_ms, delivered);
  deliveredAt_.erase(deliveredAt_.begin(), deliveredAt_.upper_bound(generation));
  inputOf_.erase(inputOf_.begin(), std::next(it));
}

}  // namespace fovea::studio
