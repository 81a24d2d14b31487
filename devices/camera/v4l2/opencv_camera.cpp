#include "devices/camera/v4l2/opencv_camera.h"

#include "devices/transport/device_error.h"

namespace fovea::devices {

namespace {
constexpr double kV4l2ExposureUnit_s = 100e-6;  // V4L2 exposure_time_absolute: 100 us steps
}

OpenCvCamera::OpenCvCamera(int index, std::string name) : index_(index), name_(std::move(name)) {}

double OpenCvCamera::now() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

void OpenCvCamera::open() {
  cap_ = std::make_unique<cv::VideoCapture>(index_, cv::CAP_V4L2);
  if (!cap_->isOpened()) {
    cap_.reset();
    throw DeviceError(DeviceError::Kind::NotFound, "cannot open camera /dev/video" + std::to_string(index_));
  }
  if (cap_->set(cv::CAP_PROP_BUFFERSIZE, 1)) queued_buffers_ = 1;
  const double fps = cap_->get(cv::CAP_PROP_FPS);
  if (fps > 0) frame_period_s_ = 1.0 / fps;
  // Probe controls: a driver that offers a control reports it and accepts it back.
  const double e = cap_->get(cv::CAP_PROP_EXPOSURE);
  exposure_ok_ = e > 0 && cap_->set(cv::CAP_PROP_EXPOSURE, e);
  const double g = cap_->get(cv::CAP_PROP_GAIN);
  gain_ok_ = g >= 0 && cap_->set(cv::CAP_PROP_GAIN, g);
}

void OpenCvCamera::close() {
  cap_.reset();
}
bool OpenCvCamera::isOpen() const {
  return cap_ && cap_->isOpened();
}

Frame OpenCvCamera::grab() {
  if (!isOpen())
    throw DeviceError(DeviceError::Kind::Disconnected, "camera /dev/video" + std::to_string(index_) + " is not open");
  Frame f;
  if (!cap_->read(f.image) || f.image.empty())
    throw DeviceError(DeviceError::Kind::Disconnected,
                      "camera /dev/video" + std::to_string(index_) + " delivered no frame");
  const double t = now();
  f.exposure_s = exposure().value_or(frame_period_s_);
  f.exposure_start_s = t - frame_period_s_ * queued_buffers_ - f.exposure_s;
  f.sequence = sequence_++;
  return f;
}

DeviceInfo OpenCvCamera::info() const {
  DeviceInfo i;
  i.kind = "camera";
  i.model = name_.empty() ? "V4L2 camera" : name_;
  i.serial = "/dev/video" + std::to_string(index_);
  return i;
}

std::optional<double> OpenCvCamera::exposure() const {
  if (!isOpen() || !exposure_ok_) return std::nullopt;
  return cap_->get(cv::CAP_PROP_EXPOSURE) * kV4l2ExposureUnit_s;
}

void OpenCvCamera::setExposure(double seconds) {
  if (!exposure_ok_) Camera::setExposure(seconds);
  if (!(seconds > 0)) throw DeviceError(DeviceError::Kind::Usage, "exposure must be positive");
  cap_->set(cv::CAP_PROP_AUTO_EXPOSURE, 1);  // V4L2 menu: 1 = manual
  if (!cap_->set(cv::CAP_PROP_EXPOSURE, seconds / kV4l2ExposureUnit_s))
    throw DeviceError(DeviceError::Kind::Io, info().serial + " refused exposure " + std::to_string(seconds) + " s");
}

std::optional<double> OpenCvCamera::gain() const {
  if (!isOpen() || !gain_ok_) return std::nullopt;
  return cap_->get(cv::CAP_PROP_GAIN);
}

void OpenCvCamera::setGain(double g) {
  if (!gain_ok_) Camera::setGain(g);
  if (!cap_->set(cv::CAP_PROP_GAIN, g)) throw DeviceError(DeviceError::Kind::Io, info().serial + " refused gain");
}

}  // namespace fovea::devices

// The module's one entry point (devices/camera/v4l2_camera.h).
extern "C" fovea::devices::Camera* fovea_v4l2_camera_create(int index, const char* name) {
  return new fovea::devices::OpenCvCamera(index, name != nullptr ? std::string(name) : std::string());
}
