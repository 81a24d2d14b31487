// The wide synthetic eye domain (determinism, subsets' definitions, corneal refraction
// against the single-surface closed form) and the learned pupil detector: the shipped ONNX
// model loads in OpenCV's DNN module, a missing or broken model file is a clear error, bad
// frames are refused, and on a held-out seed of the wide domain the learned and auto
// detectors reach the rates measured for them (docs/gaze-tracking.md, thresholds with margin).
#include <QtTest>
#include "tests/test_paths.h"

#include <algorithm>
#include <cmath>
#include <fstream>

#include "model/gaze/learned_pupil_detector.h"
#include "model/gaze/pupil_benchmark.h"
#include "model/gaze/pupil_detector_choice.h"
#include "model/gaze/tracked_calibration.h"
#include "model/gaze/wide_eye_domain.h"
#include "tests/test_files.h"

namespace tst_learned_pupil {

using namespace fovea::gaze;

namespace {
std::string shippedModel() {
  return std::string(FOVEA_SOURCE_DIR) + "/resources/pupil/pupil-net.onnx";
}
std::string shippedRefineModel() {
  return std::string(FOVEA_SOURCE_DIR) + "/resources/pupil/pupil-refine.onnx";
}
void copyFile(const std::string& from, const std::string& to) {
  std::ifstream in(from, std::ios::binary);
  std::ofstream(to, std::ios::binary) << in.rdbuf();
}
// The shipped full-frame model copied alone into a fresh directory: the one-stage detector.
std::string oneStageModel(const std::string& dir_name) {
  const std::string alone = (fovea::testing::testTmpDir(dir_name, true) / "pupil-net.onnx").string();
  copyFile(shippedModel(), alone);
  return alone;
}
struct Rates {
  int with_pupil = 0, within = 0, found_closed = 0, closed = 0;
};
Rates rates(PupilDetectorKind kind, WideSubset subset, int frames, std::uint32_t seed) {
  Rates r;
  for (int i = 0; i < frames; ++i) {
    const EyeFrame f = renderWideFrame(subset, i, seed);
    const FrameScore s = scoreDetection(f.truth, detectPupilWith(kind, f.image));
    if (!s.truth_visible) {
      ++r.closed;
      r.found_closed += s.found ? 1 : 0;
      continue;
    }
    ++r.with_pupil;
    r.within += s.within_5px ? 1 : 0;
  }
  return r;
}
}  // namespace

class TestLearnedPupil : public QObject {
  Q_OBJECT
 private slots:
  void initTestCase() {
    cv::setNumThreads(1);
    qputenv("FOVEA_PUPIL_MODEL", QByteArray::fromStdString(shippedModel()));
  }

  void wideDomainDeterministicAndSubsets() {
    const EyeFrame a = renderWideFrame(WideSubset::Hard, 3, 11), b = renderWideFrame(WideSubset::Hard, 3, 11);
    QCOMPARE(cv::norm(a.image, b.image, cv::NORM_INF), 0.0);
    QVERIFY(cv::norm(a.image, renderWideFrame(WideSubset::Hard, 4, 11).image, cv::NORM_L1) > 1000);
    // The training subset never yields a held-out frame for the same seed and index.
    QVERIFY(cv::norm(renderWideFrame(WideSubset::Train, 3, 11).image, a.image, cv::NORM_L1) > 1000);
    for (int i = 0; i < 6; ++i) {
      const EyeFrame h = renderWideFrame(WideSubset::Hard, i, 5);
      QVERIFY2(h.truth.visible_fraction >= 0.3 - 1e-9 && h.truth.visible_fraction <= 0.5 + 0.02,
               std::to_string(h.truth.visible_fraction).c_str());
      const EyeFrame o = renderWideFrame(WideSubset::Occlusion, i, 5);
      QVERIFY(o.truth.visible_fraction >= 0.3 - 1e-9 && o.truth.visible_fraction <= 0.9 + 0.02);
      QVERIFY(!renderWideFrame(WideSubset::Closed, i, 5).truth.pupil_visible);
      const EyeFrame p = renderWideFrame(WideSubset::Partial, i, 5);
      QCOMPARE(p.image.size(), cv::Size(400, 400));
      QVERIFY(p.truth.pupil_visible);
      const auto c = p.truth.pupil.centre;
      QVERIFY(c.x >= 0 && c.y >= 0 && c.x < 400 && c.y < 400);
      // At an edge: the centre within a pupil radius of one side.
      const double edge = std::min({c.x, c.y, 400 - c.x, 400 - c.y});
      QVERIFY2(edge <= p.truth.pupil.major_px / 2 + 3, std::to_string(edge).c_str());
    }
  }

