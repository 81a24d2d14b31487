// The Foveated preview's Retina image options (issue 29): speckle (N patterns per laser, pixel or
// pupil grain) and lateral colour (one calibration or per laser). The studio's frame reports the
// speckle contrast renderRetinaImage gives for the same options and `fovea-cli retina-image
// --speckle 4 --speckle-grain pupil --json` prints for the same target; per-laser calibration
// takes the lateral colour at the line of sight to 0; the options are shown only in the Retina
// image mode; with the HOE following the gaze the preview's HOE shift is the studio's one x_p
// (hoe_travel.h), the live trace's at the same gaze; the design report's retinal image takes the
// preview's options and names them in its caption.
#include <QtTest>
#include "tests/test_paths.h"

#include <QComboBox>
#include <QLabel>
#include <QProcess>
#include <QSpinBox>

#include <cmath>

#include <nlohmann/json.hpp>

#include "app/studio/analysis_features.h"
#include "app/studio/live_trace_features.h"
#include "app/studio/main_window.h"
#include "app/studio/report_data.h"
#include "model/analysis/hoe_travel.h"
#include "model/image/foveation.h"
#include "model/image/image_io.h"
#include "model/image/retina_image.h"
#include "model/image/test_target.h"
#include "model/physics/lateral_colour.h"
#include "tests/test_files.h"
#include "widgets/gaze_panel.h"
#include "widgets/live_trace.h"
#include "widgets/preview_panel.h"
#include "widgets/retina_image_controls.h"
#include "widgets/scene_document.h"

namespace tst_preview_retina_options {

using namespace fovea;
using widgets::PreviewPanel;
using widgets::RetinaPreviewOptions;

namespace {

// The shown frame is a Retina image frame of this gaze, accommodation and options.
bool retinaFrameOf(const PreviewPanel* panel, std::array<double, 2> gaze, double accommodation_d,
                   const RetinaPreviewOptions& o) {
  const widgets::PreviewFrame& f = panel->lastFrame();
  return f.accommodation_d && *f.accommodation_d == accommodation_d && f.gaze_deg == gaze && f.retinaOptions == o &&
         !f.retina.isNull() && f.error.isEmpty();
}

}  // namespace

class TestPreviewRetinaOptions : public QObject {
  Q_OBJECT
 private slots:
  void controlsOnlyInRetinaImageMode() {
    studio::MainWindow w;
    w.setPersistentSettings(false);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    auto* panel = w.findChild<PreviewPanel*>("PreviewPanel");
    QVERIFY(panel);
    auto* controls = panel->findChild<QWidget*>("RetinaImageControls");
    QVERIFY(controls);
    auto* speckle = controls->findChild<QSpinBox*>("RetinaSpeckle");
    auto* grain = controls->findChild<QComboBox*>("RetinaSpeckleGrain");
    auto* calibration = controls->findChild<QComboBox*>("RetinaCalibration");
    QVERIFY(speckle && grain && calibration);
    QCOMPARE(panel->mode(), PreviewPanel::Mode::Displays);
    QVERIFY(controls->isHidden());
    panel->setMode(PreviewPanel::Mode::RetinaImage);
    QVERIFY(controls->isVisible() && speckle->isVisible() && grain->isVisible() && calibration->isVisible());
    QCOMPARE(speckle->minimum(), 0);
    QCOMPARE(speckle->maximum(), 16);
    QCOMPARE(speckle->text(), QString("off"));
    auto* seed = controls->findChild<QSpinBox*>("RetinaSpeckleSeed");
    QVERIFY(seed);
    QVERIFY(!grain->isEnabled() && !seed->isEnabled());  // no speckle, no grain or seed to choose
    QCOMPARE(seed->value(), 1);
    speckle->setValue(3);
    QVERIFY(grain->isEnabled() && seed->isEnabled());
    grain->setCurrentIndex(1);
    calibration->setCurrentIndex(1);
    QCOMPARE(panel->retinaOptions(), (RetinaPreviewOptions{3, true, true}));
    // Kept across the modes (for the session).
    panel->setMode(PreviewPanel::Mode::Displays);
    QVERIFY(controls->isHidden());
    panel->setMode(PreviewPanel::Mode::RetinaImage);
    QCOMPARE(panel->retinaOptions(), (RetinaPreviewOptions{3, true, true}));
    // The controls fit the dock's width (nothing clipped at the panel's minimum).
    QVERIFY2(controls->minimumSizeHint().width() <= 340,
             qPrintable(QString::number(controls->minimumSizeHint().width())));
  }

