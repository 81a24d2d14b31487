// The studio's "Fit to measurements" (analysis "fit"): a run from the Analyses dock on a
// targets file made by our own forward model from a perturbed prototype fills the residual
// plot (one row per target, the fitted residuals small), and "Apply fitted values" sets every
// fitted value as one undo step that Undo takes back. Screenshots at 1366x768 and 1920x1080.
#include <QtTest>
#include "tests/test_paths.h"

#include <QComboBox>
#include <QDockWidget>
#include <QFile>
#include <QPushButton>
#include <QTextBrowser>
#include <QUndoStack>

#include "app/studio/analysis_features.h"
#include "app/studio/main_window.h"
#include "model/analysis/fit_targets.h"
#include "model/scene/scene_parameters.h"
#include "tests/gui/analysis_panel_fixture.h"
#include "widgets/analyses/analyses_panel.h"
#include "widgets/analyses/fit_form_extras.h"
#include "widgets/plots/plots_panel.h"
#include "widgets/scene_document.h"

namespace tst_fit_panel {

using namespace fovea;
using namespace fovea::widgets;
using fovea::embeddedDefaultScene;
using fovea::testing::testTmpPath;

namespace {
QString tmpDir() {
  return testTmpPath("gui_fit_panel");
}

// Targets from the prototype with the HOE 35.2 mm high and the green n1 at 0.0165.
QString writeTargets() {
  const Scene nominal = embeddedDefaultScene();
  const Scene built = withParameter(withParameter(nominal, "hoe.size_mm[1]", 35.2), "hoe_layers[1].n1", 0.0165);
  std::vector<FitTarget> t = parseFitTargets(nlohmann::json::parse(R"([
    {"id": "eff", "observable": "mean_efficiency", "shift": "none", "wavelength_nm": 532, "value": 0, "sigma": 0.002},
    {"id": "fov-h", "observable": "fov_deg", "shift": "none", "wavelength_nm": 532, "value": 0, "sigma": 0.05},
    {"id": "fov-v", "observable": "fov_deg", "shift": "none", "direction": "vertical", "wavelength_nm": 532,
     "value": 0, "sigma": 0.05}])"));
  const std::vector<double> v = evaluateTargets(built, t);
  for (std::size_t i = 0; i < t.size(); ++i) t[i].value = v[i];
  const QString path = tmpDir() + "/targets.json";
  QFile f(path);
  if (!f.open(QIODevice::WriteOnly)) qFatal("cannot write %s", qPrintable(path));
  f.write(QByteArray::fromStdString(fitTargetsJson(t, "synthetic").dump(2)));
  return path;
}
}  // namespace

class TestFitPanel : public QObject {
  Q_OBJECT
 private slots:
  void fitRunsPlotsAndAppliesAsOneUndoStep() {
    const QString targets = writeTargets();
    studio::MainWindow window;
    window.resize(1366, 768);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    window.findChild<QDockWidget*>("AnalysesDock")->raise();
    AnalysesPanel* panel = window.analysisFeatures()->analysesPanel();
    PlotsPanel* plots = window.analysisFeatures()->plotsPanel();
    panel->selectAnalysis("fit");
    FitFormExtras* extras = panel->fitExtras();
    QVERIFY(extras);
    QVERIFY(panel->setParameter("targets", targets));
    extras->addFreeParameter("hoe.size_mm[1]");
    extras->addFreeParameter("hoe_layers[1].n1");
    extras->addFreeParameter("hoe.size_mm[1]");  // once only
    QCOMPARE(panel->parameters().value("free").toString(), QString("hoe.size_mm[1] hoe_layers[1].n1"));
    QVERIFY(panel->setParameter("starts", 1));
    QVERIFY(!window.findChild<QPushButton*>("applyFit")->isEnabled());
    QVERIFY(window.findChild<QComboBox*>("scenePaths")->count() > 100);  // the scene's real-valued numbers
    QSignalSpy ready(panel, &AnalysesPanel::resultReady);
    QVERIFY(panel->run());
    QTRY_COMPARE_WITH_TIMEOUT(ready.count(), 1, 120000);
    QVERIFY(window.findChild<QPushButton*>("applyFit")->isEnabled());
    const auto r = panel->lastResult("fit");
    QVERIFY(r && r->json);
    QVERIFY((*r->json)["chi2"].get<double>() < 0.01);
    QVERIFY(plots->filledPlots().contains("fit-residuals"));
    const PlotData residuals = plots->plot("fit-residuals");
    QCOMPARE(residuals.rows.size(), 3);
    for (const auto& row : residuals.rows) QVERIFY(std::abs(row[9].toDouble()) < 0.1);  // normalised, fitted
    QVERIFY(std::abs(residuals.rows[0][8].toDouble()) > 5);                             // before the fit
    QTest::qWait(300);
    QVERIFY(window.captureWindow().save(tmpDir() + "/fit-1366x768-analyses.png"));

    // Apply: both values, one undo step; Undo restores the prototype.
    SceneDocument* doc = window.document();
    const int steps = doc->undoStack()->count();
    window.findChild<QPushButton*>("applyFit")->click();
    QCOMPARE(doc->undoStack()->count(), steps + 1);
    QVERIFY(std::abs(parameterValue(doc->scene(), "hoe.size_mm[1]") - 35.2) < 0.05);
    QVERIFY(std::abs(parameterValue(doc->scene(), "hoe_layers[1].n1") - 0.0165) < 1e-4);
    QVERIFY(panel->statusText().contains("Applied 2 fitted values"));
    doc->undoStack()->undo();
    QCOMPARE(parameterValue(doc->scene(), "hoe.size_mm[1]"), 36.0);
    QCOMPARE(parameterValue(doc->scene(), "hoe_layers[1].n1"), 0.015);

    window.resize(1920, 1080);
    window.findChild<QDockWidget*>("PlotsDock")->raise();
    QTest::qWait(400);
    QVERIFY(window.captureWindow().save(tmpDir() + "/fit-1920x1080-plots.png"));
  }

