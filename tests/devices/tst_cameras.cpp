// Cameras: no stale frame after a move (frames exposed before the stage settled are thrown
// away), exposure and gain of the virtual camera, V4L2 listing from sysfs, a missing V4L2
// camera failing with a clear error.
#include <QtTest>

#include <filesystem>
#include <fstream>

#include <opencv2/imgproc.hpp>

#include "devices/camera/camera_enumeration.h"
#include "devices/camera/v4l2_camera.h"
#include "devices/camera/virtual_camera.h"
#include "devices/stage/stage.h"
#include "devices/virtual/virtual_transport.h"
#include "tests/test_files.h"

namespace tst_cameras {

using namespace fovea::devices;

namespace {
// A bright 8-px square whose left edge sits at 20 px + 30 px per mm of stage travel.
double squareX(double position_mm) {
  return 20.0 + 30.0 * position_mm;
}
double measuredSquareX(const cv::Mat& img) {
  cv::Mat mask = img > 128;
  const cv::Moments m = cv::moments(mask, true);
  return m.m00 > 0 ? m.m10 / m.m00 - 3.5 : -1;  // centroid -> left edge
}
}  // namespace

using fovea::testing::mappedInProcess;

class TestCameras : public QObject {
  Q_OBJECT
 private slots:
  void noStaleFrameAfterAMove() {
    auto clock = std::make_shared<SimulatedClock>();
    auto ctl = makeVirtualController("MTS25-Z8", "", clock);
    auto link = std::make_unique<VirtualTransport>(ctl, clock);
    StageConfig cfg = defaultStageConfig(ctl->config().controller, ctl->config().stage);
    cfg.settle_s = 0.1;
    Stage stage(std::move(link), cfg);
    stage.connect();
    VirtualCamera cam(
        clock,
        [&](double t) {
          cv::Mat img(64, 400, CV_32F, cv::Scalar(0.0));
          img(cv::Rect(static_cast<int>(std::lround(squareX(ctl->positionAt(t)))), 28, 8, 8)).setTo(1.0);
          return img;
        },
        {400, 64}, 30.0);
    cam.setNoiseSigma(0.0);
    cam.open();

    const double duration = stage.startMoveAbsolute(10.0);
    const Frame moving = cam.grab();  // during the move: the square is on its way
    QVERIFY(measuredSquareX(moving.image) < squareX(10.0) - 30);
    stage.waitForMotion(2 * duration + 1);
    const double settled = stage.settledAt();
    const SettledCapture c = captureSettled(cam, settled);
    QVERIFY(frameIsFresh(c.frame, settled));
    QVERIFY(!frameIsFresh(moving, settled));
    QVERIFY(std::abs(measuredSquareX(c.frame.image) - squareX(10.0)) < 0.5);
    // Frames start on 1/30 s slots: the ones that began inside the 0.1 s settle window were dropped.
    const double period = 1.0 / 30.0;
    QVERIFY(c.frame.exposure_start_s - settled < period + 1e-9);
    QVERIFY(c.frame.sequence == moving.sequence + 1 + static_cast<std::uint64_t>(c.discarded));
    QVERIFY(c.discarded >= 2);  // 0.1 s settle at 30 fps: at least two slots fall inside
    // A camera that never delivers a settled frame ends in a clear timeout.
    QVERIFY_THROWS_EXCEPTION(DeviceError, captureSettled(cam, clock->now() + 100.0, 5));
  }

