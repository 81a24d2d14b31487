// fovea-cli retina-image (issue 29): the JSON contract (every key), the written image, energy,
// speckle, and clear refusals of bad input.
#include <QtTest>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "model/image/image_io.h"
#include "model/image/test_target.h"

#include "tests/cli/cli_process.h"
#include "tests/test_files.h"

namespace tst_cli_retina_image {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {
using Run = fovea::testing::CliText;
using fovea::testing::cliText;
fs::path tmpDir() {
  return fovea::testing::testTmpDir("cli_retina_image");
}
QString target() {
  const fs::path p = tmpDir() / "target.png";
  if (!fs::exists(p))
    fovea::image::writeLinearRgb(p.string(), fovea::image::makeTestTarget(cv::Size(480, 277), {40.0, 23.1}, 15.0));
  return QString::fromStdString(p.string());
}
QString outPath(const char* name) {
  return QString::fromStdString((tmpDir() / name).string());
}
void checkSpot(const json& s) {
  QVERIFY(s.is_object());
  for (const char* k : {"spot_fwhm_arcmin", "cpd_mtf50", "cpd_mtf10"}) {
    QVERIFY2(s.contains(k) && s[k].is_number(), k);
    QVERIFY(s[k].get<double>() > 0);
  }
  QVERIFY(s["cpd_mtf10"].get<double>() > s["cpd_mtf50"].get<double>());
}
}  // namespace

class TestCliRetinaImage : public QObject {
  Q_OBJECT
 private slots:
  void contractKeys() {
    const QString out = outPath("retina.png");
    const Run r = cliText({"retina-image", "--image", target(), "--out", out, "--gaze-deg", "5,2", "--accommodation-d",
                           "2.5", "--rays", "4000", "--json"});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    const json j = r.j();
    checkSpot(j["peripheral"]);
    checkSpot(j["foveal"]);
    QVERIFY(j.contains("speckle_contrast") && j["speckle_contrast"].is_null());
    QVERIFY(j["power_in_pupil"].is_number() && j["power_in_pupil"].get<double>() > 0);
    QVERIFY(j["power_on_retina"].is_number());
    QVERIFY(std::abs(j["power_on_retina"].get<double>() - j["power_in_pupil"].get<double>()) <=
            1e-6 * j["power_in_pupil"].get<double>());
    QCOMPARE(j["accommodation_d"].get<double>(), 2.5);
    QCOMPARE(j["gaze_deg"], json({5.0, 2.0}));
    // Far from the foveal image (0.8 m = 1.25 D) the inset blurs; the periphery does not care.
    QVERIFY(j["foveal"]["cpd_mtf50"].get<double>() < 5.0);
    const cv::Mat img = fovea::image::readLinearRgb(out.toStdString());
    QCOMPARE(img.cols, 480);
    QCOMPARE(img.rows, 277);
    QVERIFY(cv::sum(img)[1] > 0);
    // Per-layer lateral colour at the line of sight: one entry per laser; the prototype's
    // lasers are at their layers' wavelengths, so the layers agree (no fringe).
    QCOMPARE(j["colour_calibration"].get<std::string>(), std::string("common"));
    QVERIFY(j["lateral_colour"].is_array() && j["lateral_colour"].size() == 3);
    for (const auto& c : j["lateral_colour"]) {
      QVERIFY(c["valid"].get<bool>());
      QVERIFY(c["wavelength_nm"].is_number() && c["field_deg"].size() == 2);
      QVERIFY(std::hypot(c["offset_arcmin"][0].get<double>(), c["offset_arcmin"][1].get<double>()) < 1e-6);
    }
    // The HOE's astigmatism at the line of sight and the field-dependent PSF at its nodes: the
    // off-axis hologram's tangential section is weaker than its sagittal one, so every spot is
    // an ellipse with its long axis nearer yaw than pitch.
    for (const auto& p : j["peripheral_per_wavelength"]) {
      QCOMPARE(p["hoe_vergence_d"].size(), std::size_t{2});
      QVERIFY(p["astigmatism_d"].get<double>() > 1.0);
      QVERIFY(p["radius_major_arcmin"].get<double>() > p["radius_minor_arcmin"].get<double>());
      QVERIFY(p["cpd_mtf50_long_axis"].get<double>() < p["cpd_mtf50"].get<double>());
      QVERIFY(p.contains("orientation_deg") && p.contains("field_deg") && p.contains("cpd_mtf10_long_axis"));
    }
    QVERIFY(j["peripheral_field"].is_array() && j["peripheral_field"].size() % 3 == 0 &&
            j["peripheral_field"].size() >= 12);
    for (const auto& f : j["peripheral_field"]) {
      checkSpot(f);
      QVERIFY(f["world_deg"].size() == 2 && f["field_deg"].size() == 2);
      QVERIFY(f["radius_major_arcmin"].get<double>() >= f["radius_minor_arcmin"].get<double>());
      QVERIFY(std::abs(f["orientation_deg"].get<double>()) < 45);
      QVERIFY(f["astigmatism_d"].get<double>() > 0);
    }
  }

