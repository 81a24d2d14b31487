// The studio's Tolerance analysis: the Analyses panel runs it off the GUI thread with progress
// and gives fovea-cli tolerance's document; Cancel stops a long run; with no spec file the
// shipped default spec runs; the plots (yield with its interval, histograms with the pass
// threshold, the sensitivity ranking with error bars) carry the result's numbers.
#include <QtTest>

#include <QChartView>
#include <QDockWidget>
#include <QFile>
#include <QLineEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QTemporaryDir>
#include <QToolButton>

#include <cmath>

#include "app/studio/analysis_features.h"
#include "app/studio/main_window.h"
#include "model/analysis/tolerance_analysis.h"
#include "tests/cli/cli_process.h"
#include "tests/gui/analysis_gate.h"
#include "tests/gui/analysis_panel_fixture.h"
#include "tests/tolerance_test_spec.h"
#include "widgets/analyses/analyses_panel.h"
#include "widgets/plots/plot_builders.h"
#include "widgets/plots/plots_panel.h"
#include "widgets/preferences.h"
#include "widgets/scene_document.h"

namespace tst_tolerance_analysis {

using namespace fovea;
using namespace fovea::widgets;
using fovea::embeddedDefaultScene;

namespace {

// The small spec with eye relief as a third tolerance (5 Saltelli blocks of 5 rows), as tol.json in d.
QString writeSpec(const QTemporaryDir& d) {
  return fovea::testing::writeTestFile(
      d, "tol.json",
      fovea::testing::smallToleranceSpec(
          R"({"name": "eye relief", "path": "eye.relief_mm", "distribution": "normal", "sigma": 1.5},)"));
}

const PlotData* find(const QList<PlotData>& plots, const QString& id) {
  for (const PlotData& p : plots)
    if (p.id == id) return &p;
  return nullptr;
}

}  // namespace

class TestToleranceAnalysis : public QObject {
  Q_OBJECT
 private slots:
  void initTestCase() { Preferences::instance().setValues(PreferenceValues{}); }

