// Gaze calibration (seed C.4): exact recovery of a polynomial map, 5- and 9-point
// calibration of a physical eye seen by an on-axis camera with held-out accuracy,
// 10-sample averaging, precision against its closed form, degenerate input.
#include <QtTest>

#include <cmath>
#include <numbers>
#include <random>

#include "model/gaze/gaze_calibration.h"
#include "model/gaze/pupil_camera.h"

namespace tst_gaze_calibration {

using namespace fovea::gaze;

namespace {
GazeTarget target(const PupilCamera& cam, double yaw, double pitch, bool holdout, int samples = 10, double noise_px = 0,
                  unsigned seed = 1) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0.0, noise_px);
  GazeTarget t;
  t.label = std::to_string(yaw) + "," + std::to_string(pitch);
  t.target_deg = {yaw, pitch};
  t.holdout = holdout;
  const Eigen::Vector2d p = pupilCentrePx(cam, yaw, pitch);
  for (int i = 0; i < samples; ++i)
    t.pupil_px.push_back(p + (noise_px > 0 ? Eigen::Vector2d(n(rng), n(rng)) : Eigen::Vector2d::Zero()));
  return t;
}
// Calibration grid: 5 points (centre + corners) or 9 points (3 x 3), +-15 x +-10 deg;
// held out: the four points halfway to the corners and the four edge midpoints of the 5-point case.
std::vector<GazeTarget> session(const PupilCamera& cam, int points) {
  std::vector<GazeTarget> t;
  for (double p : {-10.0, 0.0, 10.0})
    for (double y : {-15.0, 0.0, 15.0}) {
      const bool corner = p != 0 && y != 0, centre = p == 0 && y == 0;
      if (points == 9 || corner || centre) t.push_back(target(cam, y, p, false));
    }
  for (double p : {-5.0, 5.0})
    for (double y : {-7.5, 7.5}) t.push_back(target(cam, y, p, true));
  return t;
}
}  // namespace

class TestGazeCalibration : public QObject {
  Q_OBJECT
 private slots:
  void angles() {
    QVERIFY(std::abs(angleBetweenDeg({0, 0}, {30, 0}) - 30) < 1e-12);
    QVERIFY(std::abs(angleBetweenDeg({0, 0}, {0, -20}) - 20) < 1e-12);
    // Pitch moves along a great circle at any yaw (yaw first, then pitch about the turned x axis).
    QVERIFY(std::abs(angleBetweenDeg({25, 5}, {25, 17}) - 12) < 1e-12);
    QCOMPARE(angleBetweenDeg({3, 4}, {3, 4}), 0.0);
  }

  void exactPolynomialRecovered() {
    // Gaze given exactly by a quadratic in pixels: poly2 recovers it (any normalisation).
    auto truth = [](const Eigen::Vector2d& p) {
      const double x = p.x(), y = p.y();
      return std::array<double, 2>{-20 + 0.11 * x - 0.004 * y + 2e-5 * x * y + 3e-5 * x * x - 1e-5 * y * y,
                                   12 - 0.002 * x - 0.09 * y + 1e-5 * x * y - 2e-5 * x * x + 4e-5 * y * y};
    };
    std::vector<Eigen::Vector2d> px;
    std::vector<std::array<double, 2>> g;
    for (double y : {150.0, 240.0, 335.0})
      for (double x : {210.0, 318.0, 431.0}) {
        px.emplace_back(x + 0.1 * y, y - 0.05 * x);
        g.push_back(truth(px.back()));
      }
    const GazeMap m = fitGazeMap(px, g, GazeModel::Poly2);
    for (const Eigen::Vector2d& q : {Eigen::Vector2d(260, 190), Eigen::Vector2d(400, 300), Eigen::Vector2d(330, 245)}) {
      const auto e = m.gazeDeg(q), t = truth(q);
      QVERIFY(std::abs(e[0] - t[0]) < 1e-9 && std::abs(e[1] - t[1]) < 1e-9);
    }
    // A bilinear truth is recovered by the 4-term model from 4 points exactly.
    std::vector<Eigen::Vector2d> p4{{100, 100}, {300, 110}, {90, 280}, {310, 300}};
    std::vector<std::array<double, 2>> g4;
    for (const auto& p : p4) g4.push_back({0.1 * p.x() + 1e-4 * p.x() * p.y(), -0.1 * p.y() + 5});
    const GazeMap b = fitGazeMap(p4, g4, GazeModel::Bilinear);
    const auto e = b.gazeDeg({200, 200});
    QVERIFY(std::abs(e[0] - (20 + 4)) < 1e-9 && std::abs(e[1] - (-20 + 5)) < 1e-9);
  }

