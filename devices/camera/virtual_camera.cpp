#include "devices/camera/virtual_camera.h"

#include <cmath>

#include <opencv2/imgproc.hpp>

#include "devices/transport/device_error.h"

namespace fovea::devices {

VirtualCamera::VirtualCamera(std::shared_ptr<Clock> clock, Renderer renderer, cv::Size size, double fps, unsigned seed)
    : clock_(std::move(clock)), renderer_(std::move(renderer)), size_(size), period_s_(1.0 / fps), seed_(seed) {
  if (!renderer_) {
    const cv::Mat board = checkerboard(size_, {9, 7});
    renderer_ = [board](double) { return board; };
  }
}

cv::Mat VirtualCamera::checkerboard(cv::Size size, cv::Size squares) {
  cv::Mat img(size, CV_32F, cv::Scalar(0.5));
  const int cell = std::min(size.width * 8 / 10 / squares.width, size.height * 8 / 10 / squares.height);
  const int x0 = (size.width - cell * squares.width) / 2, y0 = (size.height - cell * squares.height) / 2;
  for (int r = 0; r < squares.height; ++r)
    for (int c = 0; c < squares.width; ++c)
      img(cv::Rect(x0 + c * cell, y0 + r * cell, cell, cell)).setTo((r + c) % 2 ? 0.9 : 0.1);
  return img;
}

Frame VirtualCamera::grab() {
  if (!isOpen()) throw DeviceError(DeviceError::Kind::Disconnected, "virtual camera is not connected");
  // Next frame slot: exposures start on multiples of the frame period; the frame is
  // delivered when its exposure ends.
  const double t = clock_->now();
  const double start = std::ceil(t / period_s_ - 1e-9) * period_s_;
  clock_->waitUntil(start + exposure_s_);
  cv::Mat radiance = renderer_(start);
  if (radiance.type() != CV_32F) radiance.convertTo(radiance, CV_32F);
  // Signal: 0..1 radiance maps to 0..255 DN at 10 ms and gain 1; Gaussian read noise.
  cv::Mat dn = radiance * (255.0 * gain_ * exposure_s_ / 0.01);
  if (noise_sigma_ > 0) {
    // One generator per exposure, seeded by (seed, slot index): the slot's noise whoever reads it.
    const auto slot = static_cast<std::uint64_t>(std::llround(start / period_s_));
    std::seed_seq seq{seed_, static_cast<unsigned>(slot & 0xffffffffu), static_cast<unsigned>(slot >> 32)};
    std::mt19937 rng(seq);
    std::normal_distribution<float> n(0.0f, static_cast<float>(noise_sigma_));
    for (int y = 0; y < dn.rows; ++y) {
      float* row = dn.ptr<float>(y);
      for (int x = 0; x < dn.cols; ++x) row[x] += n(rng);
    }
  }
  Frame f;
  dn.convertTo(f.image, CV_8U);  // saturates at 0 and 255
  f.exposure_start_s = start;
  f.exposure_s = exposure_s_;
  f.sequence = sequence_++;
  return f;
}

DeviceInfo VirtualCamera::info() const {
  DeviceInfo i;
  i.kind = "camera";
  i.model = "virtual-eye-camera";
  i.serial = "VCAM0001";
  i.description = "virtual camera at the eye position";
  i.is_virtual = true;
  return i;
}

void VirtualCamera::setExposure(double seconds) {
  if (!(seconds > 0) || seconds > 1.0)
    throw DeviceError(DeviceError::Kind::Usage, "virtual camera exposure must be in (0, 1] s");
  exposure_s_ = seconds;
}

void VirtualCamera::setGain(double g) {
  if (!(g > 0) || g > 64) throw DeviceError(DeviceError::Kind::Usage, "virtual camera gain must be in (0, 64]");
  gain_ = g;
}

}  // namespace fovea::devices
