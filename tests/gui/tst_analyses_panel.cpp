// The analyses panel and the plots area: a run off the GUI thread gives the same JSON as its
// fovea-cli twin; Cancel stops a long study (no result, runner idle); plot exports write a
// valid PNG, SVG and CSV with the result's numbers; display units convert the plotted values.
#include <QtTest>
#include "tests/test_paths.h"

#include <QChartView>
#include <QDockWidget>
#include <QImage>
#include <QProcess>
#include <QProgressBar>
#include <QPushButton>
#include <QSvgRenderer>

#include <cmath>

#include "app/studio/analysis_features.h"
#include "app/studio/main_window.h"
#include "tests/gui/analysis_gate.h"
#include "tests/gui/analysis_panel_fixture.h"
#include "widgets/analyses/analyses_panel.h"
#include "widgets/plots/plot_builders.h"
#include "widgets/plots/plot_render.h"
#include "widgets/plots/plots_panel.h"
#include "widgets/preferences.h"
#include "widgets/scene_document.h"

namespace tst_analyses_panel {

using namespace fovea;
using namespace fovea::widgets;
using fovea::embeddedDefaultScene;
using fovea::testing::AnalysisGate;
using fovea::testing::testTmpPath;

namespace {

QString tmpDir() {
  return testTmpPath("gui_analyses_panel");
}

nlohmann::json cliJson(const QStringList& args) {
  QProcess p;
  p.start(FOVEA_CLI_PATH, args);
  if (!p.waitForFinished(120000) || p.exitCode() != 0)
    qFatal("fovea-cli failed: %s", p.readAllStandardError().constData());
  return nlohmann::json::parse(p.readAllStandardOutput().toStdString());
}

// Splits one CSV line (no quoted commas in the numeric tables used here).
QStringList csvCells(const QString& line) {
  return line.trimmed().split(',');
}

}  // namespace

class TestAnalysesPanel : public QObject {
  Q_OBJECT
 private slots:
  void initTestCase() { Preferences::instance().setValues(PreferenceValues{}); }

  void everyAnalysisHasParametersAndPlots() {
    QStringList ids;
    for (const AnalysisSpec& s : analysisCatalog()) {
      ids << s.id;
      AnalysisParams p = defaultParameters(s);
      QVERIFY2(validateParameters(s, p).isEmpty(), qPrintable(s.id));
      for (const QString& plot : s.plots) QVERIFY2(plotIds().contains(plot), qPrintable(plot));
    }
    for (const char* cli :
         {"trace", "sweep", "compare-shift", "sensitivity", "resolution", "optimize-lens", "selectivity", "grating"})
      QVERIFY2(ids.contains(cli), cli);
    AnalysisParams bad = defaultParameters(*findAnalysis("sweep"));
    bad["gaze-step"] = -1.0;
    QVERIFY(!validateParameters(*findAnalysis("sweep"), bad).isEmpty());
  }