  void speckleContrastIsTheModelsAndTheClis() {
    studio::MainWindow w;
    w.setPersistentSettings(false);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    auto* panel = w.findChild<PreviewPanel*>("PreviewPanel");
    QVERIFY(panel);
    // A target already at the preview's retina width (960 px), so that the preview, the model
    // called here and fovea-cli render the very same pixels.
    const Scene scene = w.document()->scene();
    const image::DisplayAngles a = image::displayAngles(scene);
    const std::string png = (testing::testTmpDir("gui_preview_retina") / "target-960.png").string();
    image::writeLinearRgb(png, image::makeTestTarget({960, 540}, a.peripheral_fov_deg, 20.0));
    const cv::Mat target = image::readLinearRgb(png);
    QCOMPARE(target.cols, 960);
    panel->loadTarget(QString::fromStdString(png));
    panel->setMode(PreviewPanel::Mode::RetinaImage);
    const std::array<double, 2> gaze{5.0, 0.0};
    panel->setGaze(gaze[0], gaze[1]);
    panel->setAccommodation(1.25);
    const RetinaPreviewOptions wanted{4, true, false};
    panel->setRetinaOptions(wanted);
    QTRY_VERIFY_WITH_TIMEOUT(retinaFrameOf(panel, gaze, 1.25, wanted), 120000);
    const widgets::PreviewFrame f = panel->lastFrame();
    QVERIFY(f.speckle_contrast && f.speckle_expected);

    image::RetinaImageOptions o;
    o.gaze_deg = gaze;
    o.accommodation_d = 1.25;
    o.speckle_patterns = 4;
    o.speckle_grain_pupil = true;
    const image::RetinaImageResult r = image::renderRetinaImage(scene, target, o);
    QVERIFY(r.speckle_contrast && r.speckle_expected);
    qInfo("speckle contrast: studio %.12f, model %.12f (expected %.6f)", *f.speckle_contrast, *r.speckle_contrast,
          *r.speckle_expected);
    QVERIFY(std::abs(*f.speckle_contrast - *r.speckle_contrast) <= 1e-9);
    QVERIFY(std::abs(*f.speckle_expected - *r.speckle_expected) <= 1e-9);

    QProcess cli;
    const QString out = QString::fromStdString((testing::testTmpDir("gui_preview_retina") / "retina.png").string());
    cli.start(FOVEA_CLI_PATH,
              {"retina-image", "--image", QString::fromStdString(png), "--out", out, "--gaze-deg", "5,0",
               "--accommodation-d", "1.25", "--speckle", "4", "--speckle-grain", "pupil", "--json"});
    QVERIFY(cli.waitForFinished(120000));
    QVERIFY2(cli.exitCode() == 0, cli.readAllStandardError().constData());
    const nlohmann::json j = nlohmann::json::parse(cli.readAllStandardOutput().toStdString());
    const double c = j.at("speckle_contrast").get<double>();
    qInfo("speckle contrast: fovea-cli %.12f", c);
    QVERIFY(std::abs(*f.speckle_contrast - c) <= 1e-9);

    const QString info = panel->findChild<QLabel*>("RetinaImageInfo")->text();
    QVERIFY2(info.contains(QString("speckle contrast %1 (expected %2)")
                               .arg(*f.speckle_contrast, 0, 'f', 3)
                               .arg(*f.speckle_expected, 0, 'f', 3)),
             qPrintable(info));
    // Another seed (the options row's seed box): other patterns, the model's and fovea-cli's
    // `--seed 7` to 1e-9, and a contrast other than seed 1's.
    auto* seedBox = panel->findChild<QSpinBox*>("RetinaSpeckleSeed");
    QVERIFY(seedBox && seedBox->isEnabled());
    seedBox->setValue(7);
    const RetinaPreviewOptions seeded{4, true, false, 7};
    QCOMPARE(panel->retinaOptions(), seeded);
    QTRY_VERIFY_WITH_TIMEOUT(retinaFrameOf(panel, gaze, 1.25, seeded), 120000);
    o.speckle_seed = 7;
    const image::RetinaImageResult r7 = image::renderRetinaImage(scene, target, o);
    const double c7 = *panel->lastFrame().speckle_contrast;
    qInfo("speckle contrast, seed 7: studio %.12f, model %.12f", c7, *r7.speckle_contrast);
    QVERIFY(std::abs(c7 - *r7.speckle_contrast) <= 1e-9);
    QVERIFY(std::abs(c7 - *f.speckle_contrast) > 1e-6);
    QProcess cli7;
    cli7.start(FOVEA_CLI_PATH,
               {"retina-image", "--image", QString::fromStdString(png), "--out", out, "--gaze-deg", "5,0",
                "--accommodation-d", "1.25", "--speckle", "4", "--speckle-grain", "pupil", "--seed", "7", "--json"});
    QVERIFY(cli7.waitForFinished(120000));
    QVERIFY2(cli7.exitCode() == 0, cli7.readAllStandardError().constData());
    QVERIFY(std::abs(
                nlohmann::json::parse(cli7.readAllStandardOutput().toStdString()).at("speckle_contrast").get<double>() -
                c7) <= 1e-9);
    // Off again: no speckle figure.
    panel->setRetinaOptions({0, true, false});
    QTRY_VERIFY_WITH_TIMEOUT(retinaFrameOf(panel, gaze, 1.25, {0, true, false}), 120000);
    QVERIFY(!panel->lastFrame().speckle_contrast);
    QVERIFY(!panel->findChild<QLabel*>("RetinaImageInfo")->text().contains("speckle"));
  }

