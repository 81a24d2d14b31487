// Calibration on the virtual bench: the geometric capture plan runs through the emulated
// stages (real APT bytes, simulated time) and the virtual eye camera; every frame is exposed
// after the axes settled at the step's targets; the warps fitted to the detected corners
// recover the ground-truth display -> camera maps to well under 0.5 px RMS. Capture sessions
// keep every capture in their folder and resume where they stopped; measurement imports are
// checked. The virtual camera shows what the stages do.
#include <QtTest>
#include "app/embedded_scene.h"
#include "tests/test_paths.h"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "devices/bench/live_bench.h"
#include "devices/calibration/capture_session.h"
#include "model/color/color_calibration.h"
#include "model/image/geometric_calibration.h"
#include "model/scene/scene_io.h"
#include "tests/test_files.h"

namespace tst_virtual_calibration {

using namespace fovea;
using namespace fovea::devices;
namespace fs = std::filesystem;

namespace {

using fovea::embeddedDefaultScene;

fs::path tmpDir(const std::string& name) {
  return fovea::testing::testTmpDir(name, true);
}

std::unique_ptr<LiveBench> virtualBench(const Scene& scene) {
  LiveBenchOptions o;
  o.allow_hardware = false;
  o.clock = std::make_shared<SimulatedClock>();
  auto live = std::make_unique<LiveBench>(scene, o);
  for (auto& f : live->bench().connectAll()) f.get();
  live->camera().open();
  return live;
}

double coordinate(const BenchPose& p, const StageTarget& t) {
  if (t.element == "hoe") return p.hoe_shift_mm[t.axis == "x" ? 0 : 1];
  if (t.element == "foveal_display") return p.foveal_shift_mm[t.axis == "x" ? 0 : 1];
  return p.camera_gaze_deg[t.axis == "yaw" ? 0 : 1];
}

}  // namespace

class TestVirtualCalibration : public QObject {
  Q_OBJECT
 private slots:
  void planCoversTheGazeRangeWithinTheSoftLimits() {
    const Scene s = embeddedDefaultScene();
    const Plan p = geometricPlan(s);
    // Five gazes over +-20 deg: the projector at each; the micro-OLED where x_f stays within
    // +-8 mm (|alpha| <= 12 deg), so not at +-20 deg.
    QCOMPARE(p.steps.size(), std::size_t{8});
    QCOMPARE(p.skipped.size(), std::size_t{2});
    for (const auto& step : p.steps) {
      for (const auto& t : step.targets) QVERIFY(withinSoftLimits(s, t));
      QCOMPARE(captureStepFromJson(toJson(step)), step);
    }
    QCOMPARE(colorPlan(s).steps.size(), std::size_t{2 * 14});
    QCOMPARE(gazePlan(s).steps.size(), std::size_t{5});
  }

  void geometricCalibrationRecoversTheGroundTruth() {
    const Scene s = embeddedDefaultScene();
    auto live = virtualBench(s);
    const Plan plan = geometricPlan(s);
    CaptureSession session(CaptureKind::Geometric, plan.steps, tmpDir("virtual_calibration"), s.name);
    BenchRig rig = live->rig();
    QVERIFY(rig.is_virtual);
    for (std::size_t i = 0; i < plan.steps.size(); ++i) session.capture(i, rig);
    QVERIFY(session.complete());

    image::ErrorTally all;
    for (const auto& step : plan.steps) {
      const CaptureRecord* r = session.record(step.id);
      QVERIFY(r && r->pose);
      // The frame was rendered with every axis at its target (no stale frame).
      for (const auto& t : step.targets) QVERIFY(std::abs(coordinate(*r->pose, t) - t.value) < 1e-3);
      QVERIFY(fs::exists(session.folder() / r->image));
      const auto obs = image::observeBoard(session.image(step.id), step.pattern);
      QVERIFY2(obs, step.id.c_str());
      const auto fit = image::fitDisplayWarp(*obs, image::WarpModel::Poly3);
      const auto truth = live->optics()->groundTruth(step.display, *r->pose);
      const image::ErrorTally e =
          image::compareWithTruth(fit.warp, step.pattern, [&](const Eigen::Vector2d& p) { return truth->toCamera(p); });
      qInfo("%s: %d corners, residual %.3f px, ground truth %.3f px (%d points)", step.id.c_str(), fit.corners,
            fit.residual_px_rms, e.rms(), e.count);
      QVERIFY(e.count > 500);
      QVERIFY(e.rms() < 0.5);
      all.add(e);
    }
    qInfo("all captures: %.3f px RMS against the ground truth", all.rms());
    QVERIFY(all.rms() < 0.5);
  }