  void resolutionRunMatchesTheCli() {
    SceneDocument doc;
    doc.resetTo(embeddedDefaultScene(), {});
    AnalysesPanel panel(&doc);
    panel.selectAnalysis("resolution");
    QVERIFY(panel.setParameter("gaze-yaw", 5.0));
    QVERIFY(panel.setParameter("samples", 61));
    QSignalSpy finished(panel.runner(), &AnalysisRunner::finished);
    QSignalSpy ready(&panel, &AnalysesPanel::resultReady);
    QVERIFY(panel.run());
    QVERIFY(panel.runner()->isRunning());
    QVERIFY(!panel.run());  // one at a time
    QTRY_COMPARE_WITH_TIMEOUT(finished.count(), 1, 60000);
    QCOMPARE(ready.count(), 1);
    const auto r = panel.lastResult("resolution");
    QVERIFY(r && r->json);
    QCOMPARE(panel.findChild<QProgressBar*>("progress")->value(), 1000);
    const nlohmann::json cli = cliJson({"resolution", "", "--gaze-deg", "5,0", "--samples", "61", "--json"});
    for (auto it = cli.begin(); it != cli.end(); ++it) QVERIFY2(r->json->contains(it.key()), it.key().c_str());
    QCOMPARE(r->json->at("samples").size(), cli["samples"].size());
    for (std::size_t i = 0; i < cli["samples"].size(); ++i)
      QVERIFY(std::abs(r->json->at("samples")[i]["perceived_cpd"].get<double>() -
                       cli["samples"][i]["perceived_cpd"].get<double>()) < 1e-9);
    QVERIFY(panel.cliCommand().isEmpty());  // unsaved: fovea-cli could not read this scene
    doc.markSaved(tmpDir() + "/resolution.json");
    QVERIFY2(panel.cliCommand().startsWith("fovea-cli resolution " + tmpDir() + "/resolution.json --gaze-deg 5,0"),
             qPrintable(panel.cliCommand()));
  }

  void sweepKeysMatchTheCli() {
    const Scene scene = embeddedDefaultScene();
    AnalysisParams p = defaultParameters(*findAnalysis("sweep"));
    p["gaze-from"] = -10.0;
    p["gaze-to"] = 10.0;
    p["gaze-step"] = 10.0;
    p["rays"] = 200;
    const auto gui = runAnalysis("sweep", scene, p);
    QVERIFY(gui.has_value());
    const nlohmann::json cli =
        cliJson({"sweep", "", "--gaze-from", "-10", "--gaze-to", "10", "--gaze-step", "10", "--rays", "200", "--json"});
    for (auto it = cli.begin(); it != cli.end(); ++it) QVERIFY2(gui->contains(it.key()), it.key().c_str());
    for (auto it = cli["samples"][0].begin(); it != cli["samples"][0].end(); ++it)
      QVERIFY2((*gui)["samples"][0].contains(it.key()), it.key().c_str());
    QVERIFY(std::abs((*gui)["eyebox_mm"].get<double>() - cli["eyebox_mm"].get<double>()) < 1e-9);
  }

  void cancelStopsALongStudy() {
    // The real sweep behind a gate (tests/gui/analysis_gate.h): Cancel is pressed while the
    // study is held after its first sample, so the run is known to be in progress without
    // waiting for any time to pass.
    SceneDocument doc;
    doc.resetTo(embeddedDefaultScene(), {});
    AnalysesPanel panel(&doc);
    AnalysisGate gate(panel.runner());
    panel.selectAnalysis("sweep");
    // 81 gaze samples: more than the cores that can be inside a sample when the gate closes.
    panel.setParameter("gaze-from", -40.0);
    panel.setParameter("gaze-to", 40.0);
    panel.setParameter("gaze-step", 1.0);
    panel.setParameter("rays", 200);
    panel.setParameter("tolerance-deg", 0.37);  // a parameter set no other test caches
    QSignalSpy started(panel.runner(), &AnalysisRunner::started);
    QSignalSpy cancelled(panel.runner(), &AnalysisRunner::cancelled);
    QSignalSpy finished(panel.runner(), &AnalysisRunner::finished);
    QSignalSpy idle(panel.runner(), &AnalysisRunner::idle);
    QVERIFY(panel.run());
    QCOMPARE(started.count(), 1);
    QTRY_VERIFY_WITH_TIMEOUT(gate.reached(), 120000);  // a condition, not a time: a sample is done
    QVERIFY(panel.runner()->isRunning());
    QTest::mouseClick(panel.findChild<QPushButton*>("cancel"), Qt::LeftButton);
    gate.open();
    QTRY_COMPARE_WITH_TIMEOUT(cancelled.count(), 1, 120000);
    QCOMPARE(finished.count(), 0);
    QCOMPARE(idle.count(), 1);
    QVERIFY(!panel.runner()->isRunning());
    QVERIFY(!panel.lastResult("sweep").has_value());
    QVERIFY(panel.statusText().contains("Cancelled"));
    QVERIFY(panel.findChild<QPushButton*>("run")->isEnabled());
    // The study stopped: only the samples already running when Cancel came finished.
    QVERIFY2(gate.lastFraction() < 1.0 && gate.reports() < 81, qPrintable(QString::number(gate.reports())));
  }

