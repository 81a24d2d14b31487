#include "app/studio/main_window.h"

#include <QAction>
#include <QApplication>
#include <QCloseEvent>
#include <QDockWidget>
#include <QFileDialog>
#include <QFileInfo>
#include <QLabel>
#include <QMenuBar>
#include <QMessageBox>
#include <QScreen>
#include <QSettings>
#include <QShortcut>
#include <QStatusBar>
#include <QTimer>
#include <QUndoStack>

#include "app/embedded_scene.h"
#include "app/studio/about_text.h"
#include "app/studio/analysis_features.h"
#include "app/studio/dock_layout.h"
#include "app/studio/help_dialogs.h"
#include "app/studio/live_trace_features.h"
#include "app/studio/undo_shortcuts.h"
#include "app/studio/window_capture.h"
#include "model/scene/scene_io.h"
#include "model/vector_state.h"
#include "viz/scene_view.h"
#include "widgets/bench/devices_panel.h"
#include "widgets/dialog_start.h"
#include "widgets/focus_ring.h"
#include "widgets/message_log.h"
#include "widgets/preview_panel.h"
#include "widgets/property_editor.h"
#include "widgets/scene_document.h"
#include "widgets/scene_tree.h"
#include "widgets/wheel_guard.h"

// The resources live in the static fovea_app library: register them explicitly.
static void initStudioResources() {
  Q_INIT_RESOURCE(resources);
}

