#pragma once
// A V4L2 camera through OpenCV's VideoCapture. Exposure and gain are used when the driver
// accepts them (CAP_PROP_EXPOSURE in the driver's units: for V4L2 "exposure_time_absolute"
// is 100 us steps, so seconds * 1e4; manual exposure needs CAP_PROP_AUTO_EXPOSURE = 1, the
// V4L2 "manual" menu value). The driver queues a few buffers, so a frame returned by read()
// may be older than the call: its exposure start is estimated conservatively as
//   t_returned - frame_period * queued_buffers - exposure,
// with the buffer queue shrunk to 1 where the driver allows (CAP_PROP_BUFFERSIZE).
#include <chrono>
#include <memory>

#include <opencv2/videoio.hpp>

#include "devices/camera/camera.h"

namespace fovea::devices {

class OpenCvCamera : public Camera {
 public:
  explicit OpenCvCamera(int index, std::string name = {});
  void open() override;
  void close() override;
  bool isOpen() const override;
  Frame grab() override;
  DeviceInfo info() const override;
  double now() const override;

  bool hasExposure() const override { return exposure_ok_; }
  std::optional<double> exposure() const override;
  void setExposure(double seconds) override;
  bool hasGain() const override { return gain_ok_; }
  std::optional<double> gain() const override;
  void setGain(double gain) override;

 private:
  int index_;
  std::string name_;
  std::unique_ptr<cv::VideoCapture> cap_;
  bool exposure_ok_ = false, gain_ok_ = false;
  double frame_period_s_ = 1.0 / 30.0;
  int queued_buffers_ = 4;
  std::uint64_t sequence_ = 0;
};

}  // namespace fovea::devices