  void trainHardSubsetIsTrainingOnly() {
    // The hard subset's combination for training: named, parsed back, never held out, seeded
    // apart from the hard subset, 20-65 % of the pupil visible (the bisection's target band).
    QCOMPARE(std::string(wideSubsetName(WideSubset::TrainHard)), std::string("train_hard"));
    QVERIFY(parseWideSubset("train_hard") == WideSubset::TrainHard);
    const auto held = heldOutWideSubsets();
    QVERIFY(std::find(held.begin(), held.end(), WideSubset::TrainHard) == held.end());
    QVERIFY(std::find(held.begin(), held.end(), WideSubset::Train) == held.end());
    const EyeFrame a = renderWideFrame(WideSubset::TrainHard, 2, 9);
    QCOMPARE(cv::norm(a.image, renderWideFrame(WideSubset::TrainHard, 2, 9).image, cv::NORM_INF), 0.0);
    QVERIFY(cv::norm(a.image, renderWideFrame(WideSubset::Hard, 2, 9).image, cv::NORM_L1) > 1000);
    double lo = 1, hi = 0;
    for (int i = 0; i < 12; ++i) {
      const EyeFrame f = renderWideFrame(WideSubset::TrainHard, i, 9);
      QVERIFY(f.truth.pupil_visible);
      lo = std::min(lo, f.truth.visible_fraction), hi = std::max(hi, f.truth.visible_fraction);
    }
    qInfo("train_hard: visible fraction %.3f-%.3f over 12 frames", lo, hi);
    QVERIFY2(lo >= 0.2 - 1e-9 && hi <= 0.65 + 0.02, (std::to_string(lo) + " " + std::to_string(hi)).c_str());
  }

  void trainPartialSubsetIsTrainingOnly() {
    // train's draws with every frame partial: named, parsed back, never held out, seeded apart
    // from the partial subset, every frame's pupil visible with its centre within a pupil
    // radius of a frame edge (as the partial subset's, above).
    QCOMPARE(std::string(wideSubsetName(WideSubset::TrainPartial)), std::string("train_partial"));
    QVERIFY(parseWideSubset("train_partial") == WideSubset::TrainPartial);
    const auto held = heldOutWideSubsets();
    QVERIFY(std::find(held.begin(), held.end(), WideSubset::TrainPartial) == held.end());
    const EyeFrame a = renderWideFrame(WideSubset::TrainPartial, 3, 9);
    QCOMPARE(cv::norm(a.image, renderWideFrame(WideSubset::TrainPartial, 3, 9).image, cv::NORM_INF), 0.0);
    QVERIFY(cv::norm(a.image, renderWideFrame(WideSubset::Partial, 3, 9).image, cv::NORM_L1) > 1000);
    for (int i = 0; i < 12; ++i) {
      const EyeFrame f = renderWideFrame(WideSubset::TrainPartial, i, 9);
      QVERIFY(f.truth.pupil_visible);
      const auto c = f.truth.pupil.centre;
      const double edge = std::min({c.x, c.y, 400 - c.x, 400 - c.y});
      QVERIFY2(edge <= f.truth.pupil.major_px / 2 + 3, std::to_string(edge).c_str());
    }
  }

