// The eye-view camera's ground truth (model/physics/display_camera_map.h): what a camera at the eye sees of
// the projector through the traced HOE and of the micro-OLED through its combiner. The maps
// are consistent both ways, smooth but far from a homography, move with the HOE, micro-OLED
// and camera stages, recentre the foveal image on the gaze with x_f(alpha), and a board
// rendered through them is found by the corner detector where the map puts its corners.
#include <QtTest>

#include <cmath>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "app/embedded_scene.h"
#include "model/image/chessboard.h"
#include "model/image/display_pattern.h"
#include "model/image/geometric_calibration.h"
#include "model/image/warp.h"
#include "model/physics/display_camera_map.h"
#include "model/scene/scene_io.h"

namespace tst_display_camera_map {

using namespace fovea;

namespace {

using fovea::embeddedDefaultScene;

// Display points on a grid over a board's inner-corner rectangle.
std::vector<Eigen::Vector2d> boardGrid(const image::DisplayPattern& b, int n = 15) {
  std::vector<Eigen::Vector2d> out;
  const Eigen::Vector2d lo = b.cornerPx(0, 0), hi = b.cornerPx(b.innerColumns() - 1, b.innerRows() - 1);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      out.push_back(lo + Eigen::Vector2d((hi - lo).x() * i / (n - 1), (hi - lo).y() * j / (n - 1)));
  return out;
}

image::DisplayPattern boardFor(const Scene& s, BenchDisplay d) {
  if (d == BenchDisplay::Foveal) return image::centredCheckerboard(s.foveal_display.pixels, {8, 5}, 0.9);
  const auto r = projectorRegionOnHoe(s, 7.0 / 9.0, 5.0);
  const double mx = 0.125 * (r[2] - r[0]), my = 0.125 * (r[3] - r[1]);
  return image::checkerboardInRect({r[0] + mx, r[1] + my, r[2] - mx, r[3] - my}, {7, 9});
}

cv::Mat render(const DisplayCameraMap& m, const image::DisplayPattern& p) {
  cv::Mat mx, my, b, radiance;
  m.cameraMaps(mx, my, b);
  image::renderPattern(p, mx, my, b, radiance);
  cv::GaussianBlur(radiance, radiance, cv::Size(0, 0), 0.6);
  cv::Mat img;
  radiance.convertTo(img, CV_8U, 255.0);
  return img;
}

}  // namespace

class TestDisplayCameraMap : public QObject {
  Q_OBJECT
 private slots:
  void bothWaysAgree() {
    const Scene s = embeddedDefaultScene();
    const EyeViewCamera cam;
    for (BenchDisplay d : {BenchDisplay::Peripheral, BenchDisplay::Foveal}) {
      const auto m = makeDisplayMap(d, s, cam, BenchPose{});
      int n = 0;
      double worst = 0;
      for (const auto& p : boardGrid(boardFor(s, d))) {
        const auto c = m->toCamera(p);
        QVERIFY2(c, qPrintable(QString("%1: no camera pixel for (%2, %3)").arg(toString(d)).arg(p.x()).arg(p.y())));
        QVERIFY((*c)[0] > 0 && (*c)[1] > 0 && (*c)[0] < cam.pixels[0] && (*c)[1] < cam.pixels[1]);
        const auto back = m->toDisplay(*c);
        QVERIFY(back);
        worst = std::max(worst, (*back - p).norm());
        ++n;
      }
      qInfo("%s: %d points, worst round trip %.2e display px", toString(d), n, worst);
      QVERIFY(worst < 1e-3);
      QVERIFY(m->brightness(boardFor(s, d).cornerPx(4, 3)) > 0.3);
    }
  }

