#pragma once
// The virtual bench's camera: frames from a renderer function of the bench time, taken at
// a fixed frame rate on the shared clock (simulated or steady), with sensor noise seeded by
// (camera seed, frame slot), exposure and gain scaling the signal. The noise belongs to the
// exposure, as on a sensor: a frame's noise does not depend on how many frames the host read
// before it, so a capture that discards one stale frame more (thread timing on a loaded
// machine) still sees the same image in the same slot. The renderer is where the
// simulated optics plug in (what a camera at the eye sees); without one it shows a
// calibration checkerboard. Each grab waits for the next frame slot, so a frame's
// exposure start is a whole number of frame periods: the stale-frame rule applies exactly
// as with hardware.
#include <functional>
#include <memory>
#include <random>

#include "devices/camera/camera.h"
#include "devices/virtual/sim_clock.h"

namespace fovea::devices {

class VirtualCamera : public Camera {
 public:
  // Renders the scene radiance (CV_32F, 0..1 at exposure 10 ms and gain 1) at time t.
  using Renderer = std::function<cv::Mat(double t_s)>;
  VirtualCamera(std::shared_ptr<Clock> clock, Renderer renderer = {}, cv::Size size = {640, 480}, double fps = 30.0,
                unsigned seed = 1);
  void open() override { open_ = true; }
  void close() override { open_ = false; }
  bool isOpen() const override { return open_ && !unplugged_; }
  Frame grab() override;
  DeviceInfo info() const override;
  double now() const override { return clock_->now(); }
  bool hasExposure() const override { return true; }
  std::optional<double> exposure() const override { return exposure_s_; }
  void setExposure(double seconds) override;
  bool hasGain() const override { return true; }
  std::optional<double> gain() const override { return gain_; }
  void setGain(double gain) override;
  void setNoiseSigma(double sigma_dn) { noise_sigma_ = sigma_dn; }
  void simulateUnplug() { unplugged_ = true; }

  // A checkerboard of `squares` (cols x rows) filling most of the frame.
  static cv::Mat checkerboard(cv::Size size, cv::Size squares);

 private:
  std::shared_ptr<Clock> clock_;
  Renderer renderer_;
  cv::Size size_;
  double period_s_;
  unsigned seed_;
  double exposure_s_ = 0.01, gain_ = 1.0, noise_sigma_ = 2.0;
  std::uint64_t sequence_ = 0;
  bool open_ = false, unplugged_ = false;
};

}  // namespace fovea::devices