  void cornealRefractionMatchesSingleSurface() {
    // Le Grand pupil 3.6 mm behind a 7.8 mm cornea, n = 1.3375: n/s + 1/s' = (n - 1)/r gives
    // s' = -3.046 mm (3.05 mm behind the apex) and magnification n s' / s = 1.1317. The camera
    // (f = 350 px) 35 mm from the rotation centre on axis: the apex is 13.6 mm out, the
    // entrance pupil 10.554 mm, its 5 mm x 1.1317 disc 24.446 mm away: 350 * 5.658 / 24.446 px.
    IrCameraPose cam;
    EyeAppearance eye;
    EyeFrameSpec spec;
    const double plain = eyeFrameTruth(cam, eye, spec).pupil.major_px;
    eye.corneal_refraction = true;
    const double refracted = eyeFrameTruth(cam, eye, spec).pupil.major_px;
    const double s = 3.6, r = 7.8, n = 1.3375, sp = 1 / ((n - 1) / r - n / s);
    const double m = n * sp / -s, z = 35 - (10 + 3.6 + sp);
    qInfo("entrance pupil: s' %.3f mm, magnification %.4f, %.2f px (plain %.2f px)", sp, m, refracted, plain);
    QVERIFY(std::abs(sp + 3.046) < 0.01 && std::abs(m - 1.1317) < 0.001);
    QVERIFY(std::abs(refracted - 350 * 5 * m / z) < 0.3);
    QVERIFY(std::abs(plain - 70) < 0.2);
  }

  void missingOrBrokenModelIsAClearError() {
    const std::string missing = "/nonexistent/dir/pupil-net.onnx";
    try {
      LearnedPupilDetector d(missing);
      QFAIL("no exception for a missing model");
    } catch (const std::runtime_error& e) {
      QVERIFY2(std::string(e.what()).find(missing) != std::string::npos, e.what());
    }
    const auto dir = fovea::testing::testTmpDir("learned_pupil", true);
    const std::string garbage = (dir / "garbage.onnx").string();
    std::ofstream(garbage) << "not an onnx model";
    try {
      LearnedPupilDetector d(garbage);
      QFAIL("no exception for a broken model");
    } catch (const std::runtime_error& e) {
      QVERIFY2(std::string(e.what()).find(garbage) != std::string::npos, e.what());
      QVERIFY2(std::string(e.what()).find("ONNX") != std::string::npos, e.what());
    }
    // The default search with $FOVEA_PUPIL_MODEL set looks only there.
    qputenv("FOVEA_PUPIL_MODEL", QByteArray::fromStdString(missing));
    QCOMPARE(pupilModelCandidates(), std::vector<std::string>{missing});
    QVERIFY_THROWS_EXCEPTION(std::runtime_error, findPupilModel());
    qputenv("FOVEA_PUPIL_MODEL", QByteArray::fromStdString(shippedModel()));
    QCOMPARE(findPupilModel(), shippedModel());
    // A refining stage beside the model that does not load is an error naming it, not a
    // silent fall-back to one stage.
    const std::string model = (dir / "pupil-net.onnx").string(), refine = (dir / "pupil-refine.onnx").string();
    copyFile(shippedModel(), model);
    std::ofstream(refine) << "not an onnx model either";
    try {
      LearnedPupilDetector d(model);
      QFAIL("no exception for a broken refining stage");
    } catch (const std::runtime_error& e) {
      QVERIFY2(std::string(e.what()).find(refine) != std::string::npos, e.what());
    }
  }