  void physicalEyeFiveAndNinePoints() {
    const PupilCamera cam;
    const GazeCalibrationResult nine = calibrateGaze(session(cam, 9));
    const GazeCalibrationResult five = calibrateGaze(session(cam, 5));
    qInfo(
        "noise-free eye: 9-point %s fit %.4f deg, held-out accuracy %.4f mean %.4f max; 5-point %s fit %.4f, "
        "accuracy %.4f mean %.4f max",
        modelName(nine.map.model), nine.fit_rms_deg, nine.accuracy_mean_deg, nine.accuracy_max_deg,
        modelName(five.map.model), five.fit_rms_deg, five.accuracy_mean_deg, five.accuracy_max_deg);
    QCOMPARE(nine.map.model, GazeModel::Poly2);
    QCOMPARE(five.map.model, GazeModel::Bilinear);
    QCOMPARE(nine.calibration_targets, 9);
    QCOMPARE(five.calibration_targets, 5);
    QCOMPARE(nine.validation, std::string("holdout"));
    QCOMPARE(nine.validated.size(), std::size_t{4});
    // The camera sees the pupil through sin() (rotation) and perspective. The symmetric
    // 5-point set fits the 4 bilinear terms exactly (yaw is odd in x, pitch odd in y); a
    // 3 x 3 grid samples each axis at 3 levels only, so the cubic term of the inverse sine
    // aliases into the linear one and poly2 gains through the perspective's even terms:
    // measured 0.23 deg (poly2, 9 points) against 0.29 deg (bilinear, 5 points) at the
    // held-out targets halfway to the corners.
    QVERIFY(five.fit_rms_deg < 1e-9);
    QVERIFY(nine.fit_rms_deg > 0.05 && nine.fit_rms_deg < 0.3);
    // docs/preview.md prints 0.135 deg (poly2 fit), 0.23 and 0.29 deg (held-out accuracy of the
    // 9- and 5-point maps): held to those digits.
    QVERIFY2(std::abs(nine.fit_rms_deg - 0.135) < 5e-4, qPrintable(QString::number(nine.fit_rms_deg, 'g', 6)));
    QVERIFY2(std::abs(nine.accuracy_mean_deg - 0.23) < 5e-3,
             qPrintable(QString::number(nine.accuracy_mean_deg, 'g', 6)));
    QVERIFY2(std::abs(five.accuracy_mean_deg - 0.29) < 5e-3,
             qPrintable(QString::number(five.accuracy_mean_deg, 'g', 6)));
    QVERIFY(nine.accuracy_max_deg < 0.3);
    QVERIFY(five.accuracy_max_deg < 0.4);
    QVERIFY(nine.accuracy_mean_deg < five.accuracy_mean_deg);
    // Noise-free samples: no scatter.
    QVERIFY(nine.precision_sd_deg < 1e-9);

    // Leave-one-out when nothing is held out (9 points, poly2 refits from 8).
    std::vector<GazeTarget> calOnly;
    for (const auto& t : session(cam, 9))
      if (!t.holdout) calOnly.push_back(t);
    const GazeCalibrationResult loo = calibrateGaze(calOnly);
    QCOMPARE(loo.validation, std::string("leave-one-out"));
    QCOMPARE(loo.validated.size(), std::size_t{9});
    QVERIFY(loo.accuracy_mean_deg > nine.accuracy_mean_deg);  // extrapolating to corners is harder
    QVERIFY(loo.accuracy_max_deg < 3.0);
  }

  void temporalAveraging() {
    const PupilCamera cam;
    GazeTarget t = target(cam, 5, 3, false, 10);
    // Five samples of the saccade landing first: the average of the last 10 ignores them.
    for (int i = 0; i < 5; ++i) t.pupil_px.insert(t.pupil_px.begin(), Eigen::Vector2d(0, 0));
    QVERIFY((averagedPupil(t.pupil_px, 10) - pupilCentrePx(cam, 5, 3)).norm() < 1e-12);
    QVERIFY((averagedPupil(t.pupil_px, 15) - pupilCentrePx(cam, 5, 3) * (10.0 / 15.0)).norm() < 1e-9);
    QVERIFY((averagedPupil({{1, 2}, {3, 4}}, 10) - Eigen::Vector2d(2, 3)).norm() < 1e-15);
  }

