// The closed gaze loop on the virtual bench: main-sequence saccades, the tracked frames
// against the true gaze, and the stage simulation: fast stages keep the inset on the
// fovea, the prototype's slow screw stages do not, and added latency makes it worse.
#include <QtTest>
#include "app/embedded_scene.h"
#include "tests/test_paths.h"

#include <cmath>

#include "devices/bench/closed_gaze_loop.h"
#include "devices/camera/virtual_eye_renderer.h"
#include "devices/virtual/sim_clock.h"
#include "model/gaze/pupil_detector.h"
#include "model/scene/scene_io.h"

namespace tst_closed_gaze_loop {

using namespace fovea;
using namespace fovea::devices;

namespace {
using fovea::embeddedDefaultScene;
ClosedLoopOptions smallRun() {
  ClosedLoopOptions o;
  o.saccades = 3;
  o.seed = 4;
  o.camera_fps = 60;
  o.exposure_s = 0.004;
  o.readout_s = 0.002;
  return o;
}
}  // namespace

class TestClosedGazeLoop : public QObject {
  Q_OBJECT
  Scene scene_ = embeddedDefaultScene();
  TrackedRun run_;

 private slots:
  void initTestCase() { run_ = trackTrajectory(scene_, smallRun()); }

  void mainSequence() {
    // V = 700 (1 - exp(-A/10)); minimum-jerk duration 1.875 A / V.
    QVERIFY(std::abs(mainSequencePeakVelocity(10) - 700 * (1 - std::exp(-1.0))) < 1e-9);
    QVERIFY(std::abs(saccadeDuration(10) - 1.875 * 10 / (700 * (1 - std::exp(-1.0)))) < 1e-12);
    QVERIFY(saccadeDuration(2) > 0.025 && saccadeDuration(2) < 0.035);
    QVERIFY(saccadeDuration(20) > 0.055 && saccadeDuration(20) < 0.07);
    QVERIFY(mainSequencePeakVelocity(20) > mainSequencePeakVelocity(5));
  }

  void trajectoryStaysInRange() {
    const EyeTrajectory t = makeSaccadeTrajectory(scene_, smallRun());
    QCOMPARE(static_cast<int>(t.saccades.size()), 3);
    for (const auto& s : t.saccades) {
      const auto end = t.gazeAt(s.onset_s + s.duration_s);
      QVERIFY(std::abs(end[0] - s.to_deg[0]) < 1e-9 && std::abs(end[1] - s.to_deg[1]) < 1e-9);
      for (double v : s.to_deg) QVERIFY(v >= scene_.eye.gaze_range_deg[0] && v <= scene_.eye.gaze_range_deg[1]);
      QVERIFY(s.amplitude_deg > 0.5);
    }
  }

  void trackedGazeFollowsTruth() {
    QVERIFY(run_.calibration_accuracy_deg < 1.0);
    int found = 0;
    double err = 0;
    for (const auto& f : run_.frames) {
      if (!f.found) continue;
      ++found;
      err += std::hypot(f.gaze_deg[0] - f.true_gaze_deg[0], f.gaze_deg[1] - f.true_gaze_deg[1]);
    }
    QVERIFY(found > 0.9 * static_cast<double>(run_.frames.size()));
    qInfo("tracked %d of %zu frames, mean gaze error %.3f deg", found, run_.frames.size(), err / found);
    QVERIFY(err / found < 1.5);
  }

  void fastStagesKeepInsetOnFovea() {
    ClosedLoopOptions o = smallRun();
    o.stage_model = "DDSM50";
    const ClosedLoopResult fast = simulateStages(scene_, run_, o);
    o.stage_model = "MTS25-Z8";
    const ClosedLoopResult slow = simulateStages(scene_, run_, o);
    qInfo("DDSM50: inset error mean %.2f deg, off fovea %.3f s, settle %.1f ms; MTS25-Z8: %.2f deg, %.3f s, %.1f ms",
          fast.inset_error_deg.mean, fast.time_off_fovea_s, fast.settle_s.mean * 1e3, slow.inset_error_deg.mean,
          slow.time_off_fovea_s, slow.settle_s.mean * 1e3);
    QCOMPARE(fast.hoe_stage, std::string("DDSM50"));
    QVERIFY(fast.inset_error_deg.mean < 1.5);
    QVERIFY(fast.settle_s.mean < 0.15);
    QCOMPARE(fast.unsettled, 0);
    QVERIFY(slow.unsettled > 0);  // the screw stages are still travelling at the next saccade
    QVERIFY(slow.inset_error_deg.mean > 2 * fast.inset_error_deg.mean);
    QVERIFY(slow.time_off_fovea_s > fast.time_off_fovea_s);
    QVERIFY(slow.fov_partly_lost_s >= fast.fov_partly_lost_s);
    // Latency budget: capture + detect + map + command.
    QVERIFY(std::abs(fast.latency_to_command_s - (0.006 + o.detect_s + o.map_s + o.command_s)) < 1e-12);
    o.stage_model = "DDSM50";
    o.extra_latency_s = 0.05;
    const ClosedLoopResult late = simulateStages(scene_, run_, o);
    QVERIFY(late.inset_error_deg.mean > fast.inset_error_deg.mean);
    QVERIFY(late.settle_s.mean > fast.settle_s.mean + 0.03);
    QCOMPARE(late.unsettled, 0);
  }

  void virtualEyeCameraFramesAreTracked() {
    // The bench's virtual eye camera shows the renderer's eye at the gaze of the bench time;
    // the detector finds the pupil where the renderer's ground truth puts it.
    auto clock = std::make_shared<SimulatedClock>();
    const auto gazeAt = [](double t) { return std::array<double, 2>{-12 + 100 * t, 4}; };
    VirtualCamera cam(clock, virtualEyeRenderer(scene_, gazeAt), {400, 400}, 60.0, 3);
    cam.open();
    for (int i = 0; i < 3; ++i) {
      const Frame f = cam.grab();
      QCOMPARE(f.image.size(), cv::Size(400, 400));
      const gaze::PupilDetection d = gaze::detectPupil(f.image);
      QVERIFY2(d.found, d.reason.c_str());
      gaze::EyeAppearance eye;
      eye.pupil_diameter_mm = scene_.eye.pupil_diameter_mm;
      gaze::EyeFrameSpec spec;
      spec.gaze_deg = gazeAt(f.exposure_start_s);
      const auto truth = gaze::renderEyeFrame({}, eye, spec).truth;
      QVERIFY(std::hypot(d.ellipse.centre.x - truth.pupil.centre.x, d.ellipse.centre.y - truth.pupil.centre.y) < 1.0);
    }
  }

  void unknownStageModelRefused() {
    ClosedLoopOptions o = smallRun();
    o.stage_model = "K10CR1";  // a rotation mount cannot carry the HOE's translation
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, simulateStages(scene_, run_, o));
  }
};

QTEST_APPLESS_MAIN(TestClosedGazeLoop)

}  // namespace tst_closed_gaze_loop
#include "tst_closed_gaze_loop.moc"
