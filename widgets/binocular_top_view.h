#pragma once
// The binocular top view (issue 30 item 5): the two eyes seen from above — their rotation
// centres one IPD apart, the two lines of sight, the fixation point where they meet and its
// distance. Draws what it is given (the Gaze dock computes it with model/gaze/); +x (the
// right eye's side) to the right, straight ahead (+z) up. The lateral and depth scales differ
// (a 63 mm IPD beside up to 2.5 m of depth); each axis carries its own scale.

#include <QWidget>

#include <array>
#include <optional>

#include <Eigen/Core>

namespace fovea::widgets {

class BinocularTopView : public QWidget {
  Q_OBJECT
 public:
  explicit BinocularTopView(QWidget* parent = nullptr);

  struct State {
    bool binocular = false;  // false: a monocular scene, nothing to draw but a note
    double ipd_mm = 63.0;
    std::array<double, 2> left_deg{0, 0}, right_deg{0, 0};  // gazes (yaw, pitch), head frame
    std::optional<Eigen::Vector3d> fixation_mm;             // head frame; none: the lines do not meet
    double vergence_deg = 0;
  };
  void setState(const State& s);
  const State& state() const { return state_; }
  // The fixation point's place in the widget (pixels); none without a point.
  std::optional<QPointF> fixationPixel() const;

  QSize sizeHint() const override { return {260, 200}; }
  QSize minimumSizeHint() const override { return {200, 150}; }

 protected:
  void paintEvent(QPaintEvent* event) override;

 private:
  struct Mapping {
    QRectF plot;
    double x_half_mm = 0, z_max_mm = 0;
    QPointF map(double x_mm, double z_mm) const;
  };
  Mapping mapping() const;
  State state_;
};

}  // namespace fovea::widgets