  void panelRunEqualsTheCliAndFillsThePlots() {
    QTemporaryDir dir;
    const QString spec = writeSpec(dir);
    SceneDocument doc;
    doc.resetTo(embeddedDefaultScene(), {});
    AnalysesPanel panel(&doc);
    panel.selectAnalysis("tolerance");
    QCOMPARE(panel.currentAnalysis(), QString("tolerance"));
    QVERIFY(panel.findChild<QToolButton*>("spec-browse"));
    QVERIFY(panel.setParameter("spec", spec));
    QVERIFY(panel.setParameter("trials", 25));  // 5 Saltelli blocks of 5
    QVERIFY(panel.setParameter("seed", 7));
    QSignalSpy progress(panel.runner(), &AnalysisRunner::progress);
    QSignalSpy finished(panel.runner(), &AnalysisRunner::finished);
    QVERIFY(panel.run());
    QTRY_COMPARE_WITH_TIMEOUT(finished.count(), 1, 120000);
    QVERIFY(progress.count() >= 1);
    QCOMPARE(panel.findChild<QProgressBar*>("progress")->value(), 1000);
    const auto r = panel.lastResult("tolerance");
    QVERIFY(r && r->json);
    nlohmann::json studio = *r->json;
    studio.erase("cached");

    const auto cli =
        fovea::testing::runFoveaCli({"tolerance", "--spec", spec, "--trials", "25", "--seed", "7", "--json"});
    QCOMPARE(cli.code, 0);
    const nlohmann::json expected = nlohmann::json::parse(cli.out.toStdString());
    QVERIFY2(studio == expected, qPrintable(QString::fromStdString(studio.dump().substr(0, 400))));

    // The plots: numbers from the document.
    const QList<PlotData> plots = plotsFromResult("tolerance", studio, DisplayUnits{});
    QCOMPARE(plots.size(), 7);
    const PlotData* yield = find(plots, "tolerance-yield");
    QVERIFY(yield);
    const double y = 100 * studio["yield"]["value"].get<double>();
    QCOMPARE(yield->series[0].points[1].x(), y);  // the bar ends at the yield
    const double lo = 100 * studio["yield"]["confidence_95"][0].get<double>(),
                 hi = 100 * studio["yield"]["confidence_95"][1].get<double>();
    QVERIFY(lo <= y && y <= hi && lo < hi);
    QCOMPARE(yield->series[1].points[0].x(), lo);
    QCOMPARE(yield->series[1].points[1].x(), hi);
    QCOMPARE(yield->series[2].points[0].x(), 90.0);  // the target yield

    const PlotData* fov = find(plots, "tolerance-fov_min_deg");
    QVERIFY(fov);
    double units = 0;
    for (const QVariantList& row : fov->rows) units += row[2].toDouble();
    QCOMPARE(units, studio["figures"]["fov_min_deg"]["count"].get<double>());
    QCOMPARE(fov->series[1].name, QString("pass threshold"));
    QCOMPARE(fov->series[1].points[0].x(), 60.0);
    const PlotData* eyebox = find(plots, "tolerance-eyebox_mm");
    QVERIFY(eyebox && eyebox->series.size() == 2);  // no bound on the eye box: histogram and nominal

    const PlotData* ranking = find(plots, "tolerance-ranking");
    QVERIFY(ranking);
    const auto& order = studio["sensitivity"]["ranking"];
    QCOMPARE(ranking->rows.size(), static_cast<int>(order.size()));
    QCOMPARE(ranking->y.categories.size(), 3);
    QCOMPARE(ranking->y.categories.last().toStdString(), order[0].get<std::string>());  // rank 1 drawn at the top
    const std::string by = studio["sensitivity"]["ranked_by"].get<std::string>();
    for (int i = 0; i < ranking->rows.size(); ++i) {
      QCOMPARE(ranking->rows[i][1].toString().toStdString(), order[i].get<std::string>());
      for (const auto& e : studio["sensitivity"]["outputs"][by])
        if (e["parameter"] == order[i]) {
          QCOMPARE(ranking->rows[i][2].toDouble(), e["total"].get<double>());
          QCOMPARE(ranking->rows[i][3].toDouble(), e["total_se"].get<double>());
          // The error bar spans total +- its standard error.
          QCOMPARE(ranking->series[2].points[4 * i].x(), e["total"].get<double>() - e["total_se"].get<double>());
        }
    }
    PlotsPanel view;
    view.showResult("tolerance", studio);
    for (const char* id : {"tolerance-yield", "tolerance-ranking", "tolerance-inset_error_deg"})
      QVERIFY2(view.filledPlots().contains(id), id);
  }

  void defaultSpecRunsWithNoFile() {
    const nlohmann::json shipped = nlohmann::json::parse(std::string(analysis::defaultToleranceSpecText()));
    QCOMPARE(shipped["format"].get<std::string>(), std::string("fovea-tolerance"));
    AnalysisParams p = defaultParameters(*findAnalysis("tolerance"));
    QVERIFY(!p["spec"].isValid());  // unset: the shipped spec
    p["trials"] = 16;               // one Saltelli block of the 14 parameters
    const auto r = runAnalysis("tolerance", embeddedDefaultScene(), p);
    QVERIFY(r.has_value());
    QCOMPARE((*r)["spec"], shipped);
    QCOMPARE((*r)["trials"].get<int>(), 16);
    QCOMPARE((*r)["parameters"].size(), std::size_t{14});
    QVERIFY((*r)["figures"]["fov_min_deg"]["mean"].get<double>() > 40);
  }

