// The Bench dock's pupil tracker under Xvfb: with "Track gaze" on, it calibrates on the
// virtual IR eye camera, finds the pupil in the live frames (ellipse, glints, confidence
// overlaid) and emits the tracked gaze, which lands within a degree of the eye's gaze; with
// the detector combo on "auto" (learned proposal, classical refinement) it does the same.
#include <QtTest>
#include "tests/test_paths.h"

#include <QComboBox>
#include <QSignalSpy>

#include <cmath>
#include <filesystem>

#include "model/scene/scene_io.h"
#include "widgets/bench/pupil_tracker_view.h"

namespace tst_pupil_tracker_view {

using namespace fovea;

class TestPupilTrackerView : public QObject {
  Q_OBJECT
 private slots:
  void tracksTheVirtualEye() {
    auto r = loadSceneFile(std::string(FOVEA_SOURCE_DIR) + "/resources/scenes/prototype-bench.json");
    QVERIFY(r.ok());
    widgets::PupilTrackerView view(*r.scene);
    view.resize(520, 600);
    view.show();
    QSignalSpy spy(&view, &widgets::PupilTrackerView::gazeTracked);
    view.setEyeGaze(8, -4);
    view.setTracking(true);
    QTRY_VERIFY_WITH_TIMEOUT(spy.count() >= 2, 120000);
    const auto g = view.trackedGaze();
    QVERIFY(g.has_value());
    qInfo("tracked %.2f, %.2f deg (eye at 8, -4); calibration accuracy %.2f deg", (*g)[0], (*g)[1],
          view.calibrationAccuracyDeg().value_or(-1));
    QVERIFY(std::hypot((*g)[0] - 8, (*g)[1] + 4) < 1.0);
    QVERIFY(view.lastDetection().found);
    QVERIFY(view.lastDetection().glints_px.size() >= 4);
    QVERIFY(view.calibrationAccuracyDeg().value_or(99) < 1.0);
    const auto dir = std::filesystem::path(qEnvironmentVariable("FOVEA_TEST_TMP", "/tmp").toStdString());
    view.grab().save(QString::fromStdString((dir / "pupil_tracker_view.png").string()));
    view.setTracking(false);
    QVERIFY(!view.tracking());
  }

  void tracksWithTheAutoDetector() {
    qputenv("FOVEA_PUPIL_MODEL", QByteArray(FOVEA_SOURCE_DIR) + "/resources/pupil/pupil-net.onnx");
    auto r = loadSceneFile(std::string(FOVEA_SOURCE_DIR) + "/resources/scenes/prototype-bench.json");
    QVERIFY(r.ok());
    widgets::PupilTrackerView view(*r.scene);
    view.show();
    auto* combo = view.findChild<QComboBox*>("pupilDetector");
    QVERIFY(combo);
    QCOMPARE(combo->count(), 3);
    QCOMPARE(view.detector(), gaze::PupilDetectorKind::Classical);
    view.setDetector(gaze::PupilDetectorKind::Auto);
    QCOMPARE(combo->currentText(), QString("auto"));
    QSignalSpy spy(&view, &widgets::PupilTrackerView::gazeTracked);
    view.setEyeGaze(-6, 3);
    view.setTracking(true);
    QTRY_VERIFY_WITH_TIMEOUT(spy.count() >= 2, 120000);
    const auto g = view.trackedGaze();
    QVERIFY(g.has_value());
    qInfo("auto: tracked %.2f, %.2f deg (eye at -6, 3)", (*g)[0], (*g)[1]);
    QVERIFY(std::hypot((*g)[0] + 6, (*g)[1] - 3) < 1.0);
    view.setTracking(false);
  }
};

QTEST_MAIN(TestPupilTrackerView)

}  // namespace tst_pupil_tracker_view
#include "tst_pupil_tracker_view.moc"