namespace fovea::studio {

namespace {
constexpr int kMaxRecent = 8;
// Saved dock states of an older arrangement are not restored (version 1 stacked three
// groups in the right column and did not fit a 1080-line screen).
constexpr int kDockLayoutVersion = 2;
bool benchAutoStart = true;
const char* kSceneFilter = "Scene files (*.json);;All files (*)";
}  // namespace

MainWindow::MainWindow(QWidget* parent) : QMainWindow(parent) {
  initStudioResources();
  // TBB workers start from the GUI thread's dirty AVX state: cleared as each joins
  // (model/vector_state.h; also for the GUI tests, which make windows without main()).
  clearUpperVectorState();
  clearUpperVectorStateOnTbbThreads();
  // Before any field exists: the wheel changes a spin box, combo or slider of any dock or
  // dialog only while it has the focus (widgets/wheel_guard.h).
  widgets::installWheelGuard();
  // A keyboard focus that shows: Tab from the 3-D view (or any widget that draws no focus of
  // its own) rings the widget it reaches (widgets/focus_ring.h).
  widgets::installFocusRing();
  setObjectName("MainWindow");
  setWindowIcon(QIcon(":/icons/fovea-studio.svg"));
  document_ = new widgets::SceneDocument(this);
  view_ = new viz::SceneView(this);
  view_->setObjectName("SceneView");
  setCentralWidget(view_);
  createDocks();
  createMenus();
  analysisFeatures_ = new AnalysisFeatures(this);
  statusBar()->showMessage(tr("Drag: orbit · Shift+drag or middle: pan · wheel or right-drag: zoom · click: select"));

  connect(document_, &widgets::SceneDocument::sceneChanged, this, [this] { view_->setScene(document_->scene()); });
  connect(document_, &widgets::SceneDocument::sceneReplaced, this, [this] {
    view_->setScene(document_->scene(), true);
    selectElement({});
  });
  connect(document_, &widgets::SceneDocument::modifiedChanged, this, [this] { updateTitle(); });
  connect(document_, &widgets::SceneDocument::filePathChanged, this, [this] { updateTitle(); });
  connect(tree_, &widgets::SceneTree::elementSelected, this, &MainWindow::selectElement);
  connect(view_, &viz::SceneView::elementPicked, this, &MainWindow::selectElement);
  connect(properties_, &widgets::PropertyEditor::editRefused, this,
          [this](const QString&, const QString& message) { log_->warning(tr("edit refused: %1").arg(message)); });
  connect(document_->undoStack(), &QUndoStack::indexChanged, this, [this] {
    const QUndoStack* s = document_->undoStack();
    if (s->index() > 0) statusBar()->showMessage(s->text(s->index() - 1), 4000);
  });
  resize(initialWindowSize());
  openEmbeddedDefault();
  liveTraceFeatures_ = new LiveTraceFeatures(this);
  applyDefaultDockLayout(this);
  // Ctrl+Z / Ctrl+Y reach the document's undo stack from any focus, property fields included.
  qApp->installEventFilter(new DocumentUndoShortcuts(this));
}

QSize MainWindow::initialWindowSize() const {
  // 1400 x 900 where the screen has room, else 94 % of its free area (a 1366 x 768 laptop).
  const QScreen* s = screen() ? screen() : QGuiApplication::primaryScreen();
  if (!s) return {1400, 900};
  const QRect free = s->availableGeometry();
  return {std::min(1400, free.width() * 94 / 100), std::min(900, free.height() * 90 / 100)};
}

void MainWindow::resetLayout() {
  applyDefaultDockLayout(this);
  view_->resetCamera();
}

MainWindow::~MainWindow() {
  // The document is a child: ~QWidget deletes it after this object is no MainWindow any more,
  // and its undo stack's clear() then emits indexChanged into the lambdas above (UBSan: member
  // access on a QWidget; the status bar touched mid-destruction corrupted the heap under load).
  QObject::disconnect(document_, nullptr, this, nullptr);
  QObject::disconnect(document_->undoStack(), nullptr, this, nullptr);
}

void MainWindow::setBenchAutoStart(bool on) {
  benchAutoStart = on;
}

void MainWindow::createDocks() {
  tree_ = new widgets::SceneTree(document_, this);
  addPanel(tree_, tr("Scene"), "SceneTreeDock", Qt::LeftDockWidgetArea);
  properties_ = new widgets::PropertyEditor(document_, this);
  addPanel(properties_, tr("Properties"), "PropertiesDock", Qt::RightDockWidgetArea);
  log_ = new widgets::MessageLog(this);
  addPanel(log_, tr("Messages"), "MessagesDock", Qt::BottomDockWidgetArea);
  preview_ = new widgets::PreviewPanel(document_, this);
  QDockWidget* preview = addPanel(preview_, tr("Foveated preview"), "PreviewDock", Qt::RightDockWidgetArea);
  previewDock_ = preview;
  // The bench: a tab behind the preview (its camera runs only while the tab is shown).
  widgets::DevicesPanelOptions bench;
  bench.auto_connect = benchAutoStart;
  devices_ = new widgets::DevicesPanel(document_, this, bench);
  devicesDock_ = addPanel(devices_, tr("Bench"), "DevicesDock", Qt::RightDockWidgetArea);
  tabifyDockWidget(preview, devicesDock_);
  preview->raise();
  // The Bench panel's axis rows (position, state, jog, Home, go-to, Go) are wider than the
  // default right column: shown (or given its rows, below), it widens the column to fit, as
  // far as the 3-D view keeps 30 % of the window (issue 27: at 1920 x 1080 Home, go-to and
  // Go were cut off behind a horizontal scroll bar).
  connect(devicesDock_, &QDockWidget::visibilityChanged, this, [this](bool visible) {
    if (visible) QTimer::singleShot(0, this, [this] { widenDockToFit(this, devicesDock_); });
  });
  benchStatus_ = new QLabel(this);
  benchStatus_->setObjectName("benchStatusBarLabel");
  statusBar()->addPermanentWidget(benchStatus_);
  benchStatus_->hide();
  connect(devices_, &widgets::DevicesPanel::benchConnected, this, [this](bool is_virtual) {
    // The axis rows exist from now on: fit the column to them if the dock is in view.
    QTimer::singleShot(0, this, [this] { widenDockToFit(this, devicesDock_); });
    benchStatus_->setText(is_virtual ? tr(" VIRTUAL BENCH ") : tr(" Bench: hardware "));
    benchStatus_->setToolTip(is_virtual ? tr("No stage controller of the scene is plugged in: the stages and the eye "
                                             "camera are simulated (View ▸ Bench)")
                                        : tr("Stage controllers on USB"));
    benchStatus_->setStyleSheet(is_virtual ? "QLabel { background: #e68a00; color: black; font-weight: bold; }"
                                           : "QLabel { background: #2e7d32; color: white; font-weight: bold; }");
    benchStatus_->show();
  });
  connect(devices_, &widgets::DevicesPanel::benchDisconnected, this, [this] { benchStatus_->hide(); });
  // The bench's refusals, stops and errors also go to the Messages dock (the routine "done"
  // of each jog stays in the Bench dock's status line).
  connect(devices_, &widgets::DevicesPanel::message, this, [this](const QString& text, bool error) {
    if (error)
      log_->error(tr("Bench: %1").arg(text));
    else if (!text.endsWith(tr(" done")))
      log_->info(tr("Bench: %1").arg(text));
  });
  // Esc in the 3-D view is the e-stop too (the panel has its own; dialogs keep theirs).
  auto* esc = new QShortcut(QKeySequence(Qt::Key_Escape), view_);
  esc->setContext(Qt::WidgetWithChildrenShortcut);
  esc->setWhatsThis(tr("Emergency stop of every axis"));
  esc->setProperty("where", tr("3-D view"));
  connect(esc, &QShortcut::activated, devices_, &widgets::DevicesPanel::emergencyStop);
  resizeDocks({findChild<QDockWidget*>("SceneTreeDock"), findChild<QDockWidget*>("PropertiesDock")}, {300, 380},
              Qt::Horizontal);
  resizeDocks({findChild<QDockWidget*>("MessagesDock")}, {130}, Qt::Vertical);
}

QDockWidget* MainWindow::addPanel(QWidget* panel, const QString& title, const QString& objectName,
                                  Qt::DockWidgetArea area) {
  auto* dock = new QDockWidget(title, this);
  dock->setObjectName(objectName);
  dock->setWidget(scrollableDockContent(panel));
  addDockWidget(area, dock);
  if (panelsMenu_) panelsMenu_->addAction(dock->toggleViewAction());
  return dock;
}

void MainWindow::createMenus() {
  QMenu* file = menuBar()->addMenu(tr("&File"));
  file->addAction(tr("&New"), QKeySequence::New, this, &MainWindow::newScene);
  file->addAction(tr("&Open…"), QKeySequence::Open, this, &MainWindow::openDialog);
  recentMenu_ = file->addMenu(tr("Open &Recent"));
  connect(recentMenu_, &QMenu::aboutToShow, this, &MainWindow::fillRecentMenu);
  file->addSeparator();
  file->addAction(tr("&Save"), QKeySequence::Save, this, &MainWindow::save);
  file->addAction(tr("Save &As…"), QKeySequence::SaveAs, this, &MainWindow::saveAsDialog);
  file->addSeparator();
  file->addAction(tr("Export Screens&hot…"), QKeySequence(tr("Ctrl+E")), this, &MainWindow::exportScreenshotDialog);
  file->addSeparator();
  file->addAction(tr("&Quit"), QKeySequence::Quit, this, &QWidget::close);

  QMenu* edit = menuBar()->addMenu(tr("&Edit"));
  QAction* undo = document_->undoStack()->createUndoAction(this, tr("&Undo"));
  undo->setShortcut(QKeySequence::Undo);
  QAction* redo = document_->undoStack()->createRedoAction(this, tr("&Redo"));
  // Ctrl+Shift+Z (the X11 standard) and Ctrl+Y (what users of other platforms press).
  redo->setShortcuts({QKeySequence(QKeySequence::Redo), QKeySequence(tr("Ctrl+Y"))});
  edit->addAction(undo);
  edit->addAction(redo);

  viewMenu_ = menuBar()->addMenu(tr("&View"));
  using SV = viz::StandardView;
  auto addView = [this](const QString& name, const QString& keys, SV v) {
    viewMenu_->addAction(name, QKeySequence(keys), this, [this, v] { view_->showStandardView(v); });
  };
  addView(tr("&Isometric"), tr("Ctrl+0"), SV::Isometric);
  addView(tr("&Top"), tr("Ctrl+1"), SV::Top);
  addView(tr("&Side"), tr("Ctrl+2"), SV::Side);
  addView(tr("&Eye's View"), tr("Ctrl+3"), SV::EyeView);
  viewMenu_->addAction(tr("&Reset Camera"), QKeySequence(tr("Home")), this, [this] { view_->resetCamera(); });
  labelsAction_ = viewMenu_->addAction(tr("Element &Labels"));
  labelsAction_->setObjectName("labelsAction");
  labelsAction_->setShortcut(QKeySequence(tr("Ctrl+L")));
  labelsAction_->setCheckable(true);
  labelsAction_->setChecked(view_->labelsVisible());
  labelsAction_->setToolTip(tr("Names of the projector, HOE, eye, micro-OLED, combiner and lens in the 3-D view"));
  connect(labelsAction_, &QAction::toggled, this, [this](bool on) {
    view_->setLabelsVisible(on);
    if (persistSettings_) QSettings().setValue("view/labels", on);
  });
  viewMenu_->addAction(tr("Reset &Layout"), this, &MainWindow::resetLayout);
  viewMenu_->addSeparator();
  panelsMenu_ = viewMenu_->addMenu(tr("&Panels"));
  for (QDockWidget* dock : findChildren<QDockWidget*>()) panelsMenu_->addAction(dock->toggleViewAction());

  createBenchMenu();

  QMenu* help = menuBar()->addMenu(tr("&Help"));
  help->addAction(tr("&User Guide"), QKeySequence::HelpContents, this, [this] { showUserGuide(this); })
      ->setObjectName("userGuideAction");
  help->addAction(tr("&Keyboard Shortcuts"), QKeySequence(tr("Ctrl+/")), this, [this] { showKeyboardShortcuts(this); })
      ->setObjectName("shortcutsAction");
  help->addSeparator();
  help->addAction(tr("&About Foveated AR Studio"), this, &MainWindow::showAbout);
  help->addAction(tr("About &Qt"), qApp, &QApplication::aboutQt);
}

void MainWindow::createBenchMenu() {
  QMenu* menu = menuBar()->addMenu(tr("&Bench"));
  menu->addAction(tr("Show &Bench Panel"), QKeySequence(tr("Ctrl+B")), this, [this] {
    devicesDock_->show();
    devicesDock_->raise();
    devices_->setFocus();
  });
  menu->addSeparator();
  menu->addAction(tr("&Connect"), devices_, &widgets::DevicesPanel::connectBench);
  menu->addAction(tr("&Disconnect"), devices_, &widgets::DevicesPanel::disconnectBench);
  menu->addAction(tr("&Home All Axes"), devices_, &widgets::DevicesPanel::homeAll);
  // Shown with its key; the key itself is the panel's and the 3-D view's shortcut.
  QAction* stop = menu->addAction(tr("&Emergency Stop\tEsc"), devices_, &widgets::DevicesPanel::emergencyStop);
  stop->setToolTip(tr("Immediate stop of every axis"));
  menu->addSeparator();
  menu->addAction(tr("Calibration &Capture…"), this, [this] {
    devicesDock_->show();
    devicesDock_->raise();
    devices_->openCaptureWizard();
  });
}

void MainWindow::openEmbeddedDefault() {
  SceneLoadResult r = parseScene(embeddedDefaultSceneJson(), std::string(kEmbeddedSceneName));
  if (!r.ok()) {  // cannot happen: a test keeps the embedded scene valid
    for (const auto& e : r.errors) log_->error(QString::fromStdString(e));
    return;
  }
  document_->resetTo(*r.scene, {}, QString::fromUtf8(kEmbeddedSceneName.data(), kEmbeddedSceneName.size()));
  log_->info(tr("Opened the default scene: %1").arg(QString::fromStdString(sceneSummary(*r.scene))));
}

bool MainWindow::openFile(const QString& path, bool interactive) {
  SceneLoadResult r = loadSceneFile(path.toStdString());
  for (const auto& w : r.warnings) log_->warning(QString::fromStdString(w));
  if (!r.ok()) {
    QStringList problems;
    for (const auto& e : r.errors) {
      problems << QString::fromStdString(e);
      log_->error(problems.back());
    }
    log_->error(
        tr("%1 was not opened (%n problem(s)); the current scene is unchanged.", "", problems.size()).arg(path));
    if (interactive) {
      QMessageBox box(QMessageBox::Warning, tr("Cannot open scene"),
                      tr("%1 has %n problem(s); the current scene is unchanged.", "", problems.size()).arg(path),
                      QMessageBox::Ok, this);
      box.setDetailedText(problems.join('\n'));
      box.setInformativeText(problems.mid(0, 8).join('\n'));
      box.exec();
    }
    return false;
  }
  document_->resetTo(*r.scene, QFileInfo(path).absoluteFilePath());
  addRecent(QFileInfo(path).absoluteFilePath());
  log_->info(tr("Opened %1: %2").arg(path, QString::fromStdString(sceneSummary(*r.scene))));
  return true;
}

bool MainWindow::saveTo(const QString& path, bool interactive) {
  // The save code of the CLI (model/scene/scene_io.h): atomic, through symlinks, and its
  // temporary files are the ones the next open finds and removes if a save was killed.
  QString error;
  try {
    writeFileAtomic(path.toStdString(), serializeScene(document_->scene()));
  } catch (const SceneIoError& e) {
    error = QString::fromStdString(e.what());
  }
  if (!error.isEmpty()) {
    const QString message = tr("Saving %1 failed (%2); any existing file is unchanged.").arg(path, error);
    log_->error(message);
    if (interactive) QMessageBox::critical(this, tr("Save failed"), message);
    return false;
  }
  document_->markSaved(QFileInfo(path).absoluteFilePath());
  addRecent(QFileInfo(path).absoluteFilePath());
  log_->info(tr("Saved %1").arg(path));
  return true;
}

void MainWindow::newScene() {
  if (!maybeDiscardChanges()) return;
  SceneLoadResult r = parseScene(embeddedDefaultSceneJson(), "new scene");
  if (!r.ok()) return;
  r.scene->name = "untitled";
  document_->resetTo(*r.scene, {}, "untitled.json");
  log_->info(tr("New scene from the prototype bench template"));
}

void MainWindow::openDialog() {
  if (!maybeDiscardChanges()) return;
  const QString path =
      QFileDialog::getOpenFileName(this, tr("Open scene"), widgets::dialogStart(document_), tr(kSceneFilter));
  if (!path.isEmpty()) openFile(path);
}

bool MainWindow::save() {
  if (document_->filePath().isEmpty()) return saveAsDialog();
  return saveTo(document_->filePath());
}

bool MainWindow::saveAsDialog() {
  const QString suggestion = widgets::dialogStart(
      document_, document_->filePath().isEmpty() ? document_->displayName().section(' ', 0, 0) : document_->filePath());
  const QString path = QFileDialog::getSaveFileName(this, tr("Save scene as"), suggestion, tr(kSceneFilter));
  return !path.isEmpty() && saveTo(path);
}

void MainWindow::exportScreenshotDialog() {
  const QString path = QFileDialog::getSaveFileName(
      this, tr("Export screenshot"), widgets::dialogStart(document_, "fovea-studio.png"), tr("PNG images (*.png)"));
  if (path.isEmpty()) return;
  if (captureWindow().save(path, "PNG"))
    log_->info(tr("Screenshot saved to %1").arg(path));
  else
    log_->error(tr("Could not write the screenshot %1").arg(path));
}

void MainWindow::showAbout() {
  QMessageBox::about(this, tr("About Foveated AR Studio"), versionsHtml());
}

bool MainWindow::maybeDiscardChanges() {
  if (!document_->isModified()) return true;
  const auto answer = QMessageBox::warning(
      this, tr("Unsaved changes"), tr("%1 has unsaved changes. Save them?").arg(document_->displayName()),
      QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel, QMessageBox::Save);
  if (answer == QMessageBox::Save) return save();
  return answer == QMessageBox::Discard;
}

void MainWindow::closeEvent(QCloseEvent* event) {
  if (!maybeDiscardChanges()) {
    event->ignore();
    return;
  }
  saveSettings();
  event->accept();
}

void MainWindow::selectElement(const QString& id) {
  selected_ = id;
  tree_->setSelectedElement(id);
  view_->setSelectedElement(id);
  properties_->showElement(id);
  // A selection is for editing: bring the properties forward (it may be behind a tab).
  if (!id.isEmpty())
    if (auto* dock = findChild<QDockWidget*>("PropertiesDock"); dock && dock->isVisible()) dock->raise();
}

QImage MainWindow::captureWindow() {
  return captureWithOpenGl(this);
}

void MainWindow::updateTitle() {
  setWindowTitle(document_->displayName() + "[*] — Foveated AR Studio");
  setWindowModified(document_->isModified());
}

void MainWindow::addRecent(const QString& path) {
  recent_.removeAll(path);
  recent_.prepend(path);
  while (recent_.size() > kMaxRecent) recent_.removeLast();
  if (persistSettings_) QSettings().setValue("recentFiles", recent_);
}

void MainWindow::fillRecentMenu() {
  recentMenu_->clear();
  for (const QString& path : recent_) {
    recentMenu_->addAction(QFileInfo(path).fileName() + "   " + QFileInfo(path).absolutePath(), this, [this, path] {
      if (maybeDiscardChanges()) openFile(path);
    });
  }
  if (recent_.isEmpty()) recentMenu_->addAction(tr("(none)"))->setEnabled(false);
}

void MainWindow::restoreSettings() {
  if (!persistSettings_) return;
  QSettings s;
  restoreGeometry(s.value("window/geometry").toByteArray());
  restoreState(s.value("window/state").toByteArray(), kDockLayoutVersion);
  recent_ = s.value("recentFiles").toStringList();
  labelsAction_->setChecked(s.value("view/labels", true).toBool());
}

void MainWindow::saveSettings() {
  if (!persistSettings_) return;
  QSettings s;
  s.setValue("window/geometry", saveGeometry());
  s.setValue("window/state", saveState(kDockLayoutVersion));
  s.setValue("recentFiles", recent_);
}

}  // namespace fovea::studio
