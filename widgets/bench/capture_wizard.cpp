#include "widgets/bench/capture_wizard.h"

#include <QCloseEvent>
#include <QComboBox>
#include <QDateTime>
#include <QDir>
#include <QFileDialog>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QProgressBar>
#include <QPushButton>
#include <QStandardPaths>
#include <QVBoxLayout>

#include <opencv2/imgproc.hpp>

#include "model/gaze/eye_tracker_calibration.h"
#include "model/gaze/tracked_calibration.h"

namespace fovea::widgets {

CaptureWizard::CaptureWizard(const Scene& scene, devices::LiveBench* live, QWidget* parent)
    : QDialog(parent), scene_(scene), live_(live) {
  setObjectName("CaptureWizard");
  setWindowTitle(tr("Calibration capture"));
  setModal(false);
  resize(720, 520);
  auto* root = new QVBoxLayout(this);

  auto* top = new QGridLayout;
  top->addWidget(new QLabel(tr("Calibration"), this), 0, 0);
  kind_ = new QComboBox(this);
  kind_->setObjectName("captureKind");
  kind_->addItem(tr("Geometric — checkerboards per micro-OLED and HOE position over the gaze range"),
                 static_cast<int>(devices::CaptureKind::Geometric));
  kind_->addItem(tr("Colour — patch sequence, then import the measurements"),
                 static_cast<int>(devices::CaptureKind::Color));
  kind_->addItem(scene_.binocular ? tr("Gaze — 5-point fixation sequence, both eye cameras")
                                  : tr("Gaze — 5-point fixation sequence"),
                 static_cast<int>(devices::CaptureKind::Gaze));
  top->addWidget(kind_, 0, 1, 1, 2);
  top->addWidget(new QLabel(tr("Folder"), this), 1, 0);
  folder_ = new QLineEdit(this);
  folder_->setObjectName("captureFolder");
  top->addWidget(folder_, 1, 1);
  browse_ = new QPushButton(tr("Browse…"), this);
  top->addWidget(browse_, 1, 2);
  root->addLayout(top);
  if (live_ && live_->rig().is_virtual) {
    auto* v = new QLabel(tr("VIRTUAL BENCH: the captures are rendered by the simulated optics"), this);
    v->setStyleSheet("QLabel { background: #e68a00; color: black; font-weight: bold; padding: 3px; }");
    root->addWidget(v);
  }

  auto* middle = new QHBoxLayout;
  steps_ = new QListWidget(this);
  steps_->setObjectName("captureSteps");
  middle->addWidget(steps_, 1);
  auto* right = new QVBoxLayout;
  thumbnail_ = new QLabel(this);
  thumbnail_->setObjectName("captureThumbnail");
  thumbnail_->setFixedSize(320, 240);
  thumbnail_->setAlignment(Qt::AlignCenter);
  thumbnail_->setStyleSheet("QLabel { background: #141418; color: #aaa; }");
  thumbnail_->setText(tr("last capture"));
  right->addWidget(thumbnail_);
  instruction_ = new QLabel(this);
  instruction_->setWordWrap(true);
  right->addWidget(instruction_);
  right->addStretch();
  middle->addLayout(right);
  root->addLayout(middle, 1);

  progress_ = new QProgressBar(this);
  root->addWidget(progress_);
  auto* buttons = new QHBoxLayout;
  open_ = new QPushButton(tr("Open session"), this);
  open_->setObjectName("openSession");
  start_ = new QPushButton(tr("Start"), this);
  start_->setObjectName("startCapture");
  pause_ = new QPushButton(tr("Pause"), this);
  pause_->setObjectName("pauseCapture");
  import_ = new QPushButton(tr("Import measurement…"), this);
  import_->setObjectName("importMeasurement");
  for (QPushButton* b : {open_, start_, pause_, import_}) buttons->addWidget(b);
  buttons->addStretch();
  root->addLayout(buttons);
  status_ = new QLabel(this);
  status_->setObjectName("captureStatus");
  status_->setWordWrap(true);
  root->addWidget(status_);
  hoe_source_ = new QLabel(this);
  hoe_source_->setObjectName("hoeShiftSource");
  hoe_source_->setWordWrap(true);
  root->addWidget(hoe_source_);
  gaze_result_ = new QLabel(this);
  gaze_result_->setObjectName("gazeCalibration");
  gaze_result_->setWordWrap(true);
  gaze_result_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  root->addWidget(gaze_result_);

  folder_->setText(defaultFolder());
  connect(kind_, &QComboBox::currentIndexChanged, this, [this] {
    if (!running_) {
      session_.reset();
      folder_->setText(defaultFolder());
      refreshList();
    }
  });
  connect(browse_, &QPushButton::clicked, this, [this] {
    const QString d = QFileDialog::getExistingDirectory(this, tr("Capture folder"), folder_->text());
    if (!d.isEmpty()) setFolder(d);
  });
  connect(open_, &QPushButton::clicked, this, [this] { openSession(); });
  connect(start_, &QPushButton::clicked, this, &CaptureWizard::start);
  connect(pause_, &QPushButton::clicked, this, &CaptureWizard::pause);
  connect(import_, &QPushButton::clicked, this, [this] {
    const QString f = QFileDialog::getOpenFileName(
        this, tr("Import colour measurements"), folder_->text(),
        tr("Measurements (*.json *.csv);;Spectroradiometer readings (*.csv);;JSON (*.json)"));
    if (f.isEmpty()) return;
    QString error;
    if (!importMeasurement(f, &error)) status_->setText(error);
  });
  refreshList();
}

CaptureWizard::~CaptureWizard() {
  pause_requested_ = true;
  join();
}

void CaptureWizard::join() {
  if (worker_.joinable()) worker_.join();
}

void CaptureWizard::detachBench() {
  pause_requested_ = true;
  join();
  running_ = false;
  live_ = nullptr;
  status_->setText(tr("The bench was disconnected; the captures so far are saved in %1").arg(folder()));
  updateButtons();
}

void CaptureWizard::setKind(devices::CaptureKind k) {
  kind_->setCurrentIndex(kind_->findData(static_cast<int>(k)));
}

devices::CaptureKind CaptureWizard::kind() const {
  return static_cast<devices::CaptureKind>(kind_->currentData().toInt());
}

void CaptureWizard::setFolder(const QString& folder) {
  if (running_) return;
  folder_->setText(folder);
  session_.reset();
  refreshList();
}

QString CaptureWizard::folder() const {
  return folder_->text();
}

QString CaptureWizard::defaultFolder() const {
  QString base = QStandardPaths::writableLocation(QStandardPaths::DocumentsLocation);
  if (base.isEmpty()) base = QDir::homePath();
  return QDir(base).filePath("fovea-captures/" + QString(devices::toString(kind())) + "-" +
                             QDateTime::currentDateTime().toString("yyyyMMdd-HHmmss"));
}

int CaptureWizard::stepCount() const {
  return session_ ? static_cast<int>(session_->plan().size()) : 0;
}

bool CaptureWizard::openSession() {
  if (running_) return false;
  devices::Plan plan;
  switch (kind()) {
    case devices::CaptureKind::Geometric: {
      devices::GeometricPlanOptions o;
      o.hoe_shift = hoe_shift_;
      plan = devices::geometricPlan(scene_, o);
      break;
    }
    case devices::CaptureKind::Color:
      plan = devices::colorPlan(scene_);
      break;
    case devices::CaptureKind::Gaze:
      plan = devices::gazePlan(scene_);
      break;
  }
  skipped_.clear();
  for (const auto& s : plan.skipped) skipped_ << QString::fromStdString(s);
  try {
    session_ = std::make_unique<devices::CaptureSession>(kind(), plan.steps, folder().toStdString(), scene_.name);
  } catch (const std::exception& e) {
    session_.reset();
    status_->setText(tr("Cannot open the session: %1").arg(QString::fromStdString(e.what())));
    refreshList();
    return false;
  }
  captured_ = static_cast<int>(session_->capturedCount());
  QString text =
      captured_ > 0
          ? tr("Resumed: %1 of %2 steps were already captured in %3").arg(captured_).arg(stepCount()).arg(folder())
          : tr("New session in %1 (%2 steps)").arg(folder()).arg(stepCount()) +
                (skipped_.isEmpty() ? QString() : tr("; skipped: ") + skipped_.join("; "));
  status_->setText(text);
  hoe_source_->clear();
  hoe_source_->setStyleSheet("");
  showGazeCalibration();
  if (kind() == devices::CaptureKind::Geometric && hoe_shift_source_) {
    const auto [analysed, source] = hoe_shift_source_();
    hoe_source_->setText(analysed ? tr("HOE at x_p(α) from the %1").arg(QString::fromStdString(source))
                                  : tr("WARNING: the gaze study's x_p(α) is not ready yet; the HOE goes to the "
                                       "geometric guess (reopen the session once the Bench dock's follow-gaze line "
                                       "names the gaze study)"));
    hoe_source_->setStyleSheet(analysed ? "" : "color: #c62828; font-weight: bold;");
  }
  refreshList();
  return true;
}

void CaptureWizard::start() {
  if (running_ || !live_) return;
  if (!session_ && !openSession()) return;
  if (session_->complete()) {
    status_->setText(tr("Every step is captured (%1)").arg(folder()));
    return;
  }
  pause_requested_ = false;
  running_ = true;
  updateButtons();
  runNext();
}

void CaptureWizard::resume() {
  start();
}

void CaptureWizard::pause() {
  if (!running_) return;
  pause_requested_ = true;
  status_->setText(tr("Pausing after the running step…"));
}

void CaptureWizard::runNext() {
  join();
  const auto next = session_->nextStep();
  const bool uncalibrated =
      session_->gazeCalibration().is_null() || (scene_.binocular && session_->leftGazeCalibration().is_null());
  if (!next && kind() == devices::CaptureKind::Gaze && uncalibrated && live_ && !pause_requested_) {
    calibrateGaze();  // the last part of the gaze session; runStopped when it is done
    return;
  }
  if (!next || pause_requested_ || !live_) {
    running_ = false;
    status_->setText(!next ? tr("Complete: %1 captures in %2").arg(captured_).arg(folder())
                           : tr("Paused: %1 of %2 captured; Resume goes on from step %3")
                                 .arg(captured_)
                                 .arg(stepCount())
                                 .arg(*next + 1));
    updateButtons();
    emit runStopped();
    return;
  }
  const int index = static_cast<int>(*next);
  instruction_->setText(QString::fromStdString(session_->plan()[*next].instruction));
  status_->setText(tr("Capturing step %1 of %2: %3")
                       .arg(index + 1)
                       .arg(stepCount())
                       .arg(QString::fromStdString(session_->plan()[*next].id)));
  if (auto* item = steps_->item(index)) steps_->setCurrentItem(item);
  devices::BenchRig rig = live_->rig();
  devices::CaptureSession* session = session_.get();
  worker_ = std::thread([this, session, rig, index]() mutable {
    QString error;
    try {
      session->capture(static_cast<std::size_t>(index), rig);
    } catch (const std::exception& e) {
      error = QString::fromStdString(e.what());
    }
    QMetaObject::invokeMethod(
        this, [this, index, error] { stepFinished(index, error); }, Qt::QueuedConnection);
  });
}

void CaptureWizard::stepFinished(int index, const QString& error) {
  join();
  if (!session_) return;
  if (!error.isEmpty()) {
    running_ = false;
    status_->setText(
        tr("Step %1 failed: %2 — fix it and Resume; the earlier captures are kept").arg(index + 1).arg(error));
    refreshList();
    updateButtons();
    emit stepFailed(error);
    emit runStopped();
    return;
  }
  captured_ = static_cast<int>(session_->capturedCount());
  const std::string id = session_->plan()[static_cast<std::size_t>(index)].id;
  const cv::Mat img = session_->image(id);
  if (!img.empty()) {
    cv::Mat small;
    cv::resize(img, small, cv::Size(320, std::max(1, 320 * img.rows / std::max(1, img.cols))), 0, 0, cv::INTER_AREA);
    const QImage q(small.data, small.cols, small.rows, static_cast<int>(small.step), QImage::Format_Grayscale8);
    thumbnail_->setPixmap(QPixmap::fromImage(q.copy()));
  }
  refreshList();
  emit stepCaptured(index, QString::fromStdString(id));
  runNext();
}

nlohmann::json CaptureWizard::gazeCalibration() const {
  return session_ ? session_->gazeCalibration() : nlohmann::json();
}

nlohmann::json CaptureWizard::leftGazeCalibration() const {
  return session_ ? session_->leftGazeCalibration() : nlohmann::json();
}

void CaptureWizard::calibrateGaze() {
  if (calibrating_ || !session_) return;
  join();
  calibrating_ = true;
  running_ = true;
  updateButtons();
  status_->setText(scene_.binocular
                       ? tr("Gaze calibration: the pupil tracker on both eye cameras, 5 targets × 10 samples each…")
                       : tr("Gaze calibration: the pupil tracker on the eye camera, 5 targets × 10 samples…"));
  // Both eye cameras of a binocular scene, each with its own noise and eye, as the
  // binocular closed loop calibrates them (model/gaze/eye_tracker_calibration.h).
  worker_ = std::thread([this, scene = scene_] {
    nlohmann::json result, left;
    QString error;
    try {
      const gaze::EyeTrackerCalibrations c = gaze::calibrateEyeTrackers(scene);
      result = trackedCalibrationJson(c.right, c.right_options);
      if (c.left) left = trackedCalibrationJson(*c.left, *c.left_options);
    } catch (const std::exception& e) {
      error = QString::fromStdString(e.what());
    }
    QMetaObject::invokeMethod(
        this, [this, result, left, error] { gazeCalibrationFinished(result, left, error); }, Qt::QueuedConnection);
  });
}

void CaptureWizard::gazeCalibrationFinished(const nlohmann::json& result, const nlohmann::json& left,
                                            const QString& error) {
  join();
  calibrating_ = false;
  running_ = false;
  if (session_ && error.isEmpty()) {
    session_->setGazeCalibration(result, left);
    status_->setText(tr("Complete: %1 captures and the gaze calibration in %2").arg(captured_).arg(folder()));
    showGazeCalibration();
    emit gazeCalibrated(result["accuracy_mean_deg"].get<double>(), result["precision_rms_s2s_deg"].get<double>());
  } else if (!error.isEmpty()) {
    status_->setText(tr("Gaze calibration failed: %1 — Start runs it again").arg(error));
    emit stepFailed(error);
  }
  updateButtons();
  emit runStopped();
}

void CaptureWizard::showGazeCalibration() {
  const nlohmann::json right = gazeCalibration(), left = leftGazeCalibration();
  if (right.is_null()) {
    gaze_result_->clear();
    return;
  }
  auto line = [](const QString& title, const nlohmann::json& r) {
    return tr("<b>%1</b> (pupil tracker, %2 targets × %3 samples, confidence ≥ %4): accuracy "
              "<b>%5°</b> mean, %6° max; precision <b>%7°</b> RMS sample-to-sample (%8° SD) over %9 held-out "
              "targets; %10 frames, %11 rejected.")
        .arg(title)
        .arg(r["targets"].get<int>())
        .arg(r["samples_per_target"].get<int>())
        .arg(r["min_confidence"].get<double>())
        .arg(r["accuracy_mean_deg"].get<double>(), 0, 'f', 2)
        .arg(r["accuracy_max_deg"].get<double>(), 0, 'f', 2)
        .arg(r["precision_rms_s2s_deg"].get<double>(), 0, 'f', 3)
        .arg(r["precision_sd_deg"].get<double>(), 0, 'f', 3)
        .arg(r["held_out_targets"].get<int>())
        .arg(r["frames"].get<int>())
        .arg(r["rejected"].get<int>());
  };
  const QString text = left.is_null()
                           ? line(tr("Gaze calibration"), right)
                           : line(tr("Left eye camera"), left) + "<br>" + line(tr("Right eye camera"), right);
  gaze_result_->setText(text + " " + tr("Pupil Core reports 0.6° / 0.08°."));
}

bool CaptureWizard::importMeasurement(const QString& file, QString* error) {
  if (!session_ && !openSession()) {
    if (error) *error = status_->text();
    return false;
  }
  try {
    const auto path = session_->importMeasurement(file.toStdString());
    status_->setText(tr("Imported %1 as %2").arg(file, QString::fromStdString(path.string())));
    return true;
  } catch (const std::exception& e) {
    const QString m = tr("Measurement not imported: %1").arg(QString::fromStdString(e.what()));
    status_->setText(m);
    if (error) *error = m;
    return false;
  }
}

void CaptureWizard::refreshList() {
  steps_->clear();
  if (session_) {
    for (std::size_t i = 0; i < session_->plan().size(); ++i) {
      const auto& s = session_->plan()[i];
      auto* item = new QListWidgetItem((session_->done(i) ? QStringLiteral("✓ ") : QStringLiteral("   ")) +
                                       QString::number(i + 1) + ". " + QString::fromStdString(s.id));
      item->setToolTip(QString::fromStdString(s.instruction));
      steps_->addItem(item);
    }
    progress_->setRange(0, std::max(1, stepCount()));
    progress_->setValue(captured_);
  } else {
    progress_->setRange(0, 1);
    progress_->setValue(0);
  }
  updateButtons();
}

void CaptureWizard::updateButtons() {
  const bool have_bench = live_ != nullptr;
  kind_->setEnabled(!running_);
  folder_->setEnabled(!running_);
  browse_->setEnabled(!running_);
  open_->setEnabled(!running_);
  start_->setEnabled(!running_ && have_bench && (!session_ || !session_->complete()));
  start_->setText(session_ && captured_ > 0 && !session_->complete() ? tr("Resume") : tr("Start"));
  pause_->setEnabled(running_);
  import_->setEnabled(!running_ && kind() == devices::CaptureKind::Color);
}

void CaptureWizard::reject() {
  pause();
  QDialog::reject();
}

void CaptureWizard::closeEvent(QCloseEvent* event) {
  pause();  // a running step finishes and is saved; the dialog just hides
  QDialog::closeEvent(event);
}

}  // namespace fovea::widgets
