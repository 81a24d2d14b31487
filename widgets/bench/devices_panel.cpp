#include "widgets/bench/devices_panel.h"

#include <QGroupBox>
#include <QHBoxLayout>
#include <QKeyEvent>
#include <QLabel>
#include <QPushButton>
#include <QShortcut>
#include <QTimer>
#include <QVBoxLayout>

#include "widgets/bench/axis_table.h"
#include "widgets/bench/capture_wizard.h"
#include "widgets/bench/eye_camera_box.h"
#include "widgets/bench/follow_gaze_box.h"
#include "widgets/bench/pupil_tracker_view.h"
#include "widgets/scene_document.h"

namespace fovea::widgets {

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

  axes_ = new AxisTable(this);
  root->addWidget(axes_);
  root->addWidget(axes_->jogControls());
  connect(axes_, &AxisTable::report, this, &DevicesPanel::report);

  auto scene = [this] { return currentScene(); };
  follow_ = new FollowGazeBox(scene, options_.analysed_follow, this);
  root->addWidget(follow_);
  connect(follow_, &FollowGazeBox::report, this, &DevicesPanel::report);
  connect(follow_, &FollowGazeBox::axisNote, axes_, &AxisTable::setRowNote);

  camera_ = new EyeCameraBox(scene, options_.live_camera, this);
  root->addWidget(camera_, 1);
  connect(camera_, &EyeCameraBox::report, this, &DevicesPanel::report);
  connect(camera_, &EyeCameraBox::liveToggled, this, [this](bool on) {
    if (on && isVisible())
      camera_->start();
    else
      camera_->stop();
  });

  // The pupil tracker (pupil_tracker_view.h): while it tracks, its gaze drives follow gaze.
  auto* trackBox = new QGroupBox(tr("Pupil tracker"), this);
  auto* tl = new QVBoxLayout(trackBox);
  tl->setContentsMargins(4, 4, 4, 4);
  tracker_ = new PupilTrackerView(currentScene(), trackBox);
  tl->addWidget(tracker_);
  root->addWidget(trackBox, 1);
  connect(tracker_, &PupilTrackerView::gazeTracked, this,
          [this](double y, double p, double) { follow_->setFollowerGaze(y, p); });
  // The virtual eye looks where the sliders say; the sliders drive the axes unless the tracker does.
  follow_->setGazeHooks([this](double y, double p) { tracker_->setEyeGaze(y, p); },
                        [this] { return tracker_->tracking(); });

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
  camera_->setBench(nullptr);
  follow_->detachBench();
  if (wizard_) wizard_->detachBench();
  live_.reset();  // joins the axis threads before the widgets go
}

Scene DevicesPanel::currentScene() const {
  return document_ ? document_->scene() : Scene{};
}

// ---------------------------------------------------------------------------------------

void DevicesPanel::connectBench() {
  startBench(true);
}

void DevicesPanel::startBench(bool announce) {
  want_connected_ = true;
  if (live_ || connect_thread_.joinable()) return;  // connected, or a start is under way
  const Scene scene = currentScene();
  devices::LiveBenchOptions o;
  o.allow_hardware = options_.allow_hardware;
  o.clock = options_.clock;
  const int generation = ++connect_generation_;
  if (announce) report(tr("Starting the bench…"), false);
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
    // A start superseded by a newer one (the scene replaced meanwhile): the user was told the
    // bench is starting; start again without saying it twice.
    if (want_connected_) startBench(false);
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
  axes_->setFocusModel(focusStageModel(currentScene()));
  axes_->setBench(live_.get());
  camera_->setBench(live_.get());
  follow_->setBench(live_.get());
  scene_gaze_ = currentScene().eye.gaze_deg;
  follow_->setSceneGaze(scene_gaze_);
  if (options_.live_camera && isVisible()) camera_->start();
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
  camera_->setBench(nullptr);
  follow_->detachBench();
  if (wizard_) wizard_->detachBench();
  axes_->setBench(nullptr);
  connecting_.clear();
  live_.reset();
  report(tr("Disconnected"), false);
  refresh();
  emit benchDisconnected();
}

void DevicesPanel::homeAll() {
  axes_->homeAll();
}

void DevicesPanel::emergencyStop() {
  if (!live_) return;
  if (follow_->followGaze()) follow_->setFollowGaze(false);  // a follower would start the axes again
  axes_->noteEmergencyStop();
  live_->bench().emergencyStopAll();
  report(tr("EMERGENCY STOP: every axis was sent an immediate stop"), true);
}