  void plotExportsCarryTheNumbers() {
    const Scene scene = embeddedDefaultScene();
    AnalysisParams p = defaultParameters(*findAnalysis("resolution"));
    p["samples"] = 41;
    const auto r = runAnalysis("resolution", scene, p);
    QVERIFY(r.has_value());
    PlotsPanel plots;
    plots.showResult("resolution", *r);
    QVERIFY(plots.filledPlots().contains("resolution-vs-eccentricity"));
    QCOMPARE(plots.currentPlot(), QString("resolution-vs-eccentricity"));
    QVERIFY(plots.chartView("resolution-vs-eccentricity")->chart()->series().size() >= 3);
    const QString base = tmpDir() + "/resolution";
    QString error;
    QVERIFY2(plots.exportPlot("resolution-vs-eccentricity", base + ".png", &error), qPrintable(error));
    QVERIFY2(plots.exportPlot("resolution-vs-eccentricity", base + ".svg", &error), qPrintable(error));
    QVERIFY2(plots.exportPlot("resolution-vs-eccentricity", base + ".csv", &error), qPrintable(error));
    QVERIFY(!plots.exportPlot("resolution-vs-eccentricity", base + ".bmp", &error));
    QVERIFY(error.contains("png"));
    QVERIFY(!plots.exportPlot("fov-vs-gaze", base + "-empty.csv", &error));  // never filled

    QImage png(base + ".png");
    QVERIFY(!png.isNull());
    QVERIFY(png.width() >= 900 && png.height() >= 560);
    // The chart fills the image: many non-white pixels (curves, axes, labels), not a blank.
    int ink = 0;
    for (int y = 0; y < png.height(); y += 3)
      for (int x = 0; x < png.width(); x += 3)
        if (qGray(png.pixel(x, y)) < 200) ++ink;
    QVERIFY2(ink > 2000, qPrintable(QString::number(ink)));
    QSvgRenderer svg(base + ".svg");
    QVERIFY(svg.isValid());
    QFile svgFile(base + ".svg");
    QVERIFY(svgFile.open(QIODevice::ReadOnly));
    QVERIFY(svgFile.readAll().contains("<path"));

    QFile csv(base + ".csv");
    QVERIFY(csv.open(QIODevice::ReadOnly));
    const QStringList lines = QString::fromUtf8(csv.readAll()).split("\r\n", Qt::SkipEmptyParts);
    QCOMPARE(lines.size(), 1 + static_cast<int>((*r)["samples"].size()));
    const QStringList header = csvCells(lines[0]);
    QCOMPARE(header[0], QString("eccentricity (deg)"));
    const int perceived = header.indexOf("perceived (cpd)"), foveal = header.indexOf("foveal (cpd)");
    QVERIFY(perceived > 0 && foveal > 0);
    for (int i = 1; i < lines.size(); ++i) {
      const QStringList c = csvCells(lines[i]);
      const auto& s = (*r)["samples"][i - 1];
      QVERIFY(std::abs(c[0].toDouble() - s["eccentricity_deg"].get<double>()) < 1e-8);
      QVERIFY(std::abs(c[perceived].toDouble() - s["perceived_cpd"].get<double>()) <
              1e-7 * (1 + s["perceived_cpd"].get<double>()));
      // Outside the micro-OLED's field the foveal value is null: an empty cell.
      QCOMPARE(c[foveal].isEmpty(), s["foveal_cpd"].is_null());
    }
  }