  void exposureAndGainScaleTheSignal() {
    auto clock = std::make_shared<SimulatedClock>();
    VirtualCamera cam(clock, [](double) { return cv::Mat(32, 32, CV_32F, cv::Scalar(0.25)); }, {32, 32});
    cam.setNoiseSigma(0.0);
    cam.open();
    QCOMPARE(cv::mean(cam.grab().image)[0], std::round(0.25 * 255));  // 63.75 -> 64 at 10 ms, gain 1
    cam.setExposure(0.02);
    QCOMPARE(cv::mean(cam.grab().image)[0], std::round(0.5 * 255));
    cam.setGain(4.0);
    QCOMPARE(cv::mean(cam.grab().image)[0], 255.0);  // saturates
    QVERIFY_THROWS_EXCEPTION(DeviceError, cam.setExposure(-1));
    // Noise: seeded by (seed, frame slot), so two cameras with one seed agree slot for slot, and
    // a camera that skipped frames sees in a slot what one that read every frame saw there.
    const auto grey = [](double) { return cv::Mat(100, 100, CV_32F, cv::Scalar(0.5)); };
    auto clock_a = std::make_shared<SimulatedClock>(), clock_b = std::make_shared<SimulatedClock>();
    VirtualCamera a(clock_a, grey, {100, 100}, 30, 7);
    VirtualCamera b(clock_b, grey, {100, 100}, 30, 7);
    a.open();
    b.open();
    const Frame fa = a.grab(), fb = b.grab();
    QCOMPARE(fa.exposure_start_s, fb.exposure_start_s);
    QCOMPARE(cv::norm(fa.image, fb.image, cv::NORM_L1), 0.0);
    const Frame a1 = a.grab(), a2 = a.grab(), a3 = a.grab();   // slots 1, 2, 3
    QVERIFY(cv::norm(a1.image, a2.image, cv::NORM_L1) > 0.0);  // a new exposure, new noise
    clock_b->waitUntil(a3.exposure_start_s - 0.5 / 30);        // b reads slot 3 only
    const Frame b3 = b.grab();
    QCOMPARE(b3.exposure_start_s, a3.exposure_start_s);
    QCOMPARE(cv::norm(a3.image, b3.image, cv::NORM_L1), 0.0);
    VirtualCamera other(std::make_shared<SimulatedClock>(), grey, {100, 100}, 30, 8);  // another seed
    other.open();
    QVERIFY(cv::norm(other.grab().image, fa.image, cv::NORM_L1) > 0.0);
    cv::Scalar mean, sd;
    cv::meanStdDev(fa.image, mean, sd);
    QVERIFY(std::abs(sd[0] - 2.0) < 0.2);  // default 2 DN read noise (quantisation adds ~0.3 in quadrature)
    a.simulateUnplug();
    QVERIFY_THROWS_EXCEPTION(DeviceError, a.grab());
  }

  void v4l2ListingFromSysfs() {
    namespace fs = std::filesystem;
    const fs::path root = fovea::testing::testTmpDir("v4l2", true);
    auto node = [&](const char* name, const char* label, const char* index) {
      fs::create_directories(root / name);
      std::ofstream(root / name / "name") << label << "\n";
      std::ofstream(root / name / "index") << index << "\n";
    };
    node("video2", "Pixel cam", "0");
    node("video0", "UVC Camera", "0");
    node("video1", "UVC Camera", "1");  // metadata node of video0
    const auto list = enumerateV4l2(root.string());
    QCOMPARE(list.size(), std::size_t{2});
    QCOMPARE(list[0].index, 0);
    QCOMPARE(list[0].name, std::string("UVC Camera"));
    QCOMPARE(list[1].device_path, std::string("/dev/video2"));
    QCOMPARE(toDeviceInfo(list[1]).kind, std::string("camera"));
    QVERIFY(enumerateV4l2((root / "missing").string()).empty());
  }

  void v4l2ModuleIsLoadedOnlyForARealCamera() {
    // Start-up loads no videoio (issue 25); a module that is not there is a clear error.
    QVERIFY2(!mappedInProcess("libopencv_videoio"), "videoio loaded before any camera was made");
    qputenv("FOVEA_V4L2_CAMERA_MODULE", "/nonexistent/libfovea_v4l2_camera.so");
    try {
      (void)makeV4l2Camera(63);
      QFAIL("made a camera without its module");
    } catch (const DeviceError& e) {
      QVERIFY(e.kind() == DeviceError::Kind::NotFound);
      QVERIFY2(std::string(e.what()).find("cannot load the V4L2 camera module /nonexistent/libfovea_v4l2_camera.so") !=
                   std::string::npos,
               e.what());
      // The path came from the environment, and the message says so (as the image codec's does).
      QVERIFY2(std::string(e.what()).find("(from $FOVEA_V4L2_CAMERA_MODULE)") != std::string::npos, e.what());
    }
    qunsetenv("FOVEA_V4L2_CAMERA_MODULE");
    QVERIFY(!mappedInProcess("libopencv_videoio"));
  }

  void missingV4l2CameraFailsClearly() {
    const std::shared_ptr<Camera> cam = makeV4l2Camera(63);
    QVERIFY(mappedInProcess("libopencv_videoio"));  // the module came with it
    try {
      cam->open();
      QFAIL("opened /dev/video63");
    } catch (const DeviceError& e) {
      QVERIFY(e.kind() == DeviceError::Kind::NotFound);
      QVERIFY(std::string(e.what()).find("/dev/video63") != std::string::npos);
    }
    QVERIFY(!cam->isOpen());
    QVERIFY_THROWS_EXCEPTION(DeviceError, cam->grab());
  }
};

QTEST_GUILESS_MAIN(TestCameras)

}  // namespace tst_cameras
#include "tst_cameras.moc"
