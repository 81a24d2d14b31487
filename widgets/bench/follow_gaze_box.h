#pragma once
// The Bench dock's follow gaze: as the gaze (its sliders, or the scene's eye gaze) moves,
// the HOE stages track x_p(alpha) from the gaze study (devices/bench/follow_gaze_table.h,
// computed in the background on first use; the geometric guess until it is ready, said in
// the info line), the micro-OLED x_f(alpha) and the camera the gaze itself.
#include <QGroupBox>

#include <array>
#include <functional>
#include <map>
#include <memory>

#include "devices/bench/follow_gaze_table.h"
#include "devices/bench/live_bench.h"
#include "devices/bench/target_follower.h"

class QCheckBox;
class QLabel;
class QSlider;

namespace fovea::widgets {

class FollowGazeBox : public QGroupBox {
  Q_OBJECT
 public:
  FollowGazeBox(std::function<Scene()> scene, bool analysed, QWidget* parent = nullptr);
  ~FollowGazeBox() override;

  void setBench(devices::LiveBench* live);  // nullptr: stops following, forgets the table
  bool followGaze() const;
  void setFollowGaze(bool on);
  void setGaze(double yaw_deg, double pitch_deg);
  // A gaze from elsewhere (the pupil tracker): drives the axes, leaves the sliders.
  void setFollowerGaze(double yaw_deg, double pitch_deg) {
    if (follower_) follower_->setGaze(yaw_deg, pitch_deg);
  }
  // on_gaze: told every slider gaze (the virtual eye looks there); hold: while true the
  // sliders do not drive the axes (the tracker does).
  void setGazeHooks(std::function<void(double, double)> on_gaze, std::function<bool()> hold) {
    on_gaze_ = std::move(on_gaze);
    hold_ = std::move(hold);
  }
  void setSceneGaze(std::array<double, 2> gaze_deg);  // moves the sliders
  bool tableReady() const;
  // Starts the gaze study's table now (follow gaze starts it on first use anyway).
  void ensureTable() { startTable(); }
  // x_p(alpha) for a gaze; `analysed` says whether it came from the gaze study (else the
  // geometric guess). `source` names where it came from.
  std::array<double, 2> hoeShift(std::array<double, 2> gaze_deg, bool* analysed = nullptr,
                                 std::string* source = nullptr) const;
  void refresh();

 signals:
  void report(const QString& text, bool error);

 private:
  std::map<devices::GazeFollower::Key, double> targets(double yaw, double pitch) const;
  void startTable();

  std::function<Scene()> scene_;
  bool analysed_;
  devices::LiveBench* live_ = nullptr;
  QCheckBox* follow_ = nullptr;
  QSlider *yaw_ = nullptr, *pitch_ = nullptr;
  QLabel *gaze_label_ = nullptr, *info_ = nullptr;
  std::unique_ptr<devices::GazeFollower> follower_;
  std::unique_ptr<devices::FollowGazeTableTask> task_;
  bool table_applied_ = false;
  std::array<double, 2> gaze_{0.0, 0.0};
  std::function<void(double, double)> on_gaze_;
  std::function<bool()> hold_;
};

}  // namespace fovea::widgets