  // The refining stage runs when its file is beside the model and moves the centre; without it
  // the detector is the one full-frame stage.
  void refiningStageIsFoundBesideTheModelAndUsed() {
    LearnedPupilDetector two(shippedModel());
    QCOMPARE(two.refineModelPath(), shippedRefineModel());
    LearnedPupilDetector one(oneStageModel("learned_pupil_one_stage"));
    QVERIFY(one.refineModelPath().empty());
    double moved = 0;
    for (int i = 0; i < 4; ++i) {
      const EyeFrame f = renderWideFrame(WideSubset::Hard, i, 2026);
      const PupilDetection a = one.detect(f.image), b = two.detect(f.image);
      // The full-frame stage decides whether there is a pupil: alone from the frame and its mirror
      // image, before the refining stage from the frame (away from the threshold), alike here.
      QCOMPARE(a.found, b.found);
      if (a.found)
        moved = std::max(moved,
                         std::hypot(a.ellipse.centre.x - b.ellipse.centre.x, a.ellipse.centre.y - b.ellipse.centre.y));
    }
    qInfo("the refining stage moved the centre by up to %.2f px on 4 hard frames", moved);
    QVERIFY(moved > 0.1);
  }

  void shippedModelLoadsAndRefusesBadFrames() {
    LearnedPupilDetector net(shippedModel());
    QCOMPARE(net.modelPath(), shippedModel());
    QVERIFY(!net.detect(cv::Mat()).found);
    QCOMPARE(net.detect(cv::Mat()).reason, std::string("empty frame"));
    QCOMPARE(net.detect(cv::Mat(100, 100, CV_32SC2, cv::Scalar(1))).reason, std::string("unsupported image type"));
    QVERIFY(!net.detect(cv::Mat(400, 400, CV_8U, cv::Scalar(0))).found);  // lens cap
    // An easy frame of the project's renderer (not the wide domain): found, near the truth.
    IrCameraPose cam;
    EyeAppearance eye;
    EyeFrameSpec spec;
    spec.gaze_deg = {8, -4};
    spec.leds_mm = ledRing(cam, 6, 10);
    const EyeFrame f = renderEyeFrame(cam, eye, spec);
    const PupilDetection d = net.detect(f.image);
    QVERIFY2(d.found, d.reason.c_str());
    const double err =
        std::hypot(d.ellipse.centre.x - f.truth.pupil.centre.x, d.ellipse.centre.y - f.truth.pupil.centre.y);
    qInfo("easy frame: centre error %.2f px, major %.1f (truth %.1f), confidence %.3f", err, d.ellipse.major_px,
          f.truth.pupil.major_px, d.confidence);
    QVERIFY(err < 5);
    QVERIFY(std::abs(d.ellipse.major_px - f.truth.pupil.major_px) < 0.25 * f.truth.pupil.major_px);
    // A non-square frame is padded, not stretched: the same eye cropped keeps its centre.
    const cv::Rect crop(0, 40, 400, 320);
    const PupilDetection dc = net.detect(f.image(crop));
    QVERIFY(dc.found);
    QVERIFY(std::hypot(dc.ellipse.centre.x - f.truth.pupil.centre.x,
                       dc.ellipse.centre.y + 40 - f.truth.pupil.centre.y) < 6);
  }

