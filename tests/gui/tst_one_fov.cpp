// One FOV and one x_p in the studio (issue 26): the live trace's FOV (what the Gaze and Retina
// docks show) and its follow-gaze x_p against `fovea-cli trace` and `fovea-cli sweep` for the
// same scene, gaze and shift (0.01 deg, 0.01 mm), the report's x_p and FOV against the same,
// and the docks naming the FOV they show.
#include <QtTest>
#include "tests/test_paths.h"

#include <QComboBox>
#include <QLabel>
#include <QUndoStack>

#include <cmath>

#include <nlohmann/json.hpp>

#include "app/studio/live_trace_features.h"
#include "app/studio/main_window.h"
#include "app/studio/report_data.h"
#include "tests/cli/cli_process.h"
#include "widgets/gaze_panel.h"
#include "widgets/live_trace.h"
#include "widgets/scene_document.h"

namespace tst_one_fov {

using namespace fovea;

namespace {
const QString kScene = QString(FOVEA_SOURCE_DIR) + "/resources/scenes/prototype-bench.json";

nlohmann::json cliJson(const QStringList& args) {
  const auto r = testing::runFoveaCli(args);
  if (r.code != 0) qWarning("%s", r.err.constData());
  return r.code == 0 ? nlohmann::json::parse(r.out.toStdString()) : nlohmann::json();
}
}  // namespace

class TestOneFov : public QObject {
  Q_OBJECT
 private:
  std::unique_ptr<studio::MainWindow> w;
  studio::LiveTraceFeatures* live() { return w->liveTraceFeatures(); }

 private slots:
  void init() {
    w = std::make_unique<studio::MainWindow>();
    w->resize(1366, 768);
    w->show();
    QVERIFY(QTest::qWaitForWindowExposed(w.get()));
    QVERIFY(w->openFile(kScene, false));
    QVERIFY(live()->waitForTrace());
  }
  void cleanup() {
    w->document()->undoStack()->setClean();
    w.reset();
  }

  void zeroGazeShowsTheExactFov() {
    const auto r = live()->liveTrace()->latest();
    QVERIFY(r && r->error.empty());
    const auto t = cliJson({"trace", kScene, "--gaze-deg", "0", "--json"});
    QVERIFY(t.is_object());
    QVERIFY2(std::abs(r->fov.horizontal - t["fov_deg"]["horizontal"].get<double>()) < 0.01 &&
                 std::abs(r->fov.vertical - t["fov_deg"]["vertical"].get<double>()) < 0.01,
             qPrintable(QString("studio %1 x %2").arg(r->fov.horizontal).arg(r->fov.vertical)));
    QVERIFY2(std::abs(r->fov.horizontal - 90.00) < 0.005, qPrintable(QString::number(r->fov.horizontal)));
    // The Gaze dock shows it and names the definition.
    const QString text = live()->gazePanel()->findChild<QLabel*>("gazeReadout")->text();
    QVERIFY2(text.contains(QString::fromUtf8("FOV 90.00° × 78.58°")) && text.contains("ours (arrival directions)"),
             qPrintable(text));
  }

  void followGazeAgreesWithTheCli() {
    for (const char* rule : {"plateau-middle", "follow-focus"}) {
      auto* combo = live()->gazePanel()->findChild<QComboBox*>("xpRule");
      QVERIFY(combo);
      combo->setCurrentIndex(combo->findData(QString(rule)));
      QCOMPARE(w->document()->scene().view.xp_rule, std::string(rule));
      live()->gazePanel()->setGaze(20.0, 0.0);
      live()->gazePanel()->setFollowGaze(true);
      QVERIFY(live()->waitForTrace());
      const auto r = live()->liveTrace()->latest();
      QVERIFY(r && r->error.empty());
      QCOMPARE(r->shift_source, std::string("search"));
      const auto s = cliJson(
          {"sweep", kScene, "--gaze-from", "20", "--gaze-to", "20", "--gaze-step", "5", "--xp-rule", rule, "--json"});
      QVERIFY(s.is_object());
      const double sweep_xp = s["samples"][0]["hoe_shift_mm"].get<double>();
      const auto t = cliJson({"trace", kScene, "--gaze-deg", "20", "--hoe-shift-mm",
                              QString::number(r->hoe_shift_mm[0], 'g', 17), "--json"});
      QVERIFY(t.is_object());
      const QString msg = QString("%1: studio x_p %2 FOV %3 x %4; sweep x_p %5 FOV %6; trace FOV %7 x %8")
                              .arg(rule)
                              .arg(r->hoe_shift_mm[0])
                              .arg(r->fov.horizontal)
                              .arg(r->fov.vertical)
                              .arg(sweep_xp)
                              .arg(s["samples"][0]["fov_deg"]["horizontal"].get<double>())
                              .arg(t["fov_deg"]["horizontal"].get<double>())
                              .arg(t["fov_deg"]["vertical"].get<double>());
      QVERIFY2(std::abs(r->hoe_shift_mm[0] - sweep_xp) < 0.01, qPrintable(msg));
      QVERIFY2(std::abs(r->fov.horizontal - t["fov_deg"]["horizontal"].get<double>()) < 0.01 &&
                   std::abs(r->fov.vertical - t["fov_deg"]["vertical"].get<double>()) < 0.01 &&
                   std::abs(r->fov.horizontal - s["samples"][0]["fov_deg"]["horizontal"].get<double>()) < 0.01,
               qPrintable(msg));
      qInfo("%s", qPrintable(msg));
      // The report (same code as the studio's Export Report and `fovea-cli report`).
      studio::ReportOptions ro;
      ro.gazes_deg = {{20.0, 0.0}};
      ro.follow_gaze = true;
      ro.kogelnik_vs_rcwa = false;
      ro.sweep_step_deg = 20.0;
      const auto d = studio::computeReportData(w->document()->scene(), kScene, ro);
      QVERIFY(d && !d->traces.isEmpty());
      QVERIFY2(std::abs(d->traces[0].hoe_shift_mm[0] - sweep_xp) < 0.01,
               qPrintable(QString("report x_p %1").arg(d->traces[0].hoe_shift_mm[0])));
      QVERIFY(std::abs(d->traces[0].json["fov_deg"]["horizontal"].get<double>() - r->fov.horizontal) < 0.01);
      live()->gazePanel()->setFollowGaze(false);
      live()->gazePanel()->setGaze(0.0, 0.0);
      QVERIFY(live()->waitForTrace());
    }
  }
};

QTEST_MAIN(TestOneFov)

}  // namespace tst_one_fov
#include "tst_one_fov.moc"
