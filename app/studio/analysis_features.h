#pragma once
// The studio's analysis features around the main window, kept out of main_window.cpp: the
// Analyses and Plots docks, the Analyses menu, Preferences, File ▸ Export Report…, autosave
// and crash recovery. Created by MainWindow; everything it adds goes through the window's
// public API (addPanel, menus found by name).

#include <QObject>
#include <QPointer>

#include <memory>

#include "app/studio/report_data.h"
#include "app/studio/report_document.h"

class QDockWidget;
class QMenu;

namespace fovea::widgets {
class AnalysesPanel;
class PlotsPanel;
class Autosaver;
struct RecoveryEntry;
struct AnalysisResult;
}  // namespace fovea::widgets

namespace fovea::studio {

class MainWindow;

class AnalysisFeatures : public QObject {
  Q_OBJECT
 public:
  explicit AnalysisFeatures(MainWindow* window);
  ~AnalysisFeatures() override;

  widgets::AnalysesPanel* analysesPanel() const { return analyses_; }
  widgets::PlotsPanel* plotsPanel() const { return plots_; }
  widgets::Autosaver* autosaver() const { return autosaver_.get(); }

  // Interactive sessions: preferences from QSettings, autosave into `recoveryDir` (default
  // Autosaver::defaultDirectory()), then the recovery offer for what a crashed session left.
  void startSession(const QString& recoveryDir = {}, bool offerRecovery = true);
  // Offers every orphaned recovery file (Recover / Discard / Later); returns how many were
  // recovered. Recovering replaces the open scene: the saved file (when it still loads) with
  // the recovered changes as one undoable step on top, marked unsaved.
  int offerRecovery(const QString& recoveryDir);
  bool recover(const widgets::RecoveryEntry& entry);

  // Computes and writes a report of the open scene (blocking, with events processed; the
  // analyses run on a worker thread). False with `error` set on failure or cancel.
  // "HOE follows gaze" of the gaze panel applies to the report's traces too. `gazeFigures`
  // gets what each "bench at the gaze" figure drew, `sections` the headings of the report's
  // sections. A tolerance result of the Analyses panel for this scene gives the Tolerance section.
  // `eyes` gets, for a binocular scene, the manifest's "eye" ("left"/"right": a report of that
  // eye) or "eyes" (each eye's key numbers, ReportData::eyes) as an object; else null.
  bool exportReport(const QString& path, const ReportOptions& options, QString* error = nullptr, int* pages = nullptr,
                    int* figures = nullptr, QList<GazeFigureStats>* gazeFigures = nullptr,
                    QStringList* sections = nullptr, nlohmann::json* eyes = nullptr);

  void showPreferences();
  void exportReportDialog();

 private:
  void createMenus();
  void onResult(const widgets::AnalysisResult& result);

  MainWindow* window_;
  widgets::AnalysesPanel* analyses_ = nullptr;
  widgets::PlotsPanel* plots_ = nullptr;
  QDockWidget* analysesDock_ = nullptr;
  QDockWidget* plotsDock_ = nullptr;
  std::unique_ptr<widgets::Autosaver> autosaver_;
  QString recoveryDir_;
  bool fromDialog_ = false;  // exportReport() runs for File ▸ Export Report…: show its progress
};

}  // namespace fovea::studio