  // Test-time flip augmentation makes the full-frame stage, alone, mirror-equivariant: a mirrored
  // frame gives the mirrored ellipse (x -> side - 1 - x, pixel centres at integers, and angle ->
  // -angle), which one pass of the network alone does not (measured there: up to several px
  // apart). Before the refining stage the first stage runs one pass unless its visibility is
  // within kFirstStageFlipBandLogit of the threshold's, and the refining stage runs one pass (the
  // 3 ms budget), so the two-stage detector finds a pupil in a frame and its mirror image alike,
  // and its centres are mirrored only to within its own error: the frame's and the mirror's x sum
  // to 399 within 1.7 px on these hard frames (the shipped stages, 2026-12-07; 0.9 px with the
  // refining stage before and its flipped pair for large pupils, up to 9.3 px with earlier ones, whose figures
  // docs/gaze-tracking.md keeps), so the bound is 12 px - it catches a window placed or mapped
  // back wrongly, which moves them by tens of px. With the threshold set at the frame's own
  // one-pass confidence the band holds the frame and its mirror image: both take the averaged
  // visibility, so their confidences agree exactly.
  void mirroredFrameGivesTheMirroredPupil() {
    LearnedPupilDetector one(oneStageModel("learned_pupil_mirror")), two(shippedModel());
    for (int i = 0; i < 4; ++i) {
      const EyeFrame f = renderWideFrame(WideSubset::Hard, i, 2026);
      cv::Mat mirrored;
      cv::flip(f.image, mirrored, 1);
      const double side = f.image.cols;
      const PupilDetection d = one.detect(f.image), m = one.detect(mirrored);
      const PupilDetection d2 = two.detect(f.image), m2 = two.detect(mirrored);
      QCOMPARE(d.found, m.found);
      QCOMPARE(d2.found, m2.found);
      QVERIFY(std::abs(d.confidence - m.confidence) < 1e-4);
      if (!d.found || !d2.found) continue;
      qInfo(
          "hard frame %d: x %.3f + mirrored x %.3f = %.3f (side %.0f - 1), y %.3f / %.3f; two stages: %.3f, "
          "confidence %.6f / %.6f",
          i, d.ellipse.centre.x, m.ellipse.centre.x, d.ellipse.centre.x + m.ellipse.centre.x, side, d.ellipse.centre.y,
          m.ellipse.centre.y, d2.ellipse.centre.x + m2.ellipse.centre.x, d2.confidence, m2.confidence);
      // INTER_AREA's 400 -> 96 weights are mirror-symmetric, so only float rounding remains.
      QVERIFY(std::abs(d.ellipse.centre.x + m.ellipse.centre.x - (side - 1)) < 0.01);
      QVERIFY(std::abs(d.ellipse.centre.y - m.ellipse.centre.y) < 0.01);
      QVERIFY(std::abs(d.ellipse.major_px - m.ellipse.major_px) < 0.01);
      QVERIFY(std::abs(d.ellipse.minor_px - m.ellipse.minor_px) < 0.01);
      const double angle_sum = std::fmod(d.ellipse.angle_deg + m.ellipse.angle_deg + 360.0, 180.0);
      QVERIFY2(std::min(angle_sum, 180.0 - angle_sum) < 0.1 || d.ellipse.major_px - d.ellipse.minor_px < 0.5,
               qPrintable(QString("angles %1 and %2").arg(d.ellipse.angle_deg).arg(m.ellipse.angle_deg)));
      QVERIFY(std::hypot(d2.ellipse.centre.x + m2.ellipse.centre.x - (side - 1),
                         d2.ellipse.centre.y - m2.ellipse.centre.y) < 12);
      // The band: a threshold 2 below the logit (its distance from it 2, in the band of 4) makes
      // both frames take the averaged logit, equal for the two.
      const double logit = std::log(d2.confidence / (1 - d2.confidence)) - 2;
      if (!std::isfinite(logit)) continue;
      const double threshold = 1 / (1 + std::exp(-logit));
      const PupilDetection db = two.detect(f.image, threshold), mb = two.detect(mirrored, threshold);
      qInfo("  threshold %.6f: confidence %.6f / %.6f", threshold, db.confidence, mb.confidence);
      QVERIFY(db.found && mb.found);
      QVERIFY(std::abs(db.confidence - mb.confidence) < 1e-6);
    }
  }

