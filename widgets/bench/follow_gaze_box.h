#pragma once
// The Bench dock's follow gaze: as the studio's one gaze (the scene's eye.gaze_deg, set in
// the Gaze dock) moves, the HOE stages track x_p(alpha) from the gaze study
// (devices/bench/follow_gaze_table.h, computed in the background on first use; the geometric
// guess until it is ready, said in the info line), the micro-OLED x_f(alpha)
// (fovealShiftForGaze) and the camera the gaze itself. The box has no gaze control of its own.
//
// A target outside an axis's soft limits is not sent: the refusal names the target and the
// limits in the row's (element) frame and the user's units, and goes to the axis row
// (axisNote) and to the panel's report (the status line and the Messages dock) at once.
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

namespace fovea::widgets {

class FollowGazeBox : public QGroupBox {
  Q_OBJECT
 public:
  FollowGazeBox(std::function<Scene()> scene, bool analysed, QWidget* parent = nullptr);
  ~FollowGazeBox() override;

  void setBench(devices::LiveBench* live);  // nullptr: stops following, forgets the table
  // The owner is going: stops following and forgets the bench without a refresh (the scene
  // callback may name what is already destroyed).
  void detachBench();
  bool followGaze() const;
  void setFollowGaze(bool on);
  void setGaze(double yaw_deg, double pitch_deg);
  // A gaze from elsewhere (the pupil tracker): drives the axes, leaves the sliders.
  void setFollowerGaze(double yaw_deg, double pitch_deg) {
    if (follower_) follower_->setGaze(yaw_deg, pitch_deg);
  }
  // on_gaze: told every gaze (the virtual eye looks there); hold: while true the gaze does
  // not drive the axes (the tracker does).
  void setGazeHooks(std::function<void(double, double)> on_gaze, std::function<bool()> hold) {
    on_gaze_ = std::move(on_gaze);
    hold_ = std::move(hold);
  }
  void setSceneGaze(std::array<double, 2> gaze_deg);  // the scene's gaze moved: same as setGaze
  bool tableReady() const;
  // Starts the gaze study's table now (follow gaze starts it on first use anyway).
  void ensureTable() { startTable(); }
  // x_p(alpha) for a gaze; `analysed` says whether it came from the gaze study (else the
  // geometric guess). `source` names where it came from.
  std::array<double, 2> hoeShift(std::array<double, 2> gaze_deg, bool* analysed = nullptr,
                                 std::string* source = nullptr) const;
  void refresh();
  QString infoText() const;

 signals:
  void report(const QString& text, bool error);
  // A follow target refused (error; a short note for the row, the whole message for its
  // tooltip) or back within the limits (empty note) on an axis "hoe.x".
  void axisNote(const QString& axis_key, const QString& note, const QString& message, bool error);

 private:
  std::map<devices::GazeFollower::Key, double> targets(double yaw, double pitch) const;
  void startTable();
  void followTo(double yaw, double pitch);  // the follower's setGaze, then the refusals reported

  std::function<Scene()> scene_;
  bool analysed_;
  devices::LiveBench* live_ = nullptr;
  QCheckBox* follow_ = nullptr;
  QLabel *gaze_label_ = nullptr, *info_ = nullptr;
  // Refused follow targets by axis key (the message); filled by targets(), reported by followTo().
  mutable std::map<QString, QString> refused_, refused_note_;
  std::map<QString, QString> reported_;
  std::unique_ptr<devices::GazeFollower> follower_;
  std::unique_ptr<devices::FollowGazeTableTask> task_;
  bool table_applied_ = false;
  std::array<double, 2> gaze_{0.0, 0.0};
  std::function<void(double, double)> on_gaze_;
  std::function<bool()> hold_;
};

}  // namespace fovea::widgets
