#include "devices/bench/live_bench.h"

#include "devices/camera/camera_enumeration.h"
#include "devices/camera/v4l2_camera.h"
#include "devices/camera/virtual_camera.h"
#include "devices/transport/libusb_transport.h"

namespace fovea::devices {

LiveBench::LiveBench(const Scene& scene, LiveBenchOptions o) : clock_(o.clock) {
  if (!clock_) clock_ = std::make_shared<SteadyClock>();
  BenchOptions bo;
  bo.use_hardware = o.allow_hardware;
  bo.virtual_clock = clock_;
  bo.idle_poll = o.idle_poll;
  std::optional<std::vector<DeviceInfo>> usb = o.usb;
  if (o.allow_hardware && !usb) usb = enumerateUsbControllers();
  if (!o.allow_hardware) usb = std::vector<DeviceInfo>{};
  bench_ = std::make_unique<Bench>(scene, bo, usb);
  for (AxisWorker* w : bench_->axes()) {
    if (bench_->virtualController(w->binding().element, w->binding().axis))
      ++virtual_axes_;
    else
      all_virtual_ = false;
  }

  std::shared_ptr<Camera> cam;
  if (!all_virtual_) {
    const auto cams = enumerateV4l2();
    if (o.v4l2_index || !cams.empty()) cam = makeV4l2Camera(o.v4l2_index.value_or(cams.front().index));
  }
  if (!cam) {
    optics_ = std::make_unique<VirtualOptics>(scene, o.camera_model, benchPoseSource(*bench_));
    auto v = std::make_shared<VirtualCamera>(clock_, optics_->renderer(),
                                             cv::Size(o.camera_model.pixels[0], o.camera_model.pixels[1]), o.camera_fps,
                                             o.camera_seed);
    v->setNoiseSigma(o.camera_noise_dn);
    cam = v;
  }
  camera_ = std::make_shared<SynchronizedCamera>(cam);
}

LiveBench::~LiveBench() {
  // Stop the axis threads before the optics they feed go away.
  bench_.reset();
}

BenchRig LiveBench::rig() {
  BenchRig r;
  r.bench = bench_.get();
  r.camera = camera_.get();
  r.is_virtual = optics_ != nullptr;
  if (optics_) {
    VirtualOptics* o = optics_.get();
    r.show = [o](BenchDisplay d, const image::DisplayPattern& p) { o->show(d, p); };
    r.pose = [o](double t) { return o->poseAt(t); };
  }
  return r;
}

}  // namespace fovea::devices