  void theCameraSeesTheStagesMove() {
    // The HOE stage moves the projector's board in the camera; the frame after the move shows it.
    const Scene s = embeddedDefaultScene();
    auto live = virtualBench(s);
    BenchRig rig = live->rig();
    CaptureStep a;
    a.id = "a";
    a.display = BenchDisplay::Peripheral;
    a.pattern = peripheralBoard(s);
    a.targets = {{"hoe", "x", 0.0}};
    CaptureStep b = a;
    b.id = "b";
    b.targets = {{"hoe", "x", 2.0}};
    CaptureSession session(CaptureKind::Geometric, {a, b}, {});
    session.capture(0, rig);
    session.capture(1, rig);
    const auto oa = image::observeBoard(session.image("a"), a.pattern);
    const auto ob = image::observeBoard(session.image("b"), b.pattern);
    QVERIFY(oa && ob);
    const double shift = (oa->pairs[20].dst - ob->pairs[20].dst).norm();
    qInfo("HOE 0 -> 2 mm moved the board by %.1f px", shift);
    QVERIFY(shift > 10.0);
    // The frame of "b" was exposed with the HOE at its target, after the frame of "a".
    QVERIFY(std::abs(session.record("b")->positions.at("hoe.x") - 2.0) < 1e-6);
    QVERIFY(std::abs(session.record("a")->positions.at("hoe.x") - 0.0) < 1e-6);
    QVERIFY(session.record("b")->sequence > session.record("a")->sequence);
  }

  void theAxesOfOneStepMoveAtOnceWhateverTheThreadTiming() {
    // A step that moves the camera's yaw and the HOE: both moves start at the same simulated
    // instant, so the frame comes max(durations) after the step began, not their sum, and the
    // same frame whichever axis thread runs first (a late thread once meant a later move, and
    // captures that changed from run to run on a loaded machine).
    const Scene s = embeddedDefaultScene();
    CaptureStep both;
    both.id = "both";
    both.display = BenchDisplay::Peripheral;
    both.pattern = peripheralBoard(s);
    both.targets = {{"camera", "yaw", 10.0}, {"hoe", "x", 2.0}};
    CaptureStep yaw = both, hoe = both;
    yaw.id = "yaw", yaw.targets = {both.targets[0]};
    hoe.id = "hoe", hoe.targets = {both.targets[1]};
    // Seconds from the step's start to its frame; `late` keeps the HOE's thread busy for 300 ms
    // of wall time before it gets the move.
    const auto delay = [&s](const CaptureStep& step, const char* late) {
      auto live = virtualBench(s);
      BenchRig rig = live->rig();
      if (late)
        live->bench().find(late, late == std::string("hoe") ? "x" : "yaw")->submit([](Stage&) {
          std::this_thread::sleep_for(std::chrono::milliseconds(300));
        });
      const double t0 = live->camera().now();
      CaptureSession session(CaptureKind::Geometric, {step}, {});
      session.capture(0, rig);
      return session.record(step.id)->exposure_start_s - t0;
    };
    const double d_yaw = delay(yaw, nullptr), d_hoe = delay(hoe, nullptr), d_both = delay(both, nullptr);
    const double d_hoe_late = delay(both, "hoe"), d_yaw_late = delay(both, "camera");
    qInfo("frame after: yaw alone %.3f s, HOE alone %.3f s, both %.3f s (HOE thread late %.3f s, yaw late %.3f s)",
          d_yaw, d_hoe, d_both, d_hoe_late, d_yaw_late);
    QVERIFY(d_yaw > 0.2 && d_hoe > 0.2);     // both moves take time
    const double frame = 1.0 / 30.0 + 1e-9;  // the camera's frame period: the frame slot rounds up
    QVERIFY(d_both <= std::max(d_yaw, d_hoe) + frame);
    QVERIFY(d_both < d_yaw + d_hoe - frame);
    QCOMPARE(d_hoe_late, d_both);
    QCOMPARE(d_yaw_late, d_both);
  }

