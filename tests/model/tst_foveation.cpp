// Foveated composite and blending (seed B.2.3): the blend profile at the named
// eccentricities, the perceived composite equal to the target where both displays are
// perfect, incremental gaze updates identical to a fresh render, FLIP seam metric, I/O.
#include <QtTest>

#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "app/embedded_scene.h"
#include "model/color/srgb.h"
#include "model/image/flip.h"
#include "model/image/foveation.h"
#include "model/image/image_io.h"
#include "model/scene/scene_io.h"

namespace tst_foveation {

using namespace fovea;
using namespace fovea::image;

namespace {
using fovea::embeddedDefaultScene;
cv::Mat constant(float v) {
  return cv::Mat(1080, 1920, CV_32FC3, cv::Scalar::all(v));
}
// Smooth colour pattern of spatial frequency `cpd` on the 40 deg wide target grid.
cv::Mat sinusoid(double cpd) {
  cv::Mat m(1080, 1920, CV_32FC3);
  const double ppd = 1920 / 40.0;
  for (int y = 0; y < m.rows; ++y)
    for (int x = 0; x < m.cols; ++x) {
      const double a = 2 * std::numbers::pi * cpd / ppd;
      m.at<cv::Vec3f>(y, x) = cv::Vec3f(0.5f + 0.3f * std::sin(a * x), 0.5f + 0.3f * std::cos(a * y),
                                        0.4f + 0.2f * std::sin(a * (x + y) * 0.7));
    }
  return m;
}
double maxAbsDiff(const cv::Mat& a, const cv::Mat& b) {
  double m = 0;
  const cv::Mat d = cv::abs(a - b);
  cv::minMaxLoc(d.reshape(1), nullptr, &m);
  return m;
}
}  // namespace

class TestFoveation : public QObject {
  Q_OBJECT
 private slots:
  void displayAnglesFromScene() {
    const DisplayAngles a = displayAngles(embeddedDefaultScene());
    // 15.55 mm x 21.9 at 800 mm: 2 atan(170.3/800) = 24.03 deg for 1920 px.
    const double fov = 2 * std::atan(21.9 * 15.55 / 1600.0) * 180 / std::numbers::pi;
    QVERIFY(std::abs(fov - 24.03) < 0.01);
    QVERIFY(std::abs(a.foveal_fov_deg[0] - fov) < 1e-12);
    QVERIFY(std::abs(a.foveal_fov_deg[1] - 13.66) < 0.005);  // docs/preview.md: 24.03° x 13.66°
    QVERIFY(std::abs(a.fovealCpd() - 960 / fov) < 1e-12);
    QVERIFY(std::abs(a.peripheralCpd() - 640 / 40.0) < 1e-12);
  }

  void blendProfileAtNamedEccentricities() {
    const Scene s = embeddedDefaultScene();
    const BlendProfile p = blendProfile(s, true);
    const DisplayAngles a = displayAngles(s);
    const double pp = 1 / a.peripheralPpd(), pf = 1 / a.fovealPpd();
    const double sm = std::sqrt((pp * pp - pf * pf) / 12);
    QVERIFY(std::abs(p.sigma_match_deg - sm) < 1e-15);
    QCOMPARE(p.fovealWeight(0), 1.0);
    QCOMPARE(p.fovealWeight(3), 1.0);
    QCOMPARE(p.fovealWeight(5), 1.0);
    QVERIFY(std::abs(p.fovealWeight(5.5) - 0.5) < 1e-12);
    QVERIFY(std::abs(p.fovealWeight(5.75) - 0.25) < 1e-12);
    QCOMPARE(p.fovealWeight(6), 0.0);
    QCOMPARE(p.fovealWeight(9), 0.0);
    QCOMPARE(p.blurSigmaDeg(2.9), 0.0);
    QCOMPARE(p.blurSigmaDeg(3), 0.0);
    QVERIFY(std::abs(p.blurSigmaDeg(4) - sm / 2) < 1e-15);
    QVERIFY(std::abs(p.blurSigmaDeg(5) - sm) < 1e-15);
    QVERIFY(std::abs(p.blurSigmaDeg(5.7) - sm) < 1e-15);
    // Without blending: a hard switch at eps_o and no blur.
    const BlendProfile hard = blendProfile(s, false);
    QCOMPARE(hard.fovealWeight(4.999), 1.0);
    QCOMPARE(hard.fovealWeight(5.0), 0.0);
    QCOMPARE(hard.blurSigmaDeg(4.5), 0.0);
    // Equal displays need no blur.
    QCOMPARE(matchingBlurSigmaDeg(16, 16), 0.0);
    QCOMPARE(matchingBlurSigmaDeg(10, 16), 0.0);
  }