  void smoothAndNonLinear() {
    // The optics bend the board; a cubic follows them to a few hundredths of a pixel. The HOE
    // recorded with point sources is close to a homography at its recording wavelength (two
    // central projections of the plate); the HOE shift and the camera lens take it away from
    // one, and an affine map is pixels off. The micro-OLED's magnifier distorts only a little
    // over its small image (about 200 px wide in this camera).
    const Scene s = embeddedDefaultScene();
    for (BenchDisplay d : {BenchDisplay::Peripheral, BenchDisplay::Foveal}) {
      const auto m = makeDisplayMap(d, s, EyeViewCamera{}, BenchPose{{2.0, 0.0}, {3.0, 0.0}, {8.0, 0.0}});
      std::vector<image::PointPair> pairs;
      for (const auto& p : boardGrid(boardFor(s, d), 21))
        if (auto c = m->toCamera(p)) pairs.push_back({p, *c});
      QCOMPARE(pairs.size(), std::size_t{21 * 21});
      auto rms = [&](image::WarpModel w) { return image::rmsResidual(image::fitWarp(pairs, w), pairs); };
      const double a = rms(image::WarpModel::Poly1), h = rms(image::WarpModel::Homography),
                   c3 = rms(image::WarpModel::Poly3);
      qInfo("%s: affine %.2f px, homography %.3f px, poly3 %.4f px RMS", toString(d), a, h, c3);
      if (d == BenchDisplay::Peripheral) {
        // docs/bench-devices.md prints 4.7, 0.24 and 0.02 px: held to those digits.
        QVERIFY(std::abs(a - 4.7) < 0.05);
        QVERIFY(std::abs(h - 0.24) < 0.005);
        QVERIFY(std::abs(c3 - 0.02) < 0.005);
      } else {
        QVERIFY(a > 0.05 && h < a && c3 < 0.01);
      }
    }
  }

  void stagesMoveTheImage() {
    const Scene s = embeddedDefaultScene();
    const EyeViewCamera cam;
    const auto pb = boardFor(s, BenchDisplay::Peripheral), fb = boardFor(s, BenchDisplay::Foveal);
    const Eigen::Vector2d pc = pb.cornerPx(4, 3), fc = fb.cornerPx(4, 3);
    const auto p0 = makePeripheralMap(s, cam, {})->toCamera(pc);
    const auto p1 = makePeripheralMap(s, cam, {{1.5, 0.0}, {0, 0}, {0, 0}})->toCamera(pc);
    QVERIFY(p0 && p1);
    qInfo("HOE +1.5 mm moves the projector's centre by %.2f px", (*p1 - *p0).norm());
    QVERIFY(std::abs((*p1 - *p0).norm() - 29.0) < 0.5);  // docs/bench-devices.md: 29 px
    const auto f0 = makeFovealMap(s, cam, {})->toCamera(fc);
    const auto f1 = makeFovealMap(s, cam, {{0, 0}, {1.0, 0.0}, {0, 0}})->toCamera(fc);
    QVERIFY(f0 && f1);
    qInfo("micro-OLED +1 mm moves its image by (%.2f, %.2f) px", (*f1 - *f0).x(), (*f1 - *f0).y());
    QVERIFY(std::abs(std::abs((*f1 - *f0).x()) - 11.0) < 0.5);  // docs: 11 px
    // Camera yaw: the image moves the other way in the camera.
    const auto f2 = makeFovealMap(s, cam, {{0, 0}, {0, 0}, {5.0, 0.0}})->toCamera(fc);
    QVERIFY(f2 && std::abs((*f2 - *f0).x()) > 20.0);
  }

  void fovealImageFollowsTheGaze() {
    // x_f(alpha) and the camera at alpha: the micro-OLED's centre stays near the camera's centre.
    const Scene s = embeddedDefaultScene();
    const EyeViewCamera cam;
    const Eigen::Vector2d centre(0.5 * (s.foveal_display.pixels[0] - 1), 0.5 * (s.foveal_display.pixels[1] - 1));
    for (double a : {-10.0, 0.0, 10.0}) {
      BenchPose pose;
      pose.camera_gaze_deg = {a, 0};
      pose.foveal_shift_mm = fovealShiftForGaze(s, {a, 0});
      const auto c = makeFovealMap(s, cam, pose)->toCamera(centre);
      QVERIFY(c);
      qInfo("gaze %+.0f deg: micro-OLED centre at (%.2f, %.2f) px", a, c->x(), c->y());
      QVERIFY(std::abs(c->x() - 0.5 * (cam.pixels[0] - 1)) < 0.8);  // docs: within 0.8 px at +-10 deg
      QVERIFY(std::abs(c->y() - 0.5 * (cam.pixels[1] - 1)) < 1e-6 + 1.0);
    }
  }

