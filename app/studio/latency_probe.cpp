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

void LatencyProbe::noteDrawn(quint64 generation, const char* detail, double compute_ms, double paint_ms) {
  const auto it = inputOf_.find(generation);
  if (it == inputOf_.end()) return;
  std::fprintf(stderr, "latency: %s %lld compute %.1f paint %.1f\n", detail, clock_.elapsed() - it->second, compute_ms,
               paint_ms);
  inputOf_.erase(inputOf_.begin(), std::next(it));
}

}  // namespace fovea::studio
