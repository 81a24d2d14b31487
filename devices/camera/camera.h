#pragma once
// Cameras of the bench: a common interface for V4L2 cameras (OpenCV VideoCapture) and the
// virtual camera, and the "no stale frame" rule for captures after a stage move.
//
// Every frame carries the time its exposure started, on the camera's clock (the same clock
// as the stage link's: steady time for hardware, the simulated clock on the virtual bench).
// A frame whose exposure began before the stage settled shows the stage in motion or at
// its old place: captureSettled() throws such frames away.
#include <cstdint>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

#include "devices/transport/transport.h"

namespace fovea::devices {

struct Frame {
  cv::Mat image;
  std::uint64_t sequence = 0;     // 0, 1, 2, ... per camera
  double exposure_start_s = 0.0;  // camera clock
  double exposure_s = 0.0;
};

class Camera {
 public:
  virtual ~Camera() = default;
  virtual void open() = 0;  // throws DeviceError
  virtual void close() = 0;
  virtual bool isOpen() const = 0;
  virtual Frame grab() = 0;  // the next frame; throws DeviceError(Disconnected/Timeout)
  virtual DeviceInfo info() const = 0;
  virtual double now() const = 0;  // camera clock, seconds

  // Exposure (seconds) and gain (driver units), where the driver offers them.
  virtual bool hasExposure() const { return false; }
  virtual std::optional<double> exposure() const { return std::nullopt; }
  virtual void setExposure(double seconds);  // throws DeviceError(Usage) when not offered
  virtual bool hasGain() const { return false; }
  virtual std::optional<double> gain() const { return std::nullopt; }
  virtual void setGain(double gain);
};

// A frame is fresh when its exposure started at or after the settle time.
inline bool frameIsFresh(const Frame& f, double settled_at_s) {
  return f.exposure_start_s >= settled_at_s;
}

// Grabs frames until one exposed after `settled_at_s` (camera clock) arrives; stale ones
// are discarded and counted. Throws DeviceError(Timeout) after `max_frames` stale frames.
struct SettledCapture {
  Frame frame;
  int discarded = 0;
};
SettledCapture captureSettled(Camera& camera, double settled_at_s, int max_frames = 30);

}  // namespace fovea::devices