  void perceivedEqualsTargetWithPerfectDisplays() {
    const Scene s = embeddedDefaultScene();
    FoveatedCompositor c(s, true);
    c.setTarget(constant(0.6f));
    c.update({4.0, -2.0});
    // Flat field: the crossfade weights sum to one, so the eye sees the target exactly
    // (up to the interpolation of the weight ramp on two pixel grids).
    QVERIFY2(maxAbsDiff(c.perceivedImage(), c.target()) < 0.6 * 0.01,
             qPrintable(QString::number(maxAbsDiff(c.perceivedImage(), c.target()))));
    // Smooth content below both displays' resolution (1 cpd): equal within 1% (away from
    // the outermost pixels, where the projector's edge pixel is extended).
    c.setTarget(sinusoid(1.0));
    c.update({-7.5, 3.0});
    const cv::Rect inner(4, 4, 1920 - 8, 1080 - 8);
    QVERIFY2(maxAbsDiff(c.perceivedImage()(inner), c.target()(inner)) < 0.01,
             qPrintable(QString::number(maxAbsDiff(c.perceivedImage()(inner), c.target()(inner)))));
    // Energy: the foveal image is dark beyond eps_e, the peripheral image dark inside eps_o.
    const auto& f = c.fovealImage();
    QCOMPARE(f.size(), cv::Size(1920, 1080));
    QCOMPARE(c.peripheralImage().size(), cv::Size(1280, 720));
    QVERIFY(cv::norm(f.at<cv::Vec3f>(0, 0)) == 0.0);
    QVERIFY(cv::norm(f.at<cv::Vec3f>(540, 960)) > 0.1);
    // Projector pixel at the gaze (-7.5, 3): x = (-7.5/40 + 0.5) * 1280 - 0.5, y = (0.5 - 3/22.5*... )
    const double px = (-7.5 / 40 + 0.5) * 1280 - 0.5, py = (0.5 - 3.0 / s.projector.fov_deg[1]) * 720 - 0.5;
    QVERIFY(cv::norm(c.peripheralImage().at<cv::Vec3f>(int(py), int(px))) == 0.0);

    // Without blending a flat field shows the seam: the two displays' pixel grids switch
    // at different places, leaving a visible ring.
    FoveatedCompositor hard(s, false);
    hard.setTarget(constant(0.6f));
    hard.update({4.0, -2.0});
    QVERIFY(maxAbsDiff(hard.perceivedImage(), hard.target()) > 0.6 * 0.05);
  }

  void incrementalUpdateMatchesFreshRender() {
    const Scene s = embeddedDefaultScene();
    FoveatedCompositor moving(s, true), fresh(s, true);
    const cv::Mat t = sinusoid(3.0);
    moving.setTarget(t);
    fresh.setTarget(t);
    moving.update({-15, 8});
    moving.update({0.5, 0.25});
    moving.update({12, -6});
    fresh.update({12, -6});
    QCOMPARE(maxAbsDiff(moving.fovealImage(), fresh.fovealImage()), 0.0);
    QCOMPARE(maxAbsDiff(moving.peripheralImage(), fresh.peripheralImage()), 0.0);
    QCOMPARE(maxAbsDiff(moving.perceivedImage(), fresh.perceivedImage()), 0.0);
  }

