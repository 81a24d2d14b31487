#include "widgets/bench/follow_gaze_box.h"

#include <QCheckBox>
#include <QGridLayout>
#include <QLabel>

#include <cmath>

#include "model/physics/display_camera_map.h"
#include "widgets/bench/axis_table.h"

namespace fovea::widgets {

FollowGazeBox::FollowGazeBox(std::function<Scene()> scene, bool analysed, QWidget* parent)
    : QGroupBox(tr("Follow gaze"), parent), scene_(std::move(scene)), analysed_(analysed) {
  auto* fl = new QGridLayout(this);
  fl->setContentsMargins(4, 4, 4, 4);
  follow_ = new QCheckBox(tr("HOE → x_p(α), micro-OLED → x_f(α), camera → α"), this);
  follow_->setObjectName("followGaze");
  follow_->setToolTip(tr("Move the bench's stages with the studio's gaze (set in the Gaze dock)"));
  fl->addWidget(follow_, 0, 0, 1, 2);
  // One gaze for the studio: the Gaze dock's (the scene's eye.gaze_deg); shown here, not set.
  gaze_label_ = new QLabel(this);
  gaze_label_->setObjectName("followGazeAngle");
  gaze_label_->setWordWrap(true);
  gaze_label_->setToolTip(tr("The studio's gaze: set it in the Gaze dock (eye.gaze_deg)"));
  fl->addWidget(gaze_label_, 1, 0, 1, 2);
  info_ = new QLabel(this);
  info_->setObjectName("followInfo");
  info_->setWordWrap(true);
  info_->setStyleSheet("color: palette(mid);");
  fl->addWidget(info_, 2, 0, 1, 2);
  connect(follow_, &QCheckBox::toggled, this, &FollowGazeBox::setFollowGaze);
  refresh();
}

FollowGazeBox::~FollowGazeBox() {
  follower_.reset();
  task_.reset();  // cancels and waits for the running sample
}

void FollowGazeBox::detachBench() {
  follower_.reset();
  task_.reset();  // the next bench may hold another scene
  table_applied_ = false;
  live_ = nullptr;
}

void FollowGazeBox::setBench(devices::LiveBench* live) {
  detachBench();
  live_ = live;
  if (live_ && follow_->isChecked()) setFollowGaze(true);
  refresh();
}

bool FollowGazeBox::followGaze() const {
  return follow_->isChecked();
}

void FollowGazeBox::startTable() {
  if (task_ || !analysed_ || !scene_) return;
  const Scene scene = scene_();
  bool any_hoe = false;
  for (const auto& b : scene.stages) any_hoe = any_hoe || b.element == "hoe";
  if (!any_hoe) return;
  task_ = std::make_unique<devices::FollowGazeTableTask>(scene);
  table_applied_ = false;
}

void FollowGazeBox::setFollowGaze(bool on) {
  if (follow_->isChecked() != on) {
    follow_->setChecked(on);  // re-enters through the signal
    return;
  }
  follower_.reset();
  for (const auto& [key, text] : reported_)
    if (!text.isEmpty()) emit axisNote(key, QString(), QString(), false);  // no follower: no refusal stands
  reported_.clear();
  if (!on || !live_) {
    refresh();
    return;
  }
  startTable();  // the gaze study's x_p(alpha) table, computed on first use
  follower_ = std::make_unique<devices::GazeFollower>(
      live_->bench().axes(), [this](double y, double p) { return targets(y, p); }, 0.005);
  emit report(tr("Following the gaze (α = %1, %2, the Gaze dock's)")
                  .arg(formatAxisValue(gaze_[0], "deg"), formatAxisValue(gaze_[1], "deg")),
              false);
  followTo(gaze_[0], gaze_[1]);  // refusals are reported after the "following" line
  refresh();
}

void FollowGazeBox::setGaze(double yaw, double pitch) {
  gaze_ = {yaw, pitch};
  if (on_gaze_) on_gaze_(yaw, pitch);
  if (follower_ && !(hold_ && hold_())) followTo(yaw, pitch);
  refresh();
}

void FollowGazeBox::setSceneGaze(std::array<double, 2> gaze) {
  setGaze(gaze[0], gaze[1]);
}

void FollowGazeBox::followTo(double yaw, double pitch) {
  refused_.clear();
  refused_note_.clear();
  follower_->setGaze(yaw, pitch);  // calls targets(), which fills refused_
  // Each change of an axis's refusal goes to its row and to the report (status + Messages).
  for (const auto& [key, text] : refused_)
    if (reported_[key] != text) {
      emit axisNote(key, refused_note_[key], text, true);
      if (reported_[key].isEmpty()) emit report(text, true);
    }
  for (auto& [key, text] : reported_)
    if (!text.isEmpty() && !refused_.count(key)) {
      emit axisNote(key, QString(), QString(), false);
      emit report(tr("%1: following again (the target is back within the soft limits)").arg(key), false);
    }
  reported_.clear();
  for (const auto& [key, text] : refused_) reported_[key] = text;
}

bool FollowGazeBox::tableReady() const {
  return task_ && task_->ready();
}

std::array<double, 2> FollowGazeBox::hoeShift(std::array<double, 2> gaze, bool* analysed, std::string* source) const {
  const auto table = task_ ? task_->table() : std::nullopt;
  if (analysed) *analysed = table.has_value();
  if (table) {
    if (source) *source = table->source;
    return table->hoeShift(gaze);
  }
  if (source) *source = "geometric guess (geometricHoeShiftForGaze)";
  return geometricHoeShiftForGaze(scene_ ? scene_() : Scene{}, gaze);
}

namespace {
QString unitOf(const std::string& axis) {
  return axis == "yaw" || axis == "pitch" ? QStringLiteral("deg") : QStringLiteral("mm");
}
const char* targetName(const std::string& element) {
  return element == "hoe" ? "x_p" : element == "foveal_display" ? "x_f" : "α";
}
}  // namespace

std::map<devices::GazeFollower::Key, double> FollowGazeBox::targets(double yaw, double pitch) const {
  const Scene scene = scene_ ? scene_() : Scene{};
  const std::array<double, 2> xp = hoeShift({yaw, pitch});
  const std::array<double, 2> xf = fovealShiftForGaze(scene, {yaw, pitch});
  std::map<devices::GazeFollower::Key, double> all{{{"hoe", "x"}, xp[0]},
                                                   {{"hoe", "y"}, xp[1]},
                                                   {{"foveal_display", "x"}, xf[0]},
                                                   {{"foveal_display", "y"}, xf[1]},
                                                   {{"camera", "yaw"}, yaw},
                                                   {{"camera", "pitch"}, pitch}};
  if (!live_) return all;
  // Refused here, in the row's frame (element coordinates), before the Stage would refuse
  // it in its own: nothing is sent for a target outside the binding's soft limits.
  for (devices::AxisWorker* w : live_->bench().axes()) {
    const StageBinding& b = w->binding();
    const auto it = all.find({b.element, b.axis});
    if (it == all.end()) continue;
    const double v = it->second;
    if (std::isfinite(v) && v >= b.soft_limits[0] && v <= b.soft_limits[1]) continue;
    const QString key = QString::fromStdString(b.element + "." + b.axis), unit = unitOf(b.axis);
    QString covers;
    if (b.element == "foveal_display") {  // which gazes this stage can follow at all
      const auto c = fovealGazeCoverageDeg(scene, b.soft_limits);
      covers = tr("; they cover gaze %1 … %2").arg(formatAxisValue(c[0], "deg"), formatAxisValue(c[1], "deg"));
    }
    refused_note_[key] = tr("refused: %1 %2 %3")
                             .arg(formatAxisValue(v, unit), v < b.soft_limits[0] ? "<" : ">",
                                  formatAxisValue(b.soft_limits[v < b.soft_limits[0] ? 0 : 1], unit));
    refused_[key] =
        tr("%1: follow to %2(α = %3) = %4 refused — outside the soft limits %5 … %6 (%7 coordinates%8); "
           "nothing was sent")
            .arg(key, targetName(b.element), formatAxisValue(b.axis == "y" || b.axis == "pitch" ? pitch : yaw, "deg"),
                 formatAxisValue(v, unit), formatAxisValue(b.soft_limits[0], unit),
                 formatAxisValue(b.soft_limits[1], unit), QString::fromStdString(b.element), covers);
    all.erase(it);
  }
  return all;
}

QString FollowGazeBox::infoText() const {
  return info_->text();
}

void FollowGazeBox::refresh() {
  const bool ready = tableReady();
  if (ready && follower_ && !table_applied_) {  // retarget with the gaze study's x_p(alpha)
    table_applied_ = true;
    if (!(hold_ && hold_())) followTo(gaze_[0], gaze_[1]);
  }
  QString xp_source;
  if (ready)
    xp_source = tr("x_p(α) from the %1").arg(QString::fromStdString(task_->table()->source));
  else if (task_)
    xp_source = tr("x_p(α): geometric guess while the gaze study runs…");
  else
    xp_source = tr("x_p(α): geometric guess");
  const Scene scene = scene_ ? scene_() : Scene{};
  const auto xp = hoeShift(gaze_);
  const auto xf = fovealShiftForGaze(scene, gaze_);
  // Which number is which: the axes show the stages; the Gaze dock's x_p only shifts the
  // simulated HOE until follow gaze moves the stage there.
  info_->setText(tr("At this gaze x_p = %1, %2 and x_f = (d_f + r) tan α / M = %3, %4. %5. The axis rows show "
                    "the stage positions (scene coordinates); %6")
                     .arg(formatAxisValue(xp[0], "mm"), formatAxisValue(xp[1], "mm"), formatAxisValue(xf[0], "mm"),
                          formatAxisValue(xf[1], "mm"), xp_source,
                          follow_->isChecked() && live_
                              ? tr("follow gaze moves them to these targets.")
                              : tr("the Gaze dock's “HOE follows gaze” shifts only the simulated HOE, not the "
                                   "stage — tick Follow gaze to move the stages.")));
  gaze_label_->setText(
      tr("Gaze α = %1, %2 (the Gaze dock's)").arg(formatAxisValue(gaze_[0], "deg"), formatAxisValue(gaze_[1], "deg")));
}

}  // namespace fovea::widgets
