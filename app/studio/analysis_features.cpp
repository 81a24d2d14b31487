#include "app/studio/analysis_features.h"

#include <QAction>
#include <QApplication>
#include <QDialog>
#include <QDialogButtonBox>
#include <QDockWidget>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QLineEdit>
#include <QMenuBar>
#include <QMessageBox>
#include <QProgressDialog>
#include <QPushButton>
#include <QSpinBox>
#include <QStatusBar>
#include <QThread>
#include <QUndoStack>

#include <algorithm>
#include <atomic>

#include "app/studio/live_trace_features.h"
#include "app/studio/main_window.h"
#include "app/studio/report_document.h"
#include "model/scene/scene_io.h"
#include "model/vector_state.h"
#include "widgets/analyses/analyses_panel.h"
#include "widgets/autosave.h"
#include "widgets/dialog_start.h"
#include "widgets/gaze_panel.h"
#include "widgets/message_log.h"
#include "widgets/plots/plot_builders.h"
#include "widgets/plots/plots_panel.h"
#include "widgets/preferences.h"
#include "widgets/preview_panel.h"
#include "widgets/scene_document.h"

namespace fovea::studio {

using widgets::Preferences;

namespace {

QMenu* menuNamed(QMenuBar* bar, const QString& title) {
  for (QAction* a : bar->actions())
    if (a->menu() && a->text().remove('&') == title) return a->menu();
  return nullptr;
}

QAction* actionNamed(QMenu* menu, const QString& text) {
  if (!menu) return nullptr;
  for (QAction* a : menu->actions())
    if (a->text().remove('&').startsWith(text)) return a;
  return nullptr;
}

}  // namespace

AnalysisFeatures::AnalysisFeatures(MainWindow* window) : QObject(window), window_(window) {
  setObjectName("AnalysisFeatures");
  analyses_ = new widgets::AnalysesPanel(window->document(), window);
  analysesDock_ = window->addPanel(analyses_, tr("Analyses"), "AnalysesDock", Qt::RightDockWidgetArea);
  plots_ = new widgets::PlotsPanel(window);
  plots_->setDocument(window->document());  // exports open in the scene's folder
  plotsDock_ = window->addPanel(plots_, tr("Plots"), "PlotsDock", Qt::BottomDockWidgetArea);
  if (auto* props = window->findChild<QDockWidget*>("PropertiesDock")) {
    window->tabifyDockWidget(props, analysesDock_);
    props->raise();
  }
  if (auto* messages = window->findChild<QDockWidget*>("MessagesDock")) {
    window->tabifyDockWidget(messages, plotsDock_);
    messages->raise();
  }
  // Keep the foundation's dock proportions now that two more docks share the areas.
  auto* tree = window->findChild<QDockWidget*>("SceneTreeDock");
  auto* props = window->findChild<QDockWidget*>("PropertiesDock");
  if (tree && props) window->resizeDocks({tree, props}, {300, 400}, Qt::Horizontal);
  connect(analyses_, &widgets::AnalysesPanel::resultReady, this, &AnalysisFeatures::onResult);
  connect(plots_, &widgets::PlotsPanel::plotExported, this, [this](const QString& id, const QString& path) {
    window_->messageLog()->info(tr("Exported %1 to %2").arg(widgets::plotTitle(id), path));
  });
  connect(plots_, &widgets::PlotsPanel::exportFailed, this, [this](const QString& id, const QString& message) {
    window_->messageLog()->error(tr("Export of %1 failed: %2").arg(widgets::plotTitle(id), message));
  });
  createMenus();
}

AnalysisFeatures::~AnalysisFeatures() = default;

void AnalysisFeatures::createMenus() {
  QMenuBar* bar = window_->menuBar();
  QMenu* file = menuNamed(bar, "File");
  auto* report = new QAction(tr("Export &Report…"), this);
  report->setObjectName("exportReport");
  report->setShortcut(QKeySequence(tr("Ctrl+Shift+R")));
  connect(report, &QAction::triggered, this, &AnalysisFeatures::exportReportDialog);
  if (file) file->insertAction(actionNamed(file, "Quit"), report);
  if (file) file->insertSeparator(actionNamed(file, "Quit"));

  QMenu* edit = menuNamed(bar, "Edit");
  auto* prefs = new QAction(tr("&Preferences…"), this);
  prefs->setObjectName("preferences");
  prefs->setShortcut(QKeySequence::Preferences);
  prefs->setMenuRole(QAction::PreferencesRole);
  connect(prefs, &QAction::triggered, this, &AnalysisFeatures::showPreferences);
  if (edit) {
    edit->addSeparator();
    edit->addAction(prefs);
  }

  auto* menu = new QMenu(tr("&Analyses"), window_);
  menu->setObjectName("AnalysesMenu");
  QAction* run = menu->addAction(tr("&Run Selected Analysis"), this, [this] {
    analysesDock_->show();
    analysesDock_->raise();
    analyses_->run();
  });
  run->setShortcut(QKeySequence(tr("Ctrl+R")));
  menu->addAction(tr("&Cancel Analysis"), this, [this] { analyses_->cancel(); })
      ->setShortcut(QKeySequence(tr("Ctrl+.")));
  menu->addSeparator();
  for (const widgets::AnalysisSpec& s : widgets::analysisCatalog())
    menu->addAction(s.title + "…", this, [this, id = s.id] {
      analyses_->selectAnalysis(id);
      analysesDock_->show();
      analysesDock_->raise();
    });
  menu->addSeparator();
  menu->addAction(tr("Show &Plots"), this, [this] {
    plotsDock_->show();
    plotsDock_->raise();
  });
  QMenu* help = menuNamed(bar, "Help");
  bar->insertMenu(help ? help->menuAction() : nullptr, menu);
}

void AnalysisFeatures::onResult(const widgets::AnalysisResult& r) {
  if (!r.json) return;
  const widgets::AnalysisSpec* spec = widgets::findAnalysis(r.id);
  const QString command = spec ? widgets::cliCommandLine(*spec, r.params, window_->document()->filePath()) : QString();
  const QString source = command.isEmpty() ? r.id : command;  // no command for an unsaved scene
  plots_->showResult(r.id, *r.json, source);
  if (spec && !spec->plots.isEmpty()) {
    plotsDock_->show();
    plotsDock_->raise();
    if (!plotsDock_->isFloating() && plotsDock_->height() < 360)
      window_->resizeDocks({plotsDock_}, {std::max(360, window_->height() * 2 / 5)}, Qt::Vertical);
  }
  window_->messageLog()->info(tr("%1 finished in %2 s").arg(spec ? spec->title : r.id).arg(r.seconds, 0, 'f', 1));
}

void AnalysisFeatures::startSession(const QString& recoveryDir, bool offer) {
  Preferences::instance().load();
  recoveryDir_ = recoveryDir.isEmpty() ? widgets::Autosaver::defaultDirectory() : recoveryDir;
  // This session's autosaver first: its lock keeps its own files from ever looking orphaned,
  // and a recovered scene is then autosaved by this session.
  autosaver_ = std::make_unique<widgets::Autosaver>(window_->document(), recoveryDir_);
  autosaver_->setIntervalSeconds(Preferences::instance().values().autosaveSeconds);
  connect(&Preferences::instance(), &Preferences::changed, autosaver_.get(),
          [a = autosaver_.get()] { a->setIntervalSeconds(Preferences::instance().values().autosaveSeconds); });
  connect(autosaver_.get(), &widgets::Autosaver::autosaveFailed, this,
          [this](const QString& m) { window_->messageLog()->warning(m); });
  if (offer) offerRecovery(recoveryDir_);
}

int AnalysisFeatures::offerRecovery(const QString& recoveryDir) {
  int recovered = 0;
  for (const widgets::RecoveryEntry& e : widgets::Autosaver::findOrphans(recoveryDir)) {
    QMessageBox box(QMessageBox::Warning, tr("Recover unsaved changes?"),
                    tr("Foveated AR Studio did not close normally. Unsaved changes to <b>%1</b> were autosaved at "
                       "%2.")
                        .arg(e.displayName.toHtmlEscaped(), e.savedAt.toLocalTime().toString("yyyy-MM-dd HH:mm:ss")),
                    QMessageBox::NoButton, window_);
    box.setObjectName("RecoveryOffer");
    box.setInformativeText(e.originalPath.isEmpty()
                               ? tr("The scene had never been saved.")
                               : tr("Recovering opens %1 with the changes applied, unsaved (Undo goes back to the "
                                    "file).")
                                     .arg(e.originalPath.toHtmlEscaped()));
    QPushButton* rec = box.addButton(tr("Recover"), QMessageBox::AcceptRole);
    rec->setObjectName("recover");
    QPushButton* dis = box.addButton(tr("Discard"), QMessageBox::DestructiveRole);
    dis->setObjectName("discard");
    QPushButton* later = box.addButton(tr("Later"), QMessageBox::RejectRole);
    later->setObjectName("later");
    box.setDefaultButton(rec);
    box.exec();
    if (box.clickedButton() == rec) {
      if (recover(e)) ++recovered;
    } else if (box.clickedButton() == dis) {
      widgets::Autosaver::discard(e);
      window_->messageLog()->info(tr("Discarded the autosaved changes to %1").arg(e.displayName));
    }
  }
  return recovered;
}

bool AnalysisFeatures::recover(const widgets::RecoveryEntry& e) {
  QString error;
  const std::optional<Scene> scene = widgets::Autosaver::loadEntry(e, &error);
  if (!scene) {
    window_->messageLog()->error(tr("The recovery file %1 cannot be read (%2); it is kept.").arg(e.scenePath, error));
    return false;
  }
  widgets::SceneDocument* doc = window_->document();
  const SceneLoadResult original =
      e.originalPath.isEmpty() ? SceneLoadResult{} : loadSceneFile(e.originalPath.toStdString());
  if (original.ok()) {
    doc->resetTo(*original.scene, QFileInfo(e.originalPath).absoluteFilePath());
    const QStringList problems = doc->applyEdit(tr("Recovered unsaved changes"), [&](Scene& s) { s = *scene; });
    if (!problems.isEmpty()) {
      window_->messageLog()->error(problems.join("; "));
      return false;
    }
  } else {
    doc->resetTo(*scene, e.originalPath, e.displayName);
  }
  if (!doc->isModified()) doc->undoStack()->push(new QUndoCommand(tr("Recovered unsaved changes")));
  widgets::Autosaver::discard(e);
  if (autosaver_) autosaver_->saveNow();  // now owned by this session
  window_->messageLog()->info(tr("Recovered the unsaved changes to %1 (autosaved %2)")
                                  .arg(e.displayName, e.savedAt.toLocalTime().toString("yyyy-MM-dd HH:mm:ss")));
  return true;
}

void AnalysisFeatures::showPreferences() {
  widgets::PreferencesDialog dialog(window_);
  dialog.exec();
}

namespace {
constexpr int kReportProgressSteps = 1200;
}  // namespace

bool AnalysisFeatures::exportReport(const QString& path, const ReportOptions& requested, QString* error, int* pages,
                                    int* figures, QList<GazeFigureStats>* gazeFigures, QStringList* sections,
                                    nlohmann::json* eyes) {
  ReportOptions options = requested;
  if (window_->liveTraceFeatures() && window_->liveTraceFeatures()->gazePanel()->followGaze())
    options.follow_gaze = true;
  // The report's retinal image takes the Foveated preview's Retina image options.
  if (const widgets::PreviewPanel* preview = window_->previewPanel()) options.retina = preview->retinaOptions();
  const Scene scene = window_->document()->scene();
  const QString scenePath = window_->document()->filePath();
  auto cancel = std::make_shared<std::atomic<bool>>(false);
  auto permille = std::make_shared<std::atomic<int>>(0);
  std::optional<ReportData> data;
  QString failure;
  QThread* worker = QThread::create([&, cancel, permille] {
    clearUpperVectorState();  // inherited from the GUI thread (model/vector_state.h)
    StudyControl c;
    c.cancel = cancel.get();
    c.on_progress = [permille](double f) { permille->store(static_cast<int>(f * 1000)); };
    try {
      data = computeReportData(scene, scenePath, options, c);
    } catch (const std::exception& e) {
      failure = QString::fromUtf8(e.what());
    }
  });
  // Progress over the whole export: the analyses (0..1000 of the worker's progress), the
  // figures (1000..1100), writing the file (1100..1200); Cancel stops before the next step.
  // Shown for File ▸ Export Report… always: right after the save dialog closes the window may
  // not be active again yet (focus comes back asynchronously), and the check alone skipped it.
  std::unique_ptr<QProgressDialog> progress;
  if (fromDialog_ || (window_->isVisible() && window_->isActiveWindow())) {
    progress = std::make_unique<QProgressDialog>(tr("Computing the report's analyses…"), tr("Cancel"), 0,
                                                 kReportProgressSteps, window_);
    progress->setObjectName("reportProgress");
    progress->setWindowModality(Qt::WindowModal);
    // At once, not after QProgressDialog's estimate: when the analyses come back quickly the
    // estimate kept it hidden through "composing the figures" (a flaky gui.tst_report_export).
    progress->setMinimumDuration(0);
    progress->show();
  }
  window_->statusBar()->showMessage(tr("Writing the report %1… (computing its analyses)").arg(path));
  worker->start();
  while (!worker->isFinished()) {
    QApplication::processEvents(QEventLoop::AllEvents, 30);
    if (progress) {
      progress->setValue(permille->load());
      if (progress->wasCanceled()) cancel->store(true);
    }
    QThread::msleep(5);
  }
  worker->wait();
  delete worker;
  auto fail = [&](const QString& m) {
    progress.reset();
    if (error) *error = m;
    window_->messageLog()->error(tr("Report not written: %1").arg(m));
    window_->statusBar()->showMessage(tr("Report not written: %1").arg(m), 8000);
    return false;
  };
  auto step = [&](int value, const QString& label) {  // false: cancelled
    window_->statusBar()->showMessage(tr("Writing the report %1… (%2)").arg(path, label));
    if (!progress) return true;
    progress->setLabelText(label);
    progress->setValue(value);
    QApplication::processEvents();
    return !progress->wasCanceled();
  };
  if (!failure.isEmpty()) return fail(failure);
  if (!data) return fail(tr("cancelled"));
  // A tolerance result of this very scene from the analyses panel gives the Tolerance section.
  const std::string sceneText = serializeScene(data->scene);  // the left eye's own for a left-eye report
  if (data->tolerance.is_null())
    if (const auto r = analyses_->lastResult("tolerance"); r && r->json && r->sceneText == sceneText)
      data->tolerance = *r->json;
  if (!step(1000, tr("composing the figures"))) return fail(tr("cancelled"));

  // Plots filled in the studio for this very scene (or scene-independent ones) join the report.
  QList<widgets::PlotData> extra;
  for (const QString& id : plots_->filledPlots())
    for (const QString& a : widgets::plotSources(id)) {
      const auto r = analyses_->lastResult(a);
      if (r && (r->sceneText == sceneText || a == "grating" || a == "kogelnik-vs-rcwa")) {
        extra << plots_->plot(id);
        break;
      }
    }
  const ReportContent content = composeReport(*window_, *data, extra, Preferences::instance().units());
  if (!step(1100, tr("writing %1").arg(QFileInfo(path).fileName()))) return fail(tr("cancelled"));
  QString writeError;
  if (!writeReport(content, path, &writeError, pages)) return fail(writeError);
  step(kReportProgressSteps, tr("done"));
  progress.reset();
  window_->statusBar()->showMessage(tr("Report saved to %1").arg(path), 10000);
  if (figures) *figures = content.figureCount();
  if (gazeFigures) *gazeFigures = content.gazeFigures;
  if (sections) {
    sections->clear();
    for (const ReportSection& sec : content.sections) *sections << sec.heading;
  }
  if (eyes) {
    *eyes = nullptr;
    if (!content.eye.isEmpty()) *eyes = {{"eye", content.eye.toStdString()}};
    if (content.eyes.is_object()) *eyes = {{"eyes", content.eyes}};
  }
  window_->messageLog()->info(tr("Report saved to %1 (%n figure(s))", "", content.figureCount()).arg(path));
  for (const QString& p : data->problems) window_->messageLog()->warning(tr("report: %1").arg(p));
  return true;
}

void AnalysisFeatures::exportReportDialog() {
  QDialog dialog(window_);
  dialog.setWindowTitle(tr("Export Report"));
  auto* form = new QFormLayout(&dialog);
  auto* gazes = new QLineEdit(&dialog);
  const auto g = window_->document()->scene().eye.gaze_deg;
  gazes->setText(QString("%1,%2; -10,0; 10,0").arg(g[0]).arg(g[1]));
  gazes->setToolTip(tr("Gazes for the ray/retina figures: yaw[,pitch] in degrees, separated by ';'"));
  auto* rays = new QSpinBox(&dialog);
  rays->setRange(50, 1000000);
  rays->setValue(Preferences::instance().values().defaultRays);
  form->addRow(tr("Gazes (deg)"), gazes);
  form->addRow(tr("Rays per wavelength"), rays);
  auto* tolerance = new QSpinBox(&dialog);
  tolerance->setObjectName("reportToleranceTrials");
  tolerance->setRange(0, 1000000);
  tolerance->setSpecialValueText(tr("none"));
  tolerance->setToolTip(
      tr("Run the tolerance analysis (the shipped default spec) with this many trials for the "
         "report's Tolerance section; a tolerance result already computed for this scene in "
         "the Analyses panel is used as it is."));
  const auto last = analyses_->lastResult("tolerance");
  const bool haveTolerance = last && last->json && last->sceneText == serializeScene(window_->document()->scene());
  tolerance->setValue(0);
  form->addRow(haveTolerance ? tr("Tolerance trials (a result is there)") : tr("Tolerance trials"), tolerance);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, &dialog);
  connect(buttons, &QDialogButtonBox::accepted, &dialog, &QDialog::accept);
  connect(buttons, &QDialogButtonBox::rejected, &dialog, &QDialog::reject);
  form->addRow(buttons);
  if (dialog.exec() != QDialog::Accepted) return;
  ReportOptions options;
  options.rays = rays->value();
  options.tolerance = tolerance->value() > 0 && !haveTolerance;
  options.tolerance_trials = std::max(1, tolerance->value());
  for (const QString& part : gazes->text().split(';', Qt::SkipEmptyParts)) {
    std::array<double, 2> gz{};
    if (!parseGaze(part, &gz)) {
      QMessageBox::warning(window_, tr("Export Report"), tr("Not a gaze: \"%1\" (yaw[,pitch] in degrees)").arg(part));
      return;
    }
    options.gazes_deg << gz;
  }
  const QString base = QFileInfo(window_->document()->displayName()).completeBaseName();
  const QString path = QFileDialog::getSaveFileName(window_, tr("Export report"),
                                                    widgets::dialogStart(window_->document(), base + "-report.pdf"),
                                                    tr("PDF documents (*.pdf);;HTML pages (*.html)"));
  if (path.isEmpty()) return;
  QString error;
  fromDialog_ = true;
  const bool written = exportReport(path, options, &error);
  fromDialog_ = false;
  if (!written && error != tr("cancelled"))
    QMessageBox::critical(window_, tr("Export Report"), tr("The report could not be written: %1").arg(error));
}

}  // namespace fovea::studio
