#include "widgets/gaze_panel.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QSlider>

#include <algorithm>
#include <cmath>

#include "model/gaze/fixation_gazes.h"
#include "model/gaze/vergence.h"
#include "model/scene/eye_scene.h"
#include "widgets/binocular_top_view.h"
#include "widgets/scene_document.h"

namespace fovea::widgets {

namespace {
constexpr double kMaxGazeDeg = 40.0;
}

GazePanel::GazePanel(SceneDocument* document, QWidget* parent) : QWidget(parent), document_(document) {
  auto* grid = new QGridLayout(this);
  grid->setContentsMargins(6, 6, 6, 6);
  auto makeRow = [&](int row, const QString& label, QSlider*& slider, QDoubleSpinBox*& spin, const QString& name) {
    slider = new QSlider(Qt::Horizontal, this);
    slider->setObjectName(name + "Slider");
    slider->setRange(static_cast<int>(-kMaxGazeDeg * kStepsPerDegree), static_cast<int>(kMaxGazeDeg * kStepsPerDegree));
    slider->setPageStep(5 * kStepsPerDegree);
    slider->setTickPosition(QSlider::TicksBelow);
    slider->setTickInterval(10 * kStepsPerDegree);
    spin = new QDoubleSpinBox(this);
    spin->setObjectName(name + "Spin");
    spin->setRange(-kMaxGazeDeg, kMaxGazeDeg);
    spin->setDecimals(1);
    spin->setSingleStep(0.5);
    spin->setSuffix(QString::fromUtf8(" °"));
    spin->setKeyboardTracking(false);
    grid->addWidget(new QLabel(label, this), row, 0);
    grid->addWidget(slider, row, 1);
    grid->addWidget(spin, row, 2);
  };
  makeRow(0, tr("Yaw"), yaw_, yawSpin_, "gazeYaw");
  makeRow(1, tr("Pitch"), pitch_, pitchSpin_, "gazePitch");
  yaw_->setToolTip(tr("Gaze yaw (+ towards the projector side, bench +x); eye.gaze_deg[0]"));
  pitch_->setToolTip(tr("Gaze pitch (+ up); eye.gaze_deg[1]"));
  follow_ = new QCheckBox(tr("HOE follows gaze (apply x_p(α))"), this);
  follow_->setObjectName("followGaze");
  follow_->setToolTip(
      tr("Shift the HOE laterally by the travel x_p that maximises the FOV at this gaze "
         "(searched off the GUI thread; yaw moves it along its x, pitch along its y)"));
  // Binocular scenes: the fixation distance beside the gaze (row 2), the top view below.
  binocularBox_ = new QWidget(this);
  binocularBox_->setObjectName("fixationBox");
  auto* fixGrid = new QGridLayout(binocularBox_);
  fixGrid->setContentsMargins(0, 0, 0, 0);
  fixationOn_ = new QCheckBox(tr("Fixate at"), binocularBox_);
  fixationOn_->setObjectName("fixationToggle");
  fixationOn_->setToolTip(
      tr("Both eyes fixate the point at this distance (from midway between the eyes) in the gaze direction; "
         "off (∞): the left eye's gaze mirrors the right one's. binocular.fixation_distance_mm"));
  fixationCm_ = new QDoubleSpinBox(binocularBox_);
  fixationCm_->setObjectName("fixationDistance");
  fixationCm_->setRange(kMinFixationCm, kMaxFixationCm);
  fixationCm_->setDecimals(1);
  fixationCm_->setSingleStep(5);
  fixationCm_->setSuffix(tr(" cm"));
  fixationCm_->setKeyboardTracking(false);
  fixationCm_->setValue(80);
  fixationCm_->setToolTip(tr("Fixation distance, 30-250 cm (the focus stage's range, seed C.3)"));
  fixationReadout_ = new QLabel(binocularBox_);
  fixationReadout_->setObjectName("fixationReadout");
  fixationReadout_->setWordWrap(true);
  fixationReadout_->setTextFormat(Qt::PlainText);
  fixGrid->addWidget(fixationOn_, 0, 0);
  fixGrid->addWidget(fixationCm_, 0, 1);
  fixGrid->addWidget(fixationReadout_, 1, 0, 1, 2);
  fixGrid->setColumnStretch(1, 1);
  grid->addWidget(binocularBox_, 2, 0, 1, 3);
  // The top view has a dock of its own (the studio puts it beside the Properties: at
  // 1366x768 it does not fit under the Gaze dock's controls); this panel keeps it current.
  topView_ = new BinocularTopView(this);
  grid->addWidget(follow_, 3, 0, 1, 3);
  // The x_p rule lives in the scene too (view.xp_rule), read by every x_p caller (hoe_travel.h).
  xpRule_ = new QComboBox(this);
  xpRule_->setObjectName("xpRule");
  xpRule_->addItem(tr("plateau middle (ours)"), QStringLiteral("plateau-middle"));
  xpRule_->addItem(tr("focus on the pupil (seed)"), QStringLiteral("follow-focus"));
  xpRule_->setToolTip(
      tr("How x_p is chosen: the middle of the HOE shifts that keep the FOV within 5° of its best, or the shift "
         "putting the diffracted rays' focus on the rotated pupil centre (the seed's rule); as --xp-rule"));
  grid->addWidget(new QLabel(tr("x_p rule"), this), 4, 0);
  grid->addWidget(xpRule_, 4, 1, 1, 2);
  readout_ = new QLabel(this);
  readout_->setObjectName("gazeReadout");
  readout_->setWordWrap(true);
  readout_->setTextFormat(Qt::PlainText);
  grid->addWidget(readout_, 5, 0, 1, 3);
  grid->setColumnStretch(1, 1);
  grid->setRowStretch(6, 1);

  auto sliderMoved = [this] {
    if (refreshing_) return;
    commitGaze(yaw_->value() / double(kStepsPerDegree), pitch_->value() / double(kStepsPerDegree));
  };
  connect(yaw_, &QSlider::valueChanged, this, sliderMoved);
  connect(pitch_, &QSlider::valueChanged, this, sliderMoved);
  for (QSlider* s : {yaw_, pitch_}) {
    connect(s, &QSlider::sliderPressed, this, [this] { gesture_ = document_->newGestureId(); });
    connect(s, &QSlider::sliderReleased, this, [this] { gesture_ = -1; });
  }
  auto spinChanged = [this] {
    if (refreshing_) return;
    commitGaze(yawSpin_->value(), pitchSpin_->value());
  };
  connect(yawSpin_, &QDoubleSpinBox::valueChanged, this, spinChanged);
  connect(pitchSpin_, &QDoubleSpinBox::valueChanged, this, spinChanged);
  // The flag lives in the scene (view.hoe_follows_gaze: it changes results and is saved with
  // the design); toggling it is an undoable edit.
  connect(follow_, &QCheckBox::toggled, this, [this](bool on) {
    if (refreshing_) return;
    if (document_->scene().view.hoe_follows_gaze != on)
      document_->applyEdit(on ? tr("HOE follows gaze") : tr("HOE stops following gaze"),
                           [on](Scene& s) { s.view.hoe_follows_gaze = on; });
    emit followGazeChanged(on);
  });
  connect(xpRule_, &QComboBox::currentIndexChanged, this, [this] {
    if (refreshing_) return;
    const std::string rule = xpRule_->currentData().toString().toStdString();
    if (document_->scene().view.xp_rule != rule)
      document_->applyEdit(tr("x_p rule: %1").arg(xpRule_->currentText()), [rule](Scene& s) { s.view.xp_rule = rule; });
  });
  connect(fixationOn_, &QCheckBox::toggled, this, [this](bool on) {
    if (refreshing_) return;
    commitFixation(on ? std::optional<double>(fixationCm_->value()) : std::nullopt);
  });
  connect(fixationCm_, &QDoubleSpinBox::valueChanged, this, [this](double cm) {
    if (refreshing_ || !fixationOn_->isChecked()) return;
    commitFixation(cm);
  });
  connect(document_, &SceneDocument::sceneChanged, this, &GazePanel::refreshFromScene);
  refreshFromScene();
}

bool GazePanel::isDragging() const {
  return yaw_->isSliderDown() || pitch_->isSliderDown();
}

bool GazePanel::followGaze() const {
  return follow_->isChecked();
}
void GazePanel::setFollowGaze(bool on) {
  follow_->setChecked(on);
}

void GazePanel::setGaze(double yaw, double pitch) {
  commitGaze(yaw, pitch);
}

double GazePanel::fixationMm() const {
  const Scene& s = document_->scene();
  return s.binocular && s.binocular->fixation_distance_mm > s.binocular->ipd_mm / 2 ? s.binocular->fixation_distance_mm
                                                                                    : 0.0;
}

std::array<double, 2> GazePanel::shownGaze() const {
  const Scene& s = document_->scene();
  if (const double d = fixationMm(); d > 0)
    return gaze::fixationOnRightGaze(gaze::BinocularGeometry{s.binocular->ipd_mm}, s.eye.gaze_deg, d).direction_deg;
  return s.eye.gaze_deg;
}

void GazePanel::setFixationDistanceCm(std::optional<double> cm) {
  commitFixation(cm);
}

void GazePanel::commitFixation(std::optional<double> cm) {
  const Scene& scene = document_->scene();
  if (!scene.binocular) return;
  const double mm = cm ? std::clamp(*cm, kMinFixationCm, kMaxFixationCm) * 10 : 0.0;
  if (mm == fixationMm()) return;
  // The direction the user sees stays; the right eye turns to fixate the point on it.
  const std::array<double, 2> direction = shownGaze();
  const std::array<double, 2> right =
      mm > 0 ? gaze::gazesFixating(gaze::BinocularGeometry{scene.binocular->ipd_mm}, direction, mm).right_deg
             : direction;
  const QString text = mm > 0 ? tr("Fixate at %1 cm").arg(mm / 10, 0, 'f', 1) : tr("Fixation off");
  const QStringList problems = document_->applyEdit(text, [mm, right](Scene& s) {
    s.binocular->fixation_distance_mm = mm;
    s.eye.gaze_deg = right;
  });
  if (!problems.isEmpty()) {
    fixationReadout_->setText(problems.join('\n'));
    refreshFromScene();
  }
}

void GazePanel::commitGaze(double yaw, double pitch) {
  const auto now = shownGaze();
  if (now[0] == yaw && now[1] == pitch) return;
  // With a fixation distance the sliders give the fixation point's direction; the scene keeps
  // the right eye's gaze fixating it.
  std::array<double, 2> right{yaw, pitch};
  if (const double d = fixationMm(); d > 0)
    right =
        gaze::gazesFixating(gaze::BinocularGeometry{document_->scene().binocular->ipd_mm}, {yaw, pitch}, d).right_deg;
  const QString text = tr("Set gaze to %1°, %2°").arg(yaw, 0, 'f', 1).arg(pitch, 0, 'f', 1);
  const QStringList problems = document_->applyEdit(
      text, [right](Scene& s) { s.eye.gaze_deg = right; }, gesture_);
  if (!problems.isEmpty()) {
    readout_->setText(problems.join('\n'));
    refreshFromScene();
  }
}

void GazePanel::refreshFromScene() {
  refreshing_ = true;
  const auto g = shownGaze();
  if (!yaw_->isSliderDown()) yaw_->setValue(static_cast<int>(std::lround(g[0] * kStepsPerDegree)));
  if (!pitch_->isSliderDown()) pitch_->setValue(static_cast<int>(std::lround(g[1] * kStepsPerDegree)));
  yawSpin_->setValue(g[0]);
  pitchSpin_->setValue(g[1]);
  follow_->setChecked(document_->scene().view.hoe_follows_gaze);
  xpRule_->setCurrentIndex(std::max(0, xpRule_->findData(QString::fromStdString(document_->scene().view.xp_rule))));
  refreshBinocular();
  refreshing_ = false;
}

void GazePanel::refreshBinocular() {
  const Scene& s = document_->scene();
  binocularBox_->setVisible(s.binocular.has_value());
  if (!s.binocular) {
    topView_->setState({});  // "a monocular scene" in place of the eyes
    return;
  }
  const double d = fixationMm();
  fixationOn_->setChecked(d > 0);
  fixationCm_->setEnabled(d > 0);
  if (d > 0) fixationCm_->setValue(d / 10);
  // Both gazes in the head frame (its axes are the bench's), the point where they meet.
  const gaze::BinocularGeometry g{s.binocular->ipd_mm};
  const std::array<double, 2> right = s.eye.gaze_deg, left = leftGazeDeg(s);
  const gaze::FixationEstimate e = gaze::fixationFromGazes(g, left, right);
  BinocularTopView::State state;
  state.binocular = true;
  state.ipd_mm = g.ipd_mm;
  state.left_deg = left;
  state.right_deg = right;
  state.vergence_deg = e.vergence_deg;
  if (e.valid) state.fixation_mm = e.point;
  topView_->setState(state);
  const QString gazes = tr("left eye %1°, %2° · right eye %3°, %4°")
                            .arg(left[0], 0, 'f', 2)
                            .arg(left[1], 0, 'f', 2)
                            .arg(right[0], 0, 'f', 2)
                            .arg(right[1], 0, 'f', 2);
  fixationReadout_->setText(
      d > 0 ? tr("vergence %1° · %2").arg(e.vergence_deg, 0, 'f', 2).arg(gazes)
            : tr("off (∞): yaw, pitch are the right eye's gaze, the left eye's its mirror · %1").arg(gazes));
}

void GazePanel::showResult(const std::shared_ptr<const LiveTraceResult>& r, bool busy) {
  if (!r) {
    readout_->setText(busy ? tr("tracing…") : QString());
    return;
  }
  if (!r->error.empty()) {
    readout_->setText(tr("trace failed: %1").arg(QString::fromStdString(r->error)));
    return;
  }
  const TraceResult& t = r->trace;
  // The exact FOV (model/analysis/trace_fov.h), the one `fovea-cli trace` and `sweep` give;
  // named: ours (arrival directions), not the seed's lit footprint.
  // A binocular scene's live trace is its right eye's (the Retina dock shows either eye).
  QString text = (document_->scene().binocular ? tr("Right eye: ") : QString()) +
                 QString::fromUtf8(
                     "FOV %1° × %2° (diagonal %3°)\n  ours (arrival directions), exact edges\n"
                     "mean efficiency %4 · %5 of %6 rays in the pupil")
                     .arg(r->fov.horizontal, 0, 'f', 2)
                     .arg(r->fov.vertical, 0, 'f', 2)
                     .arg(r->fov.diagonal, 0, 'f', 2)
                     .arg(t.mean_efficiency, 0, 'f', 3)
                     .arg(t.rays_in_pupil)
                     .arg(t.rays);
  const bool coarse = r->detail == TraceDetail::Coarse;
  if (r->settings.follow_gaze)
    text += QString::fromUtf8("\nHOE travel x_p: %1 mm (x), %2 mm (y)%3, %4")
                .arg(r->hoe_shift_mm[0], 0, 'f', 2)
                .arg(r->hoe_shift_mm[1], 0, 'f', 2)
                .arg(r->shift_source.empty() ? QString() : tr(" (%1)").arg(QString::fromStdString(r->shift_source)))
                .arg(QString::fromStdString(r->scene.view.xp_rule));
  text += tr("\ntrace %1 ms%2%3")
              .arg(r->compute_ms, 0, 'f', 0)
              .arg(coarse                  ? tr(" · coarse, %1 rays per wavelength").arg(r->settings.coarse_rays)
                   : r->reused_diffraction ? tr(" (gaze stage only)")
                                           : QString())
              .arg(busy || coarse ? tr(" · refining…") : QString());
  readout_->setText(text);
}

}  // namespace fovea::widgets