  void studioOverridesReachTheSpec() {
    QTemporaryDir dir;
    AnalysisParams p = defaultParameters(*findAnalysis("tolerance"));
    p["spec"] = writeSpec(dir);
    p["compensator"] = "refind";
    p["gaze-from"] = 0.0;
    p["gaze-to"] = 0.0;
    p["gaze-step"] = 5.0;
    p["trials"] = 5;
    const auto r = runAnalysis("tolerance", embeddedDefaultScene(), p);
    QVERIFY(r.has_value());
    QCOMPARE((*r)["spec"]["compensator"].get<std::string>(), std::string("refind"));
    QCOMPARE((*r)["spec"]["gaze"]["from_deg"].get<double>(), 0.0);
    // One gaze: the smallest FOV over the gazes is the zero-gaze FOV in every unit.
    QCOMPARE((*r)["figures"]["fov_min_deg"]["mean"], (*r)["figures"]["fov_zero_gaze_deg"]["mean"]);
  }

  // The studio at the two layouts it must fit (1366x768 and 1920x1080): Run in the Analyses dock
  // feeds the Plots dock's tolerance plots; the screenshots are looked at (FOVEA_TEST_TMP).
  void studioShowsThePlots() {
    QTemporaryDir dir;
    const QString spec = writeSpec(dir);
    for (const QSize size : {QSize(1366, 768), QSize(1920, 1080)}) {
      studio::MainWindow window;
      window.resize(size);
      window.show();
      QVERIFY(QTest::qWaitForWindowExposed(&window));
      AnalysesPanel* panel = window.analysisFeatures()->analysesPanel();
      PlotsPanel* plots = window.analysisFeatures()->plotsPanel();
      panel->selectAnalysis("tolerance");
      QVERIFY(panel->setParameter("spec", spec));
      QVERIFY(panel->setParameter("trials", 25));
      QSignalSpy ready(panel, &AnalysesPanel::resultReady);
      QVERIFY(panel->run());
      QTRY_COMPARE_WITH_TIMEOUT(ready.count(), 1, 120000);
      QVERIFY(plots->filledPlots().contains("tolerance-ranking"));
      const QString dirOut = qEnvironmentVariable("FOVEA_TEST_TMP", "/tmp");
      const QString tag = QString("%1x%2").arg(size.width()).arg(size.height());
      for (const char* id : {"tolerance-yield", "tolerance-fov_min_deg", "tolerance-ranking"}) {
        plots->setCurrentPlot(id);
        QTest::qWait(150);
        QVERIFY(window.captureWindow().save(dirOut + "/tolerance-" + tag + "-" + id + ".png"));
      }
      if (auto* dock = window.findChild<QDockWidget*>("AnalysesDock")) dock->raise();
      QTest::qWait(150);
      QVERIFY(window.captureWindow().save(dirOut + "/tolerance-" + tag + "-analyses.png"));
    }
  }

  void cancelStopsALongRun() {
    SceneDocument doc;
    doc.resetTo(embeddedDefaultScene(), {});
    AnalysesPanel panel(&doc);
    fovea::testing::AnalysisGate gate(panel.runner());  // holds the run after its first trial
    panel.selectAnalysis("tolerance");
    QVERIFY(panel.setParameter("trials", 100000));  // the default spec, refind: hours if not cancelled
    QSignalSpy cancelled(panel.runner(), &AnalysisRunner::cancelled);
    QSignalSpy finished(panel.runner(), &AnalysisRunner::finished);
    QVERIFY(panel.run());
    QTRY_VERIFY_WITH_TIMEOUT(gate.reached(), 120000);  // a condition, not a time
    QVERIFY(panel.runner()->isRunning());
    QTest::mouseClick(panel.findChild<QPushButton*>("cancel"), Qt::LeftButton);
    gate.open();
    QTRY_COMPARE_WITH_TIMEOUT(cancelled.count(), 1, 120000);
    QCOMPARE(finished.count(), 0);
    QVERIFY(!panel.lastResult("tolerance").has_value());
    QVERIFY2(gate.lastFraction() < 0.01, qPrintable(QString::number(gate.lastFraction())));  // stopped early
  }
};

QTEST_MAIN(TestToleranceAnalysis)

}  // namespace tst_tolerance_analysis
#include "tst_tolerance_analysis.moc"