  void perLaserCalibrationRemovesTheLateralColour() {
    studio::MainWindow w;
    w.setPersistentSettings(false);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    auto* panel = w.findChild<PreviewPanel*>("PreviewPanel");
    QVERIFY(panel);
    // Red and blue lasers 10 nm off their layers' recording wavelengths (660, 460 nm): the layers
    // part the colours of a pixel (41 and 59 arcmin at the line of sight, tst_retinal_psf).
    const QStringList refused = w.document()->applyEdit("lasers off their layers", [](Scene& s) {
      s.projector.wavelengths_nm = {650.0, 532.0, 450.0};
    });
    QVERIFY2(refused.isEmpty(), qPrintable(refused.join("; ")));
    panel->setMode(PreviewPanel::Mode::RetinaImage);
    const std::array<double, 2> gaze{0.0, 0.0};
    panel->setGaze(0, 0);
    QTRY_VERIFY_WITH_TIMEOUT(retinaFrameOf(panel, gaze, panel->accommodation(), {}), 120000);
    const std::optional<double> common = panel->lastFrame().lateral_colour_arcmin;
    QVERIFY(common);
    double largest = 0;
    for (const LateralColour& c : lateralColourAtLineOfSight(w.document()->scene(), gaze))
      if (c.valid) largest = std::max(largest, std::hypot(c.offset_arcmin[0], c.offset_arcmin[1]));
    qInfo("lateral colour at the line of sight, one calibration: %.6f arcmin (model %.6f)", *common, largest);
    QVERIFY(largest > 50);
    QVERIFY(std::abs(*common - largest) <= 1e-9);
    QVERIFY(panel->findChild<QLabel*>("RetinaImageInfo")
                ->text()
                .contains(QString("lateral colour %1′").arg(largest, 0, 'f', 1)));

    const RetinaPreviewOptions perLaser{0, false, true};
    panel->setRetinaOptions(perLaser);
    QTRY_VERIFY_WITH_TIMEOUT(retinaFrameOf(panel, gaze, panel->accommodation(), perLaser), 120000);
    const std::optional<double> own = panel->lastFrame().lateral_colour_arcmin;
    QVERIFY(own);
    qInfo("lateral colour at the line of sight, per-laser calibration: %.6f arcmin", *own);
    QVERIFY(std::abs(*own) < 1e-6);
    QVERIFY(panel->findChild<QLabel*>("RetinaImageInfo")->text().contains("per-laser calibration"));
  }