  void accommodationPlotCarriesTheSweep() {
    // resolution with accommodation-d (issue 29) fills "resolution-vs-accommodation" too: one
    // CSV row per accommodation, the peripheral and foveal MTF50 of the result's document.
    const Scene scene = embeddedDefaultScene();
    AnalysisParams p = defaultParameters(*findAnalysis("resolution"));
    p["samples"] = 11;
    p["accommodation-d"] = "0.4,1.25,3.3";
    const auto r = runAnalysis("resolution", scene, p);
    QVERIFY(r.has_value() && (*r)["accommodation"].is_object());
    PlotsPanel plots;
    plots.showResult("resolution", *r);
    QVERIFY(plots.filledPlots().contains("resolution-vs-eccentricity"));
    QVERIFY(plots.filledPlots().contains("resolution-vs-accommodation"));
    QCOMPARE(plots.chartView("resolution-vs-accommodation")->chart()->series().size(), 5);
    const QString base = tmpDir() + "/resolution-accommodation";
    QString error;
    QVERIFY2(plots.exportPlot("resolution-vs-accommodation", base + ".csv", &error), qPrintable(error));
    QVERIFY2(plots.exportPlot("resolution-vs-accommodation", base + ".png", &error), qPrintable(error));
    qInfo("plot: %s.png", qPrintable(base));
    QFile csv(base + ".csv");
    QVERIFY(csv.open(QIODevice::ReadOnly));
    const QStringList lines = QString::fromUtf8(csv.readAll()).split("\r\n", Qt::SkipEmptyParts);
    QCOMPARE(lines.size(), 4);
    const QStringList header = csvCells(lines[0]);
    const int pc = header.indexOf("peripheral MTF50 (cpd)"), fc = header.indexOf("foveal MTF50 (cpd)");
    QVERIFY(pc > 0 && fc > 0);
    for (int i = 1; i < lines.size(); ++i) {
      const QStringList c = csvCells(lines[i]);
      const auto& s = (*r)["accommodation"]["samples"][i - 1];
      QVERIFY(std::abs(c[0].toDouble() - s["accommodation_d"].get<double>()) < 1e-9);
      const double pm = s["peripheral"]["cpd_mtf50"], fm = s["foveal"]["cpd_mtf50"];
      QVERIFY(std::abs(c[pc].toDouble() - pm) < 1e-7 * pm);
      QVERIFY(std::abs(c[fc].toDouble() - fm) < 1e-7 * fm);
    }
  }

  void analysisFeaturesFeedThePlots() {
    studio::MainWindow window;
    window.resize(1600, 1000);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    AnalysesPanel* panel = window.analysisFeatures()->analysesPanel();
    PlotsPanel* plots = window.analysisFeatures()->plotsPanel();
    panel->selectAnalysis("sweep");
    panel->setParameter("gaze-from", -20.0);
    panel->setParameter("gaze-to", 20.0);
    panel->setParameter("gaze-step", 5.0);
    panel->setParameter("rays", 300);
    QSignalSpy ready(panel, &AnalysesPanel::resultReady);
    QVERIFY(panel->run());
    QTRY_COMPARE_WITH_TIMEOUT(ready.count(), 1, 120000);
    QVERIFY(plots->filledPlots().contains("fov-vs-gaze"));
    QVERIFY(plots->filledPlots().contains("travel-vs-gaze"));
    QVERIFY(plots->isVisible());
    const PlotData travel = plots->plot("travel-vs-gaze");
    QCOMPARE(travel.rows.size(), 9);
    const auto r = panel->lastResult("sweep");
    QVERIFY(r && r->json);
    for (int i = 0; i < 9; ++i)
      QVERIFY(std::abs(travel.rows[i][1].toDouble() - (*r->json)["samples"][i]["hoe_shift_mm"].get<double>()) < 1e-9);
    QTest::qWait(300);
    QVERIFY(window.captureWindow().save(tmpDir() + "/studio-plots.png"));
    window.findChild<QDockWidget*>("AnalysesDock")->raise();
    QTest::qWait(200);
    QVERIFY(window.captureWindow().save(tmpDir() + "/studio-analyses.png"));
  }

