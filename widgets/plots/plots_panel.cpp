#include "widgets/plots/plots_panel.h"

#include <QApplication>
#include <QChart>
#include <QChartView>
#include <QFileDialog>
#include <QHBoxLayout>
#include <QLabel>
#include <QPalette>
#include <QPushButton>
#include <QStackedWidget>
#include <QTabWidget>
#include <QTextBrowser>
#include <QVBoxLayout>

#include "widgets/analyses/analysis_catalog.h"
#include "widgets/dialog_start.h"
#include "widgets/plots/plot_builders.h"
#include "widgets/plots/plot_render.h"
#include "widgets/preferences.h"

namespace fovea::widgets {

namespace {
bool darkPalette() {
  return QApplication::palette().color(QPalette::Window).lightness() < 110;
}
}  // namespace

PlotsPanel::PlotsPanel(QWidget* parent) : QWidget(parent) {
  setObjectName("PlotsPanel");
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(2, 2, 2, 2);
  tabs_ = new QTabWidget(this);
  tabs_->setObjectName("plotTabs");
  tabs_->setDocumentMode(true);
  layout->addWidget(tabs_);

  for (const QString& id : plotIds()) {
    Page page;
    auto* tab = new QWidget;
    tab->setObjectName("plot:" + id);
    auto* v = new QVBoxLayout(tab);
    v->setContentsMargins(4, 4, 4, 4);
    page.stack = new QStackedWidget(tab);
    QStringList titles;
    for (const QString& a : plotSources(id))
      if (const AnalysisSpec* s = findAnalysis(a)) titles << "“" + s->title + "”";
    page.hint = new QLabel(
        tr("No data yet. Run %1 in the Analyses panel to fill this plot.").arg(titles.join(tr(" or "))), tab);
    page.hint->setAlignment(Qt::AlignCenter);
    page.hint->setWordWrap(true);
    page.view = new QChartView(tab);
    page.view->setObjectName("chart:" + id);
    page.view->setRenderHint(QPainter::Antialiasing);
    page.view->setMinimumHeight(220);
    page.stack->addWidget(page.hint);
    page.stack->addWidget(page.view);
    v->addWidget(page.stack, 1);
    page.summary = new QTextBrowser(tab);
    page.summary->setMaximumHeight(140);
    page.summary->setVisible(false);
    v->addWidget(page.summary);
    page.caption = new QLabel(tab);
    page.caption->setWordWrap(true);
    page.caption->setTextInteractionFlags(Qt::TextSelectableByMouse);
    v->addWidget(page.caption);
    auto* buttons = new QHBoxLayout;
    buttons->addStretch(1);
    for (const QString& ext : {QStringLiteral("png"), QStringLiteral("svg"), QStringLiteral("csv")}) {
      auto* b = new QPushButton(tr("Export %1…").arg(ext.toUpper()), tab);
      b->setObjectName("export-" + ext);
      b->setEnabled(false);
      connect(b, &QPushButton::clicked, this, [this, id, ext] { exportDialog(id, ext); });
      buttons->addWidget(b);
      page.exportButtons << b;
    }
    v->addLayout(buttons);
    pages_.insert(id, page);
    tabs_->addTab(tab, plotTitle(id));
  }
  connect(&Preferences::instance(), &Preferences::changed, this, &PlotsPanel::refreshAll);
}

void PlotsPanel::showResult(const QString& analysisId, const nlohmann::json& result, const QString& source) {
  const QList<PlotData> plots = plotsFromResult(analysisId, result, Preferences::instance().units(), source);
  if (plots.isEmpty()) return;
  results_[analysisId] = {result, source};
  for (const PlotData& p : plots) {
    plots_[p.id] = p;
    rebuildPage(p.id);
  }
  setCurrentPlot(plots.front().id);
}

void PlotsPanel::refreshAll() {
  const auto results = results_;
  const QString current = currentPlot();
  for (auto it = results.begin(); it != results.end(); ++it) {
    for (const PlotData& p :
         plotsFromResult(it.key(), it.value().first, Preferences::instance().units(), it.value().second)) {
      plots_[p.id] = p;
      rebuildPage(p.id);
    }
  }
  setCurrentPlot(current);
}

void PlotsPanel::rebuildPage(const QString& id) {
  Page& page = pages_[id];
  const PlotData& p = plots_[id];
  QChart* old = page.view->chart();
  page.view->setChart(buildChart(p, darkPalette()));
  delete old;
  page.caption->setText(p.caption);
  page.summary->setHtml(p.summaryHtml);
  page.summary->setVisible(!p.summaryHtml.isEmpty());
  page.stack->setCurrentWidget(page.view);
  for (QPushButton* b : page.exportButtons) b->setEnabled(!p.rows.isEmpty());
}

QStringList PlotsPanel::filledPlots() const {
  QStringList ids;
  for (const QString& id : plotIds())
    if (plots_.contains(id)) ids << id;
  return ids;
}

void PlotsPanel::setCurrentPlot(const QString& id) {
  const int i = plotIds().indexOf(id);
  if (i >= 0) tabs_->setCurrentIndex(i);
}

QString PlotsPanel::currentPlot() const {
  return plotIds().value(tabs_->currentIndex());
}

QChartView* PlotsPanel::chartView(const QString& id) const {
  return pages_.contains(id) ? pages_[id].view : nullptr;
}

bool PlotsPanel::exportPlot(const QString& id, const QString& path, QString* error) const {
  if (!plots_.contains(id)) {
    if (error) *error = tr("the plot \"%1\" has no data").arg(plotTitle(id));
    return false;
  }
  return widgets::exportPlot(plots_[id], path, error);
}

void PlotsPanel::exportDialog(const QString& id, const QString& ext) {
  const QString filter = ext == "png"   ? tr("PNG images (*.png)")
                         : ext == "svg" ? tr("SVG drawings (*.svg)")
                                        : tr("CSV tables (*.csv)");
  QString path = QFileDialog::getSaveFileName(this, tr("Export %1").arg(plotTitle(id)),
                                              dialogStart(document_, id + "." + ext), filter);
  if (path.isEmpty()) return;
  if (!path.endsWith("." + ext, Qt::CaseInsensitive)) path += "." + ext;
  QString error;
  if (exportPlot(id, path, &error))
    emit plotExported(id, path);
  else
    emit exportFailed(id, error);
}

}  // namespace fovea::widgets
