#include "widgets/bench/follow_gaze_box.h"

#include <QCheckBox>
#include <QGridLayout>
#include <QLabel>
#include <QSignalBlocker>
#include <QSlider>

#include <cmath>

#include "model/physics/display_camera_map.h"

namespace fovea::widgets {

FollowGazeBox::FollowGazeBox(std::function<Scene()> scene, bool analysed, QWidget* parent)
    : QGroupBox(tr("Follow gaze"), parent), scene_(std::move(scene)), analysed_(analysed) {
  auto* fl = new QGridLayout(this);
  fl->setContentsMargins(4, 4, 4, 4);
  follow_ = new QCheckBox(tr("HOE → x_p(α), micro-OLED → x_f(α), camera → α"), this);
  follow_->setObjectName("followGaze");
  fl->addWidget(follow_, 0, 0, 1, 3);
  yaw_ = new QSlider(Qt::Horizontal, this);
  yaw_->setObjectName("gazeYaw");
  pitch_ = new QSlider(Qt::Horizontal, this);
  pitch_->setObjectName("gazePitch");
  for (QSlider* s : {yaw_, pitch_}) {
    s->setRange(-400, 400);  // 0.1 deg
    s->setValue(0);
  }
  fl->addWidget(new QLabel(tr("yaw"), this), 1, 0);
  fl->addWidget(yaw_, 1, 1);
  fl->addWidget(new QLabel(tr("pitch"), this), 2, 0);
  fl->addWidget(pitch_, 2, 1);
  gaze_label_ = new QLabel(this);
  gaze_label_->setMinimumWidth(90);
  fl->addWidget(gaze_label_, 1, 2, 2, 1);
  info_ = new QLabel(this);
  info_->setObjectName("followInfo");
  info_->setWordWrap(true);
  info_->setStyleSheet("color: palette(mid);");
  fl->addWidget(info_, 3, 0, 1, 3);
  connect(follow_, &QCheckBox::toggled, this, &FollowGazeBox::setFollowGaze);
  auto onSlider = [this] { setGaze(yaw_->value() / 10.0, pitch_->value() / 10.0); };
  connect(yaw_, &QSlider::valueChanged, this, onSlider);
  connect(pitch_, &QSlider::valueChanged, this, onSlider);
  refresh();
}

FollowGazeBox::~FollowGazeBox() {
  follower_.reset();
  task_.reset();  // cancels and waits for the running sample
}

void FollowGazeBox::setBench(devices::LiveBench* live) {
  follower_.reset();
  task_.reset();  // the next bench may hold another scene
  table_applied_ = false;
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
  if (!on || !live_) return;
  startTable();  // the gaze study's x_p(alpha) table, computed on first use
  follower_ = std::make_unique<devices::GazeFollower>(
      live_->bench().axes(), [this](double y, double p) { return targets(y, p); }, 0.005);
  follower_->setGaze(gaze_[0], gaze_[1]);
  emit report(tr("Following the gaze"), false);
}

void FollowGazeBox::setGaze(double yaw, double pitch) {
  gaze_ = {yaw, pitch};
  const int y = static_cast<int>(std::lround(yaw * 10)), p = static_cast<int>(std::lround(pitch * 10));
  if (yaw_->value() != y || pitch_->value() != p) {
    const QSignalBlocker a(yaw_), b(pitch_);
    yaw_->setValue(y);
    pitch_->setValue(p);
  }
  if (on_gaze_) on_gaze_(yaw, pitch);
  if (follower_ && !(hold_ && hold_())) follower_->setGaze(yaw, pitch);
  refresh();
}

void FollowGazeBox::setSceneGaze(std::array<double, 2> gaze) {
  yaw_->setValue(static_cast<int>(std::lround(gaze[0] * 10)));
  pitch_->setValue(static_cast<int>(std::lround(gaze[1] * 10)));
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

std::map<devices::GazeFollower::Key, double> FollowGazeBox::targets(double yaw, double pitch) const {
  const Scene scene = scene_ ? scene_() : Scene{};
  const std::array<double, 2> xp = hoeShift({yaw, pitch});
  const std::array<double, 2> xf = fovealShiftForGaze(scene, {yaw, pitch});
  return {{{"hoe", "x"}, xp[0]},
          {{"hoe", "y"}, xp[1]},
          {{"foveal_display", "x"}, xf[0]},
          {{"foveal_display", "y"}, xf[1]},
          {{"camera", "yaw"}, yaw},
          {{"camera", "pitch"}, pitch}};
}

void FollowGazeBox::refresh() {
  const bool ready = tableReady();
  if (ready && follower_ && !table_applied_) {  // retarget with the gaze study's x_p(alpha)
    table_applied_ = true;
    follower_->setGaze(gaze_[0], gaze_[1]);
  }
  if (ready)
    info_->setText(tr("x_p(α) from the %1").arg(QString::fromStdString(task_->table()->source)));
  else if (task_)
    info_->setText(tr("x_p(α): geometric guess while the gaze study runs…"));
  else
    info_->setText(tr("x_p(α): geometric guess"));
  gaze_label_->setText(tr("α = %1°, %2°").arg(gaze_[0], 0, 'f', 1).arg(gaze_[1], 0, 'f', 1));
}

}  // namespace fovea::widgets
