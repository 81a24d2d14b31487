#pragma once
// Everything a live session of a scene's bench needs, put together: the stages (Bench: USB
// controllers by serial, emulated ones for the rest), a camera on the stages' clock, and on
// the virtual bench the optics that render its frames. The studio's devices panel and
// `fovea-cli calibrate` build one.
//
// Virtual or not: with no stage controller of the scene on the USB bus (or hardware not
// allowed) every axis is emulated and the camera is the virtual eye camera rendering the
// displays through the simulated optics; isVirtual() is then true and the studio says so.
// With controllers on the bus, the camera is the first V4L2 camera (the virtual one when
// there is none).
#include <memory>
#include <optional>
#include <vector>

#include "devices/bench/bench.h"
#include "devices/calibration/capture_session.h"
#include "devices/camera/synchronized_camera.h"
#include "devices/virtual/virtual_optics.h"

namespace fovea::devices {

struct LiveBenchOptions {
  bool allow_hardware = true;
  std::shared_ptr<Clock> clock;  // virtual bench clock; default steady (real time)
  EyeViewCamera camera_model;
  double camera_fps = 30.0;
  unsigned camera_seed = 1;
  double camera_noise_dn = 2.0;
  std::chrono::milliseconds idle_poll{200};
  std::optional<std::vector<DeviceInfo>> usb;  // controllers present (tests); default: enumerate
  std::optional<int> v4l2_index;               // camera for a hardware bench; default: the first
};

class LiveBench {
 public:
  LiveBench(const Scene& scene, LiveBenchOptions options = {});
  ~LiveBench();

  Bench& bench() { return *bench_; }
  Camera& camera() { return *camera_; }              // thread-safe (SynchronizedCamera)
  VirtualOptics* optics() { return optics_.get(); }  // null when the camera is a real one
  const std::shared_ptr<Clock>& clock() const { return clock_; }
  bool isVirtual() const { return all_virtual_; }  // every axis emulated
  int virtualAxes() const { return virtual_axes_; }
  bool cameraIsVirtual() const { return optics_ != nullptr; }
  // Rig for capture sessions: patterns go to the virtual displays (hardware: not shown).
  BenchRig rig();

 private:
  std::shared_ptr<Clock> clock_;
  std::unique_ptr<Bench> bench_;
  std::unique_ptr<VirtualOptics> optics_;
  std::shared_ptr<SynchronizedCamera> camera_;
  bool all_virtual_ = true;
  int virtual_axes_ = 0;
};

}  // namespace fovea::devices