  void precisionClosedForm() {
    // Isotropic pupil noise sigma_px maps through the local derivative of the camera model
    // at zero gaze: d(x)/d(yaw) = f r / (D - r) per radian, so sigma_deg = sigma_px (D - r) /
    // (f r) * 180/pi per axis. For iid 2-D noise: SD = sqrt(2) sigma_deg, RMS-S2S = 2 sigma_deg.
    const PupilCamera cam;
    std::vector<GazeTarget> t = session(cam, 9);
    const double sigmaPx = 0.4;
    t.push_back(target(cam, 0, 0, true, 4000, sigmaPx, 7));
    const GazeCalibrationResult r = calibrateGaze(t);
    const TargetResult& c = r.validated.back();
    const double sigmaDeg = sigmaPx * (cam.camera_distance_mm - cam.pupil_distance_mm) /
                            (cam.focal_px * cam.pupil_distance_mm) * 180 / std::numbers::pi;
    qInfo("sigma %.4f deg: SD %.4f (expected %.4f), RMS-S2S %.4f (expected %.4f), accuracy %.4f", sigmaDeg,
          c.precision_sd_deg, std::sqrt(2.0) * sigmaDeg, c.precision_rms_s2s_deg, 2 * sigmaDeg, c.error_deg);
    QCOMPARE(c.samples, 4000);
    QVERIFY(std::abs(c.precision_sd_deg / (std::sqrt(2.0) * sigmaDeg) - 1) < 0.05);
    QVERIFY(std::abs(c.precision_rms_s2s_deg / (2 * sigmaDeg) - 1) < 0.05);
    // The 10-sample average leaves sigma/sqrt(10) per axis of scatter in the estimate.
    QVERIFY(c.error_deg < 4 * sigmaDeg / std::sqrt(10.0) + 0.1);
  }

  void degenerateInput() {
    const PupilCamera cam;
    auto throwsWith = [](auto f, const char* text) {
      try {
        f();
      } catch (const std::invalid_argument& e) {
        return std::string(e.what()).find(text) != std::string::npos;
      }
      return false;
    };
    // Too few targets for the model.
    std::vector<Eigen::Vector2d> p{{1, 2}, {3, 4}, {5, 1}};
    std::vector<std::array<double, 2>> g{{0, 0}, {1, 1}, {2, 0}};
    QVERIFY(throwsWith([&] { fitGazeMap(p, g, GazeModel::Poly2); }, "at least"));
    // Collinear pupil positions.
    std::vector<Eigen::Vector2d> line{{0, 0}, {1, 1}, {2, 2}, {3, 3}, {4, 4}};
    std::vector<std::array<double, 2>> g5(5, {0.0, 0.0});
    QVERIFY(throwsWith([&] { fitGazeMap(line, g5, GazeModel::Poly1); }, "undetermined"));
    // A "+" pattern leaves the bilinear uv term undetermined.
    std::vector<Eigen::Vector2d> plus{{0, 0}, {1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    QVERIFY(throwsWith([&] { fitGazeMap(plus, g5, GazeModel::Bilinear); }, "undetermined"));
    // Non-finite values.
    std::vector<Eigen::Vector2d> nan{{0, 0}, {1, 0}, {0, std::nan("")}};
    QVERIFY(throwsWith([&] { fitGazeMap(nan, g, GazeModel::Poly1); }, "non-finite"));
    // File format.
    nlohmann::json j = gazeSamplesToJson(session(cam, 5));
    QCOMPARE(parseGazeSamples(j).size(), std::size_t{9});
    j["targets"][2]["pupil_px"][3][1] = nullptr;
    QVERIFY(throwsWith([&] { parseGazeSamples(j); }, "targets[2].pupil_px[3]"));
    j["targets"][2]["pupil_px"] = nlohmann::json::array();
    QVERIFY(throwsWith([&] { parseGazeSamples(j); }, "targets[2].pupil_px"));
    QVERIFY(throwsWith([&] { parseGazeSamples({{"format", "other"}}); }, "format"));
    // Nothing held out and 3 targets: leave-one-out cannot refit poly1 (3 terms) from 2.
    std::vector<GazeTarget> three{target(cam, 0, 0, false), target(cam, 10, 0, false), target(cam, 0, 10, false)};
    QVERIFY(throwsWith([&] { calibrateGaze(three); }, "leave-one-out"));
  }
};

QTEST_GUILESS_MAIN(TestGazeCalibration)

}  // namespace tst_gaze_calibration
#include "tst_gaze_calibration.moc"
