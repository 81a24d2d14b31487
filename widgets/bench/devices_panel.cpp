#include "widgets/bench/devices_panel.h"

#include <QButtonGroup>
#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QGridLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QKeyEvent>
#include <QLabel>
#include <QPushButton>
#include <QRadioButton>
#include <QShortcut>
#include <QSlider>
#include <QTimer>
#include <QVBoxLayout>

#include <chrono>
#include <cmath>

#include "devices/apt/stage_models.h"
#include "devices/calibration/capture_plan.h"
#include "devices/stage/stage_binding.h"
#include "devices/transport/device_error.h"
#include "model/analysis/gaze_studies.h"
#include "model/analysis/trace_evaluator.h"
#include "widgets/bench/camera_view.h"
#include "widgets/bench/capture_wizard.h"
#include "widgets/bench/pupil_tracker_view.h"
#include "widgets/scene_document.h"

namespace fovea::widgets {

namespace {

QString axisKey(const StageBinding& b) {
  return QString::fromStdString(b.element + "." + b.axis);
}

QString fmt(double v, const QString& unit) {
  return QString::number(v, 'f', unit == "deg" ? 2 : 3) + (unit == "deg" ? QStringLiteral("°") : " " + unit);
}

double interpolate(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
  if (xs.empty()) return 0.0;
  if (x <= xs.front()) return ys.front();
  if (x >= xs.back()) return ys.back();
  std::size_t i = 1;
  while (i < xs.size() && xs[i] < x) ++i;
  const double t = (x - xs[i - 1]) / (xs[i] - xs[i - 1]);
  return (1 - t) * ys[i - 1] + t * ys[i];
}

}  // namespace

DevicesPanel::DevicesPanel(SceneDocument* document, QWidget* parent, DevicesPanelOptions options)
    : QWidget(parent), document_(document), options_(std::move(options)) {
  setObjectName("DevicesPanel");
  setFocusPolicy(Qt::StrongFocus);
  auto* root = new QVBoxLayout(this);
  root->setContentsMargins(6, 6, 6, 6);
  root->setSpacing(6);

  banner_ = new QLabel(this);
  banner_->setObjectName("benchBanner");
  banner_->setWordWrap(true);
  banner_->setAlignment(Qt::AlignCenter);
  root->addWidget(banner_);

  auto* buttons = new QHBoxLayout;
  connect_ = new QPushButton(tr("Connect"), this);
  connect_->setObjectName("connectButton");
  disconnect_ = new QPushButton(tr("Disconnect"), this);
  disconnect_->setObjectName("disconnectButton");
  homeAll_ = new QPushButton(tr("Home all"), this);
  homeAll_->setObjectName("homeAllButton");
  estop_ = new QPushButton(tr("STOP (Esc)"), this);
  estop_->setObjectName("estopButton");
  estop_->setStyleSheet("QPushButton { background: #c62828; color: white; font-weight: bold; padding: 3px 8px; }");
  estop_->setToolTip(tr("Emergency stop: immediate stop of every axis (Esc)"));
  for (QPushButton* b : {connect_, disconnect_, homeAll_}) buttons->addWidget(b);
  buttons->addStretch();
  buttons->addWidget(estop_);
  root->addLayout(buttons);
  connect(connect_, &QPushButton::clicked, this, &DevicesPanel::connectBench);
  connect(disconnect_, &QPushButton::clicked, this, &DevicesPanel::disconnectBench);
  connect(homeAll_, &QPushButton::clicked, this, &DevicesPanel::homeAll);
  connect(estop_, &QPushButton::clicked, this, &DevicesPanel::emergencyStop);
  // Esc while the panel (or one of its children) has the focus; the main window adds the same
  // shortcut on the 3-D view. Dialogs keep their own Esc.
  auto* esc = new QShortcut(QKeySequence(Qt::Key_Escape), this);
  esc->setContext(Qt::WidgetWithChildrenShortcut);
  connect(esc, &QShortcut::activated, this, &DevicesPanel::emergencyStop);

  axesBox_ = new QGroupBox(tr("Axes"), this);
  axesGrid_ = new QGridLayout(axesBox_);
  axesGrid_->setContentsMargins(4, 4, 4, 4);
  axesGrid_->setHorizontalSpacing(4);
  axesGrid_->setVerticalSpacing(2);
  selectGroup_ = new QButtonGroup(this);
  selectGroup_->setExclusive(true);
  root->addWidget(axesBox_);

  auto* jog = new QHBoxLayout;
  jog->addWidget(new QLabel(tr("Step"), this));
  step_ = new QDoubleSpinBox(this);
  step_->setObjectName("jogStep");
  step_->setDecimals(3);
  step_->setRange(0.001, 10.0);
  step_->setValue(0.1);
  step_->setSuffix(tr(" mm|°"));
  step_->setToolTip(
      tr("Jog step (mm for translation stages, degrees for rotation stages); keys + and - double and halve it"));
  jog->addWidget(step_);
  jog->addWidget(new QLabel(tr("Speed"), this));
  speed_ = new QDoubleSpinBox(this);
  speed_->setObjectName("jogSpeed");
  speed_->setDecimals(2);
  speed_->setRange(0.01, 50.0);
  speed_->setValue(1.0);
  speed_->setSuffix(tr(" /s"));
  speed_->setToolTip(tr("Jog speed (mm/s or deg/s)"));
  jog->addWidget(speed_);
  jog->addStretch();
  root->addLayout(jog);
  auto* keys = new QLabel(tr("Keys: ←/→ jog the selected axis, ↑/↓ select, +/− step, Esc stops all"), this);
  keys->setStyleSheet("color: palette(mid);");
  keys->setWordWrap(true);
  root->addWidget(keys);

  auto* followBox = new QGroupBox(tr("Follow gaze"), this);
  auto* fl = new QGridLayout(followBox);
  fl->setContentsMargins(4, 4, 4, 4);
  follow_ = new QCheckBox(tr("HOE → x_p(α), micro-OLED → x_f(α), camera → α"), followBox);
  follow_->setObjectName("followGaze");
  fl->addWidget(follow_, 0, 0, 1, 3);
  gazeYaw_ = new QSlider(Qt::Horizontal, followBox);
  gazeYaw_->setObjectName("gazeYaw");
  gazePitch_ = new QSlider(Qt::Horizontal, followBox);
  gazePitch_->setObjectName("gazePitch");
  for (QSlider* s : {gazeYaw_, gazePitch_}) {
    s->setRange(-400, 400);  // 0.1 deg
    s->setValue(0);
  }
  fl->addWidget(new QLabel(tr("yaw"), followBox), 1, 0);
  fl->addWidget(gazeYaw_, 1, 1);
  fl->addWidget(new QLabel(tr("pitch"), followBox), 2, 0);
  fl->addWidget(gazePitch_, 2, 1);
  gazeLabel_ = new QLabel(followBox);
  gazeLabel_->setMinimumWidth(90);
  fl->addWidget(gazeLabel_, 1, 2, 2, 1);
  followInfo_ = new QLabel(followBox);
  followInfo_->setObjectName("followInfo");
  followInfo_->setWordWrap(true);
  followInfo_->setStyleSheet("color: palette(mid);");
  fl->addWidget(followInfo_, 3, 0, 1, 3);
  root->addWidget(followBox);
  connect(follow_, &QCheckBox::toggled, this, &DevicesPanel::setFollowGaze);
  auto onSlider = [this] { setGaze(gazeYaw_->value() / 10.0, gazePitch_->value() / 10.0); };
  connect(gazeYaw_, &QSlider::valueChanged, this, onSlider);
  connect(gazePitch_, &QSlider::valueChanged, this, onSlider);

  auto* camBox = new QGroupBox(tr("Eye camera"), this);
  auto* cl = new QVBoxLayout(camBox);
  cl->setContentsMargins(4, 4, 4, 4);
  camera_view_ = new CameraView(camBox);
  cl->addWidget(camera_view_, 1);
  auto* camControls = new QHBoxLayout;
  live_check_ = new QCheckBox(tr("Live"), camBox);
  live_check_->setObjectName("cameraLive");
  live_check_->setChecked(options_.live_camera);
  crosshair_ = new QCheckBox(tr("Crosshair"), camBox);
  crosshair_->setChecked(true);
  camControls->addWidget(live_check_);
  camControls->addWidget(crosshair_);
  camControls->addWidget(new QLabel(tr("Exposure"), camBox));
  exposure_ = new QDoubleSpinBox(camBox);
  exposure_->setObjectName("cameraExposure");
  exposure_->setRange(0.1, 1000.0);
  exposure_->setDecimals(1);
  exposure_->setValue(10.0);
  exposure_->setSuffix(tr(" ms"));
  camControls->addWidget(exposure_);
  camControls->addWidget(new QLabel(tr("Gain"), camBox));
  gain_ = new QDoubleSpinBox(camBox);
  gain_->setObjectName("cameraGain");
  gain_->setRange(0.1, 64.0);
  gain_->setDecimals(1);
  gain_->setValue(1.0);
  camControls->addWidget(gain_);
  camControls->addStretch();
  cl->addLayout(camControls);
  auto* patternRow = new QHBoxLayout;
  patternRow->addWidget(new QLabel(tr("Displays show"), camBox));
  pattern_ = new QComboBox(camBox);
  pattern_->setObjectName("testPattern");
  pattern_->addItems({tr("nothing"), tr("checkerboards (both)"), tr("projector checkerboard"),
                      tr("micro-OLED checkerboard"), tr("white (both)")});
  pattern_->setCurrentIndex(1);
  pattern_->setToolTip(tr("Test pattern of the virtual displays"));
  patternRow->addWidget(pattern_, 1);
  cl->addLayout(patternRow);
  root->addWidget(camBox, 1);
  // The pupil tracker (pupil_tracker_view.h): while it tracks, its gaze drives follow gaze.
  auto* trackBox = new QGroupBox(tr("Pupil tracker"), this);
  auto* tl = new QVBoxLayout(trackBox);
  tl->setContentsMargins(4, 4, 4, 4);
  tracker_ = new PupilTrackerView(document_ ? document_->scene() : Scene{}, trackBox);
  tl->addWidget(tracker_);
  root->addWidget(trackBox, 1);
  connect(tracker_, &PupilTrackerView::gazeTracked, this, [this](double y, double p, double) {
    if (follower_) follower_->setGaze(y, p);
  });
  connect(crosshair_, &QCheckBox::toggled, camera_view_, &CameraView::setCrosshair);
  connect(exposure_, &QDoubleSpinBox::valueChanged, this, [this] { applyExposure(); });
  connect(gain_, &QDoubleSpinBox::valueChanged, this, [this] { applyExposure(); });
  connect(pattern_, &QComboBox::currentIndexChanged, this, &DevicesPanel::setTestPattern);
  connect(live_check_, &QCheckBox::toggled, this, [this](bool on) {
    if (on && isVisible())
      startCamera();
    else
      stopCamera();
  });

  wizardButton_ = new QPushButton(tr("Calibration capture…"), this);
  wizardButton_->setObjectName("captureWizardButton");
  connect(wizardButton_, &QPushButton::clicked, this, &DevicesPanel::openCaptureWizard);
  root->addWidget(wizardButton_);

  status_ = new QLabel(this);
  status_->setObjectName("benchStatus");
  status_->setWordWrap(true);
  status_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  root->addWidget(status_);

  timer_ = new QTimer(this);
  timer_->setInterval(100);
  connect(timer_, &QTimer::timeout, this, &DevicesPanel::refresh);
  timer_->start();

  if (document_) {
    connect(document_, &SceneDocument::sceneReplaced, this, [this] {
      scene_gaze_ = document_->scene().eye.gaze_deg;
      if (options_.auto_connect || live_) {
        disconnectBench();
        connectBench();
      }
    });
    connect(document_, &SceneDocument::sceneChanged, this, &DevicesPanel::onSceneChanged);
  }
  refresh();
  if (options_.auto_connect)
    QTimer::singleShot(0, this, [this] {
      if (!live_) connectBench();
    });
}

DevicesPanel::~DevicesPanel() {
  ++connect_generation_;
  if (connect_thread_.joinable()) connect_thread_.join();  // a pending result is dropped with this object
  stopCamera();
  stopFollowTable();
  follower_.reset();
  if (wizard_) wizard_->detachBench();
  live_.reset();  // joins the axis threads before the widgets go
}

// ---------------------------------------------------------------------------------------

void DevicesPanel::connectBench() {
  want_connected_ = true;
  if (live_ || connect_thread_.joinable()) return;  // connected, or a start is under way
  const Scene scene = document_ ? document_->scene() : Scene{};
  devices::LiveBenchOptions o;
  o.allow_hardware = options_.allow_hardware;
  o.clock = options_.clock;
  const int generation = ++connect_generation_;
  report(tr("Starting the bench…"), false);
  // USB enumeration, the emulators and the virtual optics are built off the GUI thread; the
  // result comes back as a queued call (dropped if the panel goes first: it joins this thread).
  connect_thread_ = std::thread([this, scene, o, generation] {
    auto made = std::make_shared<std::unique_ptr<devices::LiveBench>>();
    QString error, camera_error;
    try {
      *made = std::make_unique<devices::LiveBench>(scene, o);
      try {
        (*made)->camera().open();
      } catch (const std::exception& e) {
        camera_error = QString::fromStdString(e.what());
      }
    } catch (const std::exception& e) {
      error = QString::fromStdString(e.what());
    }
    QMetaObject::invokeMethod(
        this, [this, made, error, camera_error, generation] { finishConnect(generation, made, error, camera_error); },
        Qt::QueuedConnection);
  });
  refresh();
}

void DevicesPanel::finishConnect(int generation, const std::shared_ptr<std::unique_ptr<devices::LiveBench>>& made,
                                 const QString& error, const QString& camera_error) {
  if (connect_thread_.joinable()) connect_thread_.join();
  if (generation != connect_generation_) {  // disconnected (or the scene replaced) meanwhile
    made->reset();
    if (want_connected_) connectBench();
    return;
  }
  if (!error.isEmpty() || !*made) {
    report(tr("Cannot start the bench: %1").arg(error), true);
    refresh();
    return;
  }
  live_ = std::move(*made);
  connecting_ = live_->bench().connectAll();
  if (!camera_error.isEmpty()) report(tr("Camera: %1").arg(camera_error), true);
  buildAxisRows();
  setTestPattern(pattern_->currentIndex());
  applyExposure();
  if (follow_->isChecked()) setFollowGaze(true);
  if (options_.live_camera && live_check_->isChecked() && isVisible()) startCamera();
  report(live_->isVirtual()
             ? tr("Virtual bench started: %n emulated axis/axes (no stage controller of the scene on USB)", "",
                  live_->virtualAxes())
             : tr("Connected to the bench hardware (%n emulated axis/axes)", "", live_->virtualAxes()),
         false);
  refresh();
  emit benchConnected(live_->isVirtual());
}

void DevicesPanel::disconnectBench() {
  want_connected_ = false;
  ++connect_generation_;  // a start under way is dropped when it arrives
  if (!live_) {
    refresh();
    return;
  }
  stopCamera();
  follower_.reset();
  stopFollowTable();
  table_.reset();  // the next bench may hold another scene
  if (wizard_) wizard_->detachBench();
  clearAxisRows();
  connecting_.clear();
  live_.reset();
  camera_view_->setFrame({}, {});
  camera_view_->setBanner({});
  report(tr("Disconnected"), false);
  refresh();
  emit benchDisconnected();
}

void DevicesPanel::buildAxisRows() {
  clearAxisRows();
  if (!live_) return;
  int r = 0;
  for (const char* h : {"", "axis", "position", "state"}) {
    auto* l = new QLabel(tr(h), axesBox_);
    l->setStyleSheet("font-weight: bold;");
    axesGrid_->addWidget(l, 0, r++);
  }
  r = 1;
  for (devices::AxisWorker* w : live_->bench().axes()) {
    AxisRow axis;
    axis.worker = w;
    axis.key = axisKey(w->binding());
    const auto stage = apt::findStage(w->binding().stage_model);
    axis.unit = QString::fromStdString(stage ? stage->unit() : "mm");
    const bool emulated = live_->bench().virtualController(w->binding().element, w->binding().axis) != nullptr;
    axis.select = new QRadioButton(axesBox_);
    axis.select->setObjectName("select_" + axis.key);
    selectGroup_->addButton(axis.select);
    auto* name = new QLabel(axis.key + (emulated ? tr(" (virtual)") : QString()), axesBox_);
    name->setToolTip(
        QString::fromStdString(w->binding().controller + " " + w->binding().serial + ", " + w->binding().stage_model));
    axis.position = new QLabel("—", axesBox_);
    axis.position->setObjectName("position_" + axis.key);
    axis.position->setMinimumWidth(80);
    axis.position->setAlignment(Qt::AlignRight | Qt::AlignVCenter);
    axis.position->setStyleSheet("font-family: monospace;");
    axis.state = new QLabel(axesBox_);
    axis.state->setObjectName("state_" + axis.key);
    axis.state->setMinimumWidth(60);
    axis.reverse = new QPushButton("◀", axesBox_);
    axis.reverse->setObjectName("jogReverse_" + axis.key);
    axis.forward = new QPushButton("▶", axesBox_);
    axis.forward->setObjectName("jogForward_" + axis.key);
    axis.home = new QPushButton(tr("Home"), axesBox_);
    axis.home->setObjectName("home_" + axis.key);
    axis.target = new QDoubleSpinBox(axesBox_);
    axis.target->setObjectName("target_" + axis.key);
    axis.target->setDecimals(3);
    // The whole stage travel, not the soft limits: a refused target is explained, not hidden.
    const auto& b = w->binding();
    double lo = -1000, hi = 1000;
    if (stage && !stage->continuous && stage->travel_max > stage->travel_min) {
      lo = devices::stageToElement(b, stage->travel_min);
      hi = devices::stageToElement(b, stage->travel_max);
    }
    axis.target->setRange(lo, hi);
    axis.target->setValue(0.0);
    axis.target->setToolTip(tr("Element coordinate; soft limits %1 … %2")
                                .arg(fmt(b.soft_limits[0], axis.unit), fmt(b.soft_limits[1], axis.unit)));
    axis.go = new QPushButton(tr("Go"), axesBox_);
    axis.go->setObjectName("go_" + axis.key);
    for (QPushButton* pb : {axis.reverse, axis.forward}) pb->setFixedWidth(28);
    // Clicking a row keeps the keyboard on the panel (arrow keys jog, Esc stops).
    for (QAbstractButton* ab :
         std::initializer_list<QAbstractButton*>{axis.select, axis.reverse, axis.forward, axis.home})
      ab->setFocusPolicy(Qt::NoFocus);
    connect(axis.select, &QRadioButton::clicked, this, [this] { setFocus(); });
    int c = 0;
    axesGrid_->addWidget(axis.select, r, c++);
    axesGrid_->addWidget(name, r, c++);
    axesGrid_->addWidget(axis.position, r, c++);
    axesGrid_->addWidget(axis.state, r, c++);
    axesGrid_->addWidget(axis.reverse, r, c++);
    axesGrid_->addWidget(axis.forward, r, c++);
    axesGrid_->addWidget(axis.home, r, c++);
    axesGrid_->addWidget(axis.target, r, c++);
    axesGrid_->addWidget(axis.go, r, c++);
    const QString key = axis.key;
    connect(axis.reverse, &QPushButton::clicked, this, [this, key] { jog(key, -1); });
    connect(axis.forward, &QPushButton::clicked, this, [this, key] { jog(key, +1); });
    connect(axis.home, &QPushButton::clicked, this, [this, key] {
      if (AxisRow* ar = row(key)) submit(*ar, tr("home"), [](devices::Stage& s) { s.home(); });
    });
    connect(axis.go, &QPushButton::clicked, this, [this, key] {
      if (AxisRow* ar = row(key)) goTo(key, ar->target->value());
    });
    rows_.push_back(std::move(axis));
    ++r;
  }
  if (!rows_.empty()) rows_.front().select->setChecked(true);
}

void DevicesPanel::clearAxisRows() {
  rows_.clear();
  for (QAbstractButton* b : selectGroup_->buttons()) selectGroup_->removeButton(b);
  while (QLayoutItem* item = axesGrid_->takeAt(0)) {
    if (QWidget* w = item->widget()) w->deleteLater();
    delete item;
  }
}

DevicesPanel::AxisRow* DevicesPanel::row(const QString& key) {
  for (auto& r : rows_)
    if (r.key == key) return &r;
  return nullptr;
}

const DevicesPanel::AxisRow* DevicesPanel::row(const QString& key) const {
  for (const auto& r : rows_)
    if (r.key == key) return &r;
  return nullptr;
}

// ---------------------------------------------------------------------------------------

void DevicesPanel::report(const QString& text, bool error) {
  status_->setText(text);
  status_->setStyleSheet(error ? "color: #c62828; font-weight: bold;" : "");
  status_->setProperty("isError", error);
  emit statusChanged(text);
}

QString DevicesPanel::statusText() const {
  return status_->text();
}

QString DevicesPanel::bannerText() const {
  return banner_->text();
}

void DevicesPanel::submit(const AxisRow& row, const QString& what, std::function<void(devices::Stage&)> command) {
  const QString key = row.key;
  auto pending = row.pending;
  ++*pending;
  row.worker->submit([this, key, what, command = std::move(command), pending](devices::Stage& s) {
    QString error;
    try {
      command(s);
    } catch (const std::exception& e) {
      error = QString::fromStdString(e.what());
    }
    --*pending;
    // Queued to the GUI thread; dropped if the panel is gone (it joins this thread first).
    QMetaObject::invokeMethod(
        this,
        [this, key, what, error] {
          if (error.isEmpty())
            report(tr("%1: %2 done").arg(key, what), false);
          else
            report(tr("%1: %2 refused or failed — %3").arg(key, what, error), true);
          refresh();
        },
        Qt::QueuedConnection);
  });
}

void DevicesPanel::jog(const QString& key, int direction) {
  AxisRow* r = row(key);
  if (!r) return;
  if (*r->pending > 1) return;  // key auto-repeat: at most one jog queued behind the running one
  const double step = step_->value(), speed = speed_->value();
  submit(*r, direction > 0 ? tr("jog +%1").arg(step) : tr("jog −%1").arg(step),
         [step, speed, direction](devices::Stage& s) {
           devices::JogSettings j = s.jogSettings();
           if (j.continuous || std::abs(j.step - step) > 1e-9 || std::abs(j.max_velocity - speed) > 1e-9) {
             j.continuous = false;
             j.step = step;
             j.max_velocity = speed;
             if (!(j.acceleration > 0)) j.acceleration = 4.0 * speed;
             s.setJogSettings(j);
           }
           s.jog(direction > 0 ? apt::JogDirection::Forward : apt::JogDirection::Reverse);
         });
}

void DevicesPanel::goTo(const QString& key, double value) {
  AxisRow* r = row(key);
  if (!r) return;
  const StageBinding b = r->worker->binding();
  const bool inside = value >= b.soft_limits[0] && value <= b.soft_limits[1];  // the binding's soft limits
  r->target->setStyleSheet(inside ? QString() : QStringLiteral("QDoubleSpinBox { background: #ffcdd2; }"));
  if (!inside) {  // refused here: nothing is sent (the Stage would refuse it as well)
    r->target->setToolTip(tr("Refused: outside the soft limits %1 … %2")
                              .arg(fmt(b.soft_limits[0], r->unit), fmt(b.soft_limits[1], r->unit)));
    report(tr("%1: go to %2 refused — outside the soft limits %3 … %4; nothing was sent")
               .arg(r->key, fmt(value, r->unit), fmt(b.soft_limits[0], r->unit), fmt(b.soft_limits[1], r->unit)),
           true);
    return;
  }
  const double target = devices::elementToStage(b, value);
  submit(*r, tr("go to %1").arg(fmt(value, r->unit)), [target](devices::Stage& s) { s.moveAbsolute(target); });
}

void DevicesPanel::homeAll() {
  for (auto& r : rows_) submit(r, tr("home"), [](devices::Stage& s) { s.home(); });
}

void DevicesPanel::emergencyStop() {
  if (!live_) return;
  if (follow_->isChecked()) follow_->setChecked(false);  // a follower would start the axes again
  live_->bench().emergencyStopAll();
  report(tr("EMERGENCY STOP: every axis was sent an immediate stop"), true);
}

void DevicesPanel::setStepSize(double step) {
  step_->setValue(step);
}
double DevicesPanel::stepSize() const {
  return step_->value();
}
void DevicesPanel::setSpeed(double speed) {
  speed_->setValue(speed);
}

void DevicesPanel::setSelectedAxis(const QString& key) {
  if (AxisRow* r = row(key)) r->select->setChecked(true);
}

QString DevicesPanel::selectedAxis() const {
  for (const auto& r : rows_)
    if (r.select->isChecked()) return r.key;
  return {};
}

std::optional<double> DevicesPanel::axisPosition(const QString& key) const {
  const AxisRow* r = row(key);
  if (!r) return std::nullopt;
  const devices::AxisSnapshot s = r->worker->snapshot();
  if (!s.state.known) return std::nullopt;
  return s.element_position;
}

void DevicesPanel::keyPressEvent(QKeyEvent* e) {
  const QString sel = selectedAxis();
  switch (e->key()) {
    case Qt::Key_Escape:
      emergencyStop();
      return;
    case Qt::Key_Left:
      jog(sel, -1);
      return;
    case Qt::Key_Right:
      jog(sel, +1);
      return;
    case Qt::Key_Up:
    case Qt::Key_Down: {
      for (std::size_t i = 0; i < rows_.size(); ++i)
        if (rows_[i].key == sel) {
          const std::size_t n = rows_.size();
          const std::size_t j = e->key() == Qt::Key_Up ? (i + n - 1) % n : (i + 1) % n;
          rows_[j].select->setChecked(true);
          break;
        }
      return;
    }
    case Qt::Key_Plus:
    case Qt::Key_Equal:
      step_->setValue(step_->value() * 2);
      return;
    case Qt::Key_Minus:
      step_->setValue(step_->value() / 2);
      return;
    default:
      QWidget::keyPressEvent(e);
  }
}

void DevicesPanel::refresh() {
  const bool on = live_ != nullptr;
  connect_->setEnabled(!on && !connect_thread_.joinable());
  disconnect_->setEnabled(on);
  homeAll_->setEnabled(on && !rows_.empty());
  estop_->setEnabled(on);
  wizardButton_->setEnabled(on);
  if (!on) {
    banner_->setText(connect_thread_.joinable() ? tr("Starting the bench…") : tr("Bench not connected"));
    banner_->setStyleSheet("QLabel { background: palette(mid); color: white; padding: 4px; }");
    return;
  }
  if (live_->isVirtual()) {
    banner_->setText(
        tr("VIRTUAL BENCH — no stage controller of the scene is plugged in; every axis and the "
           "eye camera are simulated"));
    banner_->setStyleSheet("QLabel { background: #e68a00; color: black; font-weight: bold; padding: 4px; }");
  } else {
    QString t = tr("HARDWARE BENCH — USB stage controllers");
    if (live_->virtualAxes() > 0) t += tr("; %n axis/axes VIRTUAL", "", live_->virtualAxes());
    if (live_->cameraIsVirtual()) t += tr("; camera VIRTUAL");
    banner_->setText(t);
    banner_->setStyleSheet(live_->virtualAxes() > 0 || live_->cameraIsVirtual()
                               ? "QLabel { background: #fbc02d; color: black; font-weight: bold; padding: 4px; }"
                               : "QLabel { background: #2e7d32; color: white; font-weight: bold; padding: 4px; }");
  }
  camera_view_->setBanner(live_->cameraIsVirtual() ? tr("VIRTUAL") : QString());
  for (auto& r : rows_) {
    const devices::AxisSnapshot s = r.worker->snapshot();
    r.position->setText(s.state.known ? fmt(s.element_position, r.unit) : QStringLiteral("—"));
    QString st;
    if (!s.connected)
      st = tr("offline");
    else if (s.state.homing)
      st = tr("homing");
    else if (s.state.moving || s.busy)
      st = tr("moving");
    else if (!s.state.enabled)
      st = tr("disabled");
    else if (!s.state.homed)
      st = tr("not homed");
    else
      st = tr("ready");
    if (s.state.forward_limit || s.state.reverse_limit) st += tr(" · limit");
    r.state->setText(st);
    r.state->setToolTip(QString::fromStdString(s.last_error));
    r.state->setStyleSheet(s.last_error.empty() ? "" : "color: #c62828;");
  }
  // Connection problems from connectAll().
  for (auto it = connecting_.begin(); it != connecting_.end();) {
    if (it->wait_for(std::chrono::seconds(0)) != std::future_status::ready) {
      ++it;
      continue;
    }
    try {
      it->get();
    } catch (const std::exception& e) {
      report(tr("Connect: %1").arg(QString::fromStdString(e.what())), true);
    }
    it = connecting_.erase(it);
  }
  if (table_ && follower_ && !table_applied_ && followTableReady()) {  // retarget with the analysed x_p(alpha)
    table_applied_ = true;
    follower_->setGaze(gaze_[0], gaze_[1]);
  }
  if (table_) {
    std::lock_guard lock(table_->mutex);
    followInfo_->setText(table_->ready ? tr("x_p(α) from the analyses (traced HOE, %1 gazes)").arg(table_->gazes.size())
                                       : tr("x_p(α): geometric guess while the analyses run…"));
  } else {
    followInfo_->setText(tr("x_p(α): geometric guess"));
  }
  gazeLabel_->setText(tr("α = %1°, %2°").arg(gaze_[0], 0, 'f', 1).arg(gaze_[1], 0, 'f', 1));
}

// ---------------------------------------------------------------------------------------
// Camera

void DevicesPanel::startCamera() {
  if (!live_ || camera_thread_.joinable()) return;
  camera_stop_ = false;
  devices::Camera* cam = &live_->camera();
  camera_thread_ = std::thread([this, cam] {
    using clock = std::chrono::steady_clock;
    while (!camera_stop_) {
      const auto t0 = clock::now();
      if (!frame_pending_) {
        try {
          const devices::Frame f = cam->grab();
          QImage img(f.image.data, f.image.cols, f.image.rows, static_cast<int>(f.image.step),
                     QImage::Format_Grayscale8);
          const QString caption = QString::fromStdString(cam->info().model) + tr("  #%1  t=%2 s  exp %3 ms")
                                                                                  .arg(f.sequence)
                                                                                  .arg(f.exposure_start_s, 0, 'f', 2)
                                                                                  .arg(f.exposure_s * 1e3, 0, 'f', 1);
          frame_pending_ = true;
          QMetaObject::invokeMethod(
              this,
              [this, img = img.copy(), caption] {
                camera_view_->setFrame(img, caption);
                frame_pending_ = false;
              },
              Qt::QueuedConnection);
        } catch (const std::exception& e) {
          const QString msg = QString::fromStdString(e.what());
          QMetaObject::invokeMethod(
              this, [this, msg] { report(tr("Camera: %1").arg(msg), true); }, Qt::QueuedConnection);
          for (int i = 0; i < 20 && !camera_stop_; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(50));
        }
      }
      // About 10 frames per second for the live view.
      const auto next = t0 + std::chrono::milliseconds(100);
      while (!camera_stop_ && clock::now() < next) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  });
}

void DevicesPanel::stopCamera() {
  camera_stop_ = true;
  if (camera_thread_.joinable()) camera_thread_.join();
  frame_pending_ = false;
}

void DevicesPanel::applyExposure() {
  if (!live_) return;
  devices::Camera& c = live_->camera();
  try {
    if (c.hasExposure()) c.setExposure(exposure_->value() * 1e-3);
    if (c.hasGain()) c.setGain(gain_->value());
  } catch (const std::exception& e) {
    report(tr("Camera: %1").arg(QString::fromStdString(e.what())), true);
  }
  exposure_->setEnabled(c.hasExposure());
  gain_->setEnabled(c.hasGain());
}

void DevicesPanel::setTestPattern(int index) {
  if (pattern_->currentIndex() != index) {
    pattern_->setCurrentIndex(index);  // re-enters through the signal
    return;
  }
  if (!live_ || !live_->optics()) return;
  const Scene scene = document_ ? document_->scene() : Scene{};
  auto* o = live_->optics();
  const auto board_p = devices::peripheralBoard(scene);
  const auto board_f = devices::fovealBoard(scene);
  const auto off = image::offPattern();
  const auto white = image::flatPatch({1, 1, 1});
  switch (index) {
    case 1:
      o->show(BenchDisplay::Peripheral, board_p);
      o->show(BenchDisplay::Foveal, board_f);
      break;
    case 2:
      o->show(BenchDisplay::Peripheral, board_p);
      o->show(BenchDisplay::Foveal, off);
      break;
    case 3:
      o->show(BenchDisplay::Peripheral, off);
      o->show(BenchDisplay::Foveal, board_f);
      break;
    case 4:
      o->show(BenchDisplay::Peripheral, white);
      o->show(BenchDisplay::Foveal, white);
      break;
    default:
      o->show(BenchDisplay::Peripheral, off);
      o->show(BenchDisplay::Foveal, off);
  }
}

void DevicesPanel::showEvent(QShowEvent* e) {
  QWidget::showEvent(e);
  if (options_.live_camera && live_check_->isChecked()) startCamera();
}

void DevicesPanel::hideEvent(QHideEvent* e) {
  QWidget::hideEvent(e);
  stopCamera();
}

// ---------------------------------------------------------------------------------------
// Follow gaze

void DevicesPanel::onSceneChanged() {
  if (!document_) return;
  const Scene& s = document_->scene();
  if (live_ && live_->optics()) live_->optics()->setScene(s);
  if (s.eye.gaze_deg != scene_gaze_) {  // the scene's gaze moved (an analysis's gaze slider)
    scene_gaze_ = s.eye.gaze_deg;
    gazeYaw_->setValue(static_cast<int>(std::lround(scene_gaze_[0] * 10)));
    gazePitch_->setValue(static_cast<int>(std::lround(scene_gaze_[1] * 10)));
  }
}

void DevicesPanel::startFollowTable() {
  stopFollowTable();
  table_ = std::make_shared<FollowTable>();
  table_applied_ = false;
  if (!options_.analysed_follow || !document_) return;
  const Scene scene = document_->scene();
  bool any_hoe = false;
  for (const auto& b : scene.stages) any_hoe = any_hoe || b.element == "hoe";
  if (!any_hoe) return;
  table_cancel_ = std::make_shared<std::atomic<bool>>(false);
  table_thread_ = std::thread([scene, table = table_, cancel = table_cancel_] {
    TraceEvaluatorOptions to;
    to.rays = 800;
    const FovEvaluator eval = traceEvaluator(to);
    const double lo = scene.eye.gaze_range_deg[0], hi = scene.eye.gaze_range_deg[1];
    std::vector<double> gazes, sx, sy;
    const int n = 9;
    for (int i = 0; i < n; ++i) gazes.push_back(lo + (hi - lo) * i / (n - 1));
    for (double g : gazes) {
      if (*cancel) return;
      sx.push_back(optimiseShift(scene, eval, g, GazeAxis::Yaw, ShiftMethod::Hoe).shift_mm);
    }
    for (double g : gazes) {
      if (*cancel) return;
      sy.push_back(optimiseShift(scene, eval, g, GazeAxis::Pitch, ShiftMethod::Hoe).shift_mm);
    }
    std::lock_guard lock(table->mutex);
    table->gazes = gazes;
    table->shift_x = sx;
    table->shift_y = sy;
    table->ready = true;
  });
}

void DevicesPanel::stopFollowTable() {
  if (table_cancel_) *table_cancel_ = true;
  if (table_thread_.joinable()) table_thread_.join();
  table_cancel_.reset();
}

std::map<devices::GazeFollower::Key, double> DevicesPanel::followTargets(double yaw, double pitch) const {
  const Scene scene = document_ ? document_->scene() : Scene{};
  std::array<double, 2> xp = geometricHoeShiftForGaze(scene, {yaw, pitch});
  if (table_) {
    std::lock_guard lock(table_->mutex);
    if (table_->ready) {
      // The optimum at zero gaze is the reference: a zero gaze component keeps its shift at 0.
      xp[0] = interpolate(table_->gazes, table_->shift_x, yaw) - interpolate(table_->gazes, table_->shift_x, 0.0);
      xp[1] = interpolate(table_->gazes, table_->shift_y, pitch) - interpolate(table_->gazes, table_->shift_y, 0.0);
    }
  }
  const std::array<double, 2> xf = fovealShiftForGaze(scene, {yaw, pitch});
  return {{{"hoe", "x"}, xp[0]},
          {{"hoe", "y"}, xp[1]},
          {{"foveal_display", "x"}, xf[0]},
          {{"foveal_display", "y"}, xf[1]},
          {{"camera", "yaw"}, yaw},
          {{"camera", "pitch"}, pitch}};
}

bool DevicesPanel::hasCameraFrame() const {
  return !camera_view_->frame().isNull();
}

bool DevicesPanel::followTableReady() const {
  if (!table_) return false;
  std::lock_guard lock(table_->mutex);
  return table_->ready;
}

bool DevicesPanel::followGaze() const {
  return follow_->isChecked();
}

void DevicesPanel::setFollowGaze(bool on) {
  if (follow_->isChecked() != on) {
    follow_->setChecked(on);  // re-enters through the signal
    return;
  }
  follower_.reset();
  if (!on || !live_) return;
  if (!table_) startFollowTable();  // the analyses' x_p(alpha) table, computed on first use
  follower_ = std::make_unique<devices::GazeFollower>(
      live_->bench().axes(), [this](double y, double p) { return followTargets(y, p); }, 0.005);
  follower_->setGaze(gaze_[0], gaze_[1]);
  report(tr("Following the gaze"), false);
}

void DevicesPanel::setGaze(double yaw, double pitch) {
  gaze_ = {yaw, pitch};
  const int y = static_cast<int>(std::lround(yaw * 10)), p = static_cast<int>(std::lround(pitch * 10));
  if (gazeYaw_->value() != y || gazePitch_->value() != p) {
    const QSignalBlocker a(gazeYaw_), b(gazePitch_);
    gazeYaw_->setValue(y);
    gazePitch_->setValue(p);
  }
  tracker_->setEyeGaze(yaw, pitch);  // the virtual eye looks where the slider says
  if (follower_ && !tracker_->tracking()) follower_->setGaze(yaw, pitch);
  refresh();
}

// ---------------------------------------------------------------------------------------

void DevicesPanel::openCaptureWizard() {
  if (!live_) return;
  if (wizard_ && !wizard_->hasBench()) delete wizard_;  // made for a bench that was disconnected
  if (!wizard_) {
    wizard_ = new CaptureWizard(document_ ? document_->scene() : Scene{}, live_.get(), this);
    wizard_->setHoeShift([this](std::array<double, 2> g) {
      const auto t = followTargets(g[0], g[1]);
      return std::array<double, 2>{t.at({"hoe", "x"}), t.at({"hoe", "y"})};
    });
  }
  wizard_->show();
  wizard_->raise();
}

}  // namespace fovea::widgets