  void hoeFollowingTheGazeUsesTheStudiosXp() {
    studio::MainWindow w;
    w.setPersistentSettings(false);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    auto* panel = w.findChild<PreviewPanel*>("PreviewPanel");
    QVERIFY(panel);
    widgets::GazePanel* gazePanel = w.liveTraceFeatures()->gazePanel();
    widgets::LiveTrace* trace = w.liveTraceFeatures()->liveTrace();
    const std::array<double, 2> gaze{10.0, 0.0};
    gazePanel->setFollowGaze(true);
    gazePanel->setGaze(gaze[0], gaze[1]);
    panel->setMode(PreviewPanel::Mode::RetinaImage);
    panel->setGaze(gaze[0], gaze[1]);
    QTRY_VERIFY_WITH_TIMEOUT(retinaFrameOf(panel, gaze, panel->accommodation(), {}), 120000);
    QTRY_VERIFY_WITH_TIMEOUT(trace->latest() && trace->latest()->detail == widgets::TraceDetail::Refined &&
                                 trace->latest()->scene.eye.gaze_deg == gaze && trace->latest()->settings.follow_gaze,
                             120000);
    const Scene scene = w.document()->scene();
    QVERIFY(scene.view.hoe_follows_gaze);
    const std::array<double, 2> xp = hoeTravel(scene, gaze, sceneXpRule(scene)).shift_mm;
    const std::array<double, 2> shown = panel->lastFrame().hoe_shift_mm, traced = trace->latest()->hoe_shift_mm;
    qInfo("x_p at yaw 10 deg: preview %.6f mm, live trace %.6f mm, hoeTravel %.6f mm", shown[0], traced[0], xp[0]);
    QVERIFY(std::abs(xp[0]) > 0.1);
    QCOMPARE(shown, xp);
    QCOMPARE(traced, xp);
    QVERIFY(panel->findChild<QLabel*>("RetinaImageInfo")->text().contains("HOE x_p"));
    // Not following: no shift.
    gazePanel->setFollowGaze(false);
    QTRY_VERIFY_WITH_TIMEOUT(!w.document()->scene().view.hoe_follows_gaze, 20000);
    QTRY_VERIFY_WITH_TIMEOUT(retinaFrameOf(panel, gaze, panel->accommodation(), {}) &&
                                 panel->lastFrame().hoe_shift_mm == (std::array<double, 2>{0, 0}),
                             120000);
  }

  void reportTakesThePreviewsOptions() {
    studio::MainWindow w;
    w.setPersistentSettings(false);
    auto* panel = w.findChild<PreviewPanel*>("PreviewPanel");
    QVERIFY(panel);
    panel->setRetinaOptions({2, true, true});
    studio::ReportOptions o;
    o.rays = 300;
    o.sweep_step_deg = 10;
    o.kogelnik_vs_rcwa = false;
    const QString html =
        QString::fromStdString((testing::testTmpDir("gui_preview_retina") / "report-retina-options.html").string());
    QString error;
    QVERIFY2(w.analysisFeatures()->exportReport(html, o, &error), qPrintable(error));
    const QString text = QString::fromStdString(testing::readFileText(html.toStdString()));
    QVERIFY(text.contains("The retinal image at gaze"));
    QVERIFY2(text.contains("Speckle: 2 patterns per laser, pupil grain (seed 1), contrast "),
             "no speckle in the caption");
    QVERIFY(text.contains("each laser warped on its own (per-laser calibration), lateral colour 0.0 arcmin"));
    // The preview's defaults: no speckle, one calibration.
    panel->setRetinaOptions({});
    QVERIFY2(w.analysisFeatures()->exportReport(html, o, &error), qPrintable(error));
    const QString plain = QString::fromStdString(testing::readFileText(html.toStdString()));
    QVERIFY(plain.contains(
        "Speckle off; one geometric calibration (the laser nearest 555 nm), lateral colour 0.0 arcmin."));
  }
};

QTEST_MAIN(TestPreviewRetinaOptions)

}  // namespace tst_preview_retina_options
#include "tst_preview_retina_options.moc"