  void seamMetricFlip() {
    // FLIP: zero for identical images, in [0, 1], larger for larger differences.
    cv::Mat a(64, 64, CV_32FC3, cv::Scalar::all(0.5)), b = a.clone(), c = a.clone();
    QCOMPARE(cv::norm(flipErrorMap(a, a, 48)), 0.0);
    b(cv::Rect(20, 20, 20, 20)).setTo(cv::Scalar(0.55, 0.5, 0.5));
    c(cv::Rect(20, 20, 20, 20)).setTo(cv::Scalar(0.9, 0.5, 0.5));
    double mb = 0, mc = 0;
    cv::minMaxLoc(flipErrorMap(a, b, 48), nullptr, &mb);
    cv::minMaxLoc(flipErrorMap(a, c, 48), nullptr, &mc);
    QVERIFY(mb > 0 && mc > mb && mc <= 1.0);
    // Black vs white is (nearly) the largest difference.
    double mw = 0;
    cv::minMaxLoc(
        flipErrorMap(cv::Mat(32, 32, CV_32FC3, cv::Scalar::all(0)), cv::Mat(32, 32, CV_32FC3, cv::Scalar::all(1)), 48),
        nullptr, &mw);
    QVERIFY(mw > 0.9);

    // The blending makes the seam less visible than the hard switch.
    const Scene s = embeddedDefaultScene();
    FoveatedCompositor soft(s, true), hard(s, false);
    const cv::Mat t = sinusoid(2.0);
    soft.setTarget(t);
    hard.setTarget(t);
    soft.update({2, 1});
    hard.update({2, 1});
    const auto ss = soft.seamMetric(), hs = hard.seamMetric();
    qInfo("seam FLIP: blended mean %.4f (p95 %.4f), hard mean %.4f (p95 %.4f) over %d px", ss.mean_flip, ss.p95_flip,
          hs.mean_flip, hs.p95_flip, ss.pixels);
    QVERIFY(ss.pixels > 1000);
    QVERIFY(ss.mean_flip < hs.mean_flip);
    // docs/preview.md prints 0.028 blended against 0.036 for the hard switch: held to those digits.
    QVERIFY2(std::abs(ss.mean_flip - 0.028) < 5e-4, qPrintable(QString::number(ss.mean_flip, 'g', 6)));
    QVERIFY2(std::abs(hs.mean_flip - 0.036) < 5e-4, qPrintable(QString::number(hs.mean_flip, 'g', 6)));
  }

  void imageFiles() {
    const std::string dir = qEnvironmentVariable("FOVEA_TEST_TMP", "/tmp").toStdString();
    cv::Mat img(20, 30, CV_32FC3);
    for (int y = 0; y < 20; ++y)
      for (int x = 0; x < 30; ++x) img.at<cv::Vec3f>(y, x) = cv::Vec3f(x / 29.0f, y / 19.0f, 0.25f);
    writeLinearRgb(dir + "/io.png", img, true);
    const cv::Mat back = readLinearRgb(dir + "/io.png");
    QVERIFY(maxAbsDiff(back, img) < 1e-3);
    QVERIFY(std::abs(fovea::color::srgbToLinear(fovea::color::linearToSrgb(0.18f)) - 0.18f) < 1e-6);
    try {
      readLinearRgb(dir + "/missing.png");
      QFAIL("missing file read");
    } catch (const ImageIoError& e) {
      QVERIFY(std::string(e.what()).find("missing.png") != std::string::npos);
    }
    std::ofstream(dir + "/garbage.png") << "not an image";
    QVERIFY_THROWS_EXCEPTION(ImageIoError, readLinearRgb(dir + "/garbage.png"));
    // Written through the one writer (issue 28): a FIFO, a device or a directory is refused and
    // stays what it was; an existing file is replaced whole (no temporary file left beside it).
    const std::string fifo = dir + "/io-fifo.png";
    std::filesystem::remove(fifo);
    QCOMPARE(::mkfifo(fifo.c_str(), 0600), 0);
    for (const std::string& bad : {fifo, std::string("/dev/null"), dir}) {
      try {
        writeLinearRgb(bad, img);
        QFAIL(qPrintable(QString::fromStdString(bad) + ": written"));
      } catch (const ImageIoError& e) {
        QVERIFY2(std::string(e.what()).rfind(bad + ": ", 0) == 0, e.what());
      }
    }
    QVERIFY(std::filesystem::is_fifo(fifo));
    QVERIFY(std::filesystem::is_character_file("/dev/null"));
    std::filesystem::remove(fifo);
    const std::string sub = dir + "/io-writer";
    std::filesystem::remove_all(sub);
    std::filesystem::create_directories(sub);
    std::ofstream(sub + "/old.exr") << "an older file";
    writeLinearRgb(sub + "/old.exr", img);
    QVERIFY(maxAbsDiff(readLinearRgb(sub + "/old.exr"), img) < 1e-6);  // float EXR: exact
    int files = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(sub)) ++files;
    QCOMPARE(files, 1);
  }
};

QTEST_GUILESS_MAIN(TestFoveation)

}  // namespace tst_foveation
#include "tst_foveation.moc"