  void heldOutRates_data() {
    QTest::addColumn<int>("kind");
    QTest::addColumn<int>("subset");
    QTest::addColumn<double>("min_rate");
    // Thresholds: the rates measured on these 16 frames per subset (seed 2026, the first 16 of
    // the docs' table: `fovea-cli track --virtual 128 --domain wide --seed 2026`) less two
    // frames; for closed: the false positives allowed (measured + 1). Sixteen frames cannot hold
    // the targets (95 %, 97 %; over 1000 frames, docs/gaze-tracking.md); these catch a detector
    // that got worse by more than two frames in sixteen. Measured with the stages of 2026-12-07
    // (both with three more convolutions at 6 x 6; the first stage on 18000 train, 6000 train_hard
    // and 6000 train_partial frames, closed eyes weighted 10x, its mirror's pass near the
    // threshold; the refining stage on 72000 train, 18000 train_hard and 18000 train_partial
    // frames' windows, 9 epochs, 5 of fine-tuning and 4 on windows that scale with the pupil,
    // one pass) and auto's 2 px radius. Off-axis was 15/16 with the refining stage before.
    QTest::newRow("learned/easy") << 1 << 1 << 14.0 / 16;         // measured 16/16
    QTest::newRow("learned/glints") << 1 << 2 << 14.0 / 16;       // measured 16/16
    QTest::newRow("learned/occlusion") << 1 << 3 << 14.0 / 16;    // measured 16/16
    QTest::newRow("learned/motion_blur") << 1 << 4 << 14.0 / 16;  // measured 16/16
    QTest::newRow("learned/off_axis") << 1 << 5 << 14.0 / 16;     // measured 16/16
    QTest::newRow("learned/hard") << 1 << 7 << 14.0 / 16;         // measured 16/16
    QTest::newRow("learned/closed") << 1 << 8 << 1.0;             // measured 0/16 false positives
    QTest::newRow("auto/easy") << 2 << 1 << 14.0 / 16;            // measured 16/16
    QTest::newRow("auto/glints") << 2 << 2 << 14.0 / 16;          // measured 16/16
    QTest::newRow("auto/occlusion") << 2 << 3 << 14.0 / 16;       // measured 16/16
    QTest::newRow("auto/motion_blur") << 2 << 4 << 14.0 / 16;     // measured 16/16
    QTest::newRow("auto/off_axis") << 2 << 5 << 14.0 / 16;        // measured 16/16
    QTest::newRow("auto/hard") << 2 << 7 << 14.0 / 16;            // measured 16/16
    QTest::newRow("auto/closed") << 2 << 8 << 1.0;                // measured 0/16 false positives
  }
  void heldOutRates() {
    QFETCH(int, kind);
    QFETCH(int, subset);
    QFETCH(double, min_rate);
    const auto k = static_cast<PupilDetectorKind>(kind);
    const auto s = static_cast<WideSubset>(subset);
    const Rates r = rates(k, s, 16, 2026);
    if (s == WideSubset::Closed) {
      qInfo("%s closed: %d false positives of %d", detectorName(k), r.found_closed, r.closed);
      QCOMPARE(r.closed, 16);
      QVERIFY(r.found_closed <= static_cast<int>(min_rate));  // for closed: the allowed false positives
      return;
    }
    const double rate = static_cast<double>(r.within) / std::max(r.with_pupil, 1);
    qInfo("%s %s: %.3f within 5 px (%d/%d)", detectorName(k), wideSubsetName(s), rate, r.within, r.with_pupil);
    QCOMPARE(r.with_pupil, 16);
    QVERIFY(rate >= min_rate);
  }

  void calibrationWithLearnedDetector() {
    TrackedCalibrationOptions o;
    o.camera.pose_deg = {10, -20};
    o.detector_kind = PupilDetectorKind::Auto;
    const TrackedCalibration c = calibrateWithTracker(o);
    qInfo("auto: accuracy %.3f deg, precision %.3f deg, rejected %d/%d", c.result.accuracy_mean_deg,
          c.result.precision_rms_s2s_deg, c.rejected, c.frames);
    QCOMPARE(static_cast<int>(c.result.validated.size()), 8);
    QCOMPARE(trackedCalibrationJson(c, o)["detector"].get<std::string>(), std::string("auto"));
    QVERIFY(c.result.accuracy_mean_deg < 1.0);
  }
};

QTEST_APPLESS_MAIN(TestLearnedPupil)

}  // namespace tst_learned_pupil
#include "tst_learned_pupil.moc"