  void speckleIsReported() {
    const Run r = cliText({"retina-image", "--image", target(), "--out", outPath("speckle.png"), "--speckle", "3",
                           "--rays", "4000", "--json"});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    const json j = r.j();
    QVERIFY(j["speckle_contrast"].is_number());
    const double expected = 1.0 / std::sqrt(3.0 * 3.0);  // 3 patterns x 3 lasers
    QVERIFY(std::abs(j["speckle_contrast"].get<double>() / expected - 1) < 0.05);
    QCOMPARE(j["speckle_grain"].get<std::string>(), std::string("pixel"));
    // The pupil's grain: each canvas pixel (480 px over 40 deg: 5 arcmin) integrates M grains.
    const Run g = cliText({"retina-image", "--image", target(), "--out", outPath("speckle-pupil.png"), "--speckle", "3",
                           "--speckle-grain", "pupil", "--rays", "4000", "--json"});
    QVERIFY2(g.code == 0, qPrintable(g.err));
    const json k = g.j();
    QCOMPARE(k["speckle_grain"].get<std::string>(), std::string("pupil"));
    QCOMPARE(k["speckle_dof"].size(), std::size_t{3});
    double var = 0;
    for (const auto& m : k["speckle_dof"]) {
      QVERIFY(m.get<double>() > 50);
      var += 1.0 / (3.0 * m.get<double>());
    }
    const double expect_pupil = std::sqrt(var) / 3.0;
    QVERIFY(std::abs(k["speckle_expected"].get<double>() / expect_pupil - 1) < 1e-12);
    QVERIFY(std::abs(k["speckle_contrast"].get<double>() / expect_pupil - 1) < 0.05);
  }

  void badInput() {
    const QString out = outPath("bad.png");
    Run r = cliText({"retina-image", "--image", outPath("missing.png"), "--out", out});
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains("missing.png"), qPrintable(r.err));
    r = cliText({"retina-image", "--image", target(), "--out", out, "--accommodation-d", "nan"});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("--accommodation-d"), qPrintable(r.err));
    r = cliText({"retina-image", "--image", target(), "--out", out, "--accommodation-d", "7"});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("0..4"), qPrintable(r.err));
    r = cliText({"retina-image", "--image", target(), "--out", out, "--gaze-deg", "1,x"});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("--gaze-deg"), qPrintable(r.err));
    r = cliText({"retina-image", "--image", target(), "--out", out, "--speckle", "2", "--speckle-grain", "coarse"});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("--speckle-grain") && r.err.contains("coarse"), qPrintable(r.err));
    r = cliText({"retina-image", "--image", target(), "--out", out, "--speckle", "1.5"});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains("--speckle"), qPrintable(r.err));
    const fs::path notImage = tmpDir() / "not-an-image.png";
    std::ofstream(notImage) << "hello";
    r = cliText({"retina-image", "--image", QString::fromStdString(notImage.string()), "--out", out});
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains("not-an-image.png"), qPrintable(r.err));
  }
};

QTEST_GUILESS_MAIN(TestCliRetinaImage)

}  // namespace tst_cli_retina_image
#include "tst_cli_retina_image.moc"
