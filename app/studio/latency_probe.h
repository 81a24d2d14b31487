#pragma once
// Measuring the studio's drag latency (docs/benchmarks.md, "Responsive drag"): with the
// environment variable FOVEA_LATENCY_LOG set, every mouse move with a button held is time
// stamped; each live-trace result drawn on screen (the 3-D view's next swapped frame) prints
// "latency: <detail> <ms from the move that asked for it to the frame> compute <ms> paint <ms> delivered <ms>" and each
// move "gui: <ms the GUI thread spent on it>" to stderr. Off: nothing is installed.

#include <QElapsedTimer>
#include <QObject>

#include <map>

namespace fovea::studio {

class LatencyProbe : public QObject {
  Q_OBJECT
 public:
  // The probe when FOVEA_LATENCY_LOG is set (owned by `parent`), else nullptr.
  static LatencyProbe* createIfRequested(QObject* parent);
  // The time (ms since start) of the newest mouse move, or -1.
  qint64 lastInputMs() const { return lastInput_; }
  qint64 nowMs() const { return clock_.elapsed(); }
  // Remembers that trace request `generation` answers the newest move.
  void noteRequest(quint64 generation);
  // Prints the latency of `generation`'s result, drawn now, with the trace's compute time and
  // the 3-D view's paint time of that frame.
  void noteDrawn(quint64 generation, const char* detail, double compute_ms, double paint_ms);
  // Remembers when `generation`'s result reached the GUI thread (printed with noteDrawn as
  // "delivered <ms after the move>").
  void noteDelivered(quint64 generation);

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;

 private:
  explicit LatencyProbe(QObject* parent);
  QElapsedTimer clock_;
  qint64 lastInput_ = -1;
  std::map<quint64, qint64> inputOf_;
  std::map<quint64, qint64> deliveredAt_;
};

}  // namespace fovea::studio