  void gratingSweepAgainstRcwa() {
    // The default request is an unslanted reflection grating Bragg-matched at normal incidence
    // (period = lambda / (2 n0)); rho = lambda^2/(Lambda^2 n0 n1) ~ 600: Kogelnik holds to ~1e-3.
    AnalysisParams p = defaultParameters(*findAnalysis("grating"));
    p["samples"] = 21;
    p["model"] = "kogelnik+rcwa";
    p["period-nm"] = 532.0 / 3.0;  // exactly lambda / (2 n0)
    const auto r = runAnalysis("grating", Scene{}, p);
    QVERIFY(r.has_value());
    QCOMPARE((*r)["samples"].size(), std::size_t(21));
    const auto& centre = (*r)["samples"][10];
    QVERIFY(std::abs(centre["detuning_deg"].get<double>()) < 1e-12);
    const double nu = M_PI * 0.02 * 16.0 / 0.532;
    QVERIFY(std::abs(centre["kogelnik_efficiency"].get<double>() - std::pow(std::tanh(nu), 2)) < 1e-9);
    QVERIFY2(std::abs(centre["rcwa_efficiency"].get<double>() - centre["kogelnik_efficiency"].get<double>()) < 5e-3,
             centre.dump().c_str());
    const QList<PlotData> plots = plotsFromResult("grating", *r, DisplayUnits{});
    QCOMPARE(plots.size(), 1);
    QCOMPARE(plots[0].id, QString("efficiency-vs-angle"));
    QCOMPARE(plots[0].series.size(), 2);  // Kogelnik and RCWA
    QCOMPARE(plots[0].rows.size(), 21);
  }

  void displayUnitsConvertThePlottedValues() {
    const nlohmann::json sweep = {{"axis", "yaw"},
                                  {"eyebox_mm", 7.5},
                                  {"eyebox", {{"gaze_range_deg", {-12, 12}}, {"travel_mm", {-2.54, 2.54}}}},
                                  {"samples",
                                   {{{"gaze_deg", -10.0},
                                     {"hoe_shift_mm", -2.54},
                                     {"pupil_position_mm", -3.0},
                                     {"fov_deg", {{"horizontal", 80.0}, {"vertical", 70.0}, {"diagonal", 95.0}}}},
                                    {{"gaze_deg", 10.0},
                                     {"hoe_shift_mm", 5.08},
                                     {"pupil_position_mm", 3.0},
                                     {"fov_deg", {{"horizontal", 81.0}, {"vertical", 71.0}, {"diagonal", 96.0}}}}}}};
    DisplayUnits inches{LengthUnit::Inch, AngleUnit::Radian};
    const QList<PlotData> plots = plotsFromResult("sweep", sweep, inches);
    QCOMPARE(plots.size(), 2);
    const PlotData& travel = plots[1];
    QCOMPARE(travel.id, QString("travel-vs-gaze"));
    QCOMPARE(travel.columns[1], QString("HOE shift (in)"));
    QVERIFY(std::abs(travel.rows[1][1].toDouble() - 0.2) < 1e-12);  // 5.08 mm = 0.2 in
    QVERIFY(std::abs(travel.rows[1][0].toDouble() - 10.0 * M_PI / 180.0) < 1e-12);
    QVERIFY(std::abs(travel.series[0].points[0].y() + 0.1) < 1e-12);
    const QString csv = plotCsv(travel);
    QVERIFY(csv.startsWith("gaze yaw (rad),HOE shift (in),pupil position (in)\r\n"));
  }
};

QTEST_MAIN(TestAnalysesPanel)

}  // namespace tst_analyses_panel
#include "tst_analyses_panel.moc"
