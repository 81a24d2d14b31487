#pragma once
// The virtual bench's optics: what the virtual eye camera sees. The two displays (the laser
// projector through the HOE, the micro-OLED through its combiner) each show a pattern; the
// bench pose (HOE, micro-OLED and camera stages) is read from the emulated controllers at
// the frame's exposure time; the ground-truth display -> camera maps of that pose
// (model/physics/display_camera_map.h) carry the patterns into the camera image, anti-aliased, then
// the camera lens blurs it a little. VirtualCamera adds exposure, gain and noise.
//
// Maps are cached per display for the last poses, so a still bench renders fast; a moving
// stage recomputes them every frame (a trace of the HOE and a Newton inversion per pixel).
// Thread-safe: patterns are set from one thread (the studio, a calibration session) while
// the camera renders on another.
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>

#include <opencv2/core.hpp>

#include "devices/camera/virtual_camera.h"
#include "model/image/display_pattern.h"
#include "model/physics/display_camera_map.h"
#include "model/scene/scene.h"

namespace fovea::devices {

class Bench;

class VirtualOptics {
 public:
  using PoseSource = std::function<BenchPose(double t_s)>;
  VirtualOptics(const Scene& scene, EyeViewCamera camera, PoseSource pose);

  void setScene(const Scene& scene);
  const EyeViewCamera& cameraModel() const { return camera_; }
  void show(BenchDisplay display, const image::DisplayPattern& pattern);
  image::DisplayPattern shown(BenchDisplay display) const;
  void setBlurSigma(double px) { blur_sigma_px_ = px; }

  BenchPose poseAt(double t_s) const { return pose_(t_s); }
  // Radiance (CV_32F, 0..1 at exposure 10 ms and gain 1) at bench time t.
  cv::Mat render(double t_s);
  cv::Mat render(const BenchPose& pose);
  // The ground truth of a display at a pose (cached).
  std::shared_ptr<const DisplayCameraMap> groundTruth(BenchDisplay display, const BenchPose& pose);
  VirtualCamera::Renderer renderer() {
    return [this](double t) { return render(t); };
  }

 private:
  struct Cached {
    BenchDisplay display;
    BenchPose pose;
    std::shared_ptr<const DisplayCameraMap> map;
    cv::Mat map_x, map_y, brightness;
  };
  std::shared_ptr<const Cached> cached(BenchDisplay display, const BenchPose& pose);

  mutable std::mutex mutex_;
  Scene scene_;
  EyeViewCamera camera_;
  PoseSource pose_;
  image::DisplayPattern peripheral_, foveal_;
  std::deque<std::shared_ptr<const Cached>> cache_;
  double blur_sigma_px_ = 0.6;
  // The last rendered radiance and what it was rendered for: a camera streaming a still
  // bench (no axis moving, the same patterns) gets it again instead of a new rendering.
  struct LastFrame {
    BenchPose pose;
    image::DisplayPattern peripheral, foveal;
    double blur_sigma_px = 0;
    cv::Mat radiance;
  };
  std::optional<LastFrame> last_;
  // Counts the scene changes that clear the caches: what was computed for an older scene is
  // returned to its caller but not stored.
  std::uint64_t scene_generation_ = 0;
};

// The pose of a bench's elements at time t: emulated axes by their controllers' simulated
// motion, hardware axes by their last snapshot; unbound coordinates are 0.
VirtualOptics::PoseSource benchPoseSource(Bench& bench);

}  // namespace fovea::devices
