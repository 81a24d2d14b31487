#pragma once
// The plots area: one tab per plot (plot_builders.h), filled by analysis results, each with
// Export PNG / SVG / CSV buttons. An empty plot says which analysis fills it.

#include <QMap>
#include <QWidget>

#include <nlohmann/json.hpp>

#include "widgets/plots/plot_data.h"

class QTabWidget;
class QStackedWidget;
class QLabel;
class QTextBrowser;
class QPushButton;

QT_BEGIN_NAMESPACE
class QChartView;
QT_END_NAMESPACE

namespace fovea::widgets {

class SceneDocument;

class PlotsPanel : public QWidget {
  Q_OBJECT
 public:
  explicit PlotsPanel(QWidget* parent = nullptr);
  // The scene whose folder the export dialogs open in (widgets/dialog_start.h).
  void setDocument(const SceneDocument* document) { document_ = document; }

  // Rebuilds the plots fed by this result (in the current display units) and shows the first.
  void showResult(const QString& analysisId, const nlohmann::json& result, const QString& source = {});
  // The current data of a plot (empty PlotData when never filled).
  PlotData plot(const QString& plotId) const { return plots_.value(plotId); }
  QStringList filledPlots() const;
  void setCurrentPlot(const QString& plotId);
  QString currentPlot() const;
  // Export by extension (.png/.svg/.csv); false with the reason in `error`.
  bool exportPlot(const QString& plotId, const QString& path, QString* error = nullptr) const;
  QChartView* chartView(const QString& plotId) const;

 signals:
  void plotExported(const QString& plotId, const QString& path);
  void exportFailed(const QString& plotId, const QString& message);

 private:
  const SceneDocument* document_ = nullptr;
  struct Page {
    QStackedWidget* stack = nullptr;
    QLabel* hint = nullptr;
    QChartView* view = nullptr;
    QLabel* caption = nullptr;
    QTextBrowser* summary = nullptr;
    QList<QPushButton*> exportButtons;
  };
  void rebuildPage(const QString& plotId);
  void exportDialog(const QString& plotId, const QString& extension);
  void refreshAll();

  QTabWidget* tabs_ = nullptr;
  QMap<QString, Page> pages_;
  QMap<QString, PlotData> plots_;
  // The last result of every analysis, to rebuild plots when the display units change.
  QMap<QString, std::pair<nlohmann::json, QString>> results_;
};

}  // namespace fovea::widgets