void DevicesPanel::jog(const QString& key, int direction) {
  axes_->jog(key, direction);
}
void DevicesPanel::goTo(const QString& key, double value) {
  axes_->goTo(key, value);
}
void DevicesPanel::setStepSize(double step) {
  axes_->setStepSize(step);
}
double DevicesPanel::stepSize() const {
  return axes_->stepSize();
}
void DevicesPanel::setSpeed(double speed) {
  axes_->setSpeed(speed);
}
void DevicesPanel::setSelectedAxis(const QString& key) {
  axes_->setSelectedAxis(key);
}
QString DevicesPanel::selectedAxis() const {
  return axes_->selectedAxis();
}
std::optional<double> DevicesPanel::axisPosition(const QString& key) const {
  return axes_->axisPosition(key);
}

void DevicesPanel::report(const QString& text, bool error) {
  status_->setText(text);
  status_->setStyleSheet(error ? "color: #c62828; font-weight: bold;" : "");
  status_->setProperty("isError", error);
  emit statusChanged(text);
  emit message(text, error);
}

QString DevicesPanel::statusText() const {
  return status_->text();
}

QString DevicesPanel::bannerText() const {
  return banner_->text();
}

void DevicesPanel::keyPressEvent(QKeyEvent* e) {
  switch (e->key()) {
    case Qt::Key_Escape:
      emergencyStop();
      return;
    case Qt::Key_Left:
      jog(selectedAxis(), -1);
      return;
    case Qt::Key_Right:
      jog(selectedAxis(), +1);
      return;
    case Qt::Key_Up:
      axes_->selectNext(-1);
      return;
    case Qt::Key_Down:
      axes_->selectNext(+1);
      return;
    case Qt::Key_Plus:
    case Qt::Key_Equal:
      axes_->scaleStep(2.0);
      return;
    case Qt::Key_Minus:
      axes_->scaleStep(0.5);
      return;
    default:
      QWidget::keyPressEvent(e);
  }
}

void DevicesPanel::refresh() {
  const bool on = live_ != nullptr;
  connect_->setEnabled(!on && !connect_thread_.joinable());
  disconnect_->setEnabled(on);
  homeAll_->setEnabled(on && axes_->hasRows());
  estop_->setEnabled(on);
  wizardButton_->setEnabled(on);
  follow_->refresh();
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
  camera_->setBanner(live_->cameraIsVirtual() ? tr("VIRTUAL") : QString());
  axes_->refresh();
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
}

void DevicesPanel::setTestPattern(int index) {
  camera_->setTestPattern(index);
}

bool DevicesPanel::hasCameraFrame() const {
  return camera_->hasFrame();
}

void DevicesPanel::showEvent(QShowEvent* e) {
  QWidget::showEvent(e);
  if (options_.live_camera) camera_->start();
}

void DevicesPanel::hideEvent(QHideEvent* e) {
  camera_->stop();
  QWidget::hideEvent(e);
}

// ---------------------------------------------------------------------------------------
// Follow gaze

void DevicesPanel::onSceneChanged() {
  if (!document_) return;
  const Scene& s = document_->scene();
  if (live_ && live_->optics()) live_->optics()->setScene(s);
  if (s.eye.gaze_deg != scene_gaze_) {  // the scene's gaze moved (an analysis's gaze slider)
    scene_gaze_ = s.eye.gaze_deg;
    follow_->setSceneGaze(scene_gaze_);
  }
}

bool DevicesPanel::followTableReady() const {
  return follow_->tableReady();
}

bool DevicesPanel::followGaze() const {
  return follow_->followGaze();
}

void DevicesPanel::setFollowGaze(bool on) {
  follow_->setFollowGaze(on);
}

void DevicesPanel::setGaze(double yaw, double pitch) {
  // The studio's one gaze is the scene's (the Gaze dock's): set it there, follow gaze hears it
  // through onSceneChanged.
  if (document_) {
    const QStringList problems = document_->applyEdit(tr("Gaze %1°, %2°").arg(yaw).arg(pitch), [&](Scene& s) {
      s.eye.gaze_deg = {yaw, pitch};
    });
    if (!problems.isEmpty()) report(problems.join("; "), true);
  } else {
    follow_->setGaze(yaw, pitch);
  }
  refresh();
}

QString DevicesPanel::axisStateText(const QString& key) const {
  return axes_->stateText(key);
}

QString DevicesPanel::followInfoText() const {
  return follow_->infoText();
}

// ---------------------------------------------------------------------------------------

void DevicesPanel::openCaptureWizard() {
  if (!live_) return;
  if (wizard_ && !wizard_->hasBench()) delete wizard_;  // made for a bench that was disconnected
  if (!wizard_) {
    follow_->ensureTable();  // the gaze study's x_p(alpha), as follow gaze uses it
    wizard_ = new CaptureWizard(currentScene(), live_.get(), this);
    wizard_->setHoeShift([this](std::array<double, 2> g) { return follow_->hoeShift(g); });
    wizard_->setHoeShiftSource([this] {
      bool analysed = false;
      std::string source;
      follow_->hoeShift({0.0, 0.0}, &analysed, &source);
      return std::make_pair(analysed, source);
    });
  }
  wizard_->show();
  wizard_->raise();
}

}  // namespace fovea::widgets
