#include "devices/virtual/virtual_optics.h"

#include <opencv2/imgproc.hpp>

#include "devices/bench/bench.h"
#include "devices/stage/stage_binding.h"
#include "model/scene/scene_compare.h"

namespace fovea::devices {

namespace {
constexpr std::size_t kCacheSize = 6;
}

VirtualOptics::VirtualOptics(const Scene& scene, EyeViewCamera camera, PoseSource pose)
    : scene_(scene), camera_(camera), pose_(std::move(pose)) {
  if (!pose_) pose_ = [](double) { return BenchPose{}; };
}

void VirtualOptics::setScene(const Scene& scene) {
  std::lock_guard lock(mutex_);
  // The camera maps follow the camera's pose (BenchPose::camera_gaze_deg), not the design's
  // eye gaze: a gaze drag in the studio keeps them (tst_virtual_bench checks the maps agree).
  const bool keep = equalButGaze(scene_, scene);
  scene_ = scene;
  if (!keep) {
    cache_.clear();
    last_.reset();
    ++scene_generation_;
  }
}

void VirtualOptics::show(BenchDisplay display, const image::DisplayPattern& pattern) {
  std::lock_guard lock(mutex_);
  (display == BenchDisplay::Peripheral ? peripheral_ : foveal_) = pattern;
}

image::DisplayPattern VirtualOptics::shown(BenchDisplay display) const {
  std::lock_guard lock(mutex_);
  return display == BenchDisplay::Peripheral ? peripheral_ : foveal_;
}

std::shared_ptr<const VirtualOptics::Cached> VirtualOptics::cached(BenchDisplay display, const BenchPose& pose) {
  Scene scene;
  std::uint64_t generation = 0;
  {
    std::lock_guard lock(mutex_);
    for (const auto& c : cache_)
      if (c->display == display && c->pose == pose) return c;
    scene = scene_;
    generation = scene_generation_;
  }
  // Computed outside the lock: the studio's GUI thread may set patterns meanwhile.
  auto c = std::make_shared<Cached>();
  c->display = display;
  c->pose = pose;
  c->map = makeDisplayMap(display, scene, camera_, pose);
  c->map->cameraMaps(c->map_x, c->map_y, c->brightness);
  std::lock_guard lock(mutex_);
  if (generation != scene_generation_) return c;  // the scene changed meanwhile
  cache_.push_front(c);
  while (cache_.size() > kCacheSize) cache_.pop_back();
  return c;
}

std::shared_ptr<const DisplayCameraMap> VirtualOptics::groundTruth(BenchDisplay display, const BenchPose& pose) {
  return cached(display, pose)->map;
}

cv::Mat VirtualOptics::render(double t_s) {
  return render(pose_(t_s));
}

cv::Mat VirtualOptics::render(const BenchPose& pose) {
  const image::DisplayPattern shown_p = shown(BenchDisplay::Peripheral), shown_f = shown(BenchDisplay::Foveal);
  const double blur = blur_sigma_px_;
  std::uint64_t generation = 0;
  {
    std::lock_guard lock(mutex_);
    generation = scene_generation_;
    if (last_ && last_->pose == pose && last_->peripheral == shown_p && last_->foveal == shown_f &&
        last_->blur_sigma_px == blur)
      return last_->radiance.clone();
  }
  cv::Mat radiance = cv::Mat::zeros(camera_.pixels[1], camera_.pixels[0], CV_32F);
  for (BenchDisplay d : {BenchDisplay::Peripheral, BenchDisplay::Foveal}) {
    const image::DisplayPattern& p = d == BenchDisplay::Peripheral ? shown_p : shown_f;
    if (p.kind == image::DisplayPattern::Kind::Off) continue;
    const auto c = cached(d, pose);
    image::renderPattern(p, c->map_x, c->map_y, c->brightness, radiance);
  }
  if (blur > 0) cv::GaussianBlur(radiance, radiance, cv::Size(0, 0), blur);
  std::lock_guard lock(mutex_);
  if (generation == scene_generation_) last_ = LastFrame{pose, shown_p, shown_f, blur, radiance.clone()};
  return radiance;
}

VirtualOptics::PoseSource benchPoseSource(Bench& bench) {
  struct Source {
    std::shared_ptr<VirtualAptController> emulator;
    AxisWorker* worker = nullptr;
    StageBinding binding;
    double* target = nullptr;
  };
  auto sources = std::make_shared<std::vector<Source>>();
  auto slot = [](BenchPose& p, const StageBinding& b) -> double* {
    if (b.element == "hoe" && b.axis == "x") return &p.hoe_shift_mm[0];
    if (b.element == "hoe" && b.axis == "y") return &p.hoe_shift_mm[1];
    if (b.element == "foveal_display" && b.axis == "x") return &p.foveal_shift_mm[0];
    if (b.element == "foveal_display" && b.axis == "y") return &p.foveal_shift_mm[1];
    if (b.element == "camera" && b.axis == "yaw") return &p.camera_gaze_deg[0];
    if (b.element == "camera" && b.axis == "pitch") return &p.camera_gaze_deg[1];
    return nullptr;
  };
  for (AxisWorker* w : bench.axes()) {
    Source s;
    s.worker = w;
    s.binding = w->binding();
    s.emulator = bench.virtualController(s.binding.element, s.binding.axis);
    sources->push_back(s);
  }
  return [sources, slot](double t) {
    BenchPose p;
    for (const Source& s : *sources) {
      double* target = slot(p, s.binding);
      if (!target) continue;
      if (s.emulator) {
        *target = stageToElement(s.binding, s.emulator->positionAt(t));
      } else {
        const AxisSnapshot snap = s.worker->snapshot();
        if (snap.state.known) *target = snap.element_position;
      }
    }
    return p;
  };
}

}  // namespace fovea::devices