  // The seed's targets disagree with the prototype (and with each other: simulated vs
  // measured): the form shows the reduced chi2, the scaled uncertainty and a warning naming the
  // worst targets; the residual plot is labelled by target id. A short fit (4 evaluations)
  // suffices: the misfit is the targets', not the optimiser's.
  void seedTargetsWarnOfMisfit() {
    studio::MainWindow window;
    window.resize(1366, 768);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    window.findChild<QDockWidget*>("AnalysesDock")->raise();
    AnalysesPanel* panel = window.analysisFeatures()->analysesPanel();
    panel->selectAnalysis("fit");
    QVERIFY(panel->setParameter("targets", QString(FOVEA_SOURCE_DIR) + "/resources/seed/seed-targets.json"));
    QVERIFY(panel->setParameter("free", "eye.relief_mm"));
    QVERIFY(panel->setParameter("targets-select", "sim-"));
    QVERIFY(panel->setParameter("starts", 1));
    QVERIFY(panel->setParameter("max-evals", 4));
    QSignalSpy ready(panel, &AnalysesPanel::resultReady);
    QVERIFY(panel->run());
    QTRY_COMPARE_WITH_TIMEOUT(ready.count(), 1, 300000);
    const auto r = panel->lastResult("fit");
    QVERIFY(r && r->json);
    const nlohmann::json& j = *r->json;
    QCOMPARE(j["targets"].size(), std::size_t(14));  // the 14 sim- targets of the 19
    QCOMPARE(j["dof"].get<int>(), 13);
    QVERIFY2(j["reduced_chi2"].get<double>() > 1, j["reduced_chi2"].dump().c_str());
    QCOMPARE(j["uncertainties_shown"].get<std::string>(), std::string("scaled"));
    const std::string worst = j["worst_targets"][0]["id"].get<std::string>();
    QVERIFY(worst.rfind("sim-", 0) == 0);
    const QString html = window.findChild<QTextBrowser*>("summary")->toHtml();
    QVERIFY2(html.contains("Reduced χ²") && html.contains("reduced chi2") &&
                 html.contains(QString::fromStdString(worst)) && html.contains("scaled by √(χ²/dof)"),
             qPrintable(html));
    const PlotData residuals = window.analysisFeatures()->plotsPanel()->plot("fit-residuals");
    QCOMPARE(residuals.x.categories.size(), 14);
    QCOMPARE(residuals.x.categories.first(), QString("sim-fov-h-0"));
    QTest::qWait(300);
    QVERIFY(window.captureWindow().save(tmpDir() + "/fit-seed-1366x768.png"));
  }

  void progressSaysTheTimeLeft() {
    QCOMPARE(AnalysesPanel::progressFormat(0.25, 10.0), QString("%p% — about 30 s left"));
    QCOMPARE(AnalysesPanel::progressFormat(0.1, 20.0), QString("%p% — about 3 min 00 s left"));
    QCOMPARE(AnalysesPanel::progressFormat(0.5, 1.0), QString("%p% — running"));  // no rate yet
  }
};

QTEST_MAIN(TestFitPanel)

}  // namespace tst_fit_panel
#include "tst_fit_panel.moc"