  void aStillBenchIsRenderedOnceAndTheEyesGazeChangesNothing() {
    // The camera maps follow the camera's pose, not the design's eye gaze: a scene differing
    // only in gaze renders the same radiance (a fresh bench built for it agrees), so a gaze
    // drag in the studio keeps the maps and the last frame; any other change renders anew.
    const Scene s = embeddedDefaultScene();
    auto live = virtualBench(s);
    VirtualOptics* optics = live->optics();
    QVERIFY(optics);
    optics->show(BenchDisplay::Peripheral, peripheralBoard(s));
    const BenchPose still{};
    const cv::Mat first = optics->render(still);
    QVERIFY(cv::norm(first, cv::NORM_L1) > 100.0);  // the board is seen
    QCOMPARE(cv::norm(first, optics->render(still), cv::NORM_INF), 0.0);
    Scene turned = s;
    turned.eye.gaze_deg = {12.0, -4.0};
    optics->setScene(turned);
    QCOMPARE(cv::norm(first, optics->render(still), cv::NORM_INF), 0.0);
    auto fresh = virtualBench(turned);
    fresh->optics()->show(BenchDisplay::Peripheral, peripheralBoard(s));
    QCOMPARE(cv::norm(first, fresh->optics()->render(still), cv::NORM_INF), 0.0);
    // A design change (the HOE 1.5 mm to the side) and a pattern change render anew.
    Scene moved = turned;
    moved.hoe.pose.position_mm[0] += 1.5;
    optics->setScene(moved);
    const double design = cv::norm(first, optics->render(still), cv::NORM_L1) / cv::norm(first, cv::NORM_L1);
    qInfo("HOE 1.5 mm aside: radiance changed by %.1f %% (L1)", 100.0 * design);
    QVERIFY(design > 0.05);
    optics->setScene(s);
    optics->show(BenchDisplay::Peripheral, image::DisplayPattern{});
    QVERIFY(cv::norm(optics->render(still), cv::NORM_L1) < 1e-9 * cv::norm(first, cv::NORM_L1) + 1e-6);
  }

  void sessionsResumeAndKeepTheirCaptures() {
    const Scene s = embeddedDefaultScene();
    auto live = virtualBench(s);
    BenchRig rig = live->rig();
    const Plan plan = gazePlan(s);
    const fs::path dir = tmpDir("capture_resume");
    std::string first_image;
    {
      CaptureSession session(CaptureKind::Gaze, plan.steps, dir, s.name);
      session.capture(0, rig);
      session.capture(1, rig);
      first_image = session.record(plan.steps[0].id)->image;
      QCOMPARE(session.nextStep().value(), std::size_t{2});
    }  // "paused": the studio closed
    CaptureSession resumed(CaptureKind::Gaze, plan.steps, dir, s.name);
    QCOMPARE(resumed.capturedCount(), std::size_t{2});
    QVERIFY(resumed.done(0) && resumed.done(1) && !resumed.done(2));
    QCOMPARE(resumed.nextStep().value(), std::size_t{2});
    QVERIFY(!resumed.image(plan.steps[0].id).empty());  // read back from the folder
    while (auto n = resumed.nextStep()) resumed.capture(*n, rig);
    QVERIFY(resumed.complete());
    QCOMPARE(resumed.record(plan.steps[0].id)->image, first_image);
    std::ifstream in(dir / "manifest.json");
    const auto j = nlohmann::json::parse(in);
    QCOMPARE(j["format"].get<std::string>(), std::string("fovea-capture-session"));
    QCOMPARE(j["captures"].size(), plan.steps.size());
    for (const auto& c : j["captures"]) QVERIFY(fs::exists(dir / c["image"].get<std::string>()));
    // Another plan in the same folder is refused rather than mixed in.
    QVERIFY_THROWS_EXCEPTION(std::runtime_error, CaptureSession(CaptureKind::Color, colorPlan(s).steps, dir));
  }

  void colourMeasurementsAreCheckedAndKept() {
    const Scene s = embeddedDefaultScene();
    const fs::path dir = tmpDir("capture_colour");
    CaptureSession session(CaptureKind::Color, colorPlan(s).steps, dir, s.name);
    const fs::path bad = dir.parent_path() / "bad_measurements.json";
    std::ofstream(bad) << R"({"format":"fovea-color-measurements","version":1,"foveal":{}})";
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, session.importMeasurement(bad));
    color::ColorMeasurements m;
    const std::array<color::Xy, 3> xy{{{0.68, 0.31}, {0.26, 0.69}, {0.15, 0.05}}};
    for (auto* d : {&m.foveal, &m.peripheral})
      for (int c = 0; c < 3; ++c) {
        d->channels[c].xy = xy[c];
        for (int code = 0; code < 256; ++code) d->channels[c].Y.push_back(100.0 * std::pow(code / 255.0, 2.2));
      }
    const fs::path good = dir.parent_path() / "measurements.json";
    std::ofstream(good) << color::toJson(m).dump();
    const fs::path kept = session.importMeasurement(good);
    QVERIFY(fs::exists(kept));
    CaptureSession reopened(CaptureKind::Color, colorPlan(s).steps, dir, s.name);
    QCOMPARE(reopened.measurements().size(), std::size_t{1});
  }
};

QTEST_GUILESS_MAIN(TestVirtualCalibration)

}  // namespace tst_virtual_calibration
#include "tst_virtual_calibration.moc"
