#pragma once
// The retina view: the angular image of the peripheral display as the eye sees it. Each
// cell of the projector's ray grid whose four corner rays enter the pupil is drawn at their
// visual angles (yaw right, pitch up, degrees from the gaze axis) in the colour of their
// mean diffraction efficiency (gray below 0.1); with several wavelengths shown, each is
// drawn translucently over the others. On top: the FOV box (extent of the rays in the
// pupil with efficiency >= 0.1, the trace's FOV definition) with its horizontal and
// vertical size, the fovea circle, the gaze cross and the key numbers.

#include <QImage>
#include <QWidget>

#include <memory>
#include <vector>

#include "widgets/live_trace.h"

namespace fovea::widgets {

class RetinaView : public QWidget {
  Q_OBJECT
 public:
  explicit RetinaView(QWidget* parent = nullptr);

  void setResult(std::shared_ptr<const LiveTraceResult> result, const std::vector<double>& hidden_wavelengths_nm);
  // FOV box of the shown wavelengths: yaw min, max, pitch min, max (degrees); empty rect
  // semantics: valid() false when no ray is accepted.
  struct Box {
    bool valid = false;
    double yaw_min = 0, yaw_max = 0, pitch_min = 0, pitch_max = 0;
  };
  const Box& fovBox() const { return box_; }
  // The trace shown (null before the first).
  const std::shared_ptr<const LiveTraceResult>& result() const { return result_; }
  int cellsDrawn() const { return cells_; }
  // The view drawn at `size` (for reports and baselines, independent of the dock's size).
  QImage render(const QSize& size);

  QSize sizeHint() const override { return {420, 340}; }

 protected:
  void paintEvent(QPaintEvent* event) override;

 private:
  void paint(QPainter& p, const QRect& area);
  std::shared_ptr<const LiveTraceResult> result_;
  std::vector<double> hidden_;
  Box box_;
  int cells_ = 0;
};

}  // namespace fovea::widgets
