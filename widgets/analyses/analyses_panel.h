#pragma once
// The analyses panel: pick an analysis (every analysis of fovea-cli, analysis_catalog.h),
// edit its parameters (the CLI's flags, with units and ranges), Run it off the GUI thread
// with a progress bar, Cancel it, read its key numbers; results go to the plots through
// resultReady(). "Copy CLI" puts the equivalent fovea-cli command on the clipboard.

#include <QElapsedTimer>
#include <QMap>
#include <QWidget>

#include <optional>

#include "widgets/analyses/analysis_runner.h"

class QComboBox;
class QFormLayout;
class QLabel;
class QProgressBar;
class QPushButton;
class QTextBrowser;

namespace fovea::widgets {

class FitFormExtras;
class SceneDocument;

class AnalysesPanel : public QWidget {
  Q_OBJECT
 public:
  explicit AnalysesPanel(SceneDocument* document, QWidget* parent = nullptr);

  void selectAnalysis(const QString& id);
  QString currentAnalysis() const;
  // The values in the form (and what Run uses).
  AnalysisParams parameters() const;
  // Sets a field as if typed; false for an unknown key.
  bool setParameter(const QString& key, const QVariant& value);
  void resetParameters();

  // Starts the selected analysis on the current scene; false (with the reason in the status
  // line) when busy or when a parameter is invalid.
  bool run();
  void cancel();
  AnalysisRunner* runner() const { return runner_; }
  std::optional<AnalysisResult> lastResult(const QString& id) const;
  QString statusText() const;
  // The progress bar's text while running: "%p% — about 2 min 05 s left" once the rate is known.
  static QString progressFormat(double fraction, double elapsed_s);
  QString progressText() const;
  // The equivalent fovea-cli command of the form; empty when there is none: then
  // cliUnavailableReason() says why (no twin, or the scene must be saved first).
  QString cliCommand() const;
  QString cliUnavailableReason() const;
  // The extra controls of the "fit" form while it is shown (nullptr otherwise).
  FitFormExtras* fitExtras() const { return fitExtras_; }

 signals:
  void resultReady(const fovea::widgets::AnalysisResult& result);

 private:
  void rebuildForm();
  void rememberForm();
  void setBusy(bool busy);
  void showSummary(const AnalysisResult& r);
  // The status line belongs to one analysis: switching the form shows that analysis's last
  // status (or "Ready."), never the previous analysis's.
  void setStatus(const QString& analysisId, const QString& text);

  SceneDocument* document_;
  AnalysisRunner* runner_;
  QComboBox* combo_ = nullptr;
  QLabel* description_ = nullptr;
  QWidget* formHost_ = nullptr;
  QFormLayout* form_ = nullptr;
  QMap<QString, QWidget*> fields_;
  QPushButton* runButton_ = nullptr;
  QPushButton* cancelButton_ = nullptr;
  QPushButton* defaultsButton_ = nullptr;
  QPushButton* cliButton_ = nullptr;
  QProgressBar* progress_ = nullptr;
  QElapsedTimer runClock_;  // since the running analysis started (the time-left estimate)
  QLabel* status_ = nullptr;
  QTextBrowser* summary_ = nullptr;
  QMap<QString, AnalysisParams> edited_;  // per analysis, the values last in the form
  QMap<QString, AnalysisResult> results_;
  QMap<QString, QString> statusOf_;     // per analysis, its last status line
  FitFormExtras* fitExtras_ = nullptr;  // the "fit" form's file chooser, paths and Apply (fit_form_extras.h)
};

}  // namespace fovea::widgets