  // x_f = (d_f + r) tan(alpha) / M (seed S1, derived in display_camera_map.cpp): on the
  // prototype 811.5 mm x tan(alpha) / 21.9; its +-8 mm micro-OLED stages cover +-12.18 deg of gaze.
  void fovealShiftAndTheGazeItsStagesCover() {
    const Scene s = embeddedDefaultScene();
    QVERIFY(std::abs(fovealShiftForGaze(s, {10, 0})[0] - 6.534) < 5e-4);
    QVERIFY(std::abs(fovealShiftForGaze(s, {15, 0})[0] - 9.929) < 5e-4);
    QVERIFY(std::abs(fovealShiftForGaze(s, {20, 0})[0] - 13.49) < 5e-3);
    QVERIFY(std::abs(fovealShiftForGaze(s, {0, -10})[1] + 6.534) < 5e-4);
    std::array<double, 2> limits{};
    for (const auto& b : s.stages)
      if (b.element == "foveal_display" && b.axis == "x") limits = b.soft_limits;
    QCOMPARE(limits[1], 8.0);
    const auto c = fovealGazeCoverageDeg(s, limits);
    QVERIFY(std::abs(c[1] - 12.18) < 5e-3 && std::abs(c[0] + 12.18) < 5e-3);
    // The inverse: x_f at the covered gaze is the limit.
    QVERIFY(std::abs(fovealShiftForGaze(s, {c[1], 0})[0] - 8.0) < 1e-9);
  }

  void renderedBoardsAreFoundWhereTheMapSays() {
    const Scene s = embeddedDefaultScene();
    for (BenchDisplay d : {BenchDisplay::Peripheral, BenchDisplay::Foveal}) {
      const auto m = makeDisplayMap(d, s, EyeViewCamera{}, BenchPose{{1.0, 0.0}, {2.0, 0.0}, {5.0, 0.0}});
      const auto board = boardFor(s, d);
      const cv::Mat img = render(*m, board);
      const auto obs = image::observeBoard(img, board);
      QVERIFY2(obs, toString(d));
      double sum = 0;
      for (const auto& p : obs->pairs) sum += (*m->toCamera(p.src) - p.dst).squaredNorm();
      const double rms = std::sqrt(sum / obs->pairs.size());
      qInfo("%s: %zu corners, orientation %d, marker contrast %.0f, detected vs true %.3f px RMS", toString(d),
            obs->pairs.size(), obs->orientation, obs->marker_contrast, rms);
      if (qEnvironmentVariableIsSet("FOVEA_SAVE_RENDERS"))
        cv::imwrite(std::string("/tmp/render_") + toString(d) + ".png", img);
      QVERIFY(rms < 0.25);
      if (d != BenchDisplay::Peripheral) continue;
      // docs/bench-devices.md: "the sector detector alone is 0.18 px RMS off under the HOE's
      // perspective; refined, 0.05 px" -- this peripheral board (through the HOE), held to the
      // digits printed (the doc said 0.27 px, measured on the first renderer). The sector detector's corners come in
      // its own order: each is paired with the nearest true corner (the error is far below the corner spacing).
      const auto sector = image::detectChessboard(img, board.innerColumns(), board.innerRows());
      QVERIFY(sector);
      std::vector<Eigen::Vector2d> truth;
      for (int r = 0; r < board.innerRows(); ++r)
        for (int c = 0; c < board.innerColumns(); ++c) truth.push_back(*m->toCamera(board.cornerPx(c, r)));
      double sector_sum = 0;
      for (const Eigen::Vector2d& p : sector->image_px) {
        double nearest = 1e300;
        for (const Eigen::Vector2d& t : truth) nearest = std::min(nearest, (p - t).squaredNorm());
        sector_sum += nearest;
      }
      const double sector_rms = std::sqrt(sector_sum / sector->image_px.size());
      qInfo("peripheral: sector detector alone %.3f px RMS, refined %.3f px RMS", sector_rms, rms);
      QVERIFY2(std::abs(sector_rms - 0.18) <= 0.005, qPrintable(QString::number(sector_rms)));
      QVERIFY2(std::abs(rms - 0.05) <= 0.005, qPrintable(QString::number(rms)));
    }
  }

  void patternsRoundTripThroughJson() {
    const auto b = image::centredCheckerboard({1920, 1080}, {10, 7}, 0.8);
    QCOMPARE(image::patternFromJson(image::toJson(b)), b);
    QCOMPARE(image::patternFromJson(image::toJson(image::flatPatch({0.5, 0, 1}))), image::flatPatch({0.5, 0, 1}));
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, image::patternFromJson({{"kind", "stripes"}}));
    // Corner (c, r) sits on the square grid; the box filter of a checker is 0.5 at a corner.
    const Eigen::Vector2d c = b.cornerPx(2, 3);
    QVERIFY(std::abs(b.value(c, {2.0, 2.0}) - 0.5 * (b.dark + b.light)) < 1e-9);
  }
};

QTEST_GUILESS_MAIN(TestDisplayCameraMap)

}  // namespace tst_display_camera_map
#include "tst_display_camera_map.moc"
