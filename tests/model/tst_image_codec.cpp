// The image codec module (model/image/image_codec.h): not loaded at start-up, loaded by the
// first image read or write, a missing module a clear error that is not cached; camera frames
// (8- and 16-bit grey) round-trip exactly through PNG, colour files become grey by
// cv::IMREAD_GRAYSCALE's weights, linear RGB round-trips to its 8-bit step.
#include <QtTest>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "model/image/image_io.h"
#include "tests/test_files.h"

namespace tst_image_codec {

using namespace fovea;

using fovea::testing::mappedInProcess;

namespace {
std::string tmp(const std::string& file) {
  return (fovea::testing::testTmpDir("image_codec") / file).string();
}
}  // namespace

class TestImageCodec : public QObject {
  Q_OBJECT

 private slots:
  // First: no image has been read or written in this process yet.
  void loadedOnFirstUseAndAMissingModuleIsNamed() {
    QVERIFY2(!mappedInProcess("libOpenImageIO"), "OpenImageIO loaded at start-up");
    qputenv("FOVEA_IMAGE_CODEC", "/nonexistent/libfovea_image_codec.so");
    cv::Mat frame(4, 5, CV_8UC1, cv::Scalar(7));
    try {
      image::writeCameraImage(tmp("never.png"), frame);
      QFAIL("wrote without a codec");
    } catch (const image::ImageIoError& e) {
      QVERIFY2(std::string(e.what()).find("cannot load the image codec /nonexistent/libfovea_image_codec.so") !=
                   std::string::npos,
               e.what());
    }
    QVERIFY(!std::filesystem::exists(tmp("never.png")));
    qunsetenv("FOVEA_IMAGE_CODEC");
    image::writeCameraImage(tmp("first.png"), frame);  // the failure was not kept
    QVERIFY(mappedInProcess("libOpenImageIO"));
    QCOMPARE(cv::countNonZero(image::readCameraImage(tmp("first.png")) != frame), 0);
  }

  void cameraFramesRoundTripExactly() {
    cv::Mat u8(37, 53, CV_8UC1), u16(21, 18, CV_16UC1);
    cv::randu(u8, 0, 256);
    for (int y = 0; y < u16.rows; ++y)
      for (int x = 0; x < u16.cols; ++x)
        u16.at<std::uint16_t>(y, x) = static_cast<std::uint16_t>(257 * ((x + 3 * y) % 256));
    image::writeCameraImage(tmp("u8.png"), u8);
    const cv::Mat back = image::readCameraImage(tmp("u8.png"));
    QCOMPARE(back.type(), CV_8UC1);
    QCOMPARE(back.size(), u8.size());
    QCOMPARE(cv::countNonZero(back != u8), 0);
    // 16-bit frames are stored as 16 bits; read back as 8-bit grey (k * 257 -> k).
    image::writeCameraImage(tmp("u16.png"), u16);
    const cv::Mat back16 = image::readCameraImage(tmp("u16.png"));
    for (int y = 0; y < u16.rows; ++y)
      for (int x = 0; x < u16.cols; ++x) QCOMPARE(int(back16.at<std::uint8_t>(y, x)), (x + 3 * y) % 256);
    QVERIFY_THROWS_EXCEPTION(image::ImageIoError, image::writeCameraImage(tmp("rgb.png"), cv::Mat(3, 3, CV_8UC3)));
  }

  void colourFilesBecomeGreyByLumaWeights() {
    // sRGB-encoded (50, 100, 200) stored, read as 0.299 R + 0.587 G + 0.114 B of the stored values.
    cv::Mat linear(2, 2, CV_32FC3);
    const auto decode = [](double v8) {
      const double c = v8 / 255.0;
      return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
    };
    linear.setTo(cv::Scalar(decode(50), decode(100), decode(200)));
    image::writeLinearRgb(tmp("colour.png"), linear);
    const cv::Mat grey = image::readCameraImage(tmp("colour.png"));
    QCOMPARE(int(grey.at<std::uint8_t>(1, 1)), int(std::lround(0.299 * 50 + 0.587 * 100 + 0.114 * 200)));
  }

  void linearRgbRoundTripsToItsStep() {
    cv::Mat linear(9, 11, CV_32FC3);
    cv::randu(linear, 0.0, 1.0);
    image::writeLinearRgb(tmp("linear.png"), linear, true);
    const cv::Mat back = image::readLinearRgb(tmp("linear.png"));
    double worst = 0;
    for (int y = 0; y < linear.rows; ++y)
      for (int x = 0; x < linear.cols; ++x)
        for (int c = 0; c < 3; ++c)
          worst = std::max(worst, double(std::abs(back.at<cv::Vec3f>(y, x)[c] - linear.at<cv::Vec3f>(y, x)[c])));
    QVERIFY2(worst < 1e-4, qPrintable(QString::number(worst)));  // 16-bit sRGB step, linear units
    QVERIFY(worst > 0);                                          // it was quantised: the file really was read
  }

  // Every format goes through the one writer (model/io/output_file.h): the target is replaced by
  // a rename, never rewritten in place — a hard link to the old file keeps the old bytes. SGI is
  // a format OpenImageIO 2.4 cannot encode to memory (no "ioproxy"): it is staged in a private
  // directory under $TMPDIR, which is gone afterwards (issue 28).
  void everyFormatIsReplacedByRenameNotRewritten() {
    const std::filesystem::path staging_root = fovea::testing::testTmpDir("image_codec") / "tmpdir";
    std::filesystem::create_directories(staging_root);
    const QByteArray old_tmpdir = qgetenv("TMPDIR");
    qputenv("TMPDIR", QByteArray::fromStdString(staging_root.string()));
    cv::Mat linear(6, 7, CV_32FC3, cv::Scalar(0.25, 0.5, 0.75));
    for (const std::string name : {"replaced.png", "replaced.sgi"}) {
      const std::string target = tmp(name), link = tmp(name + ".old");
      std::filesystem::remove(target);
      std::filesystem::remove(link);
      { std::ofstream(target) << "old bytes"; }
      std::filesystem::create_hard_link(target, link);
      image::writeLinearRgb(target, linear);
      std::ifstream in(link);
      const std::string kept((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      QCOMPARE(kept, std::string("old bytes"));
      const cv::Mat back = image::readLinearRgb(target);
      QCOMPARE(back.cols, 7);
      QVERIFY2(std::abs(back.at<cv::Vec3f>(5, 6)[2] - 0.75f) < 4e-3,
               name.c_str());  // half an 8-bit sRGB step near 0.75
    }
    QVERIFY2(std::filesystem::is_empty(staging_root), "a staging directory was left behind");
    qputenv("TMPDIR", old_tmpdir);
  }
};

QTEST_GUILESS_MAIN(TestImageCodec)

}  // namespace tst_image_codec
#include "tst_image_codec.moc"
